//! [`Wide<F>`]: binary floating point with the precision of `F` (`f64` or `f32`) and an
//! unbounded exponent, `x = m 2^e` with `1 <= |m| < 2` in `F` and `e` an `i64`.
//!
//! Every operation is `F`'s operation on the mantissas, rounded once to `F`'s precision, with
//! the exponents kept apart: the result is the exact result correctly rounded to `F`'s
//! precision, whatever its magnitude. Where `F` itself neither overflows nor leaves its
//! normal range, that is `F`'s own result bit for bit; elsewhere `F` returns infinity, zero or
//! a subnormal number with fewer bits, and `Wide<F>` the right value. The checked
//! [`crate::collide`] runs the generated kernels in it, so that no intermediate quantity
//! (`R_2 U_2` for a huge radius, `rho_2 ~ 1/(R_2 D)` for the same, `D` for tiny inverse masses)
//! overflows or underflows; only the result is rounded to `F`, and refused if it does not fit.

use crate::scalar::Scalar;
use num_traits::{Num, One, Signed, Zero};
use std::cmp::Ordering;
use std::fmt;
use std::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Rem, Sub, SubAssign};

/// A binary IEEE format: what [`Wide`] needs of `f64` and `f32`.
pub trait Binary:
    Copy
    + PartialOrd
    + fmt::Debug
    + fmt::Display
    + Signed
    + Num
    + Into<f64>
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Rem<Output = Self>
    + Neg<Output = Self>
{
    /// `"f64"`, `"f32"`.
    const NAME: &'static str;
    /// The largest exponent of a finite number (`1023`, `127`).
    const EXP_MAX: i64;
    /// The smallest exponent of a normal number (`-1022`, `-126`).
    const EXP_MIN: i64;
    /// Stored mantissa bits (`52`, `23`).
    const MANTISSA: i64;
    /// The gap between 1 and the next number.
    const EPSILON: Self;

    /// `2^k` for `EXP_MIN - MANTISSA <= k <= EXP_MAX` (normal or subnormal).
    fn pow2(k: i64) -> Self;
    /// `x = m 2^e` with `1 <= |m| < 2`, for finite non-zero `x` (subnormal included).
    fn split(self) -> (Self, i64);
    /// Whether the value is neither infinite nor NaN.
    fn finite(self) -> bool;
    /// `a b + c` with one rounding.
    fn fma(a: Self, b: Self, c: Self) -> Self;
    /// The correctly rounded square root (NaN below 0).
    fn root(self) -> Self;
    /// The literal of a generated constant in this format.
    fn literal(x64: f64, x32: f32) -> Self;
    /// `x` rounded to this format (`f64` input).
    fn of_f64(x: f64) -> Self;
    /// `num as F / den as F`, as the format's [`Scalar::from_ratio`].
    fn ratio(num: i64, den: i64) -> Self;
}

macro_rules! binary {
    ($f:ident, $bits:ident, $name:literal, $max:literal, $mant:literal, $lift:literal) => {
        impl Binary for $f {
            const NAME: &'static str = $name;
            const EXP_MAX: i64 = $max;
            const EXP_MIN: i64 = 1 - $max;
            const MANTISSA: i64 = $mant;
            const EPSILON: Self = <$f>::EPSILON;

            #[inline]
            fn pow2(k: i64) -> Self {
                debug_assert!((Self::EXP_MIN - Self::MANTISSA..=Self::EXP_MAX).contains(&k));
                if k >= Self::EXP_MIN {
                    <$f>::from_bits(((k + Self::EXP_MAX) as $bits) << $mant)
                } else {
                    <$f>::from_bits((1 as $bits) << (k - Self::EXP_MIN + Self::MANTISSA))
                }
            }

            #[inline]
            fn split(self) -> (Self, i64) {
                // A subnormal is lifted into the normal range first (exact).
                let (x, shift) = if self.abs() < <$f>::MIN_POSITIVE {
                    (self * Self::pow2($lift), $lift)
                } else {
                    (self, 0)
                };
                let bits = x.to_bits();
                let field = ((bits >> $mant) & ((1 << (<$bits>::BITS - 1 - $mant)) - 1)) as i64;
                let one_bits = (Self::EXP_MAX as $bits) << $mant;
                let sign_and_fraction = bits & !((((1 as $bits) << (<$bits>::BITS - 1 - $mant)) - 1) << $mant);
                (
                    <$f>::from_bits(sign_and_fraction | one_bits),
                    field - Self::EXP_MAX - shift,
                )
            }

            #[inline]
            fn finite(self) -> bool {
                self.is_finite()
            }

            #[inline]
            fn fma(a: Self, b: Self, c: Self) -> Self {
                a.mul_add(b, c)
            }

            #[inline]
            fn root(self) -> Self {
                self.sqrt()
            }

            #[inline]
            fn literal(x64: f64, x32: f32) -> Self {
                let _ = (x64, x32);
                binary!(@pick $f, x64, x32)
            }

            #[inline]
            fn of_f64(x: f64) -> Self {
                x as $f
            }

            #[inline]
            fn ratio(num: i64, den: i64) -> Self {
                num as $f / den as $f
            }
        }
    };
    (@pick f64, $x64:ident, $x32:ident) => { $x64 };
    (@pick f32, $x64:ident, $x32:ident) => { $x32 };
}

