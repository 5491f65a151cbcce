//! The languages with a back end, as `noslip gen --lang` names them, and the [`Language`]
//! hooks of each.

use super::c::{OpenCl, C};
use super::language::Language;

/// The languages with a back end, as `noslip gen --lang` names them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lang {
    /// C99 header, usable from C++ ([`C`]).
    C,
    /// OpenCL C source: device functions and batch kernels ([`OpenCl`]).
    OpenCl,
}

impl Lang {
    /// Every language, in the order `--help` lists them.
    pub const ALL: [Lang; 2] = [Lang::C, Lang::OpenCl];

    /// The name on the command line: `c`, `opencl`.
    pub fn name(self) -> &'static str {
        match self {
            Lang::C => "c",
            Lang::OpenCl => "opencl",
        }
    }

    /// The back end.
    pub fn language(self) -> &'static dyn Language {
        match self {
            Lang::C => &C,
            Lang::OpenCl => &OpenCl,
        }
    }
}
