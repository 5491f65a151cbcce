//! The velocity map of a contact, `v' = M(nu) v`, linear in `v`, behind one interface: the
//! no-slip map (the generated kernels) or the smooth (specular) one. A new contact law is one
//! variant and one arm in each of [`Law::boundary`] and [`Law::pair`].
//!
//! Both maps are rational functions of `nu` and the state, generic over [`Scalar`], so the
//! same code runs in `f64`, in exact rationals and in dual numbers (its derivative).
//!
//! - No-slip: the generated `fixed` kernel with the boundary as an immovable body at rest
//!   (its radius does not enter: the kernel uses it only as `R_1 U_1 nu`, and `U_1 = 0`), and
//!   `free` for two balls.
//! - Smooth, with a boundary: `u' = u - 2 (u . nu) nu`, the spin untouched. Two smooth balls:
//!   `dn = (u_2 - u_1) . nu`, `u_1' = u_1 + 2 w_1 dn nu / (w_1 + w_2)`,
//!   `u_2' = u_2 - 2 w_2 dn nu / (w_1 + w_2)`, spins untouched. Both are the engine's
//!   [`noslip_sim::smooth`] maps (generic over the scalar), so the tangent map differentiates
//!   the very map the engine runs.
//!
//! Which law a contact follows is the scene's (`contact = "smooth"` per boundary, per
//! obstacle and for ball pairs: [`noslip_sim::ContactKind`], converted by [`Law::of`]), unless a
//! run overrides every contact's law.

use collision_core::{Ball, BodyState, Generated, Kernel, RefArith, Scalar};
use serde::Serialize;

/// How a contact changes the velocities.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Law {
    /// The no-slip map: the reflection across the no-slip subspace in the energy metric.
    NoSlip,
    /// Specular reflection of the centre velocities; spins untouched.
    Smooth,
}

impl Law {
    /// The law of an elastic contact kind; `None` for a rough or Walton one (`e < 1` or `|beta| < 1`:
    /// no tangent map here).
    pub fn of(kind: noslip_sim::ContactKind) -> Option<Law> {
        match kind {
            noslip_sim::ContactKind::NoSlip => Some(Law::NoSlip),
            noslip_sim::ContactKind::Smooth => Some(Law::Smooth),
            noslip_sim::ContactKind::Rough { .. } | noslip_sim::ContactKind::Walton { .. } => None,
        }
    }

    /// The scene's contact kind for this law (the inverse of [`Law::of`]).
    pub fn kind(self) -> noslip_sim::ContactKind {
        match self {
            Law::NoSlip => noslip_sim::ContactKind::NoSlip,
            Law::Smooth => noslip_sim::ContactKind::Smooth,
        }
    }

    /// The state of a ball (parameters `ball`) after touching an immovable boundary at rest,
    /// `nu` from the boundary towards the ball.
    pub fn boundary<T: Scalar, const N: usize, const S: usize>(
        self,
        nu: &[T; N],
        ball: &Ball<T>,
        state: &BodyState<T, N, S>,
    ) -> BodyState<T, N, S>
    where
        for<'a> &'a T: RefArith<T>,
        Generated: Kernel<T, N, S>,
    {
        match self {
            Law::NoSlip => Generated::fixed(nu, &T::one(), ball, &BodyState::zero(), state),
            Law::Smooth => noslip_sim::smooth::fixed(nu, state),
        }
    }

    /// The states of two balls after their contact, `nu` from ball 1 to ball 2.
    pub fn pair<T: Scalar, const N: usize, const S: usize>(
        self,
        nu: &[T; N],
        balls: [&Ball<T>; 2],
        states: [&BodyState<T, N, S>; 2],
    ) -> [BodyState<T, N, S>; 2]
    where
        for<'a> &'a T: RefArith<T>,
        Generated: Kernel<T, N, S>,
    {
        match self {
            Law::NoSlip => Generated::free(nu, balls[0], balls[1], states[0], states[1]),
            Law::Smooth => noslip_sim::smooth::pair(
                nu,
                &balls[0].inv_mass,
                &balls[1].inv_mass,
                states[0],
                states[1],
            ),
        }
    }
}

/// The engine's [`noslip_sim::PairKernels`] for one law and the species' parameters: runs a
/// scene with smooth contacts (the Hamiltonian control) or no-slip ones through the same
/// engine.
#[derive(Clone, Debug)]
pub struct LawKernels {
    /// The law of every contact.
    pub law: Law,
    /// Each species' parameters.
    pub species: Vec<Ball<f64>>,
}

