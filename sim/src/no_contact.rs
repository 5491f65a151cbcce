//! Deciding that no contact will ever happen again, so that a run without a time limit stops
//! instead of crossing cells forever, and noticing long stretches without contact.
//!
//! With no further contact every velocity stays constant, so the question is about free
//! flight alone. It is decided exactly ([`NoContact::AtRest`], [`NoContact::Separated`])
//! where the relative motion of every pair closes on itself after a few box lengths;
//! otherwise the run goes on, and [`QUIET_BOX_LENGTHS`] box lengths without a contact are
//! only reported ([`super::Step::Quiet`]): a flight nearly along a corridor of a periodic
//! table can take thousands of box lengths to its next contact, and stopping it there would
//! cut a valid run short.

use super::FixedBall;
use std::fmt;

/// Box lengths (the longest side) that every moving ball travels without a contact before
/// [`super::Step::Quiet`] reports it (then again at twice, four times ... that).
pub const QUIET_BOX_LENGTHS: f64 = 1000.0;

/// A contact-free stretch this long, in box lengths flown by every moving ball, ends the run
/// (exit 0, [`crate::run::Summary::stopped`] says why): stepping cell by cell cannot reach a contact that
/// far, and a flight this long has probability about `1e-12` per contact even in an
/// infinite-horizon (Sinai) table, whose free paths `L` have `P(> L) ~ 1/L^2`. It is the
/// 11th quiet notice (1000, 2000, .. 1 024 000 box lengths).
pub const MAX_QUIET_BOX_LENGTHS: f64 = 1.0e6;

/// The most box traversals of a closed relative orbit that [`NoContact::Separated`] follows.
const MAX_WINDINGS: u64 = 64;

/// The most lattice images checked against one closed relative orbit.
const MAX_IMAGES: u64 = 100_000;

/// The relative margin by which a perpendicular distance must beat the contact distance
/// for [`NoContact::Separated`] (rounding of the distances must not hide a grazing contact).
const MARGIN: f64 = 1e-9;

/// Why no further contact happens.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum NoContact {
    /// Every ball is at rest.
    AtRest,
    /// Exact: no ball moves along a walled axis (no wall contact), and for every pair of
    /// bodies (ball-ball, ball-obstacle) the relative motion on the periodic axes is at rest
    /// or closes on itself after at most 64 box traversals (the ratios `dv_k / L_k` are
    /// commensurate: `dv_k T = m_k L_k` with whole `m_k`, `sum |m_k| <= 64`), and that closed
    /// orbit stays farther than the contact distance `R_i + R_j` (by the relative margin
    /// 1e-9) from every periodic image of the partner.
    Separated,
    /// Exact: a table without a box, and no ball has a contact ahead (every pair of balls
    /// and every ball and boundary were predicted against each other and none meets): every
    /// ball flies off to infinity.
    Escaped,
}

