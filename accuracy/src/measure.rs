//! Error measures against the exact result.
//!
//! - **Bits** of one output component (Herbie's measure): `log2(ulps + 1)`, with `ulps` the
//!   number of floats between the computed value and the exact value correctly rounded to
//!   the same format (0 bits: correctly rounded; 64 bits: nothing right).
//! - **Normwise** error of one body in its own kinetic-energy norm,
//!   `|x|_i^2 = m_i (lambda_i Tr(U U^T) + |u|^2) = m_i (2 lambda_i sum_{j<k} U_jk^2 + |u|^2)`:
//!   `|computed_i - exact_i|_i / |exact_i|_i` (the mass cancels).
//! - **Conditioning** of one body's result: how much the exact result moves, relative to
//!   itself, when every input is perturbed by a relative `2^-53` with a random sign,
//!   in units of `2^-53` (the larger of two perturbations; exact arithmetic throughout).
//!
//! The exact result is kept as a pair of floats per component, `hi` (correctly rounded) and
//! `lo` (the rest, rounded): `exact = hi + lo` to about 106 bits, so that the error measures
//! run in float arithmetic after one exact subtraction per component. Their own rounding
//! is below `2^-50` relative to the error they report.

use crate::case::Case;
use collision_core::rng::Rng;
use collision_core::{collide_exact, BodyState, Exact, ExactRelaxed, Generated, Kernel, Scalar};
use num_traits::{ToPrimitive, Zero};

/// A binary floating-point format the kernels run in.
pub trait Float: Copy + Scalar {
    /// The gap between 1 and the next float (`f64::EPSILON`).
    const EPSILON: f64;
    /// A monotone integer code: adjacent floats differ by 1, `-0` and `+0` share 0.
    fn ordinal(self) -> i128;
    /// `hi + lo` (an exact value split as in [`Truth`]) rounded to nearest, ties to even.
    fn nearest(hi: f64, lo: f64) -> Self;
}

impl Float for f64 {
    const EPSILON: f64 = f64::EPSILON;
    fn ordinal(self) -> i128 {
        let bits = self.to_bits() as i64;
        i128::from(if bits < 0 { -(bits & i64::MAX) } else { bits })
    }
    fn nearest(hi: f64, _lo: f64) -> Self {
        hi
    }
}

impl Float for f32 {
    const EPSILON: f64 = f32::EPSILON as f64;
    fn ordinal(self) -> i128 {
        let bits = self.to_bits() as i32;
        i128::from(if bits < 0 { -(bits & i32::MAX) } else { bits })
    }
    fn nearest(hi: f64, lo: f64) -> Self {
        // `hi` is the f64 nearest the exact value `y = hi + lo`, `|lo| <= ulp(hi) / 2`. An
        // f32 midpoint is an f64, so `y` lies on the same side of every midpoint as `hi`
        // unless `hi` is one: then `as` ties to even, and `lo` decides instead.
        let c = hi as f32;
        let cd = f64::from(c);
        if !c.is_finite() || lo == 0.0 || cd == hi {
            return c;
        }
        let step = if hi > cd { 1 } else { -1 };
        let other = f32_of_ordinal(c.ordinal() + step);
        let midpoint = (hi - cd).abs() == (f64::from(other) - hi).abs();
        if midpoint && (lo > 0.0) == (step > 0) {
            other
        } else {
            c
        }
    }
}

/// The inverse of [`Float::ordinal`] for `f32`.
fn f32_of_ordinal(o: i128) -> f32 {
    if o >= 0 {
        f32::from_bits(o as u32)
    } else {
        f32::from_bits((-o) as u32 | 0x8000_0000)
    }
}

/// An exact result as `hi + lo` per component of [`crate::case::flatten`].
#[derive(Clone, Debug)]
pub struct Truth {
    /// The nearest `f64` to each exact component `y`.
    pub hi: Vec<f64>,
    /// The nearest `f64` to the rest, `y - hi`.
    pub lo: Vec<f64>,
}

impl Truth {
    /// `exact` as `hi + lo`, component by component in [`crate::case::flatten`] order.
    pub fn of<const N: usize, const S: usize>(exact: &[BodyState<Exact, N, S>; 2]) -> Truth {
        let (hi, lo) = crate::case::flatten(exact)
            .iter()
            .map(|y| {
                // num-rational rounds to nearest, ties to even.
                let hi = ToPrimitive::to_f64(y).unwrap_or(f64::NAN);
                let rest = Exact::from_float(hi).map(|h| y - h);
                let lo = rest.and_then(|r| ToPrimitive::to_f64(&r)).unwrap_or(0.0);
                (hi, lo)
            })
            .unzip();
        Truth { hi, lo }
    }

    /// `computed - exact` for component `k`.
    pub(crate) fn error(&self, k: usize, computed: f64) -> f64 {
        (computed - self.hi[k]) - self.lo[k]
    }
}

