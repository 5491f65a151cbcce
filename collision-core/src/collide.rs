//! The checked entry point: validate, then run the generated kernel of the dimension.

use crate::error::{BodyField, Field, InputError};
use crate::kernels::{Generated, Kernel};
use crate::{Ball, BodyState, RefArith, Scalar};

mod fma;
pub use fma::{collide_unchecked_fma, fma_in_hardware};

/// The post-collision states of two balls in contact at normal `nu` (unit, from body 1's
/// centre to body 2's), after validating every input:
///
/// - every number finite; `| |nu|^2 - 1 | <=` [`Scalar::unit_tolerance`] (exactly unit in
///   exact arithmetic);
/// - each ball valid ([`Ball::validate`]); not both immovable; not both point masses
///   (`gamma2 = 0`) unless one of them is immovable (its inertia is then unused);
/// - approaching or grazing: `(u_2 - u_1) . nu <= 0`.
///
/// An immovable body (`inv_mass = 0`) comes back unchanged; the map is then the `fixed`
/// kernel (with the bodies swapped and `nu` negated when body 2 is the immovable one).
pub fn collide<T, const N: usize, const S: usize>(
    nu: &[T; N],
    balls: [&Ball<T>; 2],
    states: [&BodyState<T, N, S>; 2],
) -> Result<[BodyState<T, N, S>; 2], InputError>
where
    T: Scalar,
    for<'a> &'a T: RefArith<T>,
    Generated: Kernel<T, N, S>,
{
    validate(nu, balls, states)?;
    Ok(collide_unchecked(nu, balls, states))
}

/// [`collide`] without validation: the dispatch to the generated kernels alone. With
/// invalid inputs the result is meaningless (NaN or infinite in floats), never a panic.
#[inline]
pub fn collide_unchecked<T, const N: usize, const S: usize>(
    nu: &[T; N],
    balls: [&Ball<T>; 2],
    states: [&BodyState<T, N, S>; 2],
) -> [BodyState<T, N, S>; 2]
where
    T: Scalar,
    Generated: Kernel<T, N, S>,
{
    dispatch::<Plain, T, N, S>(nu, balls, states)
}

/// The two kernels [`dispatch`] picks from. A type, not `Fn` arguments: a kernel called
/// through a `Fn` bound is compiled in its own shim function, which LLVM need not inline
/// (and does not, for the larger `fixed` kernels called from two branches), and which
/// would not inherit a caller's `#[target_feature]` (see `fma.rs`).
trait Pair<T, const N: usize, const S: usize> {
    fn free(
        nu: &[T; N],
        ball1: &Ball<T>,
        ball2: &Ball<T>,
        state1: &BodyState<T, N, S>,
        state2: &BodyState<T, N, S>,
    ) -> [BodyState<T, N, S>; 2];

    fn fixed(
        nu: &[T; N],
        radius1: &T,
        ball2: &Ball<T>,
        state1: &BodyState<T, N, S>,
        state2: &BodyState<T, N, S>,
    ) -> BodyState<T, N, S>;
}

/// `free` and `fixed`.
struct Plain;

impl<T, const N: usize, const S: usize> Pair<T, N, S> for Plain
where
    Generated: Kernel<T, N, S>,
{
    #[inline(always)]
    fn free(
        nu: &[T; N],
        ball1: &Ball<T>,
        ball2: &Ball<T>,
        state1: &BodyState<T, N, S>,
        state2: &BodyState<T, N, S>,
    ) -> [BodyState<T, N, S>; 2] {
        Generated::free(nu, ball1, ball2, state1, state2)
    }

    #[inline(always)]
    fn fixed(
        nu: &[T; N],
        radius1: &T,
        ball2: &Ball<T>,
        state1: &BodyState<T, N, S>,
        state2: &BodyState<T, N, S>,
    ) -> BodyState<T, N, S> {
        Generated::fixed(nu, radius1, ball2, state1, state2)
    }
}

/// Body 1 immovable: `fixed`; body 2 immovable: `fixed` with the bodies swapped and `nu`
/// negated; otherwise `free` (kernels of `K`).
#[inline(always)]
fn dispatch<K, T, const N: usize, const S: usize>(
    nu: &[T; N],
    balls: [&Ball<T>; 2],
    states: [&BodyState<T, N, S>; 2],
) -> [BodyState<T, N, S>; 2]
where
    T: Scalar,
    K: Pair<T, N, S>,
{
    let [b1, b2] = balls;
    let [s1, s2] = states;
    if b1.is_immovable() {
        [s1.clone(), K::fixed(nu, &b1.radius, b2, s1, s2)]
    } else if b2.is_immovable() {
        let minus_nu = nu.clone().map(|x| -x);
        [K::fixed(&minus_nu, &b2.radius, b1, s2, s1), s2.clone()]
    } else {
        K::free(nu, b1, b2, s1, s2)
    }
}

