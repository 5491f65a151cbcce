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

use collision_core::{stereographic_normal, Ball, BodyState, Exact};
use num_bigint::BigInt;
use num_traits::Zero;
use rand::{Rng as _, RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// `|S|`.
pub const SET_SIZE: u64 = 1 << 20;

/// A seeded ChaCha8 stream (reproducible across platforms and crate versions), so reports
/// are reproducible.
pub struct Rng(ChaCha8Rng);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(ChaCha8Rng::seed_from_u64(seed))
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0.next_u64()
    }

    /// Uniform in `[lo, hi)`, from 53 random bits.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        let unit = (self.0.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64);
        lo + (hi - lo) * unit
    }

    /// `true` with probability 1/2.
    pub fn coin(&mut self) -> bool {
        self.0.next_u64() >> 63 == 1
    }

    /// Uniform in `S`.
    pub fn element(&mut self) -> Exact {
        Exact::from_integer(BigInt::from(self.0.random_range(1..=SET_SIZE)))
    }
}

/// One exact point: a normal and two bodies (body 1 immovable when `fixed`).
#[derive(Clone, Debug)]
pub struct Point<const N: usize, const S: usize> {
    pub nu: [Exact; N],
    pub balls: [Ball<Exact>; 2],
    pub states: [BodyState<Exact, N, S>; 2],
}

pub fn normal<const N: usize>(rng: &mut Rng) -> [Exact; N] {
    let y: Vec<Exact> = (0..N - 1).map(|_| rng.element()).collect();
    stereographic_normal(&y).try_into().expect("N components")
}

pub fn point<const N: usize, const S: usize>(rng: &mut Rng, fixed: bool) -> Point<N, S> {
    let nu = normal::<N>(rng);
    let mut ball = |movable: bool| Ball {
        inv_mass: if movable {
            rng.element()
        } else {
            Exact::zero()
        },
        radius: rng.element(),
        gamma2: rng.element(),
    };
    let balls = [ball(!fixed), ball(true)];
    let mut state = || BodyState {
        spin: std::array::from_fn(|_| rng.element()),
        velocity: std::array::from_fn(|_| rng.element()),
    };
    let states = [state(), state()];
    Point { nu, balls, states }
}
