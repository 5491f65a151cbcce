//! The smooth (specular) contact maps: the normal component of the relative velocity reverses,
//! tangential velocities and spins are untouched (no friction, no torque).
//!
//! - on an immovable body at rest: `u' = u - 2 (u . nu) nu`, `U' = U`;
//! - between balls of inverse masses `w_1`, `w_2` (`nu` from body 1 to body 2, `dv = u_2 -
//!   u_1`): the impulse `J = -2 (dv . nu) / (w_1 + w_2)` along `nu` on body 2, so
//!   `u_1' = u_1 + 2 w_1 / (w_1 + w_2) (dv . nu) nu`, `u_2' = u_2 - 2 w_2 / (w_1 + w_2) (dv .
//!   nu) nu`; an immovable ball (`w = 0`) keeps its velocity. At least one of `w_1`, `w_2`
//!   must be positive.
//!
//! Both conserve the energy `1/2 m |u|^2` exactly in exact arithmetic (tests below, exact
//! rationals), and the ball-ball map conserves linear momentum.
//!
//! The engine's smooth contacts (`noslip_sim::smooth`, the same module) and the checked
//! [`crate::collide_rough`] of two point masses at `beta = -1` (no kernel takes them: every
//! law's kernel divides by the pair's spin inertia) use these maps.

use crate::{BodyState, Scalar};

/// `a . b`, summed in order (by value: the maps run in any [`Scalar`], the checked path's
/// unbounded one too).
fn dot<T: Scalar, const N: usize>(a: &[T; N], b: &[T; N]) -> T {
    let mut s = T::zero();
    for k in 0..N {
        s += a[k].clone() * b[k].clone();
    }
    s
}

/// A ball's state after a smooth contact with an immovable body: `u' = u - 2 (u . nu) nu`.
pub fn fixed<T: Scalar, const N: usize, const S: usize>(
    nu: &[T; N],
    state: &BodyState<T, N, S>,
) -> BodyState<T, N, S> {
    let un = dot(&state.velocity, nu);
    let twice = un.clone() + un;
    BodyState {
        spin: state.spin.clone(),
        velocity: std::array::from_fn(|k| {
            state.velocity[k].clone() - twice.clone() * nu[k].clone()
        }),
    }
}

/// Two balls' states after a smooth contact (module docs); `nu` from body 1 to body 2.
pub fn pair<T: Scalar, const N: usize, const S: usize>(
    nu: &[T; N],
    w1: &T,
    w2: &T,
    state1: &BodyState<T, N, S>,
    state2: &BodyState<T, N, S>,
) -> [BodyState<T, N, S>; 2] {
    // `(1 + 1) dn` is `dn + dn` exactly (a doubling): the same bits as the elastic map always had.
    pair_restituted(nu, w1, w2, &T::one(), state1, state2)
}