binary!(f64, u64, "f64", 1023, 52, 64);
binary!(f32, u32, "f32", 127, 23, 32);

/// `m 2^e`: zero, infinities and NaN have `e = 0`; every other value has `1 <= |m| < 2`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wide<F> {
    m: F,
    e: i64,
}

impl<F: Binary> Wide<F> {
    /// `x 2^e` for any `x` of `F`.
    #[inline]
    fn scaled(x: F, e: i64) -> Self {
        if x.is_zero() || !x.finite() {
            Wide { m: x, e: 0 }
        } else {
            let (m, k) = x.split();
            Wide { m, e: e + k }
        }
    }

    /// Zero, infinite or NaN: the exponent is not used.
    #[inline]
    fn special(self) -> bool {
        self.m.is_zero() || !self.m.finite()
    }

    /// The value in `F`, correctly rounded: `±inf` above `F`'s range, a subnormal number or
    /// zero below it.
    pub fn round(self) -> F {
        if self.special() {
            return self.m;
        }
        let e = self.e;
        if e > F::EXP_MAX {
            self.m * (F::pow2(F::EXP_MAX) + F::pow2(F::EXP_MAX))
        } else if e >= F::EXP_MIN {
            self.m * F::pow2(e)
        } else if e >= F::EXP_MIN - F::MANTISSA - 2 {
            // m 2^(e - k) is exact and normal, then one rounding into the subnormal range.
            let k = F::EXP_MIN - F::MANTISSA;
            (self.m * F::pow2(e - k)) * F::pow2(k)
        } else {
            // |x| < 2^(k - 1): rounds to zero.
            self.m * F::zero()
        }
    }

    /// `sqrt(x)`, correctly rounded: `x = m 2^(2k + r)`, `r` in `{0, 1}`, has the root
    /// `sqrt(m 2^r) 2^k`, one rounding of `F`'s square root scaled exactly. Zero, infinity
    /// and NaN as `F`'s, and NaN below 0.
    pub(crate) fn sqrt(self) -> Self {
        if self.special() || self.m < F::zero() {
            return Wide::scaled(self.m.root(), 0);
        }
        let (k, r) = (self.e.div_euclid(2), self.e.rem_euclid(2));
        let two = F::one() + F::one();
        let m = if r == 1 { self.m * two } else { self.m };
        Wide::scaled(m.root(), k)
    }

    /// `|x| < |y|`, for finite non-zero values.
    fn smaller(self, other: Self) -> bool {
        (self.e, self.m.abs()) < (other.e, other.m.abs())
    }
}

impl<F: Binary> From<F> for Wide<F> {
    #[inline]
    fn from(x: F) -> Self {
        Wide::scaled(x, 0)
    }
}

