//! One family regime of one dimension: sample, compute the exact results, run every variant
//! of the regime's kernel, time it beside the no-slip kernel.

use super::{slides, FamilyRegime, Law};
use crate::case::{flatten, Case};
use crate::measure::{conditioning_of, lambda, normwise, Truth};
use crate::report::{Options, Stats};
use crate::timing::{pass_over, time, Timing};
use collision_core::rng::Rng;
use collision_core::{
    collide_unchecked, validate, BodyState, Exact, Generated, Kernel, Relaxing, RoughKernel,
    Scalar, ScalarRoot, WaltonKernel,
};
use serde::Serialize;
use std::collections::BTreeMap;

/// A way the family's kernels are run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FamilyVariant {
    /// The generated kernel in `f64`.
    F64,
    /// Its FMA form in `f64` (called directly: on a CPU without FMA in the build's target
    /// features each `mul_add` is a libm call, so it is not timed).
    F64Fma,
    /// The generated kernel in `f32`, on the inputs and the law rounded to `f32`.
    F32,
}

impl FamilyVariant {
    /// Every variant, in report order.
    pub const ALL: [FamilyVariant; 3] = [
        FamilyVariant::F64,
        FamilyVariant::F64Fma,
        FamilyVariant::F32,
    ];

    /// The variant's name in the report.
    pub fn name(self) -> &'static str {
        match self {
            FamilyVariant::F64 => "f64",
            FamilyVariant::F64Fma => "f64 FMA",
            FamilyVariant::F32 => "f32",
        }
    }

    fn epsilon(self) -> f64 {
        match self {
            FamilyVariant::F32 => f32::EPSILON as f64,
            _ => f64::EPSILON,
        }
    }
}

/// One variant's errors over a regime's cases.
#[derive(Clone, Debug, Serialize)]
pub struct VariantResult {
    /// The variant.
    pub variant: FamilyVariant,
    /// Its name in the report.
    pub name: String,
    /// Cases it ran on.
    pub evaluated: usize,
    /// Cases it could not run, with the reason (`f32`: inputs it cannot hold).
    pub unsupported: BTreeMap<String, usize>,
    /// Results with a NaN or an infinity.
    pub non_finite: usize,
    /// Normwise error per movable body in the body's energy norm, in the format's epsilons.
    pub normwise_eps: Stats,
}

/// Every figure of one dimension and family regime.
#[derive(Clone, Debug, Serialize)]
pub struct FamilyResult {
    /// The regime.
    pub regime: FamilyRegime,
    /// Its name in the report.
    pub name: String,
    /// What it samples.
    pub about: String,
    /// The generated kernels measured: `rough` or `walton`.
    pub kernel: String,
    /// Cases sampled.
    pub sampled: usize,
    /// Sampled cases refused by validation, with the reason.
    pub excluded: BTreeMap<String, usize>,
    /// Walton cases that slide (`beta_C < beta0`, estimated in `f64`).
    pub sliding: usize,
    /// One result per variant, in [`FamilyVariant::ALL`] order.
    pub variants: Vec<VariantResult>,
    /// How the `f64` kernel meets the bound.
    pub stability: FamilyStability,
    /// The `f64` kernel's time per collision on the regime's first cases.
    pub time: Option<Timing>,
    /// The no-slip `f64` kernel's time on the same cases (`collide_unchecked`).
    pub no_slip_time: Option<Timing>,
}

/// The normwise error bound of the family's `f64` kernels, in `f64` epsilons: the no-slip
/// report's bound outside its typical regime ([`crate::Regime::bound_eps`]).
pub const BOUND_EPS: f64 = 64.0;

/// How the `f64` kernel meets [`BOUND_EPS`], by the no-slip report's rule: a body above it
/// passes only if its error is within its conditioning (`error <= kappa`, the exact map's
/// own sensitivity to relative input perturbations of `2^-53`).
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct FamilyStability {
    /// The bound, in eps.
    pub bound_eps: f64,
    /// The largest normwise error of a body, in eps.
    pub max_normwise_eps: f64,
    /// Bodies above the bound.
    pub over_bound: usize,
    /// Bodies above the bound and beyond their conditioning.
    pub over_conditioning: usize,
    /// The largest condition number estimated (for the bodies above the bound).
    pub worst_kappa: f64,
}

