//! One report run: for each dimension and regime, sample, compute the exact results, run
//! and time every variant, and gather the error figures.
//!
//! The parts: the options (`report/options.rs`), the statistics (`stats.rs`), the figures
//! gathered (`results.rs`) and their accumulation over the cases (`acc.rs`), one regime's run
//! (`run.rs`), the `f64` kernel across its branch-free limits (`continuity.rs`); this file
//! runs one dimension.

mod acc;
mod continuity;
mod options;
mod results;
mod run;
mod stats;

pub use continuity::{continuity, Continuity, Limit};
pub use options::{check_samples, Options, MAX_SAMPLES};
pub use results::{DimResult, MethodResult, RegimeResult, Stability, StaticResult};
pub use run::regime_result;
pub use stats::Stats;

use crate::family::family_result;

/// Operation counts of the generated free kernels of `dim`, by arithmetic.
fn free_ops(dim: usize) -> Vec<(noslip_codegen::Arith, usize)> {
    noslip_codegen::generate(dim, "crate")
        .kernels
        .iter()
        .filter(|k| k.variant == noslip_codegen::Variant::Free)
        .map(|k| (k.arith, k.ops.total()))
        .collect()
}

/// One dimension's results, `progress` called after each regime.
pub fn dim_result(dim: usize, opts: &Options, progress: impl FnMut(&RegimeResult)) -> DimResult {
    dim_result_interruptible(dim, opts, progress, &|| false).expect("never interrupted")
}

/// [`dim_result`], asking `interrupted()` between cases, timings and regimes (a few
/// milliseconds apart): `None` once it answers true, the partial results dropped.
pub fn dim_result_interruptible(
    dim: usize,
    opts: &Options,
    mut progress: impl FnMut(&RegimeResult),
    interrupted: &dyn Fn() -> bool,
) -> Option<DimResult> {
    let ops = free_ops(dim);
    let (regimes, continuity, family) = collision_core::with_dim!(
        dim,
        |N, S| {
            let regimes = opts
                .regimes
                .iter()
                .map(|&r| {
                    let result = regime_result::<N, S>(r, opts, &ops, interrupted)?;
                    progress(&result);
                    Some(result)
                })
                .collect::<Option<Vec<_>>>()?;
            let family = opts
                .family
                .iter()
                .map(|&r| family_result::<N, S>(r, opts, interrupted))
                .collect::<Option<Vec<_>>>()?;
            if interrupted() {
                return None;
            }
            (
                regimes,
                continuity::<N, S>(opts.samples.min(200), opts.seed),
                family,
            )
        },
        panic!("no generated kernels for n = {dim}")
    );
    Some(DimResult {
        dim,
        regimes,
        continuity,
        family,
    })
}