impl<F: Binary> Add for Wide<F> {
    type Output = Self;
    #[inline]
    fn add(self, rhs: Self) -> Self {
        if !self.m.finite() || !rhs.m.finite() || (self.m.is_zero() && rhs.m.is_zero()) {
            return Wide::scaled(self.m + rhs.m, 0);
        }
        if self.m.is_zero() {
            return rhs;
        }
        if rhs.m.is_zero() {
            return self;
        }
        let (big, small) = if self.e >= rhs.e {
            (self, rhs)
        } else {
            (rhs, self)
        };
        let d = small.e - big.e;
        if d < -(F::MANTISSA + 3) {
            // |small| < ulp(big) / 4: the correctly rounded sum is `big`.
            return big;
        }
        // small.m 2^d is exact (normal), and the sum rounds once.
        Wide::scaled(big.m + small.m * F::pow2(d), big.e)
    }
}

impl<F: Binary> Neg for Wide<F> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Wide {
            m: -self.m,
            e: self.e,
        }
    }
}

impl<F: Binary> Sub for Wide<F> {
    type Output = Self;
    #[inline]
    fn sub(self, rhs: Self) -> Self {
        self + -rhs
    }
}

impl<F: Binary> Mul for Wide<F> {
    type Output = Self;
    #[inline]
    fn mul(self, rhs: Self) -> Self {
        if self.special() || rhs.special() {
            return Wide::scaled(self.m * rhs.m, 0);
        }
        // 1 <= |m| < 4: at most one halving (exact) normalises it.
        let (m, e) = (self.m * rhs.m, self.e + rhs.e);
        let two = F::one() + F::one();
        if m.abs() >= two {
            Wide {
                m: m / two,
                e: e + 1,
            }
        } else {
            Wide { m, e }
        }
    }
}

impl<F: Binary> Div for Wide<F> {
    type Output = Self;
    #[inline]
    fn div(self, rhs: Self) -> Self {
        if self.special() || rhs.special() {
            // 0/y = 0, x/0 = inf, x/inf = 0, and NaN where F gives NaN.
            return Wide::scaled(self.m / rhs.m, 0);
        }
        // 1/2 < |m| < 2 (the quotient never rounds up to 2): at most one doubling (exact).
        let (m, e) = (self.m / rhs.m, self.e - rhs.e);
        if m.abs() < F::one() {
            Wide { m: m + m, e: e - 1 }
        } else {
            Wide { m, e }
        }
    }
}

impl<F: Binary> Rem for Wide<F> {
    type Output = Self;
    /// The exact remainder `x - trunc(x / y) y`, as `F`'s `%` (which is exact too).
    fn rem(self, rhs: Self) -> Self {
        if self.special() || rhs.special() {
            // x % inf = x for finite x (NaN is the one value unequal to itself).
            let nan = rhs.m.partial_cmp(&rhs.m).is_none();
            if !rhs.m.finite() && !nan && self.m.finite() {
                return self;
            }
            return Wide::scaled(self.m % rhs.m, 0);
        }
        if self.smaller(rhs) {
            return self;
        }
        // (m_x 2^shift) mod m_y, reduced in steps that stay inside F's range: each step keeps
        // the residue modulo m_y exactly.
        let y = rhs.m.abs();
        let mut r = self.m.abs();
        let mut shift = self.e - rhs.e;
        while shift > 0 {
            let k = shift.min(F::EXP_MAX - 2);
            r = (r * F::pow2(k)) % y;
            shift -= k;
        }
        let r = Wide::scaled(r % y, rhs.e);
        if self.m < F::zero() {
            -r
        } else {
            r
        }
    }
}

macro_rules! by_reference {
    ($($tr:ident $method:ident),*) => {$(
        impl<'a, F: Binary> $tr<&'a Wide<F>> for &'a Wide<F> {
            type Output = Wide<F>;
            #[inline]
            fn $method(self, rhs: &'a Wide<F>) -> Wide<F> {
                $tr::$method(*self, *rhs)
            }
        }
    )*};
}
by_reference!(Add add, Sub sub, Mul mul, Div div, Rem rem);

impl<F: Binary> Neg for &Wide<F> {
    type Output = Wide<F>;
    #[inline]
    fn neg(self) -> Wide<F> {
        -*self
    }
}

