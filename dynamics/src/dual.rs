//! Forward-mode dual numbers `a + b eps`, `eps^2 = 0`, as a [`Scalar`], so that the generated
//! kernels (generic over `Scalar`) compute a map and its directional derivative in one run:
//!
//! ```text
//! f(x + eps dx) = f(x) + eps Df(x)[dx]        (exactly, for any rational function f)
//! ```
//!
//! `Dual<f64>` gives the derivative to rounding, `Dual<Exact>` exactly: no finite differences,
//! and no second closed form of the derivative to trust. Order and sign are those of the real
//! part (`a` decides `<`, `abs`, `signum`): the kernels are straight-line code and never
//! branch on them, so the derivative is that of the one branch they compute.

use collision_core::Scalar;
use num_traits::{Num, One, Signed, Zero};
use std::cmp::Ordering;
use std::fmt;
use std::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Rem, Sub, SubAssign};

/// `re + eps du`, `eps^2 = 0`: a value and its derivative along one direction.
#[derive(Clone, Debug, PartialEq)]
pub struct Dual<T> {
    /// The value.
    pub re: T,
    /// The derivative along the direction the inputs were seeded with.
    pub du: T,
}

impl<T: Scalar> Dual<T> {
    /// `re + eps du`.
    pub fn new(re: T, du: T) -> Self {
        Self { re, du }
    }

    /// A constant: `re + eps 0`.
    pub fn constant(re: T) -> Self {
        Self { re, du: T::zero() }
    }
}

impl<T: Scalar> Add for Dual<T> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self::new(self.re + o.re, self.du + o.du)
    }
}

impl<T: Scalar> Sub for Dual<T> {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Self::new(self.re - o.re, self.du - o.du)
    }
}

/// `(a + eps a')(b + eps b') = a b + eps (a' b + a b')`.
impl<T: Scalar> Mul for Dual<T> {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        let du = self.du * o.re.clone() + self.re.clone() * o.du;
        Self::new(self.re * o.re, du)
    }
}

/// `(a + eps a') / (b + eps b') = a/b + eps (a' b - a b') / b^2`.
impl<T: Scalar> Div for Dual<T> {
    type Output = Self;
    fn div(self, o: Self) -> Self {
        let q = self.re / o.re.clone();
        let du = (self.du - q.clone() * o.du) / o.re;
        Self::new(q, du)
    }
}

/// The remainder of the real parts, with the derivative of `a - b trunc(a/b)` away from its
/// jumps (`num_traits::Num` asks for it; the kernels never use it).
impl<T: Scalar> Rem for Dual<T> {
    type Output = Self;
    fn rem(self, o: Self) -> Self {
        let r = self.re.clone() % o.re.clone();
        let k = (self.re - r.clone()) / o.re;
        Self::new(r, self.du - k * o.du)
    }
}

impl<T: Scalar> Neg for Dual<T> {
    type Output = Self;
    fn neg(self) -> Self {
        Self::new(-self.re, -self.du)
    }
}

macro_rules! by_ref_and_assign {
    ($($op:ident $f:ident $assign:ident $fa:ident;)*) => {$(
        impl<'a, T: Scalar> $op<&'a Dual<T>> for &'a Dual<T> {
            type Output = Dual<T>;
            fn $f(self, o: &'a Dual<T>) -> Dual<T> {
                $op::$f(self.clone(), o.clone())
            }
        }
        impl<T: Scalar> $assign for Dual<T> {
            fn $fa(&mut self, o: Self) {
                *self = $op::$f(self.clone(), o);
            }
        }
    )*};
}

by_ref_and_assign! {
    Add add AddAssign add_assign;
    Sub sub SubAssign sub_assign;
    Mul mul MulAssign mul_assign;
    Div div DivAssign div_assign;
}

impl<T: Scalar> Neg for &Dual<T> {
    type Output = Dual<T>;
    fn neg(self) -> Dual<T> {
        -self.clone()
    }
}

impl<T: Scalar> Zero for Dual<T> {
    fn zero() -> Self {
        Self::constant(T::zero())
    }
    fn is_zero(&self) -> bool {
        self.re.is_zero() && self.du.is_zero()
    }
}

