//! One report run: for each dimension and regime, sample, compute the exact results, run
//! and time every variant, and gather the error figures.

use crate::case::{component_names, Case};
use crate::family::{family_result, FamilyRegime, FamilyResult};
use crate::measure::{bits, conditioning, exact_result, lambda, normwise, Float, Truth};
use crate::method::{Method, Outcome};
use crate::proven::ProvenBound;
use crate::regime::Regime;
use crate::static_box::StaticBox;
use crate::timing::Timing;
use collision_core::rng::Rng;
use collision_core::{validate, Exact, Generated, Kernel};
use serde::Serialize;
use std::collections::BTreeMap;
use std::sync::Arc;

/// The most sampled cases per dimension and regime a report takes: 100 times the default
/// (1000), about 15 minutes; every case keeps its errors for the percentiles, so the memory
/// grows with it.
pub const MAX_SAMPLES: usize = 100_000;

/// `samples` if it is in `1..=`[`MAX_SAMPLES`], else the reason, for the caller to prefix
/// with the option's name (`--samples`, `samples`).
pub fn check_samples(samples: usize) -> Result<usize, String> {
    if (1..=MAX_SAMPLES).contains(&samples) {
        Ok(samples)
    } else {
        Err(format!("must be in 1..={MAX_SAMPLES}, got {samples}"))
    }
}

/// What a report run samples and times.
#[derive(Clone, Debug, Serialize)]
pub struct Options {
    /// The dimensions `n`.
    pub dims: Vec<usize>,
    /// The regimes, in report order.
    pub regimes: Vec<Regime>,
    /// Sampled cases per dimension and regime.
    pub samples: usize,
    /// The seed every random stream derives from (one per dimension and regime).
    pub seed: u64,
    /// Cases in the timed batch (in cache), and in the exact variant's batch.
    pub batch: usize,
    /// Cases in the exact variant's timed batch.
    pub exact_batch: usize,
    /// Timed samples per variant.
    pub timing_samples: usize,
    /// Cases per dimension and regime whose conditioning is estimated (besides every
    /// body whose error exceeds the bound).
    pub conditioned: usize,
    /// The rough-ball family's regimes, in report order (`crate::family`).
    pub family: Vec<FamilyRegime>,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            dims: (2..=6).collect(),
            regimes: Regime::ALL.to_vec(),
            samples: 1000,
            seed: 2026,
            batch: 256,
            exact_batch: 32,
            timing_samples: 21,
            conditioned: 50,
            family: FamilyRegime::ALL.to_vec(),
        }
    }
}

/// Mean, 99th percentile and maximum.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct Stats {
    /// The arithmetic mean.
    pub mean: f64,
    /// The 99th percentile: the sorted value at index `round(0.99 (len - 1))`.
    pub p99: f64,
    /// The largest value.
    pub max: f64,
}

impl Stats {
    /// The statistics of `values` (all zero when there are none).
    pub fn of(values: &[f64]) -> Stats {
        if values.is_empty() {
            return Stats::default();
        }
        let mut v = values.to_vec();
        v.sort_by(f64::total_cmp);
        let p99 = v[((v.len() - 1) as f64 * 0.99).round() as usize];
        Stats {
            mean: v.iter().sum::<f64>() / v.len() as f64,
            p99,
            max: v[v.len() - 1],
        }
    }
}

/// One method's figures in one dimension and regime.
#[derive(Clone, Debug, Serialize)]
pub struct MethodResult {
    /// The method.
    pub variant: Method,
    /// Its name in the report ([`Method::name`]).
    pub name: String,
    /// Operation count of the generated kernel (the free one; `None` if not generated).
    pub ops: Option<usize>,
    /// Nanoseconds per collision; `None` with nothing to time (no case, or it refused every one).
    pub timing: Option<Timing>,
    /// Cases with a result; cases the variant refused, with the reason.
    pub evaluated: usize,
    /// The refused cases, counted by reason.
    pub unsupported: BTreeMap<String, usize>,
    /// Results with a NaN or an infinity.
    pub non_finite: usize,
    /// Bits of error over every output component of every case.
    pub bits: Stats,
    /// The output component with the largest mean bits of error, and that mean.
    pub dominant: Option<(String, f64)>,
    /// Normwise error per movable body, in units of the format's epsilon.
    pub normwise_eps: Stats,
    /// The proven bound of the normwise error per movable body, in eps (the generated float
    /// kernels only; see [`crate::proven`]): its statistics over the bodies with a finite
    /// bound.
    pub proven_eps: Option<Stats>,
    /// Bodies whose proven bound is infinite (a divisor or an overflow it cannot exclude).
    pub proven_unbounded: usize,
    /// Bodies whose measured error exceeds the proven bound (allowing the measure's own
    /// rounding, relative `2^-40`): a defect of the bound. Must be 0.
    pub proven_broken: usize,
    /// The static bound over the regime's box, against the cases in it (the generated
    /// float kernels only).
    pub static_bound: Option<StaticResult>,
}

