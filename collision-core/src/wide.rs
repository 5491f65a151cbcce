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

use crate::scalar::{Scalar, ScalarRoot};
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

impl<F: Binary> ScalarRoot for Wide<F> {
    fn sqrt(a: &Self) -> Self {
        a.sqrt()
    }
}

#[cfg(test)]
#[path = "wide_tests.rs"]
mod tests;