macro_rules! assign {
    ($($tr:ident $method:ident $op:ident),*) => {$(
        impl<F: Binary> $tr for Wide<F> {
            #[inline]
            fn $method(&mut self, rhs: Self) {
                *self = self.$op(rhs);
            }
        }
    )*};
}
assign!(AddAssign add_assign add, SubAssign sub_assign sub, MulAssign mul_assign mul, DivAssign div_assign div);

impl<F: Binary> PartialOrd for Wide<F> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        let (a, b) = (*self, *other);
        let same_sign = (a.m > F::zero()) == (b.m > F::zero());
        if a.special() || b.special() || !same_sign {
            // The sign, zero or an infinity decides, as in F.
            return a.m.partial_cmp(&b.m);
        }
        let by_magnitude = (a.e, a.m.abs()).partial_cmp(&(b.e, b.m.abs()))?;
        Some(if a.m > F::zero() {
            by_magnitude
        } else {
            by_magnitude.reverse()
        })
    }
}

impl<F: Binary> Zero for Wide<F> {
    fn zero() -> Self {
        Wide::from(F::zero())
    }
    fn is_zero(&self) -> bool {
        self.m.is_zero()
    }
}

impl<F: Binary> One for Wide<F> {
    fn one() -> Self {
        Wide::from(F::one())
    }
}

impl<F: Binary> Num for Wide<F> {
    type FromStrRadixErr = F::FromStrRadixErr;
    /// `F`'s parser: the value must be within `F`'s range.
    fn from_str_radix(text: &str, radix: u32) -> Result<Self, Self::FromStrRadixErr> {
        F::from_str_radix(text, radix).map(Wide::from)
    }
}

impl<F: Binary> Signed for Wide<F> {
    fn abs(&self) -> Self {
        Wide {
            m: self.m.abs(),
            e: self.e,
        }
    }
    fn abs_sub(&self, other: &Self) -> Self {
        if self <= other {
            Self::zero()
        } else {
            *self - *other
        }
    }
    fn signum(&self) -> Self {
        Wide::from(self.m.signum())
    }
    fn is_positive(&self) -> bool {
        self.m.is_positive()
    }
    fn is_negative(&self) -> bool {
        self.m.is_negative()
    }
}

impl<F: Binary> fmt::Display for Wide<F> {
    /// Inside `F`'s range, `F`'s shortest round-trip form; beyond it, about 7 significant
    /// digits and a decimal exponent (`1.234568e400`).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let x = self.round();
        if self.special() || (x.finite() && Wide::from(x) == *self) {
            return write!(f, "{x:?}");
        }
        let m: f64 = self.m.abs().into();
        let log10 = m.log10() + self.e as f64 * std::f64::consts::LOG10_2;
        let mut exponent = log10.floor();
        let mut mantissa = 10f64.powf(log10 - exponent);
        if format!("{mantissa:.6}").starts_with("10") {
            (mantissa, exponent) = (mantissa / 10.0, exponent + 1.0);
        }
        let sign = if self.m < F::zero() { "-" } else { "" };
        write!(f, "{sign}{mantissa:.6}e{exponent}")
    }
}

impl<F: Binary> Scalar for Wide<F> {
    const NAME: &'static str = F::NAME;
    const EXACT: bool = false;
    type Unbounded = Self;

    fn from_ratio(num: i64, den: i64) -> Self {
        Wide::from(F::ratio(num, den))
    }
    fn is_finite(&self) -> bool {
        self.m.finite()
    }
    fn to_f64(&self) -> f64 {
        Wide::<f64>::scaled(self.m.into(), self.e).round()
    }
    fn show(&self) -> String {
        self.to_string()
    }
    fn rounding_slack() -> Self {
        Wide::from(F::EPSILON * F::ratio(i64::from(crate::allowance::ULPS), 1))
    }
    fn unbounded(&self) -> Self {
        *self
    }
    fn from_unbounded(x: &Self) -> Self {
        *x
    }

