//! Velocity and angular-velocity components below the normal range of the float type.
//!
//! A component read below the normal range (`|x| < 2.2e-308` in `f64`) is rounded with an
//! absolute error of up to `2^-1075` ([`SUBNORMAL_ERROR`]) instead of `eps/2` of itself. It
//! is taken when that error is within `eps/2` of the scale it is measured against, as the
//! rounding of any normal-range input is:
//!
//! - a velocity component against the contact's speed scale
//!   `V = max_i max(|u_i|, R_i |U_i|)` (entries' magnitudes): taken iff `V >= 2^-1022`;
//! - an entry of body `i`'s angular velocity, which moves the contact point by `R_i` times
//!   its error: taken iff `V / R_i >= 2^-1022`.
//!
//! So `[1, 1e-310]` is taken (the `1e-310` is off by at most `eps/2` of the speed), while a
//! case whose whole speed scale is below the range, or a spin entry of `7e-320` on a ball of
//! radius `1e200`, is refused naming the component: f64 cannot carry it to its precision,
//! and `--exact` reads it as written. (A normal's components are measured against 1 and are
//! always taken; body scalars below the range are refused on their own, see
//! [`crate::number::scalar_from_json`].)

use crate::body::{BodyInput, Spin};
use crate::error::CaseError;
use crate::number::{InputScalar, SUBNORMAL_ERROR};

/// The fields of the components read below the normal range.
#[derive(Debug, Default)]
pub(crate) struct Tiny {
    /// Velocity components, of either body.
    pub velocity: Vec<String>,
    /// Angular-velocity entries, per body.
    pub spin: [Vec<String>; 2],
}

/// The largest magnitude of `xs`, in `f64` (exact for `f64` inputs).
fn max_abs<'a, T: InputScalar + 'a>(xs: impl IntoIterator<Item = &'a T>) -> f64 {
    xs.into_iter().map(|x| x.to_f64().abs()).fold(0.0, f64::max)
}

/// The magnitudes of the angular velocity's entries, in the form given.
fn spin_scale<T: InputScalar>(spin: &Spin<T>) -> f64 {
    match spin {
        Spin::Matrix(rows) => max_abs(rows.iter().flatten()),
        Spin::Scalar(c) => c.to_f64().abs(),
        Spin::Omega(omega) => max_abs(omega),
    }
}

impl Tiny {
    /// Refuse the first component whose rounding error is beyond `eps/2` of its scale (see
    /// the module documentation).
    pub(crate) fn check<T: InputScalar>(
        &self,
        bodies: &[BodyInput<T>; 2],
    ) -> Result<(), CaseError> {
        if self.velocity.is_empty() && self.spin.iter().all(Vec::is_empty) {
            return Ok(());
        }
        let radius = |b: usize| bodies[b].radius.to_f64();
        let speed = (0..2)
            .map(|b| max_abs(&bodies[b].velocity).max(radius(b) * spin_scale(&bodies[b].spin)))
            .fold(0.0, f64::max);
        let tail = format!(
            "a component below the normal range of {} (magnitudes under {:e}) is read with an \
             error of up to {SUBNORMAL_ERROR}",
            T::NAME,
            f64::MIN_POSITIVE
        );
        if let Some(field) = self.velocity.first().filter(|_| speed < f64::MIN_POSITIVE) {
            return Err(CaseError::new(
                field,
                format!(
                    "{tail}, beyond the rounding allowance of the contact's speed scale (up to \
                     {speed:e}, itself below the normal range); --exact reads it as written"
                ),
            ));
        }
        for (b, fields) in self.spin.iter().enumerate() {
            let r = radius(b);
            // V / R >= 2^-1022, without the quotient's underflow.
            if let Some(field) = fields.first().filter(|_| speed < f64::MIN_POSITIVE * r) {
                return Err(CaseError::new(
                    field,
                    format!(
                        "{tail}, and with body {}'s radius {r:e} it moves the contact point by \
                         up to {r:e} x 2^-1075, beyond the rounding allowance of the contact's \
                         speed scale (up to {speed:e}); --exact reads it as written",
                        b + 1,
                    ),
                ));
            }
        }
        Ok(())
    }
}
