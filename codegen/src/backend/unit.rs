//! A kernel ready to be spelled ([`Unit`]): its name, its straight-line program, its
//! parameters ([`Param`]) and the comment above it; and one parameter of a batch entry point
//! ([`BatchParam`]).

use super::precision::Precision;
use crate::program::Program;

/// One parameter of an emitted function.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Param {
    /// An input array: its name and the kernel input each element holds.
    Array(&'static str, Vec<String>),
    /// One input scalar (`fixed`'s `radius1`), named as the input.
    Scalar(String),
    /// The output array of body `body` (1 or 2): `S + N` elements, spin then velocity.
    Out(&'static str, usize),
}

/// One parameter of a batch entry point ([`Language::batch`]): the scalar function's
/// parameter `name` of C type `ty`, an array of `len` elements (`None`: one scalar), read
/// (`out == false`) or written.
///
/// [`Language::batch`]: super::language::Language::batch
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BatchParam {
    /// The parameter's name.
    pub name: String,
    /// Its element type: `double`, `float`.
    pub ty: &'static str,
    /// The array's length, or `None` for a scalar.
    pub len: Option<usize>,
    /// Whether the function writes it.
    pub out: bool,
}

impl BatchParam {
    /// An input array (`len` given) or scalar.
    pub fn input(name: &str, ty: &'static str, len: Option<usize>) -> Self {
        BatchParam {
            name: name.to_string(),
            ty,
            len,
            out: false,
        }
    }

    /// An output array of `len` elements.
    pub fn output(name: &str, ty: &'static str, len: usize) -> Self {
        BatchParam {
            name: name.to_string(),
            ty,
            len: Some(len),
            out: true,
        }
    }
}

/// A kernel ready to be spelled: its name (without the precision suffix), its program, its
/// parameters and the comment above it.
#[derive(Clone, Debug)]
pub struct Unit {
    /// The function name without the precision suffix (`noslip_d3_free`).
    pub name: String,
    /// The straight-line program.
    pub program: Program,
    /// The parameters, in order.
    pub params: Vec<Param>,
    /// The comment lines above the function (without comment markers).
    pub doc: Vec<String>,
}

impl Unit {
    /// The function name in precision `p`: `noslip_d3_free_f64`.
    pub fn function_name(&self, p: Precision) -> String {
        format!("{}_{}", self.name, p.suffix())
    }
}