    /// `a b + c` rounded once.
    fn mul_add(a: &Self, b: &Self, c: &Self) -> Self {
        if a.special() || b.special() || c.special() {
            // Not fused at the edges; exact anyway when a product or a sum is zero.
            return *a * *b + *c;
        }
        let e = a.e + b.e;
        let d = c.e - e;
        let room = F::EXP_MAX - 2 * F::MANTISSA - 8;
        if d > room {
            // |a b| < ulp(c) / 4: the result is c.
            return *c;
        }
        // Below `-room`, c only decides the rounding of a halfway product: a stand-in of the
        // same sign does the same.
        let c_scaled = c.m * F::pow2(d.max(-room));
        Wide::scaled(F::fma(a.m, b.m, c_scaled), e)
    }

    fn from_literal(x64: f64, x32: f32, _: &str, _: &str) -> Self {
        Wide::from(F::literal(x64, x32))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Exact;
    use num_traits::ToPrimitive;

    type W = Wide<f64>;

    fn w(x: f64) -> W {
        W::from(x)
    }

    /// `m 2^e` exactly.
    fn exact(x: W) -> Exact {
        let m = Exact::from_float(x.m).unwrap();
        let p = num_traits::pow(Exact::from_integer(2), x.e.unsigned_abs() as usize);
        if x.e >= 0 {
            m * p
        } else {
            m / p
        }
    }

    /// A deterministic spread of f64 values: both signs, normal and subnormal magnitudes,
    /// mantissas near 1 and 2 (carries and halfway cases).
    fn samples() -> Vec<f64> {
        let mut s = 0x9E37_79B9_7F4A_7C15_u64;
        let mut next = move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            s
        };
        let mut out = vec![
            1.0,
            -1.0,
            1.5,
            3.0,
            f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
            -0.5,
        ];
        for _ in 0..300 {
            let x = f64::from_bits(next());
            if x.is_finite() && x != 0.0 {
                out.push(x);
            }
            out.push(f64::from_bits(0x3FF0_0000_0000_0000 | (next() & 0xF)));
            out.push(-f64::from_bits(0x3FFF_FFFF_FFFF_FFF0 | (next() & 0xF)));
        }
        out
    }

    #[test]
    fn in_range_operations_are_f64_bit_for_bit() {
        // Sums are exact or correctly rounded in f64 (subnormal sums are exact), so they agree
        // everywhere, overflow included; products and quotients agree wherever f64's result
        // is normal or infinite (below, f64 rounds once into the subnormal grid and Wide
        // twice).
        let xs = samples();
        let normal = |f: f64| f.is_infinite() || f.abs() >= 2.0 * f64::MIN_POSITIVE;
        for (i, &a) in xs.iter().enumerate() {
            for (j, &b) in xs.iter().enumerate().skip(i % 7).step_by(23) {
                let c = xs[(i + j) % xs.len()];
                let bits = |x: W| x.round().to_bits();
                assert_eq!(bits(w(a) + w(b)), (a + b).to_bits(), "{a:e} + {b:e}");
                assert_eq!(bits(w(a) - w(b)), (a - b).to_bits(), "{a:e} - {b:e}");
                for (op, f, wide) in [("*", a * b, w(a) * w(b)), ("/", a / b, w(a) / w(b))] {
                    if normal(f) {
                        assert_eq!(bits(wide), f.to_bits(), "{a:e} {op} {b:e}");
                    }
                }
                let fused = a.mul_add(b, c);
                if normal(fused) {
                    assert_eq!(bits(W::mul_add(&w(a), &w(b), &w(c))), fused.to_bits());
                }
                assert_eq!(
                    w(a).partial_cmp(&w(b)),
                    a.partial_cmp(&b),
                    "{a:e} <=> {b:e}"
                );
                assert_eq!(bits(w(a) % w(b)), (a % b).to_bits(), "{a:e} % {b:e}");
            }
        }
    }

