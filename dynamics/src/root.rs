//! Square roots where the arithmetic has them: contact times with spheres solve quadratics.
//! `f64` always (of a non-negative number); exact rationals only of perfect squares (a
//! rational table whose contact times stay rational, such as one of flat walls, never needs
//! one); dual numbers by `sqrt(a + eps b) = sqrt(a) + eps b / (2 sqrt(a))`.

use crate::dual::Dual;
use collision_core::{Exact, Scalar};
use num_traits::Signed;

/// A [`Scalar`] with a square root where it exists in the type.
pub trait Root: Scalar {
    /// `sqrt(self)`, or `None` if `self < 0` or the root is not of this type.
    fn root(&self) -> Option<Self>;
}

impl Root for f64 {
    fn root(&self) -> Option<f64> {
        (*self >= 0.0).then(|| self.sqrt())
    }
}

impl Root for Exact {
    fn root(&self) -> Option<Exact> {
        if self.is_negative() {
            return None;
        }
        self.exact_sqrt()
    }
}

impl<T: Root> Root for Dual<T> {
    fn root(&self) -> Option<Self> {
        let r = self.re.root()?;
        if r.is_zero() {
            return None;
        }
        let du = self.du.clone() / ((T::one() + T::one()) * r.clone());
        Some(Dual::new(r, du))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_roots_of_squares_only() {
        let q = |n, d| Exact::from_ratio(n, d);
        assert_eq!(q(9, 4).root(), Some(q(3, 2)));
        assert_eq!(q(2, 1).root(), None);
        assert_eq!(q(-1, 1).root(), None);
        // d/da sqrt(a) at a = 9/4 is 1/(2 * 3/2) = 1/3.
        assert_eq!(
            Dual::new(q(9, 4), q(1, 1)).root(),
            Some(Dual::new(q(3, 2), q(1, 3)))
        );
        assert_eq!(4.0f64.root(), Some(2.0));
        assert_eq!((-1.0f64).root(), None);
    }
}