impl fmt::Display for NoContact {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        match self {
            NoContact::AtRest => f.write_str("no contact can happen: every ball is at rest"),
            NoContact::Separated => f.write_str(
                "no contact can happen: no ball moves along a walled axis, and every pair of \
                 bodies is at relative rest or moves on a closed orbit of the periodic box that \
                 passes the other's images at more than the contact distance",
            ),
            NoContact::Escaped => f.write_str(
                "no contact can happen: the table is unbounded and every ball flies off \
                 without meeting a boundary or another ball",
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

/// The least positive speed `sqrt(v^2)` of the squared speeds `speed2` (`None` if every one
/// is 0): the slowest moving ball's, whose travel the notices measure.
pub(crate) fn slowest(speed2: impl IntoIterator<Item = f64>) -> Option<f64> {
    let slowest = speed2
        .into_iter()
        .map(f64::sqrt)
        .filter(|&v| v > 0.0)
        .fold(f64::INFINITY, f64::min);
    slowest.is_finite().then_some(slowest)
}

impl<const N: usize> Flight<'_, N> {
    /// Whether no contact can happen again after `quiet` events without one: every ball at
    /// rest ([`NoContact::AtRest`]), or, where the pairs alone decide (`pairs`: a box and no
    /// other boundary), [`Flight::separated`] within `max(2^20, 16 quiet)` pair checks, so
    /// `O(1)` per event.
    pub(crate) fn decide(&self, quiet: u64, pairs: bool) -> Option<NoContact> {
        if self.least_speed().is_none() {
            return Some(NoContact::AtRest);
        }
        if !pairs {
            return None;
        }
        let budget = usize::try_from(quiet.saturating_mul(16)).unwrap_or(usize::MAX);
        self.separated(budget.max(1 << 20))
    }

    /// [`NoContact::Separated`] if it holds; `None` if it does not, or if the pair test would
    /// cost more than `budget` pair checks (it stops at the first pair that may touch, so in a
    /// gas it costs O(1)).
    pub(crate) fn separated(&self, budget: usize) -> Option<NoContact> {
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

    /// Whether bodies at `a` and `b` with relative velocity `dv` never come within `sigma`:
    /// decided when `dv = 0`, or when the relative motion moves along periodic axes only and
    /// closes after `sum |m_k| <= MAX_WINDINGS` box traversals ([`windings`]); `false` when
    /// undecided. The closed orbit is the segment from `d` (the minimum image of `b - a`) to
    /// `d + sum m_k L_k e_k`; every lattice image `L z` near it is checked.
    fn passes(&self, a: &[f64; N], b: &[f64; N], dv: &[f64; N], sigma: f64) -> bool {
        if dv.iter().all(|&x| x == 0.0) {
            return true;
        }
        if (0..N).any(|k| dv[k] != 0.0 && !self.periodic[k]) {
            return false;
        }
        let Some(m) = windings(dv, &self.size) else {
            return false;
        };
        let d: [f64; N] = std::array::from_fn(|k| {
            let x = b[k] - a[k];
            if self.periodic[k] {
                x - self.size[k] * (x / self.size[k]).round()
            } else {
                x
            }
        });
        // Lattice images within reach of the segment, per axis.
        let mut ranges = [(0i64, 0i64); N];
        let mut images: u64 = 1;
        for k in 0..N {
            if !self.periodic[k] {
                continue;
            }
            let reach = (sigma / self.size[k]).ceil() as i64 + 1;
            ranges[k] = (m[k].min(0) - reach, m[k].max(0) + reach);
            images = images.saturating_mul((ranges[k].1 - ranges[k].0 + 1) as u64);
        }
        if images > MAX_IMAGES {
            return false;
        }
        let span: [f64; N] = std::array::from_fn(|k| m[k] as f64 * self.size[k]);
        let span2: f64 = span.iter().map(|x| x * x).sum();
        let limit = sigma * sigma * (1.0 + MARGIN);
        let mut z: [i64; N] = std::array::from_fn(|k| ranges[k].0);
        loop {
            // Distance from the image L z to the segment d + s span, s in [0, 1].
            let e: [f64; N] = std::array::from_fn(|k| z[k] as f64 * self.size[k] - d[k]);
            let s = (e.iter().zip(&span).map(|(x, y)| x * y).sum::<f64>() / span2).clamp(0.0, 1.0);
            let dist2: f64 = (0..N).map(|k| (e[k] - s * span[k]).powi(2)).sum();
            if dist2 <= limit {
                return false;
            }
            // The next z, odometer style.
            let mut k = 0;
            loop {
                if k == N {
                    return true;
                }
                if z[k] < ranges[k].1 {
                    z[k] += 1;
                    break;
                }
                z[k] = ranges[k].0;
                k += 1;
            }
        }
    }

    /// The least speed of the moving balls (`None` if all are at rest).
    pub(crate) fn least_speed(&self) -> Option<f64> {
        (0..self.balls)
            .map(|i| (self.velocity)(i).iter().map(|x| x * x).sum::<f64>().sqrt())
            .filter(|&s| s > 0.0)
            .min_by(f64::total_cmp)
    }
}

/// The windings `m` of a relative motion `dv` on a periodic box of sides `size`: the whole
/// numbers, without a common factor, with `dv_k T = m_k L_k` for one period `T > 0`, if they
/// exist with `sum |m_k| <` [`MAX_WINDINGS`]. Exact: `dv_k / L_k` are the rationals the
/// floats spell, and `T` makes every one of them whole (`1 / T` is their greatest common
/// divisor as rationals).
fn windings<const N: usize>(dv: &[f64; N], size: &[f64; N]) -> Option<[i64; N]> {
    use num_bigint::BigInt;
    use num_integer::Integer;
    use num_rational::BigRational;
    use num_traits::{Signed, ToPrimitive, Zero};
    let ratio: Vec<BigRational> = (0..N)
        .map(|k| Some(BigRational::from_float(dv[k])? / BigRational::from_float(size[k])?))
        .collect::<Option<_>>()?;
    let (mut numer, mut denom) = (BigInt::zero(), BigInt::from(1));
    for r in ratio.iter().filter(|r| !r.is_zero()) {
        numer = numer.gcd(r.numer());
        denom = denom.lcm(r.denom());
    }
    if numer.is_zero() {
        return None;
    }
    let gcd = BigRational::new(numer, denom);
    let mut m = [0i64; N];
    let mut total: u64 = 0;
    for k in 0..N {
        let w = (&ratio[k] / &gcd).to_integer();
        total = total.checked_add(w.abs().to_u64()?)?;
        if total > MAX_WINDINGS {
            return None;
        }
        m[k] = w.to_i64()?;
    }
    Some(m)
}
