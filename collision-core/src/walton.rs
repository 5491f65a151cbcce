//! The parameters of the Walton contact law (`docs/derivation.md` §15.1): the rough-ball law
//! of [`crate::Restitution`] with the tangential restitution chosen per contact,
//!
//! ```text
//! beta = min(beta0, beta_C),   1 + beta_C = mu (1 + e) (b / a) |dn| / |t|,
//! ```
//!
//! `beta_C` being the `beta` at which the tangential impulse is exactly `mu` times the
//! normal one: the contact sticks (`t+ = -beta0 t`) while the tangential impulse that would
//! take stays within the Coulomb cone, and slides along its edge otherwise. The generated
//! kernels `kernels::dN::walton::{free, fixed, ..}` take a `&Walton<T>` beside the balls.
//!
//! ```
//! use collision_core::{kernels::d3, Ball, State3, Walton};
//! // A spinning ball falling onto a wall (body 1, immovable, below: nu points up).
//! let ball: Ball<f64> = Ball { inv_mass: 1.0, radius: 1.0, gamma2: 0.4 };
//! let falling = State3::from_omega([0.0, 0.0, 20.0], [0.0, -1.0, 0.0]);
//! let nu = [0.0, 1.0, 0.0];
//! let after = |mu| d3::walton::fixed(&nu, &1.0, &ball, &Walton::new(1.0, mu, 1.0).unwrap(),
//!     &State3::zero(), &falling);
//! // Sliding: the tangential impulse (on body 2, mass 1) is mu times the normal one, 2.
//! assert!((after(0.1).velocity[0].abs() - 0.2).abs() < 1e-15);
//! assert!(Walton::new(0.5, -0.1, 0.0).is_err()); // mu < 0
//! ```

use crate::error::{Field, InputError};
use crate::restitution::check;
use crate::scalar::Scalar;

/// Normal restitution, friction coefficient and sticking tangential restitution of the
/// Walton law.
#[derive(Clone, Debug, PartialEq)]
pub struct Walton<T> {
    /// Normal restitution `e` in `[0, 1]`: `dn+ = -e dn`.
    pub e: T,
    /// Friction coefficient `mu >= 0`: `|J_t| <= mu |J_n|`.
    pub mu: T,
    /// Tangential restitution `beta0` in `[-1, 1]` while the contact sticks.
    pub beta0: T,
}

impl<T: Scalar> Walton<T> {
    /// `(e, mu, beta0)`, checked: each finite (no NaN), `0 <= e <= 1`, `mu >= 0`,
    /// `-1 <= beta0 <= 1`; the error names the field ([`Field::RestitutionE`],
    /// [`Field::FrictionMu`], [`Field::WaltonBeta0`]).
    pub fn new(e: T, mu: T, beta0: T) -> Result<Self, InputError> {
        let one = T::one();
        check(&e, (&T::zero(), &one), "[0, 1]", Field::RestitutionE)?;
        // The negated conjunction also refuses NaN, for which every comparison is false.
        if !(mu.is_finite() && mu >= T::zero()) {
            return Err(InputError::new(
                Field::FrictionMu,
                format!("must be finite and >= 0, got {}", mu.show()),
            ));
        }
        check(&beta0, (&-one.clone(), &one), "[-1, 1]", Field::WaltonBeta0)?;
        Ok(Walton { e, mu, beta0 })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ranges_are_checked_and_nan_is_refused() {
        assert!(Walton::new(0.0, 0.0, -1.0).is_ok());
        assert!(Walton::new(1.0, 1e9, 1.0).is_ok());
        for (e, mu, beta0, field) in [
            (-0.01, 0.5, 0.0, Field::RestitutionE),
            (f64::NAN, 0.5, 0.0, Field::RestitutionE),
            (0.5, -1e-300, 0.0, Field::FrictionMu),
            (0.5, f64::NAN, 0.0, Field::FrictionMu),
            (0.5, f64::INFINITY, 0.0, Field::FrictionMu),
            (0.5, 0.5, 1.01, Field::WaltonBeta0),
            (0.5, 0.5, f64::NAN, Field::WaltonBeta0),
        ] {
            let err = Walton::new(e, mu, beta0).unwrap_err();
            assert_eq!(err.field, field, "({e}, {mu}, {beta0})");
        }
        let err = Walton::new(0.5f64, -2.0, 0.0).unwrap_err();
        assert_eq!(
            err.to_string(),
            "friction mu: must be finite and >= 0, got -2.0"
        );
    }
}
