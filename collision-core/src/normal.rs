//! Exactly unit normals for exact arithmetic.

use crate::scalar::{two, Scalar};

/// The inverse stereographic projection of `y` in R^(n-1) onto the unit sphere in R^n:
/// `nu = (2 y, |y|^2 - 1) / (|y|^2 + 1)`. With rational `y` the normal is exactly unit
/// (`|nu|^2 = 1` in [`crate::Exact`]), as the checked `collide` requires in exact mode; every
/// rational point of the sphere but the north pole arises this way.
pub fn stereographic_normal<T: Scalar>(y: &[T]) -> Vec<T> {
    let y2 = y.iter().fold(T::zero(), |s, x| s + x.clone() * x.clone());
    let den = y2.clone() + T::one();
    y.iter()
        .map(|x| two::<T>() * x.clone() / den.clone())
        .chain(std::iter::once((y2 - T::one()) / den.clone()))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Exact;

    #[test]
    fn rational_points_give_exactly_unit_normals() {
        let y = [
            Exact::from_ratio(1, 2),
            Exact::from_ratio(-3, 7),
            Exact::from_ratio(5, 1),
        ];
        let nu = stereographic_normal(&y);
        assert_eq!(nu.len(), 4);
        let norm2: Exact = nu.iter().map(|x| x * x).sum();
        assert_eq!(norm2, Exact::from_ratio(1, 1));
        assert_eq!(
            stereographic_normal(&[Exact::from_ratio(1, 2)]),
            vec![Exact::from_ratio(4, 5), Exact::from_ratio(-3, 5)]
        );
    }
}
