//! One regime of one dimension: sample and validate the cases, compute their exact results,
//! run every method on each (the `f64` kernel's stability checked against the regime's
//! bound and the case's conditioning; the static bounds computed on another core meanwhile),
//! then time every method that ran.

use super::acc::Acc;
use super::options::Options;
use super::results::{RegimeResult, Stability};
use super::stats::Stats;
use crate::case::{component_names, Case};
use crate::measure::{conditioning, exact_result, Truth};
use crate::method::{Method, Outcome};
use crate::proven::ProvenBound;
use crate::regime::Regime;
use crate::static_box::StaticBox;
use collision_core::rng::Rng;
use collision_core::{validate, Exact, Generated, Kernel};
use std::collections::BTreeMap;
use std::sync::Arc;

/// Every figure of one dimension and regime; `None` once `interrupted()` answers true (it
/// is asked before each case and each variant's timing, a few milliseconds apart).
pub fn regime_result<const N: usize, const S: usize>(
    regime: Regime,
    opts: &Options,
    ops: &[(noslip_codegen::Arith, usize)],
    interrupted: &dyn Fn() -> bool,
) -> Option<RegimeResult>
where
    Generated: Kernel<f64, N, S>
        + Kernel<f32, N, S>
        + Kernel<Exact, N, S>
        + Kernel<collision_core::ExactRelaxed, N, S>
        + collision_core::batch::BatchKernel<f64, N, S>,
{
    let mut rng = Rng::new(opts.seed ^ ((N as u64) << 32) ^ regime as u64);
    let names = component_names(N);
    let mut excluded = BTreeMap::new();
    let mut cases = Vec::new();
    for _ in 0..opts.samples {
        let case = regime.sample::<N, S>(&mut rng);
        match validate(&case.nu, case.ball_refs(), case.state_refs()) {
            Ok(()) => cases.push(case),
            Err(e) => *excluded.entry(e.to_string()).or_insert(0) += 1,
        }
    }
    let mut acc: BTreeMap<usize, Acc> = BTreeMap::new();
    let mut kappas = Vec::new();
    let mut stability = Stability {
        bound_eps: regime.bound_eps(),
        max_normwise_eps: 0.0,
        over_bound: 0,
        over_conditioning: 0,
        worst_error_over_kappa: 0.0,
        non_finite: 0,
        passed: true,
    };
    let mut cases32 = Vec::new();
    let proven: Vec<Option<Arc<ProvenBound>>> = Method::ALL
        .iter()
        .map(|&m| ProvenBound::of(N, m).map(Arc::new))
        .collect();
    // The static bounds, one per kernel with a proven bound (the batch method runs the
    // `f64` kernel: it shares its figure, and has no boxes), computed on another core while
    // the cases run; the cases keep their errors in the boxes for them.
    let boxes: Vec<Vec<StaticBox>> = Method::ALL
        .iter()
        .zip(&proven)
        .map(|(&m, p)| match p {
            Some(p) if m != Method::Batch => StaticBox::of(regime, N, p.format()),
            _ => Vec::new(),
        })
        .collect();
    let statics = {
        let (proven, boxes) = (proven.clone(), boxes.clone());
        std::thread::spawn(move || {
            proven
                .iter()
                .zip(&boxes)
                .map(|(p, b)| {
                    p.as_ref()
                        .filter(|_| !b.is_empty())
                        .map(|p| p.static_bound(b))
                })
                .collect::<Vec<Option<f64>>>()
        })
    };
    for (index, case) in cases.iter().enumerate() {
        if interrupted() {
            return None;
        }
        let exact_case = case.to_exact();
        let exact = exact_result(&exact_case);
        let truth = Truth::of(&exact);
        let mut kappa = None;
        let mut kappa_of = |rng: &mut Rng| {
            *kappa.get_or_insert_with(|| conditioning(&exact_case, &exact, &truth, rng))
        };
        if index < opts.conditioned {
            kappas.extend(kappa_of(&mut rng).iter().flatten());
        }
        let case32 = case.to_f32().map_err(String::from).and_then(|c| {
            match validate(&c.nu, c.ball_refs(), c.state_refs()) {
                Ok(()) => Ok(c),
                Err(e) => Err(format!(
                    "inputs rounded to f32 fail validation at {}",
                    e.field
                )),
            }
        });
        let truth32 = case32.as_ref().map(|c| {
            let exact = c.to_exact();
            (Truth::of(&exact_result(&exact)), exact)
        });
        for (i, &variant) in Method::ALL.iter().enumerate() {
            let a = acc.entry(i).or_default();
            if variant == Method::Exact {
                a.evaluated += 1;
                continue;
            }
            match variant.run(case, case32.as_ref().map_err(String::as_str)) {
                Outcome::NonFinite => {
                    a.non_finite += 1;
                    if variant == Method::F64 {
                        stability.non_finite += 1;
                    }
                }
                Outcome::Unsupported(why) => *a.unsupported.entry(why).or_insert(0) += 1,
                Outcome::Done(r) if variant == Method::F32 => {
                    let (t32, c32) = truth32.as_ref().expect("f32 ran on representable inputs");
                    let errs = a.record::<f32, N, S>(&r, t32, c32);
                    if let (Some(p), Ok(ran_on)) = (&proven[i], &case32) {
                        let ran_on = ran_on.map(|&x| f64::from(x));
                        a.record_proven(p, errs, &ran_on, c32);
                        a.record_static::<f32, N, S>(p, &boxes[i], &r, t32, &ran_on);
                    }
                }
                Outcome::Done(r) => {
                    let errs = a.record::<f64, N, S>(&r, &truth, &exact_case);
                    if let Some(p) = &proven[i] {
                        a.record_proven(p, errs, case, &exact_case);
                        a.record_static::<f64, N, S>(p, &boxes[i], &r, &truth, case);
                    }
                    if variant != Method::F64 {
                        continue;
                    }
                    for (b, err) in errs.iter().enumerate() {
                        let Some(err) = *err else { continue };
                        stability.max_normwise_eps = stability.max_normwise_eps.max(err);
                        if err > stability.bound_eps {
                            stability.over_bound += 1;
                            let k = kappa_of(&mut rng)[b].unwrap_or(0.0);
                            let ratio = err / k.max(f64::MIN_POSITIVE);
                            stability.worst_error_over_kappa =
                                stability.worst_error_over_kappa.max(ratio);
                            if err > k {
                                stability.over_conditioning += 1;
                            }
                        }
                    }
                }
            }
        }
        if let Ok(c) = case32 {
            cases32.push(c);
        }
    }
    stability.passed = stability.non_finite == 0 && stability.over_conditioning == 0;
    let statics = statics.join().expect("the static bounds' thread");
    for (i, bound) in statics.into_iter().enumerate() {
        if let Some(bound) = bound {
            acc.entry(i).or_default().set_static(bound);
        }
    }
    let proven_broken: usize = acc.values().map(|a| a.proven_broken).sum();
    let static_broken: usize = acc
        .values()
        .filter_map(|a| a.static_bound.map(|s| s.broken))
        .sum();
    stability.passed &= proven_broken == 0 && static_broken == 0;

    let batch: Vec<Case<f64, N, S>> = cases.iter().take(opts.batch).cloned().collect();
    let batch32: Vec<Case<f32, N, S>> = cases32.iter().take(opts.batch).cloned().collect();
    let batch_exact: Vec<Case<Exact, N, S>> = cases
        .iter()
        .take(opts.exact_batch)
        .map(Case::to_exact)
        .collect();
    let variants = Method::ALL
        .iter()
        .enumerate()
        .map(|(i, &v)| {
            if interrupted() {
                return None;
            }
            // A variant that refused every case has nothing worth timing.
            let ran = acc.get(&i).is_some_and(|a| a.evaluated > 0);
            let timing = if batch.is_empty() || !ran {
                None
            } else {
                v.time(&batch, &batch32, &batch_exact, opts.timing_samples)
            };
            let ops = v
                .generated()
                .and_then(|a| ops.iter().find(|(b, _)| *b == a).map(|(_, n)| *n));
            Some(
                acc.remove(&i)
                    .unwrap_or_default()
                    .result(v, &names, ops, timing),
            )
        })
        .collect::<Option<Vec<_>>>()?;
    Some(RegimeResult {
        regime,
        name: regime.name().into(),
        about: regime.about().into(),
        static_box: StaticBox::about(regime).into(),
        sampled: opts.samples,
        excluded,
        conditioning: Stats::of(&kappas),
        variants,
        stability,
    })
}