impl<const N: usize, const S: usize> noslip_sim::PairKernels<f64, N, S> for LawKernels
where
    Generated: Kernel<f64, N, S>,
{
    fn ball_ball(
        &self,
        a: usize,
        b: usize,
        nu: &[f64; N],
        state1: &BodyState<f64, N, S>,
        state2: &BodyState<f64, N, S>,
    ) -> [BodyState<f64, N, S>; 2] {
        self.law
            .pair(nu, [&self.species[a], &self.species[b]], [state1, state2])
    }

    fn ball_wall(
        &self,
        species: usize,
        axis: usize,
        upper: bool,
        state: &BodyState<f64, N, S>,
    ) -> BodyState<f64, N, S> {
        let sign = if upper { -1.0 } else { 1.0 };
        let nu = std::array::from_fn(|k| if k == axis { sign } else { 0.0 });
        self.law.boundary(&nu, &self.species[species], state)
    }

    fn ball_obstacle(
        &self,
        species: usize,
        nu: &[f64; N],
        state: &BodyState<f64, N, S>,
    ) -> BodyState<f64, N, S> {
        self.law.boundary(nu, &self.species[species], state)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::dot;
    use collision_core::{Exact, State2};

    fn q(n: i64, d: i64) -> Exact {
        Exact::from_ratio(n, d)
    }

    /// MATH.md's checked fact: a uniform disk (g = 1/2) on a wall, nu = e_y, coordinates
    /// `(gamma R c, u.tau)` map by `[[-1/3, -2 gamma/(3/2)], [-2 gamma/(3/2), 1/3]]`; with
    /// `R = 1`, `c = 0`, `u = (1, -1)`: `u.tau' = 1/3`, `gamma R c' = -(4/3) gamma`, i.e.
    /// `c' = -4/3`; `u.nu' = 1`. Smooth: `u' = (1, 1)`, spin untouched.
    #[test]
    fn both_laws_on_a_wall_match_the_closed_forms() {
        let ball = Ball {
            inv_mass: q(1, 1),
            radius: q(1, 1),
            gamma2: q(1, 2),
        };
        let nu = [q(0, 1), q(1, 1)];
        let s = State2::from_scalar_spin(q(0, 1), [q(1, 1), q(-1, 1)]);
        let no_slip = Law::NoSlip.boundary(&nu, &ball, &s);
        assert_eq!(no_slip.velocity, [q(1, 3), q(1, 1)]);
        assert_eq!(no_slip.scalar_spin(), q(-4, 3));
        let smooth = Law::Smooth.boundary(
            &nu,
            &ball,
            &State2::from_scalar_spin(q(5, 1), s.velocity.clone()),
        );
        assert_eq!(smooth.velocity, [q(1, 1), q(1, 1)]);
        assert_eq!(smooth.scalar_spin(), q(5, 1));
    }

    /// Smooth pair: momentum and energy conserved, the normal relative velocity flips, the
    /// tangential ones and the spins are untouched (exactly).
    #[test]
    fn smooth_pair_is_the_elastic_collision() {
        let b1 = Ball {
            inv_mass: q(1, 2),
            radius: q(1, 1),
            gamma2: q(1, 2),
        };
        let b2 = Ball {
            inv_mass: q(1, 3),
            radius: q(1, 2),
            gamma2: q(1, 2),
        };
        let nu = [q(3, 5), q(4, 5)];
        let s1 = State2::from_scalar_spin(q(7, 1), [q(1, 1), q(2, 1)]);
        let s2 = State2::from_scalar_spin(q(-1, 1), [q(-2, 1), q(1, 3)]);
        let [a1, a2] = Law::Smooth.pair(&nu, [&b1, &b2], [&s1, &s2]);
        let m = |b: &Ball<Exact>| q(1, 1) / b.inv_mass.clone();
        for k in 0..2 {
            assert_eq!(
                m(&b1) * a1.velocity[k].clone() + m(&b2) * a2.velocity[k].clone(),
                m(&b1) * s1.velocity[k].clone() + m(&b2) * s2.velocity[k].clone()
            );
        }
        let rel = |x: &State2<Exact>, y: &State2<Exact>| -> [Exact; 2] {
            std::array::from_fn(|k| y.velocity[k].clone() - x.velocity[k].clone())
        };
        let (before, after) = (rel(&s1, &s2), rel(&a1, &a2));
        assert_eq!(dot(&after, &nu), -dot(&before, &nu));
        let tau = [q(-4, 5), q(3, 5)];
        assert_eq!(dot(&after, &tau), dot(&before, &tau));
        assert_eq!(
            (a1.spin.clone(), a2.spin.clone()),
            (s1.spin.clone(), s2.spin.clone())
        );
    }
}
