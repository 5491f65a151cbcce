//! Ball parameters in the form the kernels take: inverse mass, radius and
//! `gamma^2 = 2 lambda / R^2`, all finite at the extremes (an immovable body has
//! `inv_mass = 0`; a point mass has `gamma2 = 0`).

use crate::allowance;
use crate::error::{BodyField, Field, InputError};
use crate::scalar::{self, two, Scalar};
use num_traits::Signed;

/// The kernels' parameters of one ball.
///
/// - `inv_mass` `w = 1/m >= 0`; `0` is an immovable (infinitely massive) body.
/// - `radius` `R > 0`.
/// - `gamma2` `g = gamma^2 = 2 lambda / R^2` in `[0, 2/n]`, with
///   `lambda = (1/(n m)) integral |b|^2 dmu(b)`: `0` a point mass, `2/(n+2)` uniform, `2/n`
///   a shell. In 3D `g = I / (m R^2)`.
#[derive(Clone, Debug, PartialEq)]
pub struct Ball<T> {
    /// Inverse mass `w = 1/m >= 0` (0: immovable).
    pub inv_mass: T,
    /// Radius `R > 0`.
    pub radius: T,
    /// `gamma^2 = 2 lambda / R^2`, in `[0, 2/n]`.
    pub gamma2: T,
}

