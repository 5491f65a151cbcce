//! The doc comment of an emitted batch kernel: the scalar kernel it repeats, where the law
//! and the ball parameters come from, the scalar kernel's description (less its
//! straight-line note), and the operations per contact and per call.

use super::params::Params;
use crate::emit;
use crate::model::{self, KernelGraph};
use crate::schedule::OpCount;
use proc_macro2::TokenStream;

/// The doc comment of `kernel`'s batch kernel in mode `params`, with its costs.
pub(super) fn docs(
    kernel: &KernelGraph,
    params: Params,
    per_contact: OpCount,
    per_batch: OpCount,
) -> TokenStream {
    let scalar = match kernel.law {
        model::Law::Rough => format!("rough::{}", kernel.variant.name()),
        model::Law::Walton => format!("walton::{}", kernel.variant.name()),
        model::Law::NoSlip => kernel.variant.name().to_string(),
    };
    let mut lines = vec![
        format!(
            "Batch form of [`crate::kernels::d{}::{scalar}`]: block `k` of `blocks` into `out[k]`,",
            kernel.dim
        ),
        "lane by lane, for `min(blocks.len(), out.len())` blocks.".into(),
    ];
    match (kernel.law, params) {
        (model::Law::Rough | model::Law::Walton, Params::Each) => lines.push(
            "The law: per contact, in the lanes of each block's `law`; computed in the lane loop.".into(),
        ),
        (model::Law::Rough, _) => lines.push(
            "The law `(e, beta)`: shared by every contact; `h_n`, `h_t` are computed once.".into(),
        ),
        (model::Law::Walton, _) => lines.push(
            "The law `(e, mu, beta0)`: shared by every contact; what depends on it alone is computed once."
                .into(),
        ),
        (model::Law::NoSlip, _) => {}
    }
    match params {
        Params::PerContact | Params::Each => {
            lines.push("Ball parameters: per contact, in the lanes.".into())
        }
        Params::Shared => lines.push(
            "Ball parameters: shared by every contact; what depends on them alone is computed once."
                .into(),
        ),
    }
    lines.extend([
        "Each lane runs the scalar kernel's operations on the same operands: the same bits in floats."
            .into(),
        String::new(),
    ]);
    // The scalar kernel's description, less its straight-line note (this one loops).
    // Its links are relative to the scalar kernel's module (`super::free` from
    // `dN::rough`); here they name the scalar kernels by their full path.
    let dim_module = format!("[`crate::kernels::d{}::", kernel.dim);
    lines.extend(
        emit::description(kernel)
            .into_iter()
            .filter(|l| !l.starts_with("Straight-line"))
            .map(|l| l.replace("[`super::", &dim_module)),
    );
    lines.push(String::new());
    lines.push(format!("Ops per contact: {per_contact}."));
    if params == Params::Shared {
        lines.push(format!(
            "Ops per call, on the shared parameters: {per_batch}."
        ));
    }
    emit::doc_lines(&lines)
}
