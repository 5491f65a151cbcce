//! One ball bouncing between walls (the one-ball tables of `docs/scenes.md`), n = 2..6, in
//! `f64`: the generated `fixed` kernel's energy drifts by at most [`RESIDUAL`] per contact,
//! while the two-constant form it replaced drifts at the rate its constants' rounding
//! predicts.
//!
//! Energies are exact (rationals of the `f64` states and parameters), so the measured drift
//! is the kernels' alone. Walls have exactly unit normals `+-e_k`; the axis of each contact
//! comes from a seeded stream and the side is the one the ball moves towards.
//!
//! **The prediction.** A reflection whose tangential constants are `p = g / (1 + g)` (velocity)
//! and `rho = 2 / (R (1 + g))` (spin), rounded separately to `p (1 + e_p)` and
//! `rho (1 + e_rho)`, changes the energy `|u|^2 + g R^2 sum U_ij^2` of each contact by
//!
//! ```text
//! 4 g / (1 + g)^2 (g e_p + e_rho) |t|^2       (t: the slip before the contact)
//! ```
//!
//! to first order, plus a term of either sign that averages out over a reversible orbit: a
//! bias of one sign at every contact, so the drift grows linearly. The generated kernel
//! rounds one constant, `rho`, and takes the velocity's from it (`2 - R rho`): its map is then
//! an exact reflection for `gamma2 = 2 / (R rho) - 1` (`noslip-codegen`'s `model` tests check
//! that in rationals), and only the roundings of each contact's arithmetic remain.
//!
//! **The residual.** Those roundings are not quite unbiased either: a product by a constant
//! whose significand is close to a simple fraction (`R = 1/20 = 1.6 2^-5`, `rho`) rounds
//! with a mean error that depends on where the other factor sits in its binade, and the
//! energy weights it by the factor's size. `cargo run --release -p collision-core --example
//! energy_drift -- random N R SEEDS 100000` measures it: in 20 runs (n = 2, 4, 6; R = 1/20,
//! 3/10, 1/2) at most 0.026 eps per contact, of either sign; for R = 1/2 within the random
//! walk.

use crate::kernels::Generated;
use crate::{Ball, BodyState, Exact, Kernel};
use rand::{Rng as _, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Contacts per run.
const CONTACTS: usize = 50_000;

/// The largest drift per contact allowed to the generated kernel, in eps: the residual of the
/// roundings (module docs; at most 0.026 eps measured), with room.
const RESIDUAL: f64 = 0.1;

/// Allowance for the part of the drift that is a random walk: `4.4 sqrt(CONTACTS) eps`. Each
/// contact's rounding error has an rms of 0.5 to 0.9 eps (the `energy_drift` example); a sum
/// of that many independent errors of rms 1.1 eps exceeds this with probability below 1e-4.
fn random_walk() -> f64 {
    4.0 * 1.1 * (CONTACTS as f64).sqrt() * f64::EPSILON
}

fn exact(x: f64) -> Exact {
    Exact::from_float(x).expect("finite")
}

/// Twice the kinetic energy per unit mass, exactly: `|u|^2 + g R^2 sum_{i<j} U_ij^2`.
fn energy<const N: usize, const S: usize>(ball: &Ball<f64>, s: &BodyState<f64, N, S>) -> Exact {
    let sum2 = |v: &[f64]| v.iter().map(|&x| exact(x) * exact(x)).sum::<Exact>();
    let (g, r) = (exact(ball.gamma2), exact(ball.radius));
    sum2(&s.velocity) + g * &r * &r * sum2(&s.spin)
}

/// The form `fixed` had before: `P = dn nu + p t`, `u+ = u - 2 P`, `U+ = U + rho (nu ^ t)`,
/// with `p = g / (1 + g)` and `rho = 2 / (R (1 + g))` rounded separately (body 1 at rest).
fn two_constants<const N: usize, const S: usize>(
    nu: &[f64; N],
    ball: &Ball<f64>,
    s: &BodyState<f64, N, S>,
) -> BodyState<f64, N, S> {
    let d = 1.0 + ball.gamma2;
    let (p, rho) = (ball.gamma2 / d, 2.0 / (ball.radius * d));
    let t = slip(nu, ball, s);
    let dn: f64 = (0..N).map(|k| s.velocity[k] * nu[k]).sum();
    let mut after = s.clone();
    for k in 0..N {
        after.velocity[k] -= 2.0 * (dn * nu[k] + p * t[k]);
    }
    for (e, (i, j)) in crate::state::skew_pairs(N).enumerate() {
        after.spin[e] += rho * (t[i] * nu[j] - nu[i] * t[j]);
    }
    after
}

/// The slip `t = u - (u . nu) nu - R U nu` of a ball against a wall at rest.
fn slip<const N: usize, const S: usize>(
    nu: &[f64; N],
    ball: &Ball<f64>,
    s: &BodyState<f64, N, S>,
) -> [f64; N] {
    let u = s.spin_matrix();
    let dn: f64 = (0..N).map(|k| s.velocity[k] * nu[k]).sum();
    std::array::from_fn(|k| {
        let c: f64 = (0..N).map(|j| u[k][j] * nu[j]).sum();
        s.velocity[k] - dn * nu[k] - ball.radius * c
    })
}

/// The generated kernel as the simulator calls it for a wall: body 1 at rest, radius 1.
fn generated<const N: usize, const S: usize>(
    nu: &[f64; N],
    ball: &Ball<f64>,
    s: &BodyState<f64, N, S>,
) -> BodyState<f64, N, S>
where
    Generated: Kernel<f64, N, S>,
{
    Generated::fixed(nu, &1.0, ball, &BodyState::zero(), s)
}

/// The relative drift `(E_K - E_0) / E_0` after `CONTACTS` wall contacts with `kernel`, and
/// the drift the two-constant form's bias predicts for the same contacts.
fn run<const N: usize, const S: usize>(
    ball: &Ball<f64>,
    seed: u64,
    kernel: impl Fn(&[f64; N], &Ball<f64>, &BodyState<f64, N, S>) -> BodyState<f64, N, S>,
) -> (f64, f64) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut s = BodyState::<f64, N, S> {
        spin: std::array::from_fn(|_| rng.random_range(-1.0..1.0)),
        velocity: std::array::from_fn(|_| rng.random_range(-1.0..1.0)),
    };
    let e0 = energy(ball, &s);
    let g = exact(ball.gamma2);
    let (p, rho) = two_constant_errors(ball);
    let per_slip2 = Exact::from_integer(4.into()) * &g
        / ((Exact::from_integer(1.into()) + &g).pow(2))
        * (&g * p + rho);
    let mut slip2 = 0.0;
    for _ in 0..CONTACTS {
        let axis = rng.random_range(0..N);
        let side = if s.velocity[axis] < 0.0 { 1.0 } else { -1.0 };
        let nu: [f64; N] = std::array::from_fn(|k| if k == axis { side } else { 0.0 });
        slip2 += slip(&nu, ball, &s).iter().map(|x| x * x).sum::<f64>();
        s = kernel(&nu, ball, &s);
    }
    let drift = (energy(ball, &s) - &e0) / &e0;
    let predicted = per_slip2 / e0 * exact(slip2);
    (
        num_traits::ToPrimitive::to_f64(&drift).expect("finite"),
        num_traits::ToPrimitive::to_f64(&predicted).expect("finite"),
    )
}

