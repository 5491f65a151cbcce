//! The shape of what a ball touches, as far as the tangent map needs it: how the contact
//! normal `nu` turns when the contact point moves.
//!
//! With `nu` the unit normal from the boundary (or body 1) towards the ball (body 2) and `d`
//! the displacement of the ball's centre relative to the boundary (or of `x_j - x_i` for a
//! pair) at the contact, along the contact surface (`nu . d = 0`),
//!
//! ```text
//! dnu = kappa (I - nu nu^T) d
//! ```
//!
//! with the signed curvature `kappa` of the surface the centre moves on: 0 for a flat wall,
//! `1/R_eff` for a sphere seen from outside (`R_eff = R_obstacle + r`: `nu = (x - c)/R_eff`),
//! `-1/R_eff` for a sphere seen from inside (a container, `R_eff = R - r`:
//! `nu = (c - x)/R_eff`), `1/sigma` for two balls (`sigma = r_i + r_j`,
//! `nu = (x_j - x_i)/sigma`). A new kind of boundary is one variant here and one arm in
//! [`Geometry::curvature`].

use collision_core::Scalar;

/// The contact surface of a contact, by its curvature.
#[derive(Clone, Debug, PartialEq)]
pub enum Geometry<T> {
    /// A flat wall: `nu` constant.
    Flat,
    /// A sphere seen from outside (a fixed ball obstacle): `R_eff = R_obstacle + r`.
    Convex {
        /// `R_eff`, the radius of the sphere the ball's centre touches it on.
        r_eff: T,
    },
    /// A sphere seen from inside (a spherical container): `R_eff = R - r`.
    Concave {
        /// `R_eff`.
        r_eff: T,
    },
    /// Two balls: `sigma = r_i + r_j`; the displacement is that of `x_j - x_i`.
    Pair {
        /// The contact distance.
        sigma: T,
    },
}

impl<T: Scalar> Geometry<T> {
    /// `kappa`: `dnu = kappa (I - nu nu^T) d`.
    pub fn curvature(&self) -> T {
        match self {
            Geometry::Flat => T::zero(),
            Geometry::Convex { r_eff } => T::one() / r_eff.clone(),
            Geometry::Concave { r_eff } => -(T::one() / r_eff.clone()),
            Geometry::Pair { sigma } => T::one() / sigma.clone(),
        }
    }

    /// `dnu = kappa (I - nu nu^T) d` (see the module docs).
    pub fn dnu<const N: usize>(&self, nu: &[T; N], d: &[T; N]) -> [T; N] {
        let kappa = self.curvature();
        if kappa.is_zero() {
            return std::array::from_fn(|_| T::zero());
        }
        let along = dot(nu, d);
        std::array::from_fn(|k| kappa.clone() * (d[k].clone() - along.clone() * nu[k].clone()))
    }
}

/// `a . b`.
pub(crate) fn dot<T: Scalar>(a: &[T], b: &[T]) -> T {
    a.iter()
        .zip(b)
        .fold(T::zero(), |s, (x, y)| s + x.clone() * y.clone())
}

#[cfg(test)]
mod tests {
    use super::*;
    use collision_core::Exact;

    fn q(n: i64, d: i64) -> Exact {
        Exact::from_ratio(n, d)
    }

    /// On a sphere `x = c + R_eff nu`, moving the centre by `d` (tangent) turns `nu` by
    /// `d / R_eff`; the container's `nu = (c - x)/R_eff` turns the other way.
    #[test]
    fn normals_turn_with_the_surface_they_are_normal_to() {
        let nu = [q(3, 5), q(4, 5)];
        let d = [q(-4, 1), q(3, 1)]; // tangent: nu . d = 0
        let r = q(2, 1);
        let convex = Geometry::Convex { r_eff: r.clone() }.dnu(&nu, &d);
        assert_eq!(convex, [q(-2, 1), q(3, 2)]);
        let concave = Geometry::Concave { r_eff: r }.dnu(&nu, &d);
        assert_eq!(concave, [q(2, 1), q(-3, 2)]);
        assert_eq!(Geometry::<Exact>::Flat.dnu(&nu, &d), [q(0, 1), q(0, 1)]);
        // The normal part of d is projected away.
        let skew = [q(-4, 1) + q(3, 5), q(3, 1) + q(4, 5)];
        let pair = Geometry::Pair { sigma: q(1, 1) }.dnu(&nu, &skew);
        assert_eq!(pair, [q(-4, 1), q(3, 1)]);
    }
}
