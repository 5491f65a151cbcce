//! The one dispatch from a contact law to its kernel's DAG: no-slip and rough
//! ([`crate::model`]), Walton ([`crate::walton`]).

use crate::model::{self, KernelGraph, Law, Variant};
use crate::walton;

/// The kernel of `law` for dimension `n` (`build`, `build_rough` or `build_walton`).
pub fn build_law(n: usize, variant: Variant, law: Law) -> KernelGraph {
    match law {
        Law::NoSlip => model::build(n, variant),
        Law::Rough => model::build_rough(n, variant),
        Law::Walton => walton::build_walton(n, variant),
    }
}