/// The relative roundings `(e_p, e_rho)` of the two-constant form's constants, exactly.
fn two_constant_errors(ball: &Ball<f64>) -> (Exact, Exact) {
    let d = 1.0 + ball.gamma2;
    let (p, rho) = (ball.gamma2 / d, 2.0 / (ball.radius * d));
    let g = exact(ball.gamma2);
    let one = Exact::from_integer(1.into());
    let p_exact = &g / (&one + &g);
    let rho_exact = Exact::from_integer(2.into()) / (exact(ball.radius) * (&one + &g));
    (
        (exact(p) - &p_exact) / p_exact,
        (exact(rho) - &rho_exact) / rho_exact,
    )
}

/// For each n: balls with the uniform `gamma2 = 2 / (n + 2)` and radii 1/20 and 3/10 (`f64`;
/// radius 1/2 would leave the two-constant form unbiased at n = 4 by a coincidence of its
/// roundings).
fn check<const N: usize, const S: usize>()
where
    Generated: Kernel<f64, N, S>,
{
    let walk = random_walk();
    let residual = RESIDUAL * f64::EPSILON * CONTACTS as f64;
    for (i, radius) in [0.05, 0.3].into_iter().enumerate() {
        let ball = Ball {
            inv_mass: 1.0,
            radius,
            gamma2: 2.0 / (N as f64 + 2.0),
        };
        let seed = 100 * N as u64 + i as u64;
        let (drift, _) = run::<N, S>(&ball, seed, generated);
        assert!(
            drift.abs() <= residual + walk,
            "n = {N}, R = {radius}: generated fixed drifts {drift:.3e} over {CONTACTS} contacts \
             (allowed: {residual:.3e} + {walk:.3e})"
        );
        let (drift, predicted) = run::<N, S>(&ball, seed, two_constants);
        assert!(
            predicted.abs() >= 2.0 * walk,
            "n = {N}, R = {radius}: the two-constant bias is too small to measure here ({predicted:.3e})"
        );
        assert!(
            (drift - predicted).abs() <= 0.1 * predicted.abs() + walk,
            "n = {N}, R = {radius}: the two-constant form drifts {drift:.3e}, predicted {predicted:.3e}"
        );
    }
}

#[test]
fn one_ball_between_walls_keeps_its_energy_as_predicted() {
    check::<2, 1>();
    check::<3, 3>();
    check::<4, 6>();
    check::<5, 10>();
    check::<6, 15>();
}
