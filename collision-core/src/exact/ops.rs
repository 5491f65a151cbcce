//! Arithmetic on [`Rational`]: the `std::ops` operators on values and references, `num-traits`'
//! `Zero`, `One`, `Num`, `Signed`, sums and products, and [`Scalar`].

use super::{Backend, ParseRationalError, Rational};
use crate::scalar::Scalar;
use num_traits::{Num, One, Signed, ToPrimitive, Zero};
use std::cmp::Ordering;
use std::iter::{Product, Sum};
use std::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Rem, Sub, SubAssign};

/// One binary operator for every combination of values and references, and its assignment.
macro_rules! binary {
    ($Op:ident, $op:ident, $OpAssign:ident, $op_assign:ident, $f:path) => {
        impl<'a, B: Backend> $Op<&'a Rational<B>> for &'a Rational<B> {
            type Output = Rational<B>;
            #[inline]
            fn $op(self, rhs: &'a Rational<B>) -> Rational<B> {
                Rational($f(&self.0, &rhs.0))
            }
        }
        impl<B: Backend> $Op<Rational<B>> for Rational<B> {
            type Output = Rational<B>;
            #[inline]
            fn $op(self, rhs: Rational<B>) -> Rational<B> {
                Rational($f(&self.0, &rhs.0))
            }
        }
        impl<'a, B: Backend> $Op<&'a Rational<B>> for Rational<B> {
            type Output = Rational<B>;
            #[inline]
            fn $op(self, rhs: &'a Rational<B>) -> Rational<B> {
                Rational($f(&self.0, &rhs.0))
            }
        }
        impl<'a, B: Backend> $Op<Rational<B>> for &'a Rational<B> {
            type Output = Rational<B>;
            #[inline]
            fn $op(self, rhs: Rational<B>) -> Rational<B> {
                Rational($f(&self.0, &rhs.0))
            }
        }
        impl<B: Backend> $OpAssign<Rational<B>> for Rational<B> {
            #[inline]
            fn $op_assign(&mut self, rhs: Rational<B>) {
                self.0 = $f(&self.0, &rhs.0);
            }
        }
        impl<'a, B: Backend> $OpAssign<&'a Rational<B>> for Rational<B> {
            #[inline]
            fn $op_assign(&mut self, rhs: &'a Rational<B>) {
                self.0 = $f(&self.0, &rhs.0);
            }
        }
    };
}

binary!(Add, add, AddAssign, add_assign, B::add);
binary!(Sub, sub, SubAssign, sub_assign, B::sub);
binary!(Mul, mul, MulAssign, mul_assign, B::mul);
binary!(Div, div, DivAssign, div_assign, B::div);

impl<B: Backend> Neg for Rational<B> {
    type Output = Rational<B>;
    #[inline]
    fn neg(self) -> Rational<B> {
        Rational(B::neg(&self.0))
    }
}

impl<B: Backend> Neg for &Rational<B> {
    type Output = Rational<B>;
    #[inline]
    fn neg(self) -> Rational<B> {
        Rational(B::neg(&self.0))
    }
}

impl<B: Backend> Rem for Rational<B> {
    type Output = Rational<B>;
    /// `a - b trunc(a / b)`, the remainder of truncated division (as for integers).
    fn rem(self, rhs: Rational<B>) -> Rational<B> {
        let q = (&self / &rhs).trunc();
        &self - &(&rhs * &q)
    }
}

impl<B: Backend> Zero for Rational<B> {
    fn zero() -> Self {
        Self::from_integer(0)
    }
    fn is_zero(&self) -> bool {
        B::sign(&self.0) == Ordering::Equal
    }
}

impl<B: Backend> One for Rational<B> {
    fn one() -> Self {
        Self::from_integer(1)
    }
}

impl<B: Backend> Num for Rational<B> {
    type FromStrRadixErr = ParseRationalError;
    /// Decimal only (`p` or `p/q`).
    fn from_str_radix(s: &str, radix: u32) -> Result<Self, ParseRationalError> {
        if radix != 10 {
            return Err(ParseRationalError(format!("{s} (radix {radix})")));
        }
        s.parse()
    }
}

impl<B: Backend> Signed for Rational<B> {
    fn abs(&self) -> Self {
        if self.is_negative() {
            -self
        } else {
            self.clone()
        }
    }
    fn abs_sub(&self, other: &Self) -> Self {
        if self <= other {
            Self::zero()
        } else {
            self - other
        }
    }
    fn signum(&self) -> Self {
        match B::sign(&self.0) {
            Ordering::Less => Self::from_integer(-1),
            Ordering::Equal => Self::zero(),
            Ordering::Greater => Self::one(),
        }
    }
    fn is_positive(&self) -> bool {
        B::sign(&self.0) == Ordering::Greater
    }
    fn is_negative(&self) -> bool {
        B::sign(&self.0) == Ordering::Less
    }
}

impl<B: Backend> ToPrimitive for Rational<B> {
    /// The integer part (toward zero), if it fits.
    fn to_i64(&self) -> Option<i64> {
        self.trunc().numer_string().parse().ok()
    }
    /// The integer part (toward zero), if it fits.
    fn to_u64(&self) -> Option<u64> {
        self.trunc().numer_string().parse().ok()
    }
    /// The nearest `f64` (always `Some`; `±inf` beyond its range).
    fn to_f64(&self) -> Option<f64> {
        Some(Rational::to_f64(self))
    }
}

impl<B: Backend> Sum for Rational<B> {
    fn sum<I: Iterator<Item = Self>>(iter: I) -> Self {
        iter.fold(Self::zero(), |a, b| &a + &b)
    }
}

impl<'a, B: Backend> Sum<&'a Rational<B>> for Rational<B> {
    fn sum<I: Iterator<Item = &'a Self>>(iter: I) -> Self {
        iter.fold(Self::zero(), |a, b| &a + b)
    }
}

impl<B: Backend> Product for Rational<B> {
    fn product<I: Iterator<Item = Self>>(iter: I) -> Self {
        iter.fold(Self::one(), |a, b| &a * &b)
    }
}

impl<B: Backend> Scalar for Rational<B> {
    const NAME: &'static str = "exact";
    fn show(&self) -> String {
        self.to_string()
    }
    const EXACT: bool = true;
    fn from_ratio(num: i64, den: i64) -> Self {
        Self::checked_ratio(num, den).expect("a nonzero denominator")
    }
    fn is_finite(&self) -> bool {
        true
    }
    fn to_f64(&self) -> f64 {
        Rational::to_f64(self)
    }
    fn rounding_slack() -> Self {
        Self::zero()
    }
    type Unbounded = Self;
    fn unbounded(&self) -> Self {
        self.clone()
    }
    fn from_unbounded(x: &Self) -> Self {
        x.clone()
    }
    fn mul_add(a: &Self, b: &Self, c: &Self) -> Self {
        &(a * b) + c
    }
    fn from_literal(_: f64, _: f32, num: &str, den: &str) -> Self {
        Self::from_decimal(num, den).expect("generated literal digits")
    }
}