impl FamilyResult {
    /// The `f64` kernel gave no NaN or infinity, and every body above the bound is within
    /// its conditioning.
    pub fn passed(&self) -> bool {
        self.stability.over_conditioning == 0
            && self
                .variants
                .iter()
                .filter(|v| v.variant == FamilyVariant::F64)
                .all(|v| v.non_finite == 0)
    }
}

/// The regime's kernel in `T` on `case` under `law`, dispatched as the checked entry points
/// do for the family's cases (body 1 immovable: `fixed`; no case has body 2 immovable).
fn run<T, K, const N: usize, const S: usize>(
    case: &Case<T, N, S>,
    law: &Law<T>,
    fma: bool,
) -> [BodyState<T, N, S>; 2]
where
    T: Scalar,
    K: RoughKernel<T, N, S>,
    Generated: WaltonKernel<T, N, S>,
{
    let ([b1, b2], [s1, s2]) = (case.ball_refs(), case.state_refs());
    let nu = &case.nu;
    let fixed = b1.is_immovable();
    match (law, fixed, fma) {
        (Law::Rough(l), false, false) => K::rough_free(nu, b1, b2, l, s1, s2),
        (Law::Rough(l), false, true) => K::rough_free_fma(nu, b1, b2, l, s1, s2),
        (Law::Rough(l), true, false) => [s1.clone(), K::rough_fixed(nu, &b1.radius, b2, l, s1, s2)],
        (Law::Rough(l), true, true) => [
            s1.clone(),
            K::rough_fixed_fma(nu, &b1.radius, b2, l, s1, s2),
        ],
        (Law::Walton(l), false, false) => Generated::walton_free(nu, b1, b2, l, s1, s2),
        (Law::Walton(l), false, true) => Generated::walton_free_fma(nu, b1, b2, l, s1, s2),
        (Law::Walton(l), true, false) => [
            s1.clone(),
            Generated::walton_fixed(nu, &b1.radius, b2, l, s1, s2),
        ],
        (Law::Walton(l), true, true) => [
            s1.clone(),
            Generated::walton_fixed_fma(nu, &b1.radius, b2, l, s1, s2),
        ],
    }
}

fn exact_law<T: Scalar>(law: &Law<T>) -> Law<Exact> {
    let x = |v: &T| Exact::from_float(v.to_f64()).expect("laws are finite");
    match law {
        Law::Rough(l) => Law::Rough(collision_core::Restitution {
            e: x(&l.e),
            beta: x(&l.beta),
        }),
        Law::Walton(l) => Law::Walton(collision_core::Walton {
            e: x(&l.e),
            mu: x(&l.mu),
            beta0: x(&l.beta0),
        }),
    }
}

/// The exact result of the kernel on the same (float) inputs and law: the rough kernels
/// through the fast exact path ([`Relaxing`]), the Walton kernels in [`Exact`].
fn truth<T: Scalar, const N: usize, const S: usize>(
    case: &Case<T, N, S>,
    law: &Law<T>,
) -> Exactly<N, S>
where
    Relaxing: RoughKernel<Exact, N, S>,
    Generated: WaltonKernel<Exact, N, S>,
{
    let case = case.to_exact();
    let law = exact_law(law);
    let out = run::<Exact, Relaxing, N, S>(&case, &law, false);
    Exactly {
        truth: Truth::of(&out),
        out,
        case,
        law,
    }
}

/// A sampled case and its law.
type Sampled<const N: usize, const S: usize> = (Case<f64, N, S>, Law<f64>);

/// A case, its law and its result in exact rationals.
struct Exactly<const N: usize, const S: usize> {
    truth: Truth,
    out: [BodyState<Exact, N, S>; 2],
    case: Case<Exact, N, S>,
    law: Law<Exact>,
}