/// The static bound of one kernel over a regime's box ([`crate::static_box`]), beside the
/// largest error measured over the regime's cases that lie in the box.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct StaticResult {
    /// The largest absolute error bound of a movable body's output component over the box,
    /// in eps (`+inf`, written `null` in JSON: the rules give no finite bound).
    pub bound_eps: f64,
    /// Cases of the regime that lie in the box.
    pub in_box: usize,
    /// The largest absolute error of a movable body's output component over those cases,
    /// in eps.
    pub measured_eps: f64,
    /// In-box cases with a component whose error exceeds the static bound (allowing the
    /// measure's own rounding, relative `2^-40`): a defect of the bound. Must be 0.
    pub broken: usize,
}

impl StaticResult {
    /// `bound / measured` (`None` with nothing measured).
    pub fn tightness(&self) -> Option<f64> {
        (self.measured_eps > 0.0).then(|| self.bound_eps / self.measured_eps)
    }
}

impl MethodResult {
    /// The tightness of the proven bound: its largest value over the measured largest
    /// error (`None` without a bound or with no error measured).
    pub fn tightness(&self) -> Option<f64> {
        let p = self.proven_eps?;
        (self.normwise_eps.max > 0.0).then(|| p.max / self.normwise_eps.max)
    }
}

/// How the generated `f64` kernel meets its bound in one regime.
#[derive(Clone, Debug, Serialize)]
pub struct Stability {
    /// The regime's normwise error bound, in eps ([`Regime::bound_eps`]).
    pub bound_eps: f64,
    /// The largest normwise error of a movable body, in eps.
    pub max_normwise_eps: f64,
    /// Bodies whose error exceeds the bound.
    pub over_bound: usize,
    /// Of those, bodies whose error also exceeds their conditioning (`error > kappa eps`):
    /// a kernel weakness rather than an ill-conditioned problem. Must be 0.
    pub over_conditioning: usize,
    /// Largest `error / kappa` over the bodies above the bound (both in eps units).
    pub worst_error_over_kappa: f64,
    /// Cases whose `f64` result has a NaN or an infinity.
    pub non_finite: usize,
    /// No non-finite result, no body over its conditioning, and no error above its proven
    /// or static bound.
    pub passed: bool,
}

/// Every method's figures in one dimension and regime, and the `f64` kernel's stability.
#[derive(Clone, Debug, Serialize)]
pub struct RegimeResult {
    /// The regime.
    pub regime: Regime,
    /// Its name in the report ([`Regime::name`]).
    pub name: String,
    /// How it departs from the typical distribution ([`Regime::about`]).
    pub about: String,
    /// How its static box departs from the typical box ([`StaticBox::about`]).
    pub static_box: String,
    /// Cases sampled, before validation excluded any.
    pub sampled: usize,
    /// Sampled cases refused by validation, with the reason (counted, then left out).
    pub excluded: BTreeMap<String, usize>,
    /// Estimated condition number per movable body (see `measure`).
    pub conditioning: Stats,
    /// One result per method, in [`Method::ALL`] order.
    pub variants: Vec<MethodResult>,
    /// How the generated `f64` kernel meets its bound.
    pub stability: Stability,
}

/// The figures of one dimension.
#[derive(Clone, Debug, Serialize)]
pub struct DimResult {
    /// The dimension `n`.
    pub dim: usize,
    /// One result per regime, in [`Options::regimes`] order.
    pub regimes: Vec<RegimeResult>,
    /// Agreement of the `f64` kernel across its branch-free limits.
    pub continuity: Continuity,
    /// The rough-ball family's kernels, one result per [`Options::family`] regime.
    pub family: Vec<FamilyResult>,
}

/// Per-variant accumulators.
#[derive(Default)]
struct Acc {
    bits: Vec<Vec<f64>>,
    normwise: Vec<f64>,
    proven: Vec<f64>,
    proven_unbounded: usize,
    proven_broken: usize,
    /// Per case in the method's static box, the largest absolute component error, in eps.
    static_errors: Vec<f64>,
    static_bound: Option<StaticResult>,
    non_finite: usize,
    evaluated: usize,
    unsupported: BTreeMap<String, usize>,
}

