//! Exact sample points for the identity checks, with the finite set they are drawn from
//! (what the Schwartz-Zippel bound needs).
//!
//! Every free input is drawn independently and uniformly from `S = {1, 2, .., 2^20}`: the
//! inverse masses, radii and `gamma2` of both bodies, every entry of `U_i` and `u_i`, and
//! the point `y` in S^(n-1) whose inverse stereographic projection is the normal,
//! `nu = (2 y, |y|^2 - 1) / (|y|^2 + 1)` (exactly unit). Positive values keep every
//! denominator of the map (`|y|^2 + 1`, `w_1 + w_2`, `D`, the Gram determinant) non-zero.
//! The identities are rational-function identities, so physical ranges (`gamma2 <= 2/n`,
//! approaching bodies) do not matter to them.

use collision_core::rng::Rng;
use collision_core::{stereographic_normal, Ball, BodyState, Exact};
use num_traits::Zero;

/// `|S|`.
pub const SET_SIZE: u64 = 1 << 20;

/// Uniform in `S`.
pub fn element(rng: &mut Rng) -> Exact {
    Exact::from_integer(rng.integer(1..=SET_SIZE) as i64)
}

/// One exact point: a normal and two bodies (body 1 immovable when `fixed`).
#[derive(Clone, Debug)]
pub struct Point<const N: usize, const S: usize> {
    /// The unit normal `nu`, from body 1 to body 2.
    pub nu: [Exact; N],
    /// Body 1's and body 2's parameters.
    pub balls: [Ball<Exact>; 2],
    /// Body 1's and body 2's states `(U, u)`.
    pub states: [BodyState<Exact, N, S>; 2],
}

/// An exact unit normal: `nu = (2 y, |y|^2 - 1) / (|y|^2 + 1)` with `y` uniform in `S^(n-1)`.
pub fn normal<const N: usize>(rng: &mut Rng) -> [Exact; N] {
    let y: Vec<Exact> = (0..N - 1).map(|_| element(rng)).collect();
    stereographic_normal(&y).try_into().expect("N components")
}

/// A random point: every free input uniform in `S` (body 1's `inv_mass` 0 when `fixed`).
pub fn point<const N: usize, const S: usize>(rng: &mut Rng, fixed: bool) -> Point<N, S> {
    let nu = normal::<N>(rng);
    let mut ball = |movable: bool| Ball {
        inv_mass: if movable { element(rng) } else { Exact::zero() },
        radius: element(rng),
        gamma2: element(rng),
    };
    let balls = [ball(!fixed), ball(true)];
    let mut state = || BodyState {
        spin: std::array::from_fn(|_| element(rng)),
        velocity: std::array::from_fn(|_| element(rng)),
    };
    let states = [state(), state()];
    Point { nu, balls, states }
}
