//! The parameters of the rough-ball contact law (`docs/derivation.md` §15): at contact, the
//! normal relative velocity of the contact point becomes `-e` times itself and its
//! tangential part (the slip) `-beta` times itself,
//!
//! ```text
//! dn+ = -e dn,   t+ = -beta t,   0 <= e <= 1,   -1 <= beta <= 1,
//! ```
//!
//! by one impulse at the contact point. `(1, 1)` is the no-slip map, `(1, -1)` the smooth
//! (specular) one. The generated kernels `kernels::dN::rough::{free, fixed, ..}` take a
//! `&Restitution<T>` beside the balls.
//!
//! ```
//! use collision_core::{kernels::d3, Ball, Restitution, State3};
//! // A ball falling onto a wall (body 1, immovable, below: nu points up).
//! let ball: Ball<f64> = Ball { inv_mass: 1.0, radius: 1.0, gamma2: 0.4 };
//! let law = Restitution::new(0.9, 0.5).unwrap();
//! let falling = State3::from_omega([0.0, 0.0, 2.0], [0.0, -1.0, 0.0]);
//! let after = d3::rough::fixed(&[0.0, 1.0, 0.0], &1.0, &ball, &law, &State3::zero(), &falling);
//! assert!((after.velocity[1] - 0.9).abs() < 1e-15); // dn+ = -e dn (one rounding of 1.9 - 1)
//! assert!(Restitution::new(1.5, 0.0).is_err()); // e out of [0, 1]
//! ```

use crate::error::{Field, InputError};
use crate::scalar::Scalar;

/// Normal and tangential restitution of the rough-ball law.
#[derive(Clone, Debug, PartialEq)]
pub struct Restitution<T> {
    /// Normal restitution `e` in `[0, 1]`: `dn+ = -e dn`.
    pub e: T,
    /// Tangential restitution `beta` in `[-1, 1]`: `t+ = -beta t`.
    pub beta: T,
}

impl<T: Scalar> Restitution<T> {
    /// `(e, beta)`, checked: each finite (no NaN), `0 <= e <= 1`, `-1 <= beta <= 1`; the
    /// error names the field ([`Field::RestitutionE`], [`Field::RestitutionBeta`]).
    pub fn new(e: T, beta: T) -> Result<Self, InputError> {
        let one = T::one();
        let minus_one = -T::one();
        check(&e, (&T::zero(), &one), "[0, 1]", Field::RestitutionE)?;
        check(&beta, (&minus_one, &one), "[-1, 1]", Field::RestitutionBeta)?;
        Ok(Restitution { e, beta })
    }

    /// `(1, 1)`: the no-slip law.
    pub fn no_slip() -> Self {
        Restitution {
            e: T::one(),
            beta: T::one(),
        }
    }

    /// `(1, -1)`: the smooth (specular) law.
    pub fn smooth() -> Self {
        Restitution {
            e: T::one(),
            beta: -T::one(),
        }
    }
}

pub(crate) fn check<T: Scalar>(
    x: &T,
    (lo, hi): (&T, &T),
    range: &str,
    field: Field,
) -> Result<(), InputError> {
    // The negated conjunction also refuses NaN, for which every comparison is false.
    if !(x.is_finite() && lo <= x && x <= hi) {
        return Err(InputError::new(
            field,
            format!("must be in {range}, got {}", x.show()),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Exact;

    #[test]
    fn the_ranges_are_closed_and_nan_is_refused() {
        assert!(Restitution::new(0.0, -1.0).is_ok());
        assert!(Restitution::new(1.0, 1.0).is_ok());
        for (e, beta, field) in [
            (-0.01, 0.0, Field::RestitutionE),
            (1.01, 0.0, Field::RestitutionE),
            (f64::NAN, 0.0, Field::RestitutionE),
            (f64::INFINITY, 0.0, Field::RestitutionE),
            (0.5, -1.01, Field::RestitutionBeta),
            (0.5, 1.01, Field::RestitutionBeta),
            (0.5, f64::NAN, Field::RestitutionBeta),
        ] {
            let err = Restitution::new(e, beta).unwrap_err();
            assert_eq!(err.field, field, "e = {e}, beta = {beta}");
        }
        let err = Restitution::new(1.5f64, 0.0).unwrap_err();
        assert_eq!(err.to_string(), "restitution e: must be in [0, 1], got 1.5");
    }

    #[test]
    fn exact_bounds_are_exact() {
        let q = |p, d| Exact::checked_ratio(p, d).unwrap();
        assert!(Restitution::new(q(1, 1), q(-1, 1)).is_ok());
        let err = Restitution::new(q(1, 2), q(-1000001, 1000000)).unwrap_err();
        assert_eq!(err.field, Field::RestitutionBeta);
    }
}