impl Acc {
    /// Bits of every component, and the normwise error (in eps) of each movable body.
    fn record<F: Float, const N: usize, const S: usize>(
        &mut self,
        computed: &[f64],
        truth: &Truth,
        case: &Case<Exact, N, S>,
    ) -> [Option<f64>; 2] {
        self.evaluated += 1;
        if self.bits.is_empty() {
            self.bits = vec![Vec::new(); computed.len()];
        }
        for (k, &c) in computed.iter().enumerate() {
            // `computed` holds F-floats (widened exactly when F = f32).
            let value = F::nearest(c, 0.0);
            self.bits[k].push(bits(value, truth.hi[k], truth.lo[k]));
        }
        std::array::from_fn(|b| {
            (!num_traits::Zero::is_zero(&case.balls[b].inv_mass)).then(|| {
                let err = normwise(lambda(&case.balls[b]), S, N, b, computed, truth) / F::EPSILON;
                self.normwise.push(err);
                err
            })
        })
    }

    /// The proven bounds of the bodies whose errors [`Acc::record`] returned, for the
    /// inputs the kernel ran on (`ran_on`, widened to `f64`; `case`, the same exactly).
    fn record_proven<const N: usize, const S: usize>(
        &mut self,
        proven: &ProvenBound,
        errors: [Option<f64>; 2],
        ran_on: &Case<f64, N, S>,
        case: &Case<Exact, N, S>,
    ) {
        let lambdas = [lambda(&case.balls[0]), lambda(&case.balls[1])];
        let bounds = proven.body_bounds(ran_on, lambdas);
        for (err, bound) in errors.iter().zip(bounds) {
            let (Some(err), Some(bound)) = (*err, bound) else {
                continue;
            };
            if bound.is_finite() {
                self.proven.push(bound);
            } else {
                self.proven_unbounded += 1;
            }
            if err > bound * (1.0 + 2f64.powi(-40)) {
                self.proven_broken += 1;
            }
        }
    }

    /// If the case (`ran_on`, the inputs the kernel ran on widened to `f64`) lies in one
    /// of `boxes`: the largest absolute error of a movable body's component (`computed`
    /// against `truth`, both in format `F`), in eps, kept for the static bound.
    fn record_static<F: Float, const N: usize, const S: usize>(
        &mut self,
        proven: &ProvenBound,
        boxes: &[StaticBox],
        computed: &[f64],
        truth: &Truth,
        ran_on: &Case<f64, N, S>,
    ) {
        if boxes.is_empty() || !proven.in_box(ran_on, boxes) {
            return;
        }
        let mut worst = 0.0f64;
        for b in (0..2).filter(|&b| ran_on.balls[b].inv_mass != 0.0) {
            let body = b * (S + N)..(b + 1) * (S + N);
            for (k, &c) in computed.iter().enumerate().take(body.end).skip(body.start) {
                worst = worst.max(truth.error(k, c).abs() / F::EPSILON);
            }
        }
        self.static_errors.push(worst);
    }

    /// The static bound `bound_eps` against the errors [`Acc::record_static`] kept.
    fn set_static(&mut self, bound_eps: f64) {
        let errors = std::mem::take(&mut self.static_errors);
        self.static_bound = Some(StaticResult {
            bound_eps,
            in_box: errors.len(),
            measured_eps: errors.iter().copied().fold(0.0, f64::max),
            broken: errors
                .iter()
                .filter(|&&e| e > bound_eps * (1.0 + 2f64.powi(-40)))
                .count(),
        });
    }

    fn result(
        self,
        variant: Method,
        names: &[String],
        ops: Option<usize>,
        timing: Option<Timing>,
    ) -> MethodResult {
        let all: Vec<f64> = self.bits.iter().flatten().copied().collect();
        let dominant = self
            .bits
            .iter()
            .enumerate()
            .map(|(k, v)| (k, v.iter().sum::<f64>() / v.len().max(1) as f64))
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .filter(|(_, m)| *m > 0.0)
            .map(|(k, m)| (names[k].clone(), m));
        MethodResult {
            variant,
            name: variant.name().into(),
            ops,
            timing,
            evaluated: self.evaluated,
            unsupported: self.unsupported,
            non_finite: self.non_finite,
            bits: Stats::of(&all),
            dominant,
            normwise_eps: Stats::of(&self.normwise),
            proven_eps: (!self.proven.is_empty()).then(|| Stats::of(&self.proven)),
            proven_unbounded: self.proven_unbounded,
            proven_broken: self.proven_broken,
            static_bound: self.static_bound,
        }
    }
}

