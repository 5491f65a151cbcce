//! The checked entry point: validate, then run the generated kernel of the dimension.

use crate::checked::{self, validate_parts};
use crate::error::{Field, InputError};
use crate::kernels::{Generated, Kernel};
use crate::reference;
use crate::{Ball, BodyState, Scalar};
use nalgebra::DVector;

mod fma;
mod rough;
mod walton;

pub use fma::{collide_unchecked_fma, fma_in_hardware};
pub use rough::{collide_rough, collide_rough_unchecked};
pub use walton::{collide_walton, collide_walton_unchecked};

/// The post-collision states of two balls in contact at normal `nu` (unit, from body 1's
/// centre to body 2's), after validating every input:
///
/// - every number finite; `|nu|^2 = 1`;
/// - each ball valid ([`Ball::validate`]); not both immovable; not both point masses
///   (`gamma2 = 0`) unless one of them is immovable (its inertia is then unused);
/// - approaching or grazing: `(u_2 - u_1) . nu <= 0`.
///
/// In floats, a bound missed by rounding is met by [the rounding allowance](crate::allowance):
/// `gamma2` and `(u_2 - u_1) . nu` within `8 eps` of their scale, `|nu|^2` within `(8 + 2n) eps`
/// of 1 (the rounding of `d / |d|` in `n` dimensions), are accepted and
/// clamped (`nu` renormalised, `gamma2` set to the bound, a grazing contact's normal relative
/// velocity removed); exact arithmetic takes no allowance.
///
/// In floats the kernel runs with an unbounded exponent ([`crate::Wide`]): the result is
/// the format's kernel result bit for bit wherever that kernel stays in range, and right where
/// an intermediate quantity would overflow or underflow. A result that does not fit the format
/// (a component beyond its range, or a body whose components below the normal range would
/// cost more than the rounding allowance of its energy norm) is an error naming the inputs
/// that drive it.
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
    Generated: Kernel<T::Unbounded, N, S>,
{
    checked_map(nu, balls, states, true, |nu, balls, states| {
        collide_unchecked(nu, balls, states)
    })
}

/// The checked path around a collision map `map` of any law: the inputs checked and clamped
/// ([`checked::prepare`]: two point masses are refused under a law with a tangential
/// part, `tangential`), moved into the unbounded-exponent arithmetic `T::Unbounded`, mapped,
/// and the results rounded back where they fit ([`checked::round_results`]).
pub(crate) fn checked_map<T, const N: usize, const S: usize>(
    nu: &[T; N],
    balls: [&Ball<T>; 2],
    states: [&BodyState<T, N, S>; 2],
    tangential: bool,
    map: impl FnOnce(
        &[T::Unbounded; N],
        [&Ball<T::Unbounded>; 2],
        [&BodyState<T::Unbounded, N, S>; 2],
    ) -> [BodyState<T::Unbounded, N, S>; 2],
) -> Result<[BodyState<T, N, S>; 2], InputError>
where
    T: Scalar,
{
    let inputs = states.map(|s| (s.spin.as_slice(), s.velocity.as_slice()));
    let p = checked::prepare(nu, balls, inputs, tangential)?;
    let array = |v: &[T::Unbounded]| -> Vec<T::Unbounded> { v.to_vec() };
    let nu_w: [T::Unbounded; N] = fixed_len(array(&p.nu));
    let states_w: [BodyState<T::Unbounded, N, S>; 2] = std::array::from_fn(|b| BodyState {
        spin: fixed_len(array(&p.spins[b])),
        velocity: fixed_len(array(&p.velocities[b])),
    });
    let out = map(
        &nu_w,
        [&p.balls[0], &p.balls[1]],
        [&states_w[0], &states_w[1]],
    );
    let results = [0, 1].map(|b| (out[b].spin.as_slice(), out[b].velocity.as_slice()));
    let [(s1, v1), (s2, v2)] = checked::round_results(&p, results, inputs)?;
    Ok([
        BodyState {
            spin: fixed_len(s1),
            velocity: fixed_len(v1),
        },
        BodyState {
            spin: fixed_len(s2),
            velocity: fixed_len(v2),
        },
    ])
}

/// [`collide`] for any `n = nu.len() >= 2`, through the general-n reference
/// ([`crate::reference::collide_coords`]) on the coordinates `xi = [U_1, u_1, U_2, u_2]`:
/// the same checks, the same allowance, the same unbounded exponent and the same refusal of
/// results that do not fit.
pub fn collide_general<T: Scalar>(
    nu: &[T],
    balls: [&Ball<T>; 2],
    xi: &DVector<T>,
) -> Result<DVector<T>, InputError> {
    let n = nu.len();
    let s = n * (n.max(1) - 1) / 2;
    if xi.len() != reference::state_len(n) {
        return Err(InputError::new(
            Field::Dim,
            "state length does not match the normal",
        ));
    }
    let part = |b: usize| {
        let body = &xi.as_slice()[b * (s + n)..(b + 1) * (s + n)];
        (&body[..s], &body[s..])
    };
    let inputs = [part(0), part(1)];
    let p = checked::prepare(nu, balls, inputs, true)?;
    let xi_w = DVector::from_iterator(
        xi.len(),
        (0..2).flat_map(|b| p.spins[b].iter().chain(&p.velocities[b]).cloned()),
    );
    let out = reference::collide_coords(&p.nu, [&p.balls[0], &p.balls[1]], &xi_w)?;
    let body = |b: usize| {
        let v = &out.as_slice()[b * (s + n)..(b + 1) * (s + n)];
        (&v[..s], &v[s..])
    };
    let [(s1, v1), (s2, v2)] = checked::round_results(&p, [body(0), body(1)], inputs)?;
    Ok(DVector::from_iterator(
        xi.len(),
        s1.into_iter().chain(v1).chain(s2).chain(v2),
    ))
}