/// `log2(ulps + 1)` between `computed` and the exact `hi + lo` rounded to `F`.
pub fn bits<F: Float>(computed: F, hi: f64, lo: f64) -> f64 {
    let ulps = (computed.ordinal() - F::nearest(hi, lo).ordinal()).unsigned_abs();
    (ulps as f64 + 1.0).log2()
}

/// `sqrt(sum w_k x_k^2)` without overflow or underflow.
fn weighted_norm(values: impl Iterator<Item = (f64, f64)> + Clone) -> f64 {
    let scale = values.clone().map(|(_, x)| x.abs()).fold(0.0, f64::max);
    if scale == 0.0 || !scale.is_finite() {
        return scale;
    }
    values
        .map(|(w, x)| w * (x / scale) * (x / scale))
        .sum::<f64>()
        .sqrt()
        * scale
}

/// `|computed - exact| / |exact|` of body `b` (`0` or `1`) in its energy norm; `computed`
/// is the whole flattened result. See [`relative_norm`].
pub fn normwise(lambda: f64, s: usize, n: usize, b: usize, computed: &[f64], truth: &Truth) -> f64 {
    let diff: Vec<f64> = (0..computed.len())
        .map(|k| truth.error(k, computed[k]))
        .collect();
    relative_norm(lambda, s, n, b, &diff, &truth.hi)
}

/// `|diff_b| / |exact_b|` for body `b` in its energy norm, with spin weight `2 lambda` on
/// its compact skew entries (the mass cancels); `0` when `diff_b` vanishes, infinite when
/// only `exact_b` does. Both slices are whole flattened results.
pub fn relative_norm(
    lambda: f64,
    s: usize,
    n: usize,
    b: usize,
    diff: &[f64],
    exact: &[f64],
) -> f64 {
    let range = b * (s + n)..(b + 1) * (s + n);
    let weight = move |k: usize| {
        if k - b * (s + n) < s {
            2.0 * lambda
        } else {
            1.0
        }
    };
    let err = weighted_norm(range.clone().map(|k| (weight(k), diff[k])));
    let norm = weighted_norm(range.map(|k| (weight(k), exact[k])));
    if err == 0.0 {
        0.0
    } else if norm == 0.0 {
        f64::INFINITY
    } else {
        err / norm
    }
}

/// `lambda = gamma2 R^2 / 2` (a weight: its rounding does not matter).
pub fn lambda(ball: &collision_core::Ball<Exact>) -> f64 {
    ToPrimitive::to_f64(&ball.lambda()).unwrap_or(f64::INFINITY)
}

/// The exact result of the generated kernels on exact inputs, through the fast exact path
/// ([`collide_exact`]: relaxed rationals inside the kernel, reduced outputs).
pub fn exact_result<const N: usize, const S: usize>(
    case: &Case<Exact, N, S>,
) -> [BodyState<Exact, N, S>; 2]
where
    Generated: Kernel<ExactRelaxed, N, S>,
{
    collide_exact(&case.nu, case.ball_refs(), case.state_refs())
}

/// Per body, the estimated condition number (see the module docs); `None` for an
/// immovable body (never changed).
pub fn conditioning<const N: usize, const S: usize>(
    case: &Case<Exact, N, S>,
    exact: &[BodyState<Exact, N, S>; 2],
    truth: &Truth,
    rng: &mut Rng,
) -> [Option<f64>; 2]
where
    Generated: Kernel<ExactRelaxed, N, S>,
{
    conditioning_of(case, exact, truth, rng, exact_result)
}

