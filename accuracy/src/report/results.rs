//! The figures a report run gathers: per method ([`MethodResult`], with its static bound,
//! [`StaticResult`]), per regime ([`RegimeResult`], with the `f64` kernel's [`Stability`])
//! and per dimension ([`DimResult`]).

use super::continuity::Continuity;
use super::stats::Stats;
use crate::family::FamilyResult;
use crate::method::Method;
use crate::regime::Regime;
use crate::timing::Timing;
use serde::Serialize;
use std::collections::BTreeMap;

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
    /// How its static box departs from the typical box
    /// ([`StaticBox::about`](crate::static_box::StaticBox::about)).
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
    /// One result per regime, in [`Options::regimes`](super::options::Options::regimes) order.
    pub regimes: Vec<RegimeResult>,
    /// Agreement of the `f64` kernel across its branch-free limits.
    pub continuity: Continuity,
    /// The rough-ball family's kernels, one result per
    /// [`Options::family`](super::options::Options::family) regime.
    pub family: Vec<FamilyResult>,
}
