//! The checked entry point of the Walton kernels (docs/derivation.md §15.1): the checks and
//! the unbounded-exponent arithmetic of [`collide`](super::collide), with the law
//! `(e, mu, beta0)` checked by [`Walton::new`] and the kernels `kernels::dN::walton`.

use crate::kernels::{Generated, WaltonKernel};
use crate::{Ball, BodyState, InputError, Scalar, ScalarRoot, Walton};

/// [`collide`](super::collide) under the Walton law `law`: `dn+ = -e dn`, `t+ = -beta t`
/// with `beta = min(beta0, beta_C)`. Every input is checked as there, and `law` by
/// [`Walton::new`] (the error names the field).
pub fn collide_walton<T, const N: usize, const S: usize>(
    nu: &[T; N],
    balls: [&Ball<T>; 2],
    law: &Walton<T>,
    states: [&BodyState<T, N, S>; 2],
) -> Result<[BodyState<T, N, S>; 2], InputError>
where
    T: Scalar,
    T::Unbounded: ScalarRoot,
    Generated: WaltonKernel<T::Unbounded, N, S>,
{
    let law = Walton::new(law.e.clone(), law.mu.clone(), law.beta0.clone())?;
    let law_w = Walton {
        e: law.e.unbounded(),
        mu: law.mu.unbounded(),
        beta0: law.beta0.unbounded(),
    };
    super::checked_map(nu, balls, states, true, |nu, balls, states| {
        collide_walton_unchecked(nu, balls, &law_w, states)
    })
}

/// The Walton kernels without checks, dispatched as
/// [`collide_rough_unchecked`](super::collide_rough_unchecked) does (the swap of the bodies
/// and of `nu` flips the slip's sign only, so `|dn|`, `|t|` and the chosen `beta` are kept).
pub fn collide_walton_unchecked<T, const N: usize, const S: usize>(
    nu: &[T; N],
    balls: [&Ball<T>; 2],
    law: &Walton<T>,
    states: [&BodyState<T, N, S>; 2],
) -> [BodyState<T, N, S>; 2]
where
    T: ScalarRoot,
    Generated: WaltonKernel<T, N, S>,
{
    let [b1, b2] = balls;
    let [s1, s2] = states;
    if b1.is_immovable() {
        [
            s1.clone(),
            Generated::walton_fixed(nu, &b1.radius, b2, law, s1, s2),
        ]
    } else if b2.is_immovable() {
        let minus_nu = nu.clone().map(|x| -x);
        [
            Generated::walton_fixed(&minus_nu, &b2.radius, b1, law, s2, s1),
            s2.clone(),
        ]
    } else {
        Generated::walton_free(nu, b1, b2, law, s1, s2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{collide_rough, Exact, Field, Inertia, Mass, Restitution};

    fn q(n: i64, d: i64) -> Exact {
        Exact::from_ratio(n, d)
    }

    fn ball(mass: Mass<Exact>) -> Ball<Exact> {
        Ball::new(3, mass, q(1, 1), Inertia::Uniform).unwrap()
    }

    /// A ball falling onto another with slip `t = (3, 0, 0)`, `dn = -4` (spins zero), so
    /// `|t|` is rational: with `mu` large it sticks (the rough law at `beta0`); with
    /// `mu = 0` it slides with `beta = -1` (the rough law at `(e, -1)`). Every dispatch.
    #[test]
    fn every_dispatch_sticks_or_slides_as_the_rough_law_and_bad_laws_are_refused() {
        let nu = [q(0, 1), q(1, 1), q(0, 1)];
        let zero = BodyState {
            spin: [q(0, 1), q(0, 1), q(0, 1)],
            velocity: [q(0, 1), q(0, 1), q(0, 1)],
        };
        let falling = BodyState {
            spin: [q(0, 1), q(0, 1), q(0, 1)],
            velocity: [q(3, 1), q(-4, 1), q(0, 1)],
        };
        let (e, beta0) = (q(1, 2), q(1, 3));
        for (m1, m2) in [
            (Mass::Finite(q(2, 1)), Mass::Finite(q(1, 1))),
            (Mass::Infinite, Mass::Finite(q(1, 1))),
        ] {
            let balls = [ball(m1), ball(m2)];
            let b = [&balls[0], &balls[1]];
            let s = [&zero, &falling];
            for (mu, beta) in [(q(100, 1), beta0.clone()), (q(0, 1), q(-1, 1))] {
                let law = Walton::new(e.clone(), mu, beta0.clone()).unwrap();
                let rough = Restitution::new(e.clone(), beta).unwrap();
                assert_eq!(
                    collide_walton(&nu, b, &law, s).unwrap(),
                    collide_rough(&nu, b, &rough, s).unwrap()
                );
            }
        }
        let balls = [ball(Mass::Finite(q(1, 1))), ball(Mass::Infinite)];
        let b = [&balls[0], &balls[1]];
        // Body 2 immovable: the swap. The same contact seen from the other side.
        let law = Walton::new(e.clone(), q(0, 1), beta0.clone()).unwrap();
        let rough = Restitution::new(e.clone(), q(-1, 1)).unwrap();
        let rising = BodyState {
            spin: zero.spin.clone(),
            velocity: [q(-3, 1), q(4, 1), q(0, 1)],
        };
        assert_eq!(
            collide_walton(&nu, b, &law, [&rising, &zero]).unwrap(),
            collide_rough(&nu, b, &rough, [&rising, &zero]).unwrap()
        );
        let bad = Walton {
            e: q(1, 2),
            mu: q(-1, 10),
            beta0: q(0, 1),
        };
        let err = collide_walton(&nu, b, &bad, [&rising, &zero]).unwrap_err();
        assert_eq!(err.field, Field::FrictionMu);
    }
}