/// Two balls' states after a smooth contact with normal restitution `e` (no tangential
/// impulse: the rough law at `beta = -1`), `nu` from body 1 to body 2: the impulse `J = -(1 +
/// e) (dv . nu) / (w_1 + w_2)` along `nu` on body 2, so `dv . nu` becomes `-e` times itself;
/// spins are untouched. At `e = 1` it is [`pair`]'s map.
pub fn pair_restituted<T: Scalar, const N: usize, const S: usize>(
    nu: &[T; N],
    w1: &T,
    w2: &T,
    e: &T,
    state1: &BodyState<T, N, S>,
    state2: &BodyState<T, N, S>,
) -> [BodyState<T, N, S>; 2] {
    let dv: [T; N] =
        std::array::from_fn(|k| state2.velocity[k].clone() - state1.velocity[k].clone());
    let dn = dot(&dv, nu);
    let j = (T::one() + e.clone()) * dn / (w1.clone() + w2.clone());
    let (j1, j2) = (w1.clone() * j.clone(), w2.clone() * j);
    [
        BodyState {
            spin: state1.spin.clone(),
            velocity: std::array::from_fn(|k| {
                state1.velocity[k].clone() + j1.clone() * nu[k].clone()
            }),
        },
        BodyState {
            spin: state2.spin.clone(),
            velocity: std::array::from_fn(|k| {
                state2.velocity[k].clone() - j2.clone() * nu[k].clone()
            }),
        },
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Exact;

    fn q(p: i64, d: i64) -> Exact {
        Exact::checked_ratio(p, d).expect("nonzero denominator")
    }

    /// A 3D contact: `nu = (2/7, 3/7, 6/7)` (unit), two bodies with arbitrary spins.
    fn contact() -> ([Exact; 3], BodyState<Exact, 3, 3>, BodyState<Exact, 3, 3>) {
        let s1 = BodyState {
            spin: [q(1, 2), q(-3, 1), q(5, 4)],
            velocity: [q(1, 1), q(-2, 3), q(7, 5)],
        };
        let s2 = BodyState {
            spin: [q(2, 1), q(0, 1), q(-1, 9)],
            velocity: [q(-3, 2), q(1, 4), q(-2, 1)],
        };
        ([q(2, 7), q(3, 7), q(6, 7)], s1, s2)
    }

    #[test]
    fn smooth_maps_reverse_the_normal_velocity_and_keep_energy_exactly() {
        let (nu, s1, s2) = contact();
        let post = fixed(&nu, &s1);
        assert_eq!(post.spin, s1.spin);
        assert_eq!(dot(&post.velocity, &nu), -dot(&s1.velocity, &nu));
        assert_eq!(
            dot(&post.velocity, &post.velocity),
            dot(&s1.velocity, &s1.velocity)
        );
        for (w1, w2) in [(q(1, 3), q(2, 1)), (q(0, 1), q(5, 2)), (q(3, 1), q(0, 1))] {
            let [p1, p2] = pair(&nu, &w1, &w2, &s1, &s2);
            let rel = |a: &BodyState<Exact, 3, 3>, b: &BodyState<Exact, 3, 3>| {
                let d: [Exact; 3] = std::array::from_fn(|k| &b.velocity[k] - &a.velocity[k]);
                dot(&d, &nu)
            };
            assert_eq!(rel(&p1, &p2), -rel(&s1, &s2));
            assert_eq!(
                (p1.spin.clone(), p2.spin.clone()),
                (s1.spin.clone(), s2.spin.clone())
            );
            // Energy and momentum, weighted by the masses 1/w (an immovable body: unchanged).
            for (pre, post, w) in [(&s1, &p1, &w1), (&s2, &p2, &w2)] {
                if w == &q(0, 1) {
                    assert_eq!(post.velocity, pre.velocity);
                }
            }
            if w1 != q(0, 1) && w2 != q(0, 1) {
                let energy = |a: &BodyState<Exact, 3, 3>, b: &BodyState<Exact, 3, 3>| {
                    &dot(&a.velocity, &a.velocity) / &w1 + &dot(&b.velocity, &b.velocity) / &w2
                };
                assert_eq!(energy(&p1, &p2), energy(&s1, &s2));
                for k in 0..3 {
                    let m = |a: &BodyState<Exact, 3, 3>, b: &BodyState<Exact, 3, 3>| {
                        &a.velocity[k] / &w1 + &b.velocity[k] / &w2
                    };
                    assert_eq!(m(&p1, &p2), m(&s1, &s2));
                }
            }
        }
    }

    /// The restituted smooth map: `dv . nu` becomes exactly `-e` times itself, momentum and
    /// spins are kept, and the energy lost is `(1 - e^2) (dv . nu)^2 / (2 (w_1 + w_2))`
    /// exactly; with two point masses (their only law without a tangential impulse) as with
    /// any.
    #[test]
    fn the_restituted_map_keeps_momentum_and_loses_the_closed_form_energy_exactly() {
        let (nu, s1, s2) = contact();
        let rel = |a: &BodyState<Exact, 3, 3>, b: &BodyState<Exact, 3, 3>| {
            let d: [Exact; 3] = std::array::from_fn(|k| &b.velocity[k] - &a.velocity[k]);
            dot(&d, &nu)
        };
        for e in [q(0, 1), q(4, 5), q(1, 1)] {
            for (w1, w2) in [(q(1, 3), q(2, 1)), (q(0, 1), q(5, 2)), (q(1, 1), q(1, 1))] {
                let [p1, p2] = pair_restituted(&nu, &w1, &w2, &e, &s1, &s2);
                assert_eq!(rel(&p1, &p2), -(&e * &rel(&s1, &s2)));
                assert_eq!((&p1.spin, &p2.spin), (&s1.spin, &s2.spin));
                // m_i = 1 / w_i where w_i > 0; an immovable body keeps its velocity.
                let energy = |a: &BodyState<Exact, 3, 3>, b: &BodyState<Exact, 3, 3>| {
                    let half = q(1, 2);
                    let mut sum = q(0, 1);
                    for (s, w) in [(a, &w1), (b, &w2)] {
                        sum += &(&half * &dot(&s.velocity, &s.velocity)) / w;
                    }
                    sum
                };
                let dn = rel(&s1, &s2);
                let lost = &(&(&q(1, 1) - &(&e * &e)) * &(&dn * &dn)) / &(&q(2, 1) * &(&w1 + &w2));
                // Energy and momentum need both masses finite (an immovable body 1 that moves
                // does work on body 2).
                if w1 != q(0, 1) && w2 != q(0, 1) {
                    assert_eq!(&energy(&s1, &s2) - &energy(&p1, &p2), lost);
                    for k in 0..3 {
                        let before = &(&s1.velocity[k] / &w1) + &(&s2.velocity[k] / &w2);
                        let after = &(&p1.velocity[k] / &w1) + &(&p2.velocity[k] / &w2);
                        assert_eq!(before, after);
                    }
                } else {
                    assert_eq!(p1.velocity, s1.velocity);
                }
            }
        }
    }
}