/// The checks of [`collide`], for any `n` (the reference uses them too).
pub fn validate_parts<T: Scalar>(
    nu: &[T],
    balls: [&Ball<T>; 2],
    states: [(&[T], &[T]); 2],
) -> Result<(), InputError> {
    let n = nu.len();
    if n < 2 {
        return Err(InputError::new(
            Field::Dim,
            format!("must be at least 2, got {n}"),
        ));
    }
    if let Some(x) = nu.iter().find(|x| !x.is_finite()) {
        return Err(InputError::new(
            Field::Normal,
            format!("must be finite, got {}", x.show()),
        ));
    }
    let norm2 = nu.iter().fold(T::zero(), |s, x| s + x.clone() * x.clone());
    if (norm2.clone() - T::one()).abs() > T::unit_tolerance() {
        let how = if T::EXACT {
            "exactly".to_string()
        } else {
            format!("| |nu|^2 - 1 | <= {}", T::unit_tolerance().show())
        };
        return Err(InputError::new(
            Field::Normal,
            format!(
                "must be a unit vector ({how}), got |nu|^2 = {}",
                norm2.show()
            ),
        ));
    }
    for (i, (ball, (spin, velocity))) in balls.iter().zip(states).enumerate() {
        ball.validate(n).map_err(|e| e.at_body(i))?;
        for (values, field) in [
            (spin, BodyField::AngularVelocity),
            (velocity, BodyField::Velocity),
        ] {
            if let Some(x) = values.iter().find(|x| !x.is_finite()) {
                return Err(InputError::new(
                    Field::Body(i, field),
                    format!("must be finite, got {}", x.show()),
                ));
            }
        }
    }
    let [b1, b2] = balls;
    if b1.is_immovable() && b2.is_immovable() {
        return Err(InputError::new(
            Field::Bodies,
            "both bodies are immovable (mass \"inf\"): at most one may be",
        ));
    }
    if !b1.is_immovable() && !b2.is_immovable() && b1.gamma2.is_zero() && b2.gamma2.is_zero() {
        return Err(InputError::new(
            Field::Bodies,
            "both bodies are point masses (lambda = 0): the no-slip map is undefined; at most one may be",
        ));
    }
    let dn = (0..n).fold(T::zero(), |s, k| {
        s + (states[1].1[k].clone() - states[0].1[k].clone()) * nu[k].clone()
    });
    if dn > T::zero() {
        return Err(InputError::new(
            Field::RelativeVelocity,
            format!(
                "the bodies are separating: (u_2 - u_1) . nu = {} > 0 (a collision needs them \
                 approaching or grazing; nu points from body 1 to body 2)",
                dn.show()
            ),
        ));
    }
    Ok(())
}

/// The checks of [`collide`].
pub fn validate<T: Scalar, const N: usize, const S: usize>(
    nu: &[T; N],
    balls: [&Ball<T>; 2],
    states: [&BodyState<T, N, S>; 2],
) -> Result<(), InputError> {
    validate_parts(
        nu,
        balls,
        states.map(|s| (s.spin.as_slice(), s.velocity.as_slice())),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Exact, Inertia, Mass, State2};

    fn q(n: i64, d: i64) -> Exact {
        Exact::from_ratio(n, d)
    }

    fn ball(mass: Mass<Exact>, inertia: Inertia<Exact>) -> Ball<Exact> {
        Ball::new(2, mass, q(1, 1), inertia).unwrap()
    }

    #[test]
    fn rejects_invalid_pairs_with_their_field() {
        let nu = [q(3, 5), q(4, 5)];
        let free = ball(Mass::Finite(q(1, 1)), Inertia::Uniform);
        let fixed = ball(Mass::Infinite, Inertia::Uniform);
        let point = ball(Mass::Finite(q(1, 1)), Inertia::Lambda(q(0, 1)));
        let rest = State2::zero();
        let approach = State2::from_scalar_spin(q(0, 1), [q(1, 1), q(0, 1)]);
        let away = State2::from_scalar_spin(q(0, 1), [q(-1, 1), q(0, 1)]);
        type Case<'a> = (
            &'a [Exact; 2],
            [&'a Ball<Exact>; 2],
            [&'a State2<Exact>; 2],
            Field,
        );
        let cases: [Case; 4] = [
            (&nu, [&fixed, &fixed], [&approach, &rest], Field::Bodies),
            (&nu, [&point, &point], [&approach, &rest], Field::Bodies),
            (&nu, [&free, &free], [&away, &rest], Field::RelativeVelocity),
            (
                &[q(1, 1), q(1, 1)],
                [&free, &free],
                [&approach, &rest],
                Field::Normal,
            ),
        ];
        for (nu, balls, states, field) in cases {
            assert_eq!(collide(nu, balls, states).unwrap_err().field, field);
        }
        // A point mass against an immovable one is fine: its partner's inertia is unused.
        let fixed_point = Ball {
            inv_mass: q(0, 1),
            ..point.clone()
        };
        assert!(collide(&nu, [&fixed_point, &point], [&approach, &rest]).is_ok());
        // Grazing contact is accepted.
        let graze = State2::from_scalar_spin(q(0, 1), [q(4, 1), q(-3, 1)]);
        assert!(collide(&nu, [&free, &free], [&graze, &rest]).is_ok());
    }

    #[test]
    fn float_nan_is_an_error_not_a_panic() {
        let b = Ball::new(2, Mass::Finite(1.0), 1.0, Inertia::Uniform).unwrap();
        let s = State2::from_scalar_spin(f64::NAN, [1.0, 0.0]);
        let e = collide(&[1.0, 0.0], [&b, &b], [&s, &State2::zero()]).unwrap_err();
        assert_eq!(e.field, Field::Body(0, BodyField::AngularVelocity));
    }
}