/// Operation counts of the generated free kernels of `dim`, by arithmetic.
fn free_ops(dim: usize) -> Vec<(noslip_codegen::Arith, usize)> {
    noslip_codegen::generate(dim, "crate")
        .kernels
        .iter()
        .filter(|k| k.variant == noslip_codegen::Variant::Free)
        .map(|k| (k.arith, k.ops.total()))
        .collect()
}

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

/// Agreement of the generated `f64` kernel across the limits it reaches without branches,
/// `m_1 = 1e15 m_2` against an immovable body 1 (body 2's result) and `gamma2_1 = 1e-15`
/// against `gamma2_1 = 0` (both bodies), over typical cases: the largest normwise
/// difference of the two `f64` results, of the two exact results (the model's own
/// difference at these parameters), and of the two (the rounding part, which must stay
/// within the bound: no jump at the limit). In eps, in the body's energy norm.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct Limit {
    /// The largest normwise difference of the two `f64` results.
    pub computed_eps: f64,
    /// The largest normwise difference of the two exact results (the model's own).
    pub exact_eps: f64,
    /// The largest normwise difference of the two rounding errors (`f64` minus exact).
    pub rounding_eps: f64,
}

/// The generated `f64` kernel across its two branch-free limits, over typical cases.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Continuity {
    /// Typical cases compared.
    pub cases: usize,
    /// `m_1 = 1e15 m_2` against an immovable body 1 (body 2's result).
    pub mass_1e15_vs_immovable: Limit,
    /// `gamma2_1 = 1e-15` against `gamma2_1 = 0` (both bodies).
    pub gamma2_1e15_vs_zero: Limit,
}

/// [`Continuity`] over `cases` typical cases.
pub fn continuity<const N: usize, const S: usize>(cases: usize, seed: u64) -> Continuity
where
    Generated: Kernel<f64, N, S> + Kernel<collision_core::ExactRelaxed, N, S>,
{
    use crate::measure::relative_norm;
    let mut rng = Rng::new(seed ^ 0xC0 ^ ((N as u64) << 32));
    let (mut mass, mut gamma) = (Limit::default(), Limit::default());
    let compare = |a: &Case<f64, N, S>, b: &Case<f64, N, S>, body: usize, limit: &mut Limit| {
        let run = |c: &Case<f64, N, S>| {
            let computed = crate::case::flatten(&collision_core::collide_unchecked(
                &c.nu,
                c.ball_refs(),
                c.state_refs(),
            ));
            let exact = crate::case::flatten(&exact_result(&c.to_exact()));
            (computed, exact)
        };
        let ((ca, ea), (cb, eb)) = (run(a), run(b));
        let to_f64 = |x: &Exact| num_traits::ToPrimitive::to_f64(x).unwrap_or(f64::INFINITY);
        let computed: Vec<f64> = ca.iter().zip(&cb).map(|(x, y)| x - y).collect();
        let exact: Vec<f64> = ea.iter().zip(&eb).map(|(x, y)| to_f64(&(x - y))).collect();
        let rounding: Vec<f64> = ca
            .iter()
            .zip(&cb)
            .zip(ea.iter().zip(&eb))
            .map(|((x, y), (ex, ey))| {
                let (dx, dy) = (Exact::from_float(*x), Exact::from_float(*y));
                let (dx, dy) = (dx.expect("finite"), dy.expect("finite"));
                to_f64(&((dx - ex) - (dy - ey)))
            })
            .collect();
        let reference: Vec<f64> = eb.iter().map(to_f64).collect();
        let lambda = b.balls[body].lambda();
        let rel = |d: &[f64]| relative_norm(lambda, S, N, body, d, &reference) / f64::EPSILON;
        limit.computed_eps = limit.computed_eps.max(rel(&computed));
        limit.exact_eps = limit.exact_eps.max(rel(&exact));
        limit.rounding_eps = limit.rounding_eps.max(rel(&rounding));
    };
    for _ in 0..cases {
        let case = Regime::Typical.sample::<N, S>(&mut rng);
        let mut heavy = case.clone();
        heavy.balls[0].inv_mass = heavy.balls[1].inv_mass * 1e-15;
        let mut wall = case.clone();
        wall.balls[0].inv_mass = 0.0;
        compare(&heavy, &wall, 1, &mut mass);
        let (mut small, mut point) = (case.clone(), case);
        small.balls[0].gamma2 = 1e-15;
        point.balls[0].gamma2 = 0.0;
        compare(&small, &point, 0, &mut gamma);
        compare(&small, &point, 1, &mut gamma);
    }
    Continuity {
        cases,
        mass_1e15_vs_immovable: mass,
        gamma2_1e15_vs_zero: gamma,
    }
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
