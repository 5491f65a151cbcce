//! Ball parameters in the form the kernels take: inverse mass, radius and
//! `gamma^2 = 2 lambda / R^2`, all finite at the extremes (an immovable body has
//! `inv_mass = 0`; a point mass has `gamma2 = 0`).

use crate::error::{BodyField, Field, InputError};
use crate::scalar::{two, within_slack, Scalar};

/// The kernels' parameters of one ball.
///
/// - `inv_mass` `w = 1/m >= 0`; `0` is an immovable (infinitely massive) body.
/// - `radius` `R > 0`.
/// - `gamma2` `g = gamma^2 = 2 lambda / R^2` in `[0, 2/n]`, with
///   `lambda = (1/(n m)) integral |b|^2 dmu(b)`: `0` a point mass, `2/(n+2)` uniform, `2/n`
///   a shell. In 3D `g = I / (m R^2)`.
#[derive(Clone, Debug, PartialEq)]
pub struct Ball<T> {
    pub inv_mass: T,
    pub radius: T,
    pub gamma2: T,
}

/// A mass, or an immovable body.
#[derive(Clone, Debug, PartialEq)]
pub enum Mass<T> {
    Finite(T),
    Infinite,
}

/// How the radial mass distribution is given.
#[derive(Clone, Debug, PartialEq)]
pub enum Inertia<T> {
    /// `lambda`, in `[0, R^2/n]`.
    Lambda(T),
    /// `gamma^2 = 2 lambda / R^2`, in `[0, 2/n]`.
    Gamma2(T),
    /// Uniform density: `lambda = R^2/(n+2)`.
    Uniform,
    /// All mass on the sphere: `lambda = R^2/n`.
    Shell,
}

fn err(field: BodyField, message: impl Into<String>) -> InputError {
    InputError::new(Field::Body(0, field), message)
}

fn finite<T: Scalar>(x: &T, field: BodyField) -> Result<(), InputError> {
    if x.is_finite() {
        Ok(())
    } else {
        Err(err(
            field,
            format!("must be a finite number, got {}", x.show()),
        ))
    }
}

/// Bring a value that may exceed `bound` by its own rounding back to the bound; reject
/// anything outside `[0, bound]` beyond that slack.
fn in_range<T: Scalar>(x: T, bound: &T, field: BodyField, what: &str) -> Result<T, InputError> {
    finite(&x, field)?;
    if x < T::zero() || !within_slack(&x, bound) {
        return Err(err(
            field,
            format!(
                "must be in [0, {what}] = [0, {}], got {}",
                bound.show(),
                x.show()
            ),
        ));
    }
    Ok(if x > *bound { bound.clone() } else { x })
}

impl<T: Scalar> Ball<T> {
    /// A validated ball in R^`dim`. Errors name the field (body index 0; see
    /// [`InputError::at_body`]).
    pub fn new(
        dim: usize,
        mass: Mass<T>,
        radius: T,
        inertia: Inertia<T>,
    ) -> Result<Self, InputError> {
        finite(&radius, BodyField::Radius)?;
        if radius <= T::zero() {
            return Err(err(
                BodyField::Radius,
                format!("must be positive, got {}", radius.show()),
            ));
        }
        let inv_mass = match mass {
            Mass::Infinite => T::zero(),
            Mass::Finite(m) => {
                finite(&m, BodyField::Mass)?;
                if m <= T::zero() {
                    return Err(err(
                        BodyField::Mass,
                        format!("must be positive (or \"inf\"), got {}", m.show()),
                    ));
                }
                let w = T::one() / m.clone();
                if !w.is_finite() {
                    return Err(err(
                        BodyField::Mass,
                        format!("is too small: 1/mass overflows, got {}", m.show()),
                    ));
                }
                w
            }
        };
        let n = T::from_ratio(dim as i64, 1);
        let shell = two::<T>() / n.clone();
        let gamma2 = match inertia {
            Inertia::Uniform => two::<T>() / (n + two::<T>()),
            Inertia::Shell => shell,
            Inertia::Gamma2(g) => in_range(g, &shell, BodyField::Gamma2, "2/n")?,
            Inertia::Lambda(l) => {
                let r2 = radius.clone() * radius.clone();
                if !r2.is_finite() || r2.is_zero() {
                    return Err(err(
                        BodyField::Radius,
                        format!(
                            "R^2 is out of range for {}, got R = {}; give gamma2 instead of lambda",
                            T::NAME,
                            radius.show()
                        ),
                    ));
                }
                let l = in_range(l, &(r2.clone() / n), BodyField::Lambda, "R^2/n")?;
                two::<T>() * l / r2
            }
        };
        let ball = Ball {
            inv_mass,
            radius,
            gamma2,
        };
        ball.validate(dim)?;
        Ok(ball)
    }

