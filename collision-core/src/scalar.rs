//! The scalar types the generated kernels run on: `f32`, `f64` and exact rationals.

use num_traits::{One, Signed, Zero};
use std::fmt::{Debug, Display};
use std::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

/// Arithmetic on references, `&a + &b -> T`, which the generated kernels use so that the
/// same code serves `Copy` floats and heap-allocated rationals. Implemented for every `&T`
/// that has the operations; generic callers add `where for<'a> &'a T: RefArith<T>`.
pub trait RefArith<T>:
    Sized
    + Add<Self, Output = T>
    + Sub<Self, Output = T>
    + Mul<Self, Output = T>
    + Div<Self, Output = T>
    + Neg<Output = T>
{
}

impl<'a, T: 'a> RefArith<T> for &'a T where
    &'a T: Add<&'a T, Output = T>
        + Sub<&'a T, Output = T>
        + Mul<&'a T, Output = T>
        + Div<&'a T, Output = T>
        + Neg<Output = T>
{
}

/// A field the kernels and the reference run in.
pub trait Scalar:
    Clone
    + Debug
    + Display
    + PartialEq
    + PartialOrd
    + Zero
    + One
    + Signed
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
    + DivAssign
    + 'static
{
    /// `"f32"`, `"f64"` or `"exact"`.
    const NAME: &'static str;
    /// Whether arithmetic is exact (no rounding).
    const EXACT: bool;

    /// `num / den`: exact for rationals; for floats the correctly rounded quotient whenever
    /// `num` and `den` are exactly representable (IEEE division is correctly rounded).
    fn from_ratio(num: i64, den: i64) -> Self;
    /// Neither NaN nor infinite (always true for rationals).
    fn is_finite(&self) -> bool;
    /// The nearest `f64` (for reports and tolerances).
    fn to_f64(&self) -> f64;
    /// The value as written in messages: rationals as `p/q`, floats in Rust's shortest
    /// round-trip form (`1e-300`, not 300 digits).
    fn show(&self) -> String;
    /// The factor of [the rounding allowance](crate::allowance): `ULPS eps` (`8 eps`) in
    /// floats, 0 in exact arithmetic. A bound may be crossed by `rounding_slack() * s`, `s` the
    /// scale of the quantity.
    fn rounding_slack() -> Self;

    /// The arithmetic the checked entry points compute in: the same precision with an
    /// unbounded exponent ([`crate::Wide`]) for floats, so that no intermediate quantity
    /// overflows or underflows; the type itself for exact rationals.
    type Unbounded: Scalar;
    /// The value in [`Scalar::Unbounded`] (exact).
    fn unbounded(&self) -> Self::Unbounded;
    /// The nearest value of this type: `±inf` above its range, subnormal or zero below it.
    fn from_unbounded(x: &Self::Unbounded) -> Self;

    /// `a b + c`, fused (one rounding) in floats: the FMA kernels' operation. Exact in
    /// rationals.
    fn mul_add(a: &Self, b: &Self, c: &Self) -> Self;
    /// `a b - c`, fused.
    fn mul_sub(a: &Self, b: &Self, c: &Self) -> Self {
        Self::mul_add(a, b, &-c.clone())
    }
    /// `c - a b`, fused.
    fn neg_mul_add(a: &Self, b: &Self, c: &Self) -> Self {
        Self::mul_add(&-a.clone(), b, c)
    }
    /// An exact rational constant of a specialised kernel, given by the generator as its
    /// correctly rounded `f64` and `f32` and its exact digits `num / den` (decimal
    /// integers): floats return their literal, rationals parse the digits.
    fn from_literal(x64: f64, x32: f32, num: &str, den: &str) -> Self;
}

/// The two operations the Walton kernels (`kernels::dN::walton`) add to a [`Scalar`]: the
/// square root and a branch-free select (`docs/derivation.md` §15.1).
pub trait ScalarRoot: Scalar {
    /// `sqrt(a)`, `a >= 0`: correctly rounded in floats (IEEE); in exact rationals the root
    /// when `a` is the square of a rational, else rounded (see [`crate::exact`]).
    fn sqrt(a: &Self) -> Self;
    /// `a` if `x < y`, else `b`: no rounding, and in floats compiled as a compare and a
    /// select rather than a branch where the target has one.
    fn select_lt(x: &Self, y: &Self, a: &Self, b: &Self) -> Self {
        if x < y {
            a.clone()
        } else {
            b.clone()
        }
    }
}

/// The rounding allowance of a quantity of scale `s`: `rounding_slack() |s|`.
pub(crate) fn allowance<T: Scalar>(s: &T) -> T {
    if T::EXACT {
        // `rounding_slack() = 0`: the product is 0 whatever `s`, with no product made.
        return T::zero();
    }
    T::rounding_slack() * s.abs()
}

/// `2` in any scalar (`from_ratio(2, 1)`: exactly 2 in every type, no addition made).
pub(crate) fn two<T: Scalar>() -> T {
    T::from_ratio(2, 1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Exact;

    #[test]
    fn ratios_are_exact_or_correctly_rounded() {
        assert_eq!(<f64 as Scalar>::from_ratio(1, 3), 1.0 / 3.0);
        assert_eq!(<f32 as Scalar>::from_ratio(-2, 1), -2.0);
        assert_eq!(
            Exact::from_ratio(2, 6),
            Exact::from_decimal("1", "3").unwrap()
        );
    }

    #[test]
    fn fused_operations_round_once() {
        // (1 + 2^-30)^2 - 1 = 2^-29 + 2^-60: the plain product rounds 2^-60 away.
        let a = 1.0 + 2f64.powi(-30);
        let exact = 2f64.powi(-29) + 2f64.powi(-60);
        assert_eq!(<f64 as Scalar>::mul_sub(&a, &a, &1.0), exact);
        assert_ne!(a * a - 1.0, exact);
        assert_eq!(<f64 as Scalar>::neg_mul_add(&a, &a, &1.0), -exact);
        let (x, y, z) = (
            Exact::from_ratio(1, 3),
            Exact::from_ratio(3, 7),
            Exact::from_ratio(-1, 7),
        );
        assert!(Exact::mul_add(&x, &y, &z).is_zero());
    }

    #[test]
    fn the_allowance_is_eight_ulps_in_floats_and_nothing_exactly() {
        assert_eq!(allowance(&-2.0f64), 16.0 * f64::EPSILON);
        assert_eq!(allowance(&1.0f32), 8.0 * f32::EPSILON);
        assert_eq!(allowance(&Exact::from_ratio(1, 3)), Exact::zero());
    }
}
