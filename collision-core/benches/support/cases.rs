//! Deterministic valid collision cases for the benchmark: both bodies free, unit normal,
//! masses and radii in [0.5, 2], `gamma2` in (0, 2/n], velocities and spins in [-1, 1],
//! approaching (`(u_2 - u_1) . nu` in [-1, -0.1]).

use collision_core::{Ball, BodyState};
use rand::{Rng as _, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A seeded ChaCha8 stream: the batch is the same on every machine and run.
pub type Rng = ChaCha8Rng;

/// One collision: normal, balls, states.
pub struct Case<const N: usize, const S: usize> {
    pub nu: [f64; N],
    pub balls: [Ball<f64>; 2],
    pub states: [BodyState<f64, N, S>; 2],
}

fn ball(rng: &mut Rng, n: usize) -> Ball<f64> {
    let mass = rng.random_range(0.5..2.0);
    Ball {
        inv_mass: 1.0 / mass,
        radius: rng.random_range(0.5..2.0),
        // (1 - [0, 1)) * 2/n is in (0, 2/n]; 2/n (a shell) is possible.
        gamma2: (1.0 - rng.random::<f64>()) * (2.0 / n as f64),
    }
}

fn state<const N: usize, const S: usize>(rng: &mut Rng) -> BodyState<f64, N, S> {
    BodyState {
        spin: std::array::from_fn(|_| rng.random_range(-1.0..1.0)),
        velocity: std::array::from_fn(|_| rng.random_range(-1.0..1.0)),
    }
}

/// A unit vector, uniform on the sphere (rejection from the cube).
fn normal<const N: usize>(rng: &mut Rng) -> [f64; N] {
    loop {
        let v: [f64; N] = std::array::from_fn(|_| rng.random_range(-1.0..1.0));
        let norm2: f64 = v.iter().map(|x| x * x).sum();
        if (0.01..=1.0).contains(&norm2) {
            let norm = norm2.sqrt();
            return v.map(|x| x / norm);
        }
    }
}

/// One approaching case: if `(u_2 - u_1) . nu` is above -0.1, body 2's normal velocity is
/// replaced so that it is uniform in [-1, -0.1].
pub fn case<const N: usize, const S: usize>(rng: &mut Rng) -> Case<N, S> {
    let nu = normal::<N>(rng);
    let balls = [ball(rng, N), ball(rng, N)];
    let mut states = [state::<N, S>(rng), state::<N, S>(rng)];
    let dn: f64 = (0..N)
        .map(|a| (states[1].velocity[a] - states[0].velocity[a]) * nu[a])
        .sum();
    if dn > -0.1 {
        let target = rng.random_range(-1.0..-0.1);
        for (v, n) in states[1].velocity.iter_mut().zip(&nu) {
            *v += (target - dn) * n;
        }
    }
    Case { nu, balls, states }
}

/// `len` cases from `seed`.
pub fn batch<const N: usize, const S: usize>(seed: u64, len: usize) -> Vec<Case<N, S>> {
    let mut rng = Rng::seed_from_u64(seed);
    (0..len).map(|_| case(&mut rng)).collect()
}
