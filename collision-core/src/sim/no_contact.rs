//! Deciding that no contact will ever happen again, so that a run without a time limit stops
//! instead of crossing cells forever.
//!
//! With no further contact every velocity stays constant, so the question is about free
//! flight alone. It is decided exactly in the cases that are cheap to decide
//! ([`NoContact::AtRest`], [`NoContact::Separated`]); otherwise a stated criterion
//! ([`NoContact::Quiet`]) stops runs in which the moving balls have travelled
//! [`QUIET_BOX_LENGTHS`] box lengths since the last contact of the whole system.

use super::FixedBall;
use std::fmt;

/// Box lengths (the longest side) that every moving ball must have travelled since the last
/// contact before [`NoContact::Quiet`] stops a run.
pub const QUIET_BOX_LENGTHS: f64 = 1000.0;

/// The relative margin by which a perpendicular distance must beat the contact distance
/// for [`NoContact::Separated`] (rounding of the distances must not hide a grazing contact).
const MARGIN: f64 = 1e-9;

/// Why no further contact happens.
#[derive(Clone, Debug, PartialEq)]
pub enum NoContact {
    /// Every ball is at rest.
    AtRest,
    /// Exact: no ball moves along a walled axis (no wall contact), and every pair of bodies
    /// (ball-ball, ball-obstacle) is at relative rest or moves along one periodic axis `k`
    /// only, with a minimum-image distance across the other axes above the contact distance
    /// `R_i + R_j` (by the relative margin 1e-9): the relative motion sweeps axis `k`, so the
    /// least distance it ever reaches is that one.
    Separated,
    /// The stated criterion: no contact since the last one (or the start) while every moving
    /// ball travelled at least `box_lengths` times the longest box side.
    Quiet { box_lengths: f64 },
}

impl fmt::Display for NoContact {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        match self {
            NoContact::AtRest => f.write_str("no contact can happen: every ball is at rest"),
            NoContact::Separated => f.write_str(
                "no contact can happen: no ball moves along a walled axis, and every pair of \
                 bodies is at relative rest or moves along one periodic axis, passing the other's \
                 images at more than the contact distance",
            ),
            NoContact::Quiet { box_lengths } => write!(
                f,
                "no contact while every moving ball travelled {box_lengths:.0} box lengths \
                 (the criterion is {QUIET_BOX_LENGTHS} box lengths; contacts may still be \
                 possible, but not within any run of this length)"
            ),
        }
    }
}

/// The free-flight geometry the decision needs: centres now, velocities, radii.
pub(crate) struct Flight<'a, const N: usize> {
    pub size: [f64; N],
    pub periodic: [bool; N],
    pub position: &'a dyn Fn(usize) -> [f64; N],
    pub velocity: &'a dyn Fn(usize) -> [f64; N],
    pub radius: &'a dyn Fn(usize) -> f64,
    pub balls: usize,
    pub obstacles: &'a [FixedBall<N>],
}

impl<const N: usize> Flight<'_, N> {
    /// [`NoContact::Separated`] if it holds; `None` if it does not, or if the pair test would
    /// cost more than `budget` pair checks (it stops at the first pair that may touch, so in a
    /// gas it costs O(1)).
    pub fn separated(&self, budget: usize) -> Option<NoContact> {
        let walled = (0..N).filter(|&k| !self.periodic[k]);
        for i in 0..self.balls {
            let v = (self.velocity)(i);
            if walled.clone().any(|k| v[k] != 0.0) {
                return None;
            }
        }
        let pairs = self
            .balls
            .saturating_mul(self.balls.saturating_add(self.obstacles.len()));
        if pairs > budget {
            return None;
        }
        for i in 0..self.balls {
            let (a, v, r) = ((self.position)(i), (self.velocity)(i), (self.radius)(i));
            for j in i + 1..self.balls {
                let w = (self.velocity)(j);
                let dv = std::array::from_fn(|k| w[k] - v[k]);
                let sigma = r + (self.radius)(j);
                if !self.passes(&a, &(self.position)(j), &dv, sigma) {
                    return None;
                }
            }
            for o in self.obstacles {
                if !self.passes(&a, &o.position, &v, r + o.radius) {
                    return None;
                }
            }
        }
        Some(NoContact::Separated)
    }

    /// Whether bodies at `a` and `b` with relative velocity `dv` never come within `sigma`
    /// (decided only for `dv = 0` or `dv` along one axis; `false` otherwise).
    fn passes(&self, a: &[f64; N], b: &[f64; N], dv: &[f64; N], sigma: f64) -> bool {
        let mut moving = None;
        for (k, &x) in dv.iter().enumerate() {
            if x != 0.0 {
                if moving.is_some() {
                    return false;
                }
                moving = Some(k);
            }
        }
        let Some(axis) = moving else { return true };
        if !self.periodic[axis] {
            return false;
        }
        let perp2: f64 = (0..N)
            .filter(|&k| k != axis)
            .map(|k| {
                let mut d = b[k] - a[k];
                if self.periodic[k] {
                    d -= self.size[k] * (d / self.size[k]).round();
                }
                d * d
            })
            .sum();
        perp2 > sigma * sigma * (1.0 + MARGIN)
    }

    /// The least speed of the moving balls (`None` if all are at rest).
    pub fn least_speed(&self) -> Option<f64> {
        (0..self.balls)
            .map(|i| (self.velocity)(i).iter().map(|x| x * x).sum::<f64>().sqrt())
            .filter(|&s| s > 0.0)
            .min_by(f64::total_cmp)
    }
}