/// A mass, or an immovable body.
#[derive(Clone, Debug, PartialEq)]
pub enum Mass<T> {
    /// A mass `m > 0`; the ball's `inv_mass` is `1/m`.
    Finite(T),
    /// An immovable body: `inv_mass = 0`.
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

/// `x` in `[0, bound]` under [the rounding allowance](crate::allowance) (scale `bound`):
/// clamped to the range, or an error naming `field`.
fn in_range<T: Scalar>(x: &T, bound: &T, field: BodyField, what: &str) -> Result<T, InputError> {
    allowance::within(x, &T::zero(), bound, &scalar::allowance(bound)).ok_or_else(|| {
        err(
            field,
            format!(
                "must be in [0, {what}] = [0, {}], got {}",
                bound.show(),
                x.show()
            ),
        )
    })
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
        let gamma2 = match inertia {
            Inertia::Uniform => two_over::<T>(dim + 2),
            Inertia::Shell => two_over::<T>(dim),
            Inertia::Gamma2(g) => {
                finite(&g, BodyField::Gamma2)?;
                in_range(&g, &two_over::<T>(dim), BodyField::Gamma2, "2/n")?
            }
            Inertia::Lambda(l) => {
                finite(&l, BodyField::Lambda)?;
                gamma2_of_lambda(dim, &radius, &l)?
            }
        };
        let ball = Ball {
            inv_mass,
            radius,
            gamma2,
        };
        // In exact arithmetic the checks above leave nothing for `validate` to refuse
        // (`R > 0`, `w = 1/m > 0` or `0`, `gamma2` in `[0, 2/n]` exactly, all finite), so it
        // runs in debug builds only; in floats it checks the rounded values.
        if T::EXACT {
            debug_assert!(ball.validate(dim).is_ok());
        } else {
            ball.validate(dim)?;
        }
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

    /// Whether the ball is immovable: `inv_mass = 0`.
    pub fn is_immovable(&self) -> bool {
        self.inv_mass.is_zero()
    }

    /// `lambda = gamma^2 R^2 / 2`.
    pub fn lambda(&self) -> T {
        self.gamma2.clone() * self.radius.clone() * self.radius.clone() / two::<T>()
    }

    /// Check the invariants of the fields as stored (the fields are public): finite,
    /// `inv_mass >= 0`, `radius > 0`, `0 <= gamma2 <= 2/n` under [the rounding
    /// allowance](crate::allowance).
    pub fn validate(&self, dim: usize) -> Result<(), InputError> {
        self.clamped(dim).map(|_| ())
    }

    /// The ball after [`Ball::validate`]'s checks, with `gamma2` clamped to `[0, 2/n]`.
    pub(crate) fn clamped(&self, dim: usize) -> Result<Self, InputError> {
        finite(&self.inv_mass, BodyField::Mass)?;
        finite(&self.radius, BodyField::Radius)?;
        finite(&self.gamma2, BodyField::Gamma2)?;
        if self.inv_mass < T::zero() {
            return Err(err(BodyField::Mass, "inverse mass must be >= 0"));
        }
        if self.radius <= T::zero() {
            return Err(err(BodyField::Radius, "must be positive"));
        }
        let shell = two_over::<T>(dim);
        Ok(Ball {
            gamma2: in_range(&self.gamma2, &shell, BodyField::Gamma2, "2/n")?,
            ..self.clone()
        })
    }
}

/// `2/k`: in exact arithmetic the reduced ratio made at once, in floats `2 / k` divided
/// (as before, so that every float keeps its bits).
fn two_over<T: Scalar>(k: usize) -> T {
    if T::EXACT {
        T::from_ratio(2, k as i64)
    } else {
        two::<T>() / T::from_ratio(k as i64, 1)
    }
}

/// `gamma2 = 2 lambda / R^2` of a finite `lambda`, with `lambda` in `[0, R^2/n]` and
/// `gamma2` in `[0, 2/n]` under the rounding allowance. Computed with an unbounded exponent
/// (`R^2` may be beyond the range of `T`); `gamma2` must come back to `T` within rounding,
/// that is not below `T`'s normal range.
fn gamma2_of_lambda<T: Scalar>(dim: usize, radius: &T, lambda: &T) -> Result<T, InputError> {
    let n = T::Unbounded::from_ratio(dim as i64, 1);
    let two = two::<T::Unbounded>();
    let r2 = radius.unbounded() * radius.unbounded();
    let l = in_range(
        &lambda.unbounded(),
        &(r2.clone() / n.clone()),
        BodyField::Lambda,
        "R^2/n",
    )?;
    if T::EXACT {
        // `0 <= lambda <= R^2/n` exactly gives `0 <= 2 lambda / R^2 <= 2/n`, and nothing is
        // rounded: the two checks below cannot fail, so they run in debug builds only.
        let gamma2 = two * l / r2;
        debug_assert!(
            in_range(&gamma2, &two_over(dim), BodyField::Lambda, "2/n").is_ok_and(|g| g == gamma2)
        );
        return Ok(T::from_unbounded(&gamma2));
    }
    let exact = in_range(
        &(two.clone() * l / r2),
        &(two / n),
        BodyField::Lambda,
        "2/n, as gamma2 = 2 lambda / R^2,",
    )?;
    let gamma2 = T::from_unbounded(&exact);
    if (gamma2.unbounded() - exact.clone()).abs() > scalar::allowance::<T::Unbounded>(&exact) {
        return Err(err(
            BodyField::Lambda,
            format!(
                "gamma2 = 2 lambda / R^2 = {} is below the normal range of {} and would lose \
                 precision; give gamma2 instead",
                exact.show(),
                T::NAME
            ),
        ));
    }
    Ok(gamma2)
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

    /// `x` moved by `k` ulps (positive: up, in magnitude).
    fn ulps(x: f64, k: i64) -> f64 {
        f64::from_bits((x.to_bits() as i64 + k) as u64)
    }

    fn ball(dim: usize, radius: f64, inertia: Inertia<f64>) -> Result<Ball<f64>, InputError> {
        Ball::new(dim, Mass::Finite(2.0), radius, inertia)
    }

    #[test]
    fn the_issues_thin_shell_in_f64_is_the_shell() {
        // R = 5, lambda = 25/3 computed in f64: gamma2 = 2 lambda / R^2 rounds one ulp above
        // 2/3, within rounding of the bound, and is clamped to it.
        let b = ball(3, 5.0, Inertia::Lambda(25.0 / 3.0)).unwrap();
        assert_eq!(b.gamma2, 2.0 / 3.0);
        assert_eq!(b.gamma2, ball(3, 5.0, Inertia::Shell).unwrap().gamma2);
    }

    #[test]
    fn bounds_take_eight_eps_of_their_scale_and_no_more() {
        // 4D: gamma2 <= 2/n = 1/2 (ulp 2^-53 = eps/2: 8 eps of 1/2 is 8 ulps); lambda <= R^2/n
        // = 1/4 for R = 1 (ulp eps/4: again 8 ulps). Beyond the bound by up to 8 eps of it:
        // clamped to the bound; one ulp more: refused. The same below 0.
        for (inertia, bound, field) in [
            (
                Inertia::Gamma2 as fn(f64) -> Inertia<f64>,
                0.5,
                BodyField::Gamma2,
            ),
            (Inertia::Lambda, 0.25, BodyField::Lambda),
        ] {
            let edge = ball(4, 1.0, inertia(ulps(bound, 8))).unwrap();
            assert_eq!(edge.gamma2, 0.5, "{field:?}");
            let e = ball(4, 1.0, inertia(ulps(bound, 9))).unwrap_err();
            assert_eq!(e.field, Field::Body(0, field));
            let allowance = 8.0 * f64::EPSILON * bound;
            assert_eq!(ball(4, 1.0, inertia(-allowance)).unwrap().gamma2, 0.0);
            let e = ball(4, 1.0, inertia(ulps(-allowance, 1))).unwrap_err();
            assert_eq!(e.field, Field::Body(0, field));
        }
        // Balls built by hand: validate takes the same allowance, collide clamps.
        let by_hand = Ball {
            inv_mass: 1.0,
            radius: 1.0,
            gamma2: ulps(0.5, 8),
        };
        assert!(by_hand.validate(4).is_ok());
        assert_eq!(by_hand.clamped(4).unwrap().gamma2, 0.5);
        let beyond = Ball {
            gamma2: ulps(0.5, 9),
            ..by_hand
        };
        assert!(beyond.validate(4).is_err());
        // Exact arithmetic takes no allowance.
        let exact = Ball::new(
            4,
            Mass::Finite(q(1, 1)),
            q(1, 1),
            Inertia::Gamma2(q(1, 2) + q(1, 1 << 62)),
        );
        assert_eq!(exact.unwrap_err().field, Field::Body(0, BodyField::Gamma2));
    }

    #[test]
    fn lambda_needs_no_representable_r_squared() {
        // R^2 = 1e400 is beyond f64; gamma2 = 2 lambda / R^2 = 2e-100 is not.
        let b = ball(3, 1e200, Inertia::Lambda(1e300)).unwrap();
        assert!(
            (b.gamma2 / 2e-100 - 1.0).abs() <= f64::EPSILON,
            "{}",
            b.gamma2
        );
        // A gamma2 that would land below the normal range is refused, naming lambda.
        let e = ball(3, 1e200, Inertia::Lambda(1e-250)).unwrap_err();
        assert_eq!(e.field, Field::Body(0, BodyField::Lambda));
        assert!(e.message.contains("below the normal range"), "{e}");
        // Given directly, such a gamma2 is exact and taken as it is.
        assert_eq!(
            ball(3, 1e200, Inertia::Gamma2(2e-320)).unwrap().gamma2,
            2e-320
        );
    }
}