impl<const N: usize, const S: usize> Exactly<N, S> {
    /// Per movable body, the estimated condition number of the exact map with this law
    /// ([`conditioning_of`]; the law is not perturbed).
    fn conditioning(&self, rng: &mut Rng) -> [Option<f64>; 2]
    where
        Relaxing: RoughKernel<Exact, N, S>,
        Generated: WaltonKernel<Exact, N, S>,
    {
        conditioning_of(&self.case, &self.out, &self.truth, rng, |c| {
            run::<Exact, Relaxing, N, S>(c, &self.law, false)
        })
    }
}

#[derive(Default)]
struct Acc {
    normwise: Vec<f64>,
    evaluated: usize,
    non_finite: usize,
    unsupported: BTreeMap<String, usize>,
}

impl Acc {
    /// The normwise error of each movable body, in units of `epsilon`.
    fn record<T: Scalar, const N: usize, const S: usize>(
        &mut self,
        out: &[BodyState<T, N, S>; 2],
        exactly: &Exactly<N, S>,
        epsilon: f64,
    ) -> [Option<f64>; 2] {
        self.evaluated += 1;
        let computed: Vec<f64> = flatten(out).iter().map(Scalar::to_f64).collect();
        if !computed.iter().all(|x| x.is_finite()) {
            self.non_finite += 1;
            return [None; 2];
        }
        let balls = &exactly.case.balls;
        std::array::from_fn(|b| {
            (!num_traits::Zero::is_zero(&balls[b].inv_mass)).then(|| {
                let l = lambda(&balls[b]);
                let err = normwise(l, S, N, b, &computed, &exactly.truth) / epsilon;
                self.normwise.push(err);
                err
            })
        })
    }
}