    /// An immovable ball: `inv_mass = 0`. Its inertia is never used; `gamma2` is set to the
    /// uniform value so that the ball is valid as given.
    pub fn immovable(dim: usize, radius: T) -> Self {
        let n = T::from_ratio(dim as i64, 1);
        Ball {
            inv_mass: T::zero(),
            radius,
            gamma2: two::<T>() / (n + two::<T>()),
        }
    }

    pub fn is_immovable(&self) -> bool {
        self.inv_mass.is_zero()
    }

    /// `lambda = gamma^2 R^2 / 2`.
    pub fn lambda(&self) -> T {
        self.gamma2.clone() * self.radius.clone() * self.radius.clone() / two::<T>()
    }

    /// Check the invariants of the fields as stored (the fields are public): finite,
    /// `inv_mass >= 0`, `radius > 0`, `0 <= gamma2 <= 2/n` exactly.
    pub fn validate(&self, dim: usize) -> Result<(), InputError> {
        finite(&self.inv_mass, BodyField::Mass)?;
        finite(&self.radius, BodyField::Radius)?;
        finite(&self.gamma2, BodyField::Gamma2)?;
        if self.inv_mass < T::zero() {
            return Err(err(BodyField::Mass, "inverse mass must be >= 0"));
        }
        if self.radius <= T::zero() {
            return Err(err(BodyField::Radius, "must be positive"));
        }
        let shell = two::<T>() / T::from_ratio(dim as i64, 1);
        if self.gamma2 < T::zero() || self.gamma2 > shell {
            return Err(err(
                BodyField::Gamma2,
                format!(
                    "must be in [0, 2/n] = [0, {}], got {}",
                    shell.show(),
                    self.gamma2.show()
                ),
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Exact;

    fn q(n: i64, d: i64) -> Exact {
        Exact::from_ratio(n, d)
    }

    #[test]
    fn named_distributions_give_their_lambda() {
        let uniform = Ball::new(3, Mass::Finite(q(2, 1)), q(3, 2), Inertia::Uniform).unwrap();
        assert_eq!(uniform.lambda(), q(9, 4) / q(5, 1));
        assert_eq!(uniform.inv_mass, q(1, 2));
        let shell = Ball::new(4, Mass::Infinite, q(1, 1), Inertia::Shell).unwrap();
        assert_eq!(shell.lambda(), q(1, 4));
        assert!(shell.is_immovable());
        let l = Ball::new(3, Mass::Finite(q(1, 1)), q(1, 1), Inertia::Lambda(q(1, 5))).unwrap();
        assert_eq!(l.gamma2, q(2, 5));
    }

    #[test]
    fn out_of_range_inputs_name_their_field() {
        let e = Ball::new(3, Mass::Finite(q(1, 1)), q(1, 1), Inertia::Lambda(q(1, 2))).unwrap_err();
        assert_eq!(e.field, Field::Body(0, BodyField::Lambda));
        let e = Ball::new(3, Mass::Finite(q(-1, 1)), q(1, 1), Inertia::Uniform).unwrap_err();
        assert_eq!(e.field, Field::Body(0, BodyField::Mass));
        let e = Ball::new(2, Mass::Finite(1.0), 0.0, Inertia::Uniform).unwrap_err();
        assert_eq!(e.field, Field::Body(0, BodyField::Radius));
        let e = Ball::new(2, Mass::Finite(f64::NAN), 1.0, Inertia::Uniform).unwrap_err();
        assert_eq!(e.field, Field::Body(0, BodyField::Mass));
        let e = Ball::new(2, Mass::Finite(1.0), 1.0, Inertia::Gamma2(-0.1)).unwrap_err();
        assert_eq!(e.field, Field::Body(0, BodyField::Gamma2));
    }

    #[test]
    fn a_decimal_shell_is_accepted_in_floats_only() {
        // R^2/n for R = 1, n = 3 written in decimal, rounded up in its last digit.
        let b = Ball::new(
            3,
            Mass::Finite(1.0),
            1.0,
            Inertia::Lambda(0.33333333333333337),
        )
        .unwrap();
        assert_eq!(b.gamma2, 2.0 / 3.0);
        let exact = Ball::new(
            3,
            Mass::Finite(q(1, 1)),
            q(1, 1),
            Inertia::Lambda(q(33_333_333_333_333_337, 100_000_000_000_000_000)),
        );
        assert!(exact.is_err());
    }
}
