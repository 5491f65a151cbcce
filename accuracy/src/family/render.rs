//! The family's section of `report.md`: one table, a row per dimension and regime.

use super::{FamilyResult, FamilyVariant};
use std::fmt::Write;

/// `## The rough-ball family`: the regimes' distributions, then per dimension and regime the
/// normwise errors of each variant and the `f64` kernel's time beside the no-slip kernel's.
pub fn markdown(m: &mut String, dims: &[(usize, &[FamilyResult])]) {
    let Some((_, first)) = dims.iter().find(|(_, r)| !r.is_empty()) else {
        return;
    };
    let _ = writeln!(m, "## The rough-ball family\n");
    let _ = writeln!(
        m,
        "The generated `rough` kernels (constant `(e, beta)`) and `walton` kernels \
         (`(e, mu, beta0)`) against the same kernel in exact rationals on the same inputs and law \
         (for `f32`: both rounded to `f32`). Normwise error per movable body in its energy norm, \
         in the format's epsilons: mean / p99 / max. Times: the `f64` kernel and the no-slip \
         `f64` kernel (`collide_unchecked`) on the same cases, median ns per collision. \
         *sliding*: Walton cases with `beta_C < beta0` (estimated in `f64`). *above bound*: \
         `f64` bodies above {} eps, and of them (in brackets) those beyond their conditioning \
         `kappa` (the exact map's sensitivity, as for the no-slip kernels; the law is not \
         perturbed), which fail the report; the largest `kappa` estimated follows.\n",
        super::BOUND_EPS
    );
    for r in *first {
        let _ = writeln!(m, "- **{}** (`{}`): {}", r.name, r.kernel, r.about);
    }
    let _ = writeln!(m);
    let _ = writeln!(
        m,
        "| n | regime | cases | sliding | f64 | f64 FMA | f32 | above bound | f64 ns | no-slip ns | ratio |"
    );
    let _ = writeln!(m, "|---:|---|---:|---:|---:|---:|---:|---|---:|---:|---:|");
    for (dim, results) in dims {
        for r in *results {
            let cell = |v: FamilyVariant| {
                let x = r.variants.iter().find(|x| x.variant == v);
                x.map_or("-".into(), |x| {
                    let s = &x.normwise_eps;
                    let mut c = format!("{:.2} / {:.2} / {:.2}", s.mean, s.p99, s.max);
                    if x.non_finite > 0 {
                        let _ = write!(c, " ({} NON-FINITE)", x.non_finite);
                    }
                    let refused: usize = x.unsupported.values().sum();
                    if refused > 0 {
                        let _ = write!(c, " ({refused} refused)");
                    }
                    c
                })
            };
            let ns = |t: Option<crate::timing::Timing>| t.map(|t| t.median_ns);
            let (t, base) = (ns(r.time), ns(r.no_slip_time));
            let show = |t: Option<f64>| t.map_or("-".into(), |t| format!("{t:.2}"));
            let ratio = t
                .zip(base)
                .map_or("-".into(), |(t, b)| format!("{:.2}", t / b));
            let excluded: usize = r.excluded.values().sum();
            let st = &r.stability;
            let above = if st.over_bound == 0 {
                "0".to_string()
            } else {
                format!(
                    "{} ({}{}), kappa {:.0}",
                    st.over_bound,
                    st.over_conditioning,
                    if st.over_conditioning > 0 {
                        " FAIL"
                    } else {
                        ""
                    },
                    st.worst_kappa
                )
            };
            let _ = writeln!(
                m,
                "| {dim} | {} | {} | {} | {} | {} | {} | {above} | {} | {} | {} |",
                r.name,
                r.sampled - excluded,
                if r.kernel == "walton" {
                    r.sliding.to_string()
                } else {
                    "-".into()
                },
                cell(FamilyVariant::F64),
                cell(FamilyVariant::F64Fma),
                cell(FamilyVariant::F32),
                show(t),
                show(base),
                ratio
            );
        }
    }
    let _ = writeln!(m);
}
