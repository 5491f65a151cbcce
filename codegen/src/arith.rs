//! How a kernel's arithmetic is spelled: one IEEE operation per DAG node, or single-use
//! products fused into their additions.

use crate::model::Variant;

/// How the arithmetic of a kernel is emitted.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Arith {
    /// One IEEE operation per DAG node: `free`, `fixed`.
    Plain,
    /// Single-use products fused into their addition ([`crate::fuse`]): `free_fma`,
    /// `fixed_fma`.
    Fma,
}

impl Arith {
    /// Both, in emission order.
    pub const ALL: [Arith; 2] = [Arith::Plain, Arith::Fma];

    /// The function name of `variant` emitted this way.
    pub fn function_name(self, variant: Variant) -> String {
        match self {
            Arith::Plain => variant.name().to_string(),
            Arith::Fma => format!("{}_fma", variant.name()),
        }
    }
}
