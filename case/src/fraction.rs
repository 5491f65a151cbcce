//! Short rationals on machine integers: `p / q` in lowest terms (`q > 0`,
//! `gcd(|p|, q) = 1`, so equal values have equal parts), and the exact integer tests the
//! direct path ([`crate::direct`]) makes on them before any big rational is built.
//!
//! Every product and sum is checked (`i128`): where one would overflow the answer is `None`
//! and the caller declines the case (the general path then reads it), never a rounded or
//! wrapped value.

use collision_core::{Exact, Scalar};
use std::cmp::Ordering;

/// `p / q` with `q > 0` and `gcd(|p|, q) = 1` (zero is `0 / 1`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Fraction {
    /// The numerator `p`.
    pub p: i64,
    /// The denominator `q > 0`.
    pub q: i64,
}

/// `gcd(a, b)` (binary: shifts and subtractions, no division); `gcd(0, b) = b`.
pub(crate) fn gcd(mut a: u64, mut b: u64) -> u64 {
    if a == 0 || b == 0 {
        return a | b;
    }
    let shift = (a | b).trailing_zeros();
    a >>= a.trailing_zeros();
    loop {
        b >>= b.trailing_zeros();
        if a > b {
            std::mem::swap(&mut a, &mut b);
        }
        b -= a;
        if b == 0 {
            return a << shift;
        }
    }
}

impl Fraction {
    /// The integer `p / 1`.
    pub(crate) fn integer(p: i64) -> Self {
        Fraction { p, q: 1 }
    }

    /// `p / q` (`q > 0`) in lowest terms.
    pub(crate) fn reduced(p: i64, q: i64) -> Self {
        debug_assert!(q > 0);
        let g = gcd(p.unsigned_abs(), q.unsigned_abs()) as i64;
        Fraction { p: p / g, q: q / g }
    }

    /// The same value as an [`Exact`] (an integer without any gcd; a ratio through
    /// [`Scalar::from_ratio`]).
    pub(crate) fn exact(self) -> Exact {
        if self.q == 1 {
            Exact::from_integer(self.p)
        } else {
            Exact::from_ratio(self.p, self.q)
        }
    }

    /// `1 / x` of `x > 0` (its parts swapped: still in lowest terms).
    pub(crate) fn inverse_of_positive(self) -> Self {
        debug_assert!(self.p > 0);
        Fraction {
            p: self.q,
            q: self.p,
        }
    }

    /// The sign of the value.
    pub(crate) fn sign(self) -> Ordering {
        self.p.cmp(&0)
    }

    /// `-x` (`None` for `p = i64::MIN`, which the readers never make).
    pub(crate) fn neg(self) -> Option<Self> {
        Some(Fraction {
            p: self.p.checked_neg()?,
            q: self.q,
        })
    }
}

/// `lcm(q_1, ..., q_k)` of the denominators of `xs` (1 for none).
pub(crate) fn common_denominator<'a>(xs: impl IntoIterator<Item = &'a Fraction>) -> Option<i128> {
    xs.into_iter().try_fold(1i128, |l, x| {
        let q = i128::from(x.q);
        let g = gcd_wide(l, q);
        (l / g).checked_mul(q)
    })
}