impl<T: Scalar> One for Dual<T> {
    fn one() -> Self {
        Self::constant(T::one())
    }
}

impl<T: Scalar> Num for Dual<T> {
    type FromStrRadixErr = ();
    fn from_str_radix(_: &str, _: u32) -> Result<Self, ()> {
        Err(())
    }
}

/// Sign and magnitude of the real part: `|a + eps a'| = sign(a) (a + eps a')`.
impl<T: Scalar> Signed for Dual<T> {
    fn abs(&self) -> Self {
        if self.re.is_negative() {
            -self.clone()
        } else {
            self.clone()
        }
    }
    fn abs_sub(&self, o: &Self) -> Self {
        if self.re <= o.re {
            Self::zero()
        } else {
            self.clone() - o.clone()
        }
    }
    fn signum(&self) -> Self {
        Self::constant(self.re.signum())
    }
    fn is_positive(&self) -> bool {
        self.re.is_positive()
    }
    fn is_negative(&self) -> bool {
        self.re.is_negative()
    }
}

/// Ordered by the real part.
impl<T: Scalar> PartialOrd for Dual<T> {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        self.re.partial_cmp(&o.re)
    }
}

impl<T: Scalar> fmt::Display for Dual<T> {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(f, "{} + {} eps", self.re, self.du)
    }
}

impl<T: Scalar> Scalar for Dual<T> {
    const NAME: &'static str = "dual";
    const EXACT: bool = T::EXACT;
    fn from_ratio(num: i64, den: i64) -> Self {
        Self::constant(T::from_ratio(num, den))
    }
    fn is_finite(&self) -> bool {
        self.re.is_finite() && self.du.is_finite()
    }
    fn to_f64(&self) -> f64 {
        self.re.to_f64()
    }
    fn show(&self) -> String {
        format!("{} + {} eps", self.re.show(), self.du.show())
    }
    fn rounding_slack() -> Self {
        Self::constant(T::rounding_slack())
    }
    /// The dual numbers themselves: they are for the unchecked kernels, which never widen.
    type Unbounded = Self;
    fn unbounded(&self) -> Self {
        self.clone()
    }
    fn from_unbounded(x: &Self) -> Self {
        x.clone()
    }
    fn mul_add(a: &Self, b: &Self, c: &Self) -> Self {
        a.clone() * b.clone() + c.clone()
    }
    fn from_literal(x64: f64, x32: f32, num: &str, den: &str) -> Self {
        Self::constant(T::from_literal(x64, x32, num, den))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use collision_core::Exact;

    fn q(n: i64, d: i64) -> Exact {
        Exact::from_ratio(n, d)
    }

    /// `f(x) = (x^2 + 1) / (x - 3)`, `f'(x) = (x^2 - 6x - 1) / (x - 3)^2`, at `x = 1/2`:
    /// `f = -1/2`, `f' = (1/4 - 3 - 1) / (25/4) = -15/25 = -3/5`, exactly.
    #[test]
    fn quotient_rule_is_exact_in_rationals() {
        let x = Dual::new(q(1, 2), q(1, 1));
        let one = Dual::<Exact>::one();
        let three = Dual::<Exact>::from_ratio(3, 1);
        let f = (&(&x * &x) + &one) / (x - three);
        assert_eq!(f, Dual::new(q(-1, 2), q(-3, 5)));
    }

    #[test]
    fn order_sign_and_abs_follow_the_real_part() {
        let a = Dual::new(-2.0, 5.0);
        let b = Dual::new(1.0, -7.0);
        assert!(a < b);
        assert_eq!(a.abs(), Dual::new(2.0, -5.0));
        assert_eq!(b.abs(), b);
        assert_eq!(a.signum(), Dual::constant(-1.0));
        assert!(a.is_negative() && b.is_positive());
        let mut c = a.clone();
        c *= b.clone();
        assert_eq!(c, Dual::new(-2.0, -2.0 * -7.0 + 5.0));
        assert_eq!(
            Dual::new(7.0, 1.0) % Dual::new(2.0, 1.0),
            Dual::new(1.0, -2.0)
        );
    }
}