    #[test]
    fn results_outside_f64_are_correctly_rounded() {
        // One operation on operands far outside the f64 range, against exact rationals:
        // got = want (1 + d), |d| <= eps/2.
        let xs = samples();
        let half_eps = Exact::from_float(f64::EPSILON / 2.0).unwrap();
        for (i, &a) in xs.iter().enumerate().step_by(37) {
            for &b in xs.iter().skip(i % 5).step_by(97) {
                let big = w(a) * w(f64::MAX) * w(8.0);
                let small = w(b) * w(5e-324) / w(16.0);
                let near = big * w(1.0 + f64::EPSILON);
                for (got, want) in [
                    (big * small, exact(big) * exact(small)),
                    (big / small, exact(big) / exact(small)),
                    (big + w(b), exact(big) + exact(w(b))),
                    (near - big, exact(near) - exact(big)),
                    (small + small * w(b), exact(small) + exact(small * w(b))),
                    (
                        W::mul_add(&big, &small, &w(b)),
                        exact(big) * exact(small) + exact(w(b)),
                    ),
                    (big % small, {
                        let q = (exact(big) / exact(small)).trunc();
                        exact(big) - q * exact(small)
                    }),
                ] {
                    let err = (exact(got) - want.clone()).abs();
                    assert!(
                        err <= want.abs() * half_eps.clone(),
                        "{got} against {:e}",
                        ToPrimitive::to_f64(&want).unwrap_or(0.0)
                    );
                }
            }
        }
    }

    #[test]
    fn rounding_to_f64_handles_overflow_subnormals_and_zero() {
        let max = w(f64::MAX);
        assert_eq!((max * w(2.0)).round(), f64::INFINITY);
        assert_eq!((-max * w(2.0)).round(), f64::NEG_INFINITY);
        assert_eq!((max * w(2.0) / w(2.0)).round(), f64::MAX);
        // 2^-1074; half of it is a tie (to even: zero); 3/4 and 3/2 of it round to 1 and 2.
        let min = w(5e-324);
        assert_eq!(min.round(), 5e-324);
        assert_eq!((min / w(2.0)).round(), 0.0);
        assert_eq!((min * w(0.75)).round(), 5e-324);
        assert_eq!((min * w(1.5)).round(), 1e-323);
        assert_eq!((min * min).round(), 0.0);
        assert!((-(min * min)).round().is_sign_negative());
        let m = f64::MIN_POSITIVE;
        assert_eq!((w(3.0) * w(m) / w(4.0)).round(), 3.0 * m / 4.0);
        // Special values pass through.
        assert!((w(1.0) / w(0.0)).round().is_infinite());
        assert!((w(0.0) / w(0.0)).round().is_nan());
        assert_eq!(w(-0.0).round().to_bits(), (-0.0f64).to_bits());
        assert_eq!(w(1.0) % (w(1.0) / w(0.0)), w(1.0));
    }

    #[test]
    fn far_apart_sums_and_fused_products_round_correctly() {
        let huge = w(1e300) * w(1e300);
        assert_eq!(huge + w(1.0), huge);
        assert_eq!(w(1.0) + huge * w(0.0), w(1.0));
        assert_eq!((w(1.0) - w(1e-300) * w(1e-300)).round(), 1.0);
        // (1 + 2^-30)^2 - 1 fused is exact, also scaled by 2^2000.
        let a = w(1.0 + 2f64.powi(-30));
        let want = 2f64.powi(-29) + 2f64.powi(-60);
        assert_eq!(W::mul_add(&a, &a, &w(-1.0)).round(), want);
        let s = w(2f64.powi(1000)) * w(2f64.powi(1000));
        assert_eq!((W::mul_add(&(a * s), &a, &-s) / s).round(), want);
        // f32 mantissas round to f32.
        let third = Wide::<f32>::from(1.0) / Wide::from(3.0);
        assert_eq!(third.round(), 1.0f32 / 3.0);
        let big = Wide::<f32>::from(f32::MAX) * Wide::from(4.0);
        assert_eq!((big / Wide::from(8.0)).round(), f32::MAX / 2.0);
        assert_eq!(big.to_f64(), f64::from(f32::MAX) * 4.0);
    }

    #[test]
    fn display_shows_the_magnitude() {
        assert_eq!(w(0.1).to_string(), "0.1");
        let big = w(1e300) * w(1e100);
        assert!(big.to_string().ends_with("e400"), "{big}");
        assert!(big.to_string().starts_with("1.0000"), "{big}");
        assert!((-(w(1e-300) * w(1e-300)))
            .to_string()
            .starts_with("-1.0000"));
    }
}
