//! The checked entry point of the rough-ball kernels (docs/derivation.md §15): the checks and
//! the unbounded-exponent arithmetic of [`collide`](super::collide), with the law
//! `(e, beta)` checked by [`Restitution::new`] and the kernels `kernels::dN::rough`.

use crate::kernels::{Generated, RoughKernel};
use crate::{Ball, BodyState, InputError, Restitution, Scalar};

/// [`collide`](super::collide) under the rough-ball law `law`: `dn+ = -e dn`, `t+ = -beta t`
/// for the slip of the contact point. Every input is checked as there, and `law` by
/// [`Restitution::new`] (`e` in `[0, 1]`, `beta` in `[-1, 1]`, no NaN; the error names
/// the field). `(1, 1)` gives [`collide`](super::collide)'s results. At `beta = -1` (no
/// tangential impulse) two point masses may meet: their contact is the specular map with
/// restitution `e` ([`crate::smooth::pair_restituted`]), which no kernel takes.
pub fn collide_rough<T, const N: usize, const S: usize>(
    nu: &[T; N],
    balls: [&Ball<T>; 2],
    law: &Restitution<T>,
    states: [&BodyState<T, N, S>; 2],
) -> Result<[BodyState<T, N, S>; 2], InputError>
where
    T: Scalar,
    Generated: RoughKernel<T::Unbounded, N, S>,
{
    let law = Restitution::new(law.e.clone(), law.beta.clone())?;
    let law_w = Restitution {
        e: law.e.unbounded(),
        beta: law.beta.unbounded(),
    };
    // Without a tangential part (beta = -1) two point masses may meet; no kernel takes them
    // (each divides by the pair's spin inertia), the specular map does.
    let smooth = law.beta == -T::one();
    super::checked_map(nu, balls, states, !smooth, |nu, balls, states| {
        if smooth && crate::checked::both_point_masses(balls[0], balls[1]) {
            let [b1, b2] = balls;
            return crate::smooth::pair_restituted(
                nu,
                &b1.inv_mass,
                &b2.inv_mass,
                &law_w.e,
                states[0],
                states[1],
            );
        }
        collide_rough_unchecked(nu, balls, &law_w, states)
    })
}

/// The rough kernels without checks, dispatched as
/// [`collide_unchecked`](super::collide_unchecked) does: body 1 immovable, `rough::fixed`;
/// body 2 immovable, `rough::fixed` with the bodies swapped and `-nu` (the law is symmetric
/// under the swap: it scales the slip, whose sign alone changes); else `rough::free`.
pub fn collide_rough_unchecked<T, const N: usize, const S: usize>(
    nu: &[T; N],
    balls: [&Ball<T>; 2],
    law: &Restitution<T>,
    states: [&BodyState<T, N, S>; 2],
) -> [BodyState<T, N, S>; 2]
where
    T: Scalar,
    Generated: RoughKernel<T, N, S>,
{
    let [b1, b2] = balls;
    let [s1, s2] = states;
    if b1.is_immovable() {
        [
            s1.clone(),
            Generated::rough_fixed(nu, &b1.radius, b2, law, s1, s2),
        ]
    } else if b2.is_immovable() {
        let minus_nu = nu.clone().map(|x| -x);
        [
            Generated::rough_fixed(&minus_nu, &b2.radius, b1, law, s2, s1),
            s2.clone(),
        ]
    } else {
        Generated::rough_free(nu, b1, b2, law, s1, s2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{collide, reference, Exact, Field, Inertia, Mass};

    fn q(n: i64, d: i64) -> Exact {
        Exact::from_ratio(n, d)
    }

    fn ball(mass: Mass<Exact>) -> Ball<Exact> {
        Ball::new(3, mass, q(1, 1), Inertia::Uniform).unwrap()
    }

    fn states() -> [BodyState<Exact, 3, 3>; 2] {
        [
            BodyState {
                spin: [q(1, 2), q(-1, 3), q(2, 1)],
                velocity: [q(1, 1), q(0, 1), q(1, 2)],
            },
            BodyState {
                spin: [q(0, 1), q(1, 1), q(-1, 4)],
                velocity: [q(-1, 2), q(-2, 1), q(0, 1)],
            },
        ]
    }

    #[test]
    fn every_dispatch_is_the_definition_and_one_one_is_no_slip() {
        let nu = [q(0, 1), q(3, 5), q(4, 5)];
        let s = states();
        let law = Restitution::new(q(7, 10), q(-1, 3)).unwrap();
        for (m1, m2) in [
            (Mass::Finite(q(2, 1)), Mass::Finite(q(1, 1))),
            (Mass::Infinite, Mass::Finite(q(1, 1))),
            (Mass::Finite(q(2, 1)), Mass::Infinite),
        ] {
            let balls = [ball(m1), ball(m2)];
            let b = [&balls[0], &balls[1]];
            let out = collide_rough(&nu, b, &law, [&s[0], &s[1]]).unwrap();
            let definition = reference::collide_rough(&nu, b, &law, [&s[0], &s[1]]).unwrap();
            assert_eq!(out, definition);
            let no_slip = Restitution::no_slip();
            assert_eq!(
                collide_rough(&nu, b, &no_slip, [&s[0], &s[1]]).unwrap(),
                collide(&nu, b, [&s[0], &s[1]]).unwrap()
            );
        }
    }

    #[test]
    fn a_law_out_of_range_is_refused_naming_its_field() {
        let nu = [0.0, 0.6, 0.8];
        let b = Ball::new(3, Mass::Finite(1.0), 1.0, Inertia::Uniform).unwrap();
        let s = BodyState::<f64, 3, 3>::zero();
        let mut moving = s.clone();
        moving.velocity = [0.0, -1.0, 0.0];
        for (e, beta, field) in [
            (1.5, 0.0, Field::RestitutionE),
            (f64::NAN, 0.0, Field::RestitutionE),
            (0.5, -2.0, Field::RestitutionBeta),
        ] {
            let law = Restitution { e, beta };
            let err = collide_rough(&nu, [&b, &b], &law, [&s, &moving]).unwrap_err();
            assert_eq!(err.field, field);
        }
    }
}
