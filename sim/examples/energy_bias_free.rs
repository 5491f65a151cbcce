//! The `free` kernel's energy bias, measured cheaply (issue 28 item 4): two balls that meet
//! again and again, each contact on a random axis `+-e_k` (exact unit normals), the side the
//! one towards which they approach; the generated `free` kernel in `f64`.
//!
//! ```sh
//! cargo run --release -p noslip-sim --example energy_bias_free -- 400000
//! ```
//!
//! Argument: contacts per run. Balls: `g = 1/2`, masses 1 and 2, radii `(1/4, 1/8)`,
//! `(1/20, 3/10)`, `(1/10, 1/10)`; three seeds each, n = 2 and 3. Per run: the mean change per
//! contact of `E = sum_b m_b (|u_b|^2 + g_b R_b^2 sum U_ij^2)` (double-double from the `f64`
//! states, eps of `E_0`) and `z` = mean / standard error of 40 batch means (Student's t with
//! 39 degrees of freedom when there is no bias, as in `collision-core`'s `energy_drift` test).
//! `free` still rounds its two tangential coefficients `p_t = g_1 g_2 / D` and
//! `rho_i = 2 w_i g_j / (R_i D)` separately, the constants' bias removed from `fixed`
//! (`docs/accuracy.md`, "Energy bias"). Each run is made twice: the kernel as generated, and
//! corrected onto the energy of its inputs (`collision_core::conserve::free`).

use collision_core::conserve::{self, weighted_squares};
use collision_core::{Ball, BodyState, Generated, Kernel};
use rand::{Rng as _, SeedableRng};
use rand_chacha::ChaCha8Rng;
/// `E` of the two bodies in double-double, weights `m_b` and `m_b g_b R_b^2` (`w`).
fn energy<const N: usize, const S: usize>(
    m: [f64; 2],
    w: [f64; 2],
    s: &[BodyState<f64, N, S>; 2],
) -> (f64, f64) {
    let body = |b: usize| {
        let velocity = s[b].velocity.iter().map(move |&x| (m[b], x));
        velocity.chain(s[b].spin.iter().map(move |&x| (m[b] * w[b], x)))
    };
    weighted_squares(body(0).chain(body(1)))
}
/// Mean change of `E` per contact (eps of `E_0`) and its batch-means standard error.
fn run<const N: usize, const S: usize>(
    balls: [Ball<f64>; 2],
    seed: u64,
    contacts: usize,
    corrected: bool,
) -> (f64, f64)
where
    Generated: Kernel<f64, N, S>,
{
    let nb = 40;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut s: [BodyState<f64, N, S>; 2] = std::array::from_fn(|_| BodyState {
        spin: std::array::from_fn(|_| rng.random_range(-1.0..1.0)),
        velocity: std::array::from_fn(|_| rng.random_range(-1.0..1.0)),
    });
    let m = [1.0 / balls[0].inv_mass, 1.0 / balls[1].inv_mass];
    let w = [
        balls[0].gamma2 * balls[0].radius * balls[0].radius,
        balls[1].gamma2 * balls[1].radius * balls[1].radius,
    ];
    let e0 = energy(m, w, &s).0;
    let scale = 1.0 / (e0 * f64::EPSILON);
    let mut before = energy(m, w, &s);
    let mut batches = vec![0.0; nb];
    for i in 0..contacts {
        let axis = rng.random_range(0..N);
        let du = s[1].velocity[axis] - s[0].velocity[axis];
        let side = if du < 0.0 { 1.0 } else { -1.0 };
        let nu: [f64; N] = std::array::from_fn(|k| if k == axis { side } else { 0.0 });
        let out = Generated::free(&nu, &balls[0], &balls[1], &s[0], &s[1]);
        s = if corrected {
            conserve::free(&balls[0], &balls[1], [&s[0], &s[1]], [&out[0], &out[1]])
        } else {
            out
        };
        let after = energy(m, w, &s);
        batches[i * nb / contacts] += ((after.0 - before.0) + (after.1 - before.1)) * scale;
        before = after;
    }
    let per = (contacts / nb) as f64;
    let means: Vec<f64> = batches.iter().map(|b| b / per).collect();
    let mean = means.iter().sum::<f64>() / nb as f64;
    let var = means.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (nb - 1) as f64;
    (mean, (var / nb as f64).sqrt())
}
fn main() {
    let contacts: usize = std::env::args().nth(1).unwrap().parse().unwrap();
    for (r1, r2) in [(0.25, 0.125), (0.05, 0.3), (0.1, 0.1)] {
        for seed in 0..3u64 {
            let b = |r: f64, im: f64| Ball {
                inv_mass: im,
                radius: r,
                gamma2: 0.5,
            };
            let balls = [b(r1, 1.0), b(r2, 0.5)];
            for corrected in [false, true] {
                let (m2, s2) = run::<2, 1>(balls.clone(), seed, contacts, corrected);
                let (m3, s3) = run::<3, 3>(balls.clone(), seed, contacts, corrected);
                let kind = if corrected {
                    "conserving"
                } else {
                    "generated "
                };
                println!(
                    "R = ({r1}, {r2}) seed {seed} {kind}: n=2 {m2:+.5} z {:+.1} | n=3 {m3:+.5} z {:+.1}",
                    m2 / s2,
                    m3 / s3
                );
            }
        }
    }
}
