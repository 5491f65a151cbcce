//! The tangent maps of hard-ball dynamics with no-slip (or smooth) contacts.
//!
//! Phase space per ball: centre `x` (n), centre velocity `u` (n) and angular velocity `U`
//! (its `S = n(n-1)/2` entries `U_ij`, `i < j`). The orientation is left out: the mass
//! distributions are radial, so the orientation never feeds back into `x`, `u` or `U` (its
//! own tangent block is triangular with a unit diagonal and adds `S` zero exponents per ball).
//! A tangent vector is stored per ball as the block `[dx (n), du (n), dU (S)]`.
//!
//! **Free flight** for a time `t`: `dx += t du` (`du`, `dU` constant).
//!
//! **Contact** (Dellago, Posch and Hoover's construction, for any map `v' = M(nu) v` linear
//! in the velocities): with the contact function `g` (`g = 0` at contact, `grad g = nu` in the
//! relative centre `x_rel`: `x` for a boundary, `x_j - x_i` for a pair) and `v_rel` the
//! relative centre velocity before the contact, the perturbed trajectory touches at
//! `t_c + dt_c`, compared at the same time `t_c` just after the contact:
//!
//! ```text
//! dt_c = -(nu . dx_rel) / (nu . v_rel)
//! dnu  = kappa (I - nu nu^T) (dx_rel + v_rel dt_c)          (crate::geometry)
//! dx'  = dx + (u - u') dt_c                                 (each ball's centre)
//! dv'  = M(nu) dv + (D_nu M [dnu]) v                        (v = (u, U) of the balls)
//! ```
//!
//! `dv'` is computed in one run of the law in dual numbers: the `eps` part of
//! `M(nu + eps dnu) (v + eps dv)` (crate::dual), exact in exact rationals; `dnu` is tangent
//! to the unit sphere, so the kernels' values off it (they assume `|nu| = 1`) do not enter.
//! The spin has no `(U - U') dt_c` term: `U` does not move `x` or `U` in flight.

use crate::dual::Dual;
use crate::geometry::{dot, Geometry};
use crate::law::Law;
use collision_core::{Ball, BodyState, Generated, Kernel, RefArith, Scalar};

/// The length `2n + S` of one ball's block of a tangent vector.
pub const fn block_len(n: usize, s: usize) -> usize {
    2 * n + s
}

/// Free flight of one ball's block for a time `t`: `dx += t du`.
pub fn flight<T: Scalar, const N: usize>(block: &mut [T], t: &T) {
    for k in 0..N {
        let du = block[N + k].clone();
        block[k] += t.clone() * du;
    }
}

/// `(x, u, U) + eps (dx, du, dU)`'s velocity part as a dual state.
fn lift<T: Scalar, const N: usize, const S: usize>(
    state: &BodyState<T, N, S>,
    block: &[T],
) -> BodyState<Dual<T>, N, S> {
    BodyState {
        spin: std::array::from_fn(|k| Dual::new(state.spin[k].clone(), block[2 * N + k].clone())),
        velocity: std::array::from_fn(|k| {
            Dual::new(state.velocity[k].clone(), block[N + k].clone())
        }),
    }
}

fn lift_ball<T: Scalar>(b: &Ball<T>) -> Ball<Dual<T>> {
    Ball {
        inv_mass: Dual::constant(b.inv_mass.clone()),
        radius: Dual::constant(b.radius.clone()),
        gamma2: Dual::constant(b.gamma2.clone()),
    }
}

/// `dx' = dx + (u - u') dt_c`, `dv' = eps part of the dual state after the contact`; returns
/// the real state after.
fn land<T: Scalar, const N: usize, const S: usize>(
    block: &mut [T],
    pre: &BodyState<T, N, S>,
    after: BodyState<Dual<T>, N, S>,
    dt_c: &T,
) -> BodyState<T, N, S> {
    for k in 0..N {
        let jump = pre.velocity[k].clone() - after.velocity[k].re.clone();
        block[k] += jump * dt_c.clone();
        block[N + k] = after.velocity[k].du.clone();
    }
    for k in 0..S {
        block[2 * N + k] = after.spin[k].du.clone();
    }
    BodyState {
        spin: after.spin.map(|d| d.re),
        velocity: after.velocity.map(|d| d.re),
    }
}

/// The tangent map of a ball's contact with an immovable boundary at rest: `block` (the
/// ball's `[dx, du, dU]` just before the contact) becomes the block just after; returns the
/// state after. `nu` points from the boundary towards the ball, `pre` is the state before
/// (approaching: `u . nu < 0`).
pub fn boundary_contact<T: Scalar, const N: usize, const S: usize>(
    geometry: &Geometry<T>,
    law: Law,
    ball: &Ball<T>,
    nu: &[T; N],
    pre: &BodyState<T, N, S>,
    block: &mut [T],
) -> BodyState<T, N, S>
where
    for<'a> &'a T: RefArith<T>,
    for<'a> &'a Dual<T>: RefArith<Dual<T>>,
    Generated: Kernel<Dual<T>, N, S>,
{
    let dx: [T; N] = std::array::from_fn(|k| block[k].clone());
    let dt_c = -dot(nu, &dx) / dot(nu, &pre.velocity);
    let d: [T; N] = std::array::from_fn(|k| dx[k].clone() + pre.velocity[k].clone() * dt_c.clone());
    let dnu = geometry.dnu(nu, &d);
    let nu_eps: [Dual<T>; N] = std::array::from_fn(|k| Dual::new(nu[k].clone(), dnu[k].clone()));
    let after = law.boundary(&nu_eps, &lift_ball(ball), &lift(pre, block));
    land(block, pre, after, &dt_c)
}

/// The tangent map of a contact of two balls, `nu` from ball 1 to ball 2 (`geometry` is
/// [`Geometry::Pair`]): their blocks just before become the blocks just after; returns the
/// states after.
#[allow(clippy::too_many_arguments)]
pub fn pair_contact<T: Scalar, const N: usize, const S: usize>(
    geometry: &Geometry<T>,
    law: Law,
    balls: [&Ball<T>; 2],
    nu: &[T; N],
    pre: [&BodyState<T, N, S>; 2],
    block1: &mut [T],
    block2: &mut [T],
) -> [BodyState<T, N, S>; 2]
where
    for<'a> &'a T: RefArith<T>,
    for<'a> &'a Dual<T>: RefArith<Dual<T>>,
    Generated: Kernel<Dual<T>, N, S>,
{
    let dx: [T; N] = std::array::from_fn(|k| block2[k].clone() - block1[k].clone());
    let v: [T; N] =
        std::array::from_fn(|k| pre[1].velocity[k].clone() - pre[0].velocity[k].clone());
    let dt_c = -dot(nu, &dx) / dot(nu, &v);
    let d: [T; N] = std::array::from_fn(|k| dx[k].clone() + v[k].clone() * dt_c.clone());
    let dnu = geometry.dnu(nu, &d);
    let nu_eps: [Dual<T>; N] = std::array::from_fn(|k| Dual::new(nu[k].clone(), dnu[k].clone()));
    let [a1, a2] = law.pair(
        &nu_eps,
        [&lift_ball(balls[0]), &lift_ball(balls[1])],
        [&lift(pre[0], block1), &lift(pre[1], block2)],
    );
    [
        land(block1, pre[0], a1, &dt_c),
        land(block2, pre[1], a2, &dt_c),
    ]
}

#[cfg(test)]
#[path = "tangent_tests.rs"]
mod tests;
