//! One method's figures as a regime's cases run ([`Acc`]): the bits of error of every output
//! component, the normwise error of each movable body and its proven bound, the largest
//! error of each case in the static boxes, the refused and non-finite cases; then the
//! method's [`MethodResult`].

use super::results::{MethodResult, StaticResult};
use super::stats::Stats;
use crate::case::Case;
use crate::measure::{bits, lambda, normwise, Float, Truth};
use crate::method::Method;
use crate::proven::ProvenBound;
use crate::static_box::StaticBox;
use crate::timing::Timing;
use collision_core::Exact;
use std::collections::BTreeMap;

/// Per-variant accumulators.
#[derive(Default)]
pub(super) struct Acc {
    bits: Vec<Vec<f64>>,
    normwise: Vec<f64>,
    proven: Vec<f64>,
    proven_unbounded: usize,
    pub(super) proven_broken: usize,
    /// Per case in the method's static box, the largest absolute component error, in eps.
    static_errors: Vec<f64>,
    pub(super) static_bound: Option<StaticResult>,
    pub(super) non_finite: usize,
    pub(super) evaluated: usize,
    pub(super) unsupported: BTreeMap<String, usize>,
}

impl Acc {
    /// Bits of every component, and the normwise error (in eps) of each movable body.
    pub(super) fn record<F: Float, const N: usize, const S: usize>(
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
    pub(super) fn record_proven<const N: usize, const S: usize>(
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
    pub(super) fn record_static<F: Float, const N: usize, const S: usize>(
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
    pub(super) fn set_static(&mut self, bound_eps: f64) {
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

    /// The method's figures: what was recorded, with its op count and timing (`names`: the
    /// output components', for the dominant one).
    pub(super) fn result(
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
