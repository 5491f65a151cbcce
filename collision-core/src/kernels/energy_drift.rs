//! One ball bouncing between walls (the one-ball tables of `docs/scenes.md`), n = 2..6, in
//! `f64`: the generated `fixed` kernel's energy drifts at the rate its constants' rounding
//! predicts, from first principles.
//!
//! Energies are exact (rationals of the `f64` states and parameters), so the measured drift
//! is the kernel's alone. Walls have exactly unit normals `+-e_k`; the axis of each contact
//! comes from a seeded stream and the side is the one the ball moves towards.
//!
//! **The prediction.** `fixed` computes `d = 1 + g`, the velocity's tangential constant
//! `p = g / d` and the spin's `rho = 2 / (R d)`, each rounded: `p (1 + e_p)`,
//! `rho (1 + e_rho)`. The rounded map is then not an isometry, and each contact changes the
//! energy `|u|^2 + g R^2 sum U_ij^2` by
//!
//! ```text
//! 4 g / (1 + g)^2 (g e_p + e_rho) |t|^2       (t: the slip before the contact)
//! ```
//!
//! to first order, plus a term of either sign that averages out over a reversible orbit: a
//! bias of one sign at every contact, so the drift grows linearly, by a fraction of an eps
//! per contact. A form with one rounded constant (`u+ = u - 2 (dn nu + t) + R rho t`) is an
//! exact reflection for any rounded `rho` and has no such bias, but its velocity then carries
//! an absolute error of about `eps |t|` however small `g` is: for a point mass against a
//! fast-spinning immovable body (`|t|` far above `|u|`) that was 4.5e15 eps off a
//! well-conditioned answer (`verify/tests/collide_range.rs`), so the kernel keeps the two
//! accurate constants and this bias, which this test pins.

use crate::kernels::Generated;
use crate::{Ball, BodyState, Exact, Kernel};
use rand::{Rng as _, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Contacts per run.
const CONTACTS: usize = 50_000;

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
/// the drift the constants' rounding predicts for the same contacts.
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
    let (p, rho) = constant_errors(ball);
    let per_slip2 =
        Exact::from_integer(4) * &g / ((Exact::from_integer(1) + &g).pow(2)) * (&g * p + rho);
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

/// The relative roundings `(e_p, e_rho)` of `fixed`'s constants `p = g / d`,
/// `rho = 2 / (R d)`, `d = 1 + g` (as the generated kernel rounds them), exactly.
fn constant_errors(ball: &Ball<f64>) -> (Exact, Exact) {
    let d = 1.0 + ball.gamma2;
    let (p, rho) = (ball.gamma2 / d, 2.0 / (ball.radius * d));
    let g = exact(ball.gamma2);
    let one = Exact::from_integer(1);
    let p_exact = &g / (&one + &g);
    let rho_exact = Exact::from_integer(2) / (exact(ball.radius) * (&one + &g));
    (
        (exact(p) - &p_exact) / p_exact,
        (exact(rho) - &rho_exact) / rho_exact,
    )
}

/// For each n: balls with the uniform `gamma2 = 2 / (n + 2)` and radii 1/20 and 3/10 (`f64`;
/// radius 1/2 would leave the constants unbiased at n = 4 by a coincidence of their
/// roundings, nothing to measure).
fn check<const N: usize, const S: usize>()
where
    Generated: Kernel<f64, N, S>,
{
    let walk = random_walk();
    for (i, radius) in [0.05, 0.3].into_iter().enumerate() {
        let ball = Ball {
            inv_mass: 1.0,
            radius,
            gamma2: 2.0 / (N as f64 + 2.0),
        };
        let seed = 100 * N as u64 + i as u64;
        let (drift, predicted) = run::<N, S>(&ball, seed, generated);
        assert!(
            predicted.abs() >= 2.0 * walk,
            "n = {N}, R = {radius}: the constants' bias is too small to measure here ({predicted:.3e})"
        );
        assert!(
            (drift - predicted).abs() <= 0.1 * predicted.abs() + walk,
            "n = {N}, R = {radius}: fixed drifts {drift:.3e}, predicted {predicted:.3e}"
        );
    }
}

#[test]
fn one_ball_between_walls_drifts_as_its_constants_predict() {
    check::<2, 1>();
    check::<3, 3>();
    check::<4, 6>();
    check::<5, 10>();
    check::<6, 15>();
}

/// The reason for the two constants: a point mass (`g = 0`, so `p = 0`) against an immovable
/// body whose rim moves far faster than the ball (`|t| ~ 1e12 |u|`). The exact velocity after
/// the contact is `u - 2 (u . nu) nu`, whatever the slip; the two-constant kernel multiplies
/// the slip by the exact `p = 0` and gets it to a few eps of `|u|` (the roundings of `dn` and
/// of `u - 2 dn nu`: 8 eps of the largest component allowed), where a one-constant form
/// (`R rho = 2` only up to rounding, `rho = 2 / 0.3` is not a float) errs by about
/// `eps |t| = 2e-4`.
#[test]
fn a_point_mass_keeps_its_velocity_accurate_against_a_fast_rim() {
    let ball = Ball {
        inv_mass: 1.0,
        radius: 0.3,
        gamma2: 0.0,
    };
    let nu = [0.6, 0.0, 0.8];
    let rim = BodyState::<f64, 3, 3> {
        spin: [1e6, -2e6, 5e5],
        velocity: [0.0; 3],
    };
    let s = BodyState::<f64, 3, 3> {
        spin: [0.25, -0.5, 1.0],
        velocity: [-0.3, 0.7, -1.1],
    };
    let after = Generated::fixed(&nu, &1e6, &ball, &rim, &s);
    let dn: f64 = (0..3).map(|k| s.velocity[k] * nu[k]).sum();
    for (k, (got, (u, n))) in after
        .velocity
        .iter()
        .zip(s.velocity.iter().zip(&nu))
        .enumerate()
    {
        let want = u - 2.0 * dn * n;
        assert!(
            (got - want).abs() <= 8.0 * f64::EPSILON * 1.1,
            "component {k}: {got} against {want}"
        );
    }
}