/// [`conditioning`] of the exact map `map` (a rough-ball kernel with its law, say): the
/// largest relative change of each body's exact result, in its energy norm, over two
/// perturbations of every input by a relative `+-2^-53` (random signs), per unit
/// perturbation.
pub fn conditioning_of<const N: usize, const S: usize>(
    case: &Case<Exact, N, S>,
    exact: &[BodyState<Exact, N, S>; 2],
    truth: &Truth,
    rng: &mut Rng,
    map: impl Fn(&Case<Exact, N, S>) -> [BodyState<Exact, N, S>; 2],
) -> [Option<f64>; 2] {
    const TRIALS: usize = 2;
    let unit = || Exact::from_integer(1);
    let u = Exact::pow2(-53);
    let exact = crate::case::flatten(exact);
    let mut kappa = [0.0f64; 2];
    for _ in 0..TRIALS {
        let perturbed = case.map(|x| {
            let du = if rng.coin() { u.clone() } else { -u.clone() };
            x * (unit() + du)
        });
        let change: Vec<f64> = crate::case::flatten(&map(&perturbed))
            .iter()
            .zip(&exact)
            .map(|(m, e)| ToPrimitive::to_f64(&(m - e)).unwrap_or(f64::INFINITY))
            .collect();
        for (b, k) in kappa.iter_mut().enumerate() {
            let rel = relative_norm(lambda(&case.balls[b]), S, N, b, &change, &truth.hi);
            *k = k.max(rel * (1u64 << 53) as f64);
        }
    }
    std::array::from_fn(|b| (!case.balls[b].inv_mass.is_zero()).then_some(kappa[b]))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(p: i64, d: i64) -> Exact {
        Exact::from_ratio(p, d)
    }

    /// `y` split as a [`Truth`] of one component.
    fn split(y: &Exact) -> (f64, f64) {
        let state = BodyState::<Exact, 2, 1> {
            spin: [y.clone()],
            velocity: [q(0, 1), q(0, 1)],
        };
        let t = Truth::of(&[state.clone(), state]);
        (t.hi[0], t.lo[0])
    }

    fn bits_to<F: Float>(computed: F, y: &Exact) -> f64 {
        let (hi, lo) = split(y);
        bits(computed, hi, lo)
    }

    #[test]
    fn bits_count_ulps_from_the_rounded_truth() {
        assert_eq!(bits_to(1.0f64, &q(1, 1)), 0.0);
        assert_eq!(bits_to(1.0f64 + f64::EPSILON, &q(1, 1)), 1.0);
        assert_eq!(bits_to(1.0 / 3.0, &q(1, 3)), 0.0);
        assert_eq!(bits_to(1.0f32 / 3.0, &q(1, 3)), 0.0);
        // Three ulps above the rounded third: log2(4) = 2.
        let third = 1.0f32 / 3.0;
        let up3 = f32::from_bits(third.to_bits() + 3);
        assert_eq!(bits_to(up3, &q(1, 3)), 2.0);
        // Across zero: -min and +min are two steps apart.
        let tiny = f64::from_bits(1);
        assert_eq!(
            bits_to(-tiny, &Exact::from_float(tiny).unwrap()),
            3f64.log2()
        );
        // The exact zero against a tiny value: about 62 bits wrong.
        assert!(bits_to(1e-17f64, &Exact::zero()) > 60.0);
    }

    #[test]
    fn f32_rounding_is_correct_at_double_rounding_traps() {
        // 1 + 2^-24 + 2^-60 is above the f32 midpoint 1 + 2^-24 and rounds up in f32;
        // its f64 rounding is the midpoint itself, which `as f32` ties to even (down).
        let two = |k: u32| Exact::pow2(-(k as i32));
        let above = q(1, 1) + two(24) + two(60);
        assert_eq!(split(&above).0 as f32, 1.0);
        assert_eq!(bits_to(1.0 + f32::EPSILON, &above), 0.0);
        let below = q(1, 1) + two(24) - two(60);
        assert_eq!(bits_to(1.0f32, &below), 0.0);
        assert_eq!(bits_to(-1.0f32, &-below), 0.0);
        // Exactly the midpoint: ties to even.
        assert_eq!(bits_to(1.0f32, &(q(1, 1) + two(24))), 0.0);
    }

    #[test]
    fn normwise_weights_spin_by_two_lambda() {
        let exact = BodyState::<Exact, 2, 1> {
            spin: [q(1, 1)],
            velocity: [q(0, 1), q(0, 1)],
        };
        let truth = Truth::of(&[exact.clone(), exact.clone()]);
        // Body 2's spin 10% off: |dU| sqrt(2 lambda) / (|U| sqrt(2 lambda)) = 1/10.
        let computed = [1.0, 0.0, 0.0, 1.1, 0.0, 0.0];
        assert!((normwise(3.0 / 7.0, 1, 2, 1, &computed, &truth) - 0.1).abs() < 1e-15);
        assert_eq!(normwise(3.0 / 7.0, 1, 2, 0, &computed, &truth), 0.0);
        // lambda = 0: the spin does not count.
        assert_eq!(normwise(0.0, 1, 2, 1, &computed, &truth), 0.0);
        // Only the exact result vanishes: infinitely ill-conditioned.
        let zero = Truth::of::<2, 1>(&[BodyState::zero(), BodyState::zero()]);
        assert!(normwise(1.0, 1, 2, 0, &[0.0, 1e-300, 0.0, 0.0, 0.0, 0.0], &zero).is_infinite());
    }

    #[test]
    fn extreme_magnitudes_neither_overflow_nor_underflow() {
        let big = BodyState::<Exact, 2, 1> {
            spin: [Exact::from_float(1e300).unwrap()],
            velocity: [Exact::from_float(1e300).unwrap(), q(0, 1)],
        };
        let truth = Truth::of(&[big.clone(), big]);
        let computed = [1e300, 1e300 * (1.0 + f64::EPSILON), 0.0, 1e300, 1e300, 0.0];
        let e = normwise(0.5, 1, 2, 0, &computed, &truth);
        assert!(e > 0.0 && e < f64::EPSILON, "{e}");
    }
}