/// A vector of known length as an array (the lengths are fixed by the types).
fn fixed_len<T, const K: usize>(v: Vec<T>) -> [T; K] {
    v.try_into()
        .unwrap_or_else(|_| unreachable!("the prepared inputs keep their lengths"))
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
    dispatch::<false, T, N, S>(nu, balls, states)
}

/// Body 1 immovable: `fixed`; body 2 immovable: `fixed` with the bodies swapped and `nu`
/// negated; otherwise `free`: the FMA forms (`fixed_fma`, `free_fma`) when `FUSED`.
///
/// The kernels are called directly, not through `Fn` arguments or closures: those are compiled
/// as functions of their own, which LLVM need not inline (and does not, for the larger
/// `fixed` kernels called from two branches), and which would not inherit a caller's
/// `#[target_feature]` (see `fma.rs`). `FUSED` is a constant, so its branches fold away.
#[inline(always)]
pub(crate) fn dispatch<const FUSED: bool, T, const N: usize, const S: usize>(
    nu: &[T; N],
    balls: [&Ball<T>; 2],
    states: [&BodyState<T, N, S>; 2],
) -> [BodyState<T, N, S>; 2]
where
    T: Scalar,
    Generated: Kernel<T, N, S>,
{
    let [b1, b2] = balls;
    let [s1, s2] = states;
    if b1.is_immovable() {
        let after = if FUSED {
            Generated::fixed_fma(nu, &b1.radius, b2, s1, s2)
        } else {
            Generated::fixed(nu, &b1.radius, b2, s1, s2)
        };
        [s1.clone(), after]
    } else if b2.is_immovable() {
        let minus_nu = nu.clone().map(|x| -x);
        let after = if FUSED {
            Generated::fixed_fma(&minus_nu, &b2.radius, b1, s2, s1)
        } else {
            Generated::fixed(&minus_nu, &b2.radius, b1, s2, s1)
        };
        [after, s2.clone()]
    } else if FUSED {
        Generated::free_fma(nu, b1, b2, s1, s2)
    } else {
        Generated::free(nu, b1, b2, s1, s2)
    }
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
    use crate::{BodyField, Exact, Inertia, Mass, State2};

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

    fn f64_ball(mass: f64) -> Ball<f64> {
        Ball::new(2, Mass::Finite(mass), 1.0, Inertia::Uniform).unwrap()
    }

    #[test]
    fn a_normal_within_the_allowance_is_renormalised_and_no_further_one_accepted() {
        let eps = f64::EPSILON;
        let b = f64_ball(1.0);
        let states = [
            State2::from_scalar_spin(0.5, [1.0, 0.25]),
            State2::from_scalar_spin(-1.0, [0.0, 0.0]),
        ];
        let [s1, s2] = [&states[0], &states[1]];
        let unit = collide(&[1.0, 0.0], [&b, &b], [s1, s2]).unwrap();
        // In 2D the allowance is (8 + 2 2) eps = 12 eps of |nu|^2. |nu|^2 = 1 + 12 eps and
        // 1 - 12 eps (the ulp below 1 is eps/2), and 1 + 10 eps from the decimal
        // 1.000000000000001: renormalised to the unit vector, so the same result.
        for nu0 in [1.0 + 6.0 * eps, 1.0 - 12.0 * (eps / 2.0), 1.000000000000001] {
            assert_eq!(collide(&[nu0, 0.0], [&b, &b], [s1, s2]).unwrap(), unit);
        }
        for nu0 in [1.0 + 7.0 * eps, 1.0 - 13.0 * (eps / 2.0)] {
            let e = collide(&[nu0, 0.0], [&b, &b], [s1, s2]).unwrap_err();
            assert_eq!(e.field, Field::Normal);
        }
    }

    #[test]
    fn grazing_within_eight_eps_loses_its_normal_velocity_and_no_further_one_is_accepted() {
        let eps = f64::EPSILON;
        // nu = e_0, u_1 = (1, 5), u_2 = (1 + 16 eps, -3): (u_2 - u_1) . nu = 16 eps against the
        // scale |u_1,0| + |u_2,0| = 2 + 16 eps: inside 8 eps of it.
        let (b1, b2) = (f64_ball(1.0), f64_ball(3.0));
        let s1 = State2::from_scalar_spin(0.5, [1.0, 5.0]);
        let graze = State2::from_scalar_spin(2.0, [1.0 + 16.0 * eps, -3.0]);
        let [a1, a2] = collide(&[1.0, 0.0], [&b1, &b2], [&s1, &graze]).unwrap();
        // Clamped to grazing: the kernel saw no normal relative velocity (none after), and
        // the normal momentum m_1 u_1 + m_2 u_2 = 1 + 3 (1 + 16 eps) is kept exactly.
        assert_eq!(a2.velocity[0] - a1.velocity[0], 0.0);
        assert_eq!(a1.velocity[0] + 3.0 * a2.velocity[0], 4.0 + 48.0 * eps);
        let away = State2::from_scalar_spin(2.0, [1.0 + 18.0 * eps, -3.0]);
        let e = collide(&[1.0, 0.0], [&b1, &b2], [&s1, &away]).unwrap_err();
        assert_eq!(e.field, Field::RelativeVelocity);
    }
}