/// Every figure of one dimension and family regime; `None` once `interrupted()` answers
/// true (asked before each case and each timing).
pub fn family_result<const N: usize, const S: usize>(
    regime: FamilyRegime,
    opts: &Options,
    interrupted: &dyn Fn() -> bool,
) -> Option<FamilyResult>
where
    Generated: Kernel<f64, N, S>
        + RoughKernel<f64, N, S>
        + RoughKernel<f32, N, S>
        + WaltonKernel<f64, N, S>
        + WaltonKernel<f32, N, S>
        + WaltonKernel<Exact, N, S>,
    Relaxing: RoughKernel<Exact, N, S>,
    f32: ScalarRoot,
{
    let mut rng = Rng::new(opts.seed ^ ((N as u64) << 32) ^ (0xfa00 + regime as u64));
    let mut excluded = BTreeMap::new();
    let mut cases = Vec::new();
    for _ in 0..opts.samples {
        let (case, law) = regime.sample::<N, S>(&mut rng);
        match validate(&case.nu, case.ball_refs(), case.state_refs()) {
            Ok(()) => cases.push((case, law)),
            Err(e) => *excluded.entry(e.to_string()).or_insert(0) += 1,
        }
    }
    let mut acc: [Acc; 3] = Default::default();
    let mut stability = FamilyStability {
        bound_eps: BOUND_EPS,
        ..FamilyStability::default()
    };
    for (case, law) in &cases {
        if interrupted() {
            return None;
        }
        let exact = truth(case, law);
        for (a, fma) in acc.iter_mut().zip([false, true]) {
            let out = run::<f64, Generated, N, S>(case, law, fma);
            let errors = a.record(&out, &exact, f64::EPSILON);
            if fma {
                continue;
            }
            // The no-slip report's rule: a body above the bound passes only within its
            // conditioning.
            for (b, err) in errors.iter().enumerate() {
                let Some(err) = *err else { continue };
                stability.max_normwise_eps = stability.max_normwise_eps.max(err);
                if err > stability.bound_eps {
                    stability.over_bound += 1;
                    let kappa = exact.conditioning(&mut rng)[b].unwrap_or(0.0);
                    stability.worst_kappa = stability.worst_kappa.max(kappa);
                    if err > kappa {
                        stability.over_conditioning += 1;
                    }
                }
            }
        }
        let a32 = &mut acc[2];
        let case32 = case.to_f32().map_err(String::from).and_then(|c| {
            validate(&c.nu, c.ball_refs(), c.state_refs())
                .map(|()| c)
                .map_err(|e| format!("inputs rounded to f32 fail validation at {}", e.field))
        });
        match case32 {
            Ok(c) => {
                let law32 = law.to_f32();
                let out = run::<f32, Generated, N, S>(&c, &law32, false);
                a32.record(&out, &truth(&c, &law32), FamilyVariant::F32.epsilon());
            }
            Err(why) => *a32.unsupported.entry(why).or_insert(0) += 1,
        }
    }
    let sliding = cases.iter().filter(|(c, l)| slides(c, l)).count();
    let batch: Vec<&Sampled<N, S>> = cases.iter().take(opts.batch).collect();
    let timed = |f: &dyn Fn(&Sampled<N, S>)| {
        (!batch.is_empty() && !interrupted()).then(|| {
            time(batch.len(), opts.timing_samples, || {
                pass_over(&batch, |c| f(c))
            })
        })
    };
    let family_time = timed(&|(c, l)| {
        std::hint::black_box(run::<f64, Generated, N, S>(c, l, false));
    });
    let no_slip_time = timed(&|(c, _)| {
        std::hint::black_box(collide_unchecked(&c.nu, c.ball_refs(), c.state_refs()));
    });
    if interrupted() {
        return None;
    }
    let variants = FamilyVariant::ALL
        .iter()
        .zip(acc)
        .map(|(&variant, a)| VariantResult {
            variant,
            name: variant.name().into(),
            evaluated: a.evaluated,
            unsupported: a.unsupported,
            non_finite: a.non_finite,
            normwise_eps: Stats::of(&a.normwise),
        })
        .collect();
    Some(FamilyResult {
        regime,
        name: regime.name().into(),
        about: regime.about().into(),
        kernel: regime.kernel().into(),
        sampled: opts.samples,
        excluded,
        sliding,
        variants,
        stability,
        time: family_time,
        no_slip_time,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measure::exact_result;

    /// At `(e, beta) = (1, 1)` the rough kernel is the no-slip kernel bit for bit, and its
    /// truth is the no-slip truth: the family's measurement agrees with the report's.
    #[test]
    fn the_no_slip_member_measures_as_the_no_slip_kernel() {
        let mut rng = Rng::new(29);
        for _ in 0..20 {
            let case = crate::Regime::Typical.sample::<3, 3>(&mut rng);
            let law = Law::Rough(collision_core::Restitution::no_slip());
            let out = run::<f64, Generated, 3, 3>(&case, &law, false);
            let no_slip = collide_unchecked(&case.nu, case.ball_refs(), case.state_refs());
            assert_eq!(out, no_slip);
            let exactly = truth(&case, &law);
            let reference = Truth::of(&exact_result(&exactly.case));
            assert_eq!(exactly.truth.hi, reference.hi);
            assert_eq!(exactly.truth.lo, reference.lo);
        }
    }

    #[test]
    fn every_regime_runs_without_non_finite_results() {
        let opts = Options {
            samples: 12,
            batch: 4,
            timing_samples: 1,
            ..Options::default()
        };
        for regime in FamilyRegime::ALL {
            let r = family_result::<2, 1>(regime, &opts, &|| false).expect("not interrupted");
            assert!(r.passed(), "{}", r.name);
            assert_eq!(r.variants[0].evaluated, 12, "{}", r.name);
            // Typical f64 errors of a few eps; far below 1e6 unless something is wrong.
            assert!(r.variants[0].normwise_eps.max < 1e6, "{}", r.name);
        }
        let interrupted = family_result::<2, 1>(FamilyRegime::Rough, &opts, &|| true);
        assert!(interrupted.is_none());
    }
}