/// `gcd` of two positive `i128`s (Euclid).
fn gcd_wide(mut a: i128, mut b: i128) -> i128 {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

/// `x l`, an integer when `l` is a multiple of `x`'s denominator.
pub(crate) fn over(x: Fraction, l: i128) -> Option<i128> {
    i128::from(x.p).checked_mul(l / i128::from(x.q))
}

/// Whether `sum_k x_k^2 = 1` exactly: with `l` the common denominator and `a_k = x_k l`,
/// whether `sum_k a_k^2 = l^2`.
pub(crate) fn is_unit(xs: &[Fraction]) -> Option<bool> {
    let l = common_denominator(xs)?;
    let mut sum = 0i128;
    for &x in xs {
        let a = over(x, l)?;
        sum = sum.checked_add(a.checked_mul(a)?)?;
    }
    Some(sum == l.checked_mul(l)?)
}

/// The sign of `sum_k nu_k (v_k - u_k)` (the normal part of a relative velocity): with `l`
/// the common denominator of `nu` and `m` that of `u` and `v`, the sign of the integer
/// `sum_k (nu_k l) ((v_k - u_k) m)`.
pub(crate) fn sign_of_normal_part(
    nu: &[Fraction],
    u: &[Fraction],
    v: &[Fraction],
) -> Option<Ordering> {
    let l = common_denominator(nu)?;
    let m = common_denominator(u.iter().chain(v))?;
    let mut sum = 0i128;
    for ((&nu, &u), &v) in nu.iter().zip(u).zip(v) {
        let dv = over(v, m)?.checked_sub(over(u, m)?)?;
        sum = sum.checked_add(over(nu, l)?.checked_mul(dv)?)?;
    }
    Some(sum.cmp(&0))
}

/// Whether `0 <= x <= a / b` (`b > 0`): `x.p >= 0` and `x.p b <= a x.q`.
pub(crate) fn in_range(x: Fraction, a: i128, b: i128) -> Option<bool> {
    Some(x.p >= 0 && i128::from(x.p).checked_mul(b)? <= a.checked_mul(i128::from(x.q))?)
}

/// `c x / y^2` in lowest terms (`c > 0`, `y != 0`), `None` if it does not fit.
pub(crate) fn times_over_square(c: i64, x: Fraction, y: Fraction) -> Option<Fraction> {
    let y2 = |a: i64| i128::from(a).checked_mul(i128::from(a));
    let p = i128::from(c)
        .checked_mul(i128::from(x.p))?
        .checked_mul(y2(y.q)?)?;
    let q = i128::from(x.q).checked_mul(y2(y.p)?)?;
    let g = gcd_wide(p.abs(), q);
    Some(Fraction {
        p: i64::try_from(p / g).ok()?,
        q: i64::try_from(q / g).ok()?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use collision_core::rng::Rng;
    use num_traits::{One, Zero};

    fn q(p: i64, q: i64) -> Fraction {
        Fraction::reduced(p, q)
    }

    /// The binary gcd is Euclid's on random pairs (and on zeros and powers of two).
    #[test]
    fn binary_gcd_is_euclids() {
        let euclid = |mut a: u64, mut b: u64| {
            while b != 0 {
                (a, b) = (b, a % b);
            }
            a
        };
        let mut rng = Rng::new(3);
        for _ in 0..20_000 {
            let shift = rng.integer(0..=40) as u32;
            let a = rng.integer(0..=u64::MAX >> shift);
            let b = rng.integer(0..=1 << 20) * rng.integer(0..=1 << 20);
            assert_eq!(gcd(a, b), euclid(a, b), "{a} {b}");
            assert_eq!(gcd(a << 3, b << 5 >> 5), euclid(a << 3, b << 5 >> 5));
        }
        assert_eq!(gcd(0, 0), 0);
        assert_eq!(gcd(0, 12), 12);
        assert_eq!(gcd(1 << 40, 1 << 12), 1 << 12);
    }

    /// Each test against the same question asked of `Exact` values.
    #[test]
    fn integer_tests_answer_as_exact_arithmetic() {
        let mut rng = Rng::new(5);
        let draw = |rng: &mut Rng| {
            let d = [1, 2, 3, 5, 7, 10, 25, 1000, 999_999_937][rng.integer(0..=8) as usize];
            q(rng.integer(0..=4000) as i64 - 2000, d)
        };
        let x = |f: &Fraction| f.exact();
        let mut fitted = 0;
        for _ in 0..2000 {
            let nu: Vec<Fraction> = (0..3).map(|_| draw(&mut rng)).collect();
            let u: Vec<Fraction> = (0..3).map(|_| draw(&mut rng)).collect();
            let v: Vec<Fraction> = (0..3).map(|_| draw(&mut rng)).collect();
            let norm2 = nu.iter().fold(Exact::zero(), |s, a| s + x(a) * x(a));
            assert_eq!(is_unit(&nu), Some(norm2 == Exact::one()));
            let dn = (0..3).fold(Exact::zero(), |s, k| s + x(&nu[k]) * (x(&v[k]) - x(&u[k])));
            assert_eq!(
                sign_of_normal_part(&nu, &u, &v),
                Some(dn.cmp(&Exact::zero()))
            );
            let (a, b) = (rng.integer(0..=30) as i128, rng.integer(1..=30) as i128);
            let bound = Exact::from_ratio(a as i64, b as i64);
            let inside = x(&u[0]) >= Exact::zero() && x(&u[0]) <= bound;
            assert_eq!(in_range(u[0], a, b), Some(inside));
            if v[0].p != 0 {
                // `None` only where the parts do not fit an `i64`.
                let want = Exact::from_integer(2) * x(&u[0]) / (x(&v[0]) * x(&v[0]));
                match times_over_square(2, u[0], v[0]) {
                    Some(got) => {
                        assert_eq!(x(&got), want);
                        assert_eq!(got, q(got.p, got.q), "lowest terms");
                        fitted += 1;
                    }
                    None => assert!(want.to_string().len() > 18, "{want}"),
                }
            }
        }
        assert!(fitted > 1000, "{fitted}");
        // Unit normals with large denominators, and one off by 1 in the last place.
        let (a, b, c) = (q(3, 5), q(4, 5), q(0, 1));
        assert_eq!(is_unit(&[a, b, c]), Some(true));
        let (a, b) = (q(20, 29), q(21, 29));
        assert_eq!(is_unit(&[a, b]), Some(true));
        assert_eq!(is_unit(&[a, q(21_000_001, 29_000_000)]), Some(false));
    }

    /// Where a product would overflow `i128` the answer is `None`, not a wrapped value.
    #[test]
    fn overflow_is_none() {
        let big = q(999_999_999_999_999_989, 999_999_999_999_999_877);
        let other = q(1, 999_999_999_999_999_967);
        assert_eq!(
            common_denominator(&[big, other, q(1, 999_999_999_999_999_937)]),
            None
        );
        assert_eq!(is_unit(&[big, other]), None);
        assert_eq!(times_over_square(2, big, other), None);
        assert_eq!(q(i64::MIN + 1, 1).neg(), Some(q(i64::MAX, 1)));
    }
}
