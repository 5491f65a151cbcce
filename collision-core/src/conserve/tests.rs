//! The correction checked in exact rationals on random contacts, `n = 2, 3`, at unit and
//! extreme scales and mass ratios ([`regime`]): the energy after it is the energy before to
//! within the outputs' final rounding, the momentum moves by no more than that rounding, the
//! error against the exact map grows by no more than the module docs allow, and the cases it
//! leaves alone are left alone.
//!
//! **The band.** `u = eps / 2`. Each corrected output is `x + fl(ds x')` (`x' = x - v`)
//! rounded stochastically to one of its two neighbouring floats, so `x'' = y (1 + d)` with
//! `|d| < 2u` (a whole gap, not half of it) up to `u |ds x'|`, where `y = x + ds x'`:
//! `|E(x'') - E(y)| <= (4u + 4u^2) E(y)` plus `O(u ds E)`. `E(y) - E_in` is
//! `O(ds^2 + u ds + u^2) E` (module docs). With `|ds| <= MAX_DS = 2^-38`, every term past
//! `4u E` is below `10^-3 u E`: the band is `4.001 u E_in`. The momentum's: `2u` per velocity
//! term, with the same margin.

use super::*;
use crate::kernels::Generated;
use crate::{Exact, Kernel};
use num_traits::Signed as _;
use rand::{Rng as _, SeedableRng};
use rand_chacha::ChaCha8Rng;

const U: f64 = f64::EPSILON / 2.0;
const CASES: usize = 400;

fn x(v: f64) -> Exact {
    Exact::from_float(v).expect("finite")
}

/// `sum c x^2` exactly, with the `f64` weights the correction uses.
fn energy_exact<const N: usize, const S: usize>(
    m: f64,
    ball: &Ball<f64>,
    s: &BodyState<f64, N, S>,
) -> Exact {
    let zero = [0.0; N];
    terms(m, ball, s, &zero).fold(Exact::from_integer(0), |acc, (c, v)| {
        acc + x(c) * x(v) * x(v)
    })
}

/// `sum c v^2` exactly over the exact state `e`, with the `f64` weights the correction gives
/// `ball` of mass `m`.
fn energy_of_exact<const N: usize, const S: usize>(
    m: f64,
    ball: &Ball<f64>,
    e: &BodyState<Exact, N, S>,
) -> Exact {
    let (zero, probe) = ([0.0; N], BodyState::<f64, N, S>::zero());
    let weights = terms(m, ball, &probe, &zero).map(|(c, _)| c);
    let values = e.velocity.iter().chain(e.spin.iter());
    weights
        .zip(values)
        .fold(Exact::from_integer(0), |acc, (c, v)| acc + x(c) * v * v)
}

/// The power of a check over `CASES` cases in dimension `n`: most contacts were corrected,
/// and the kernel alone was outside the band on some.
fn has_power(n: usize, (applied, outside): (usize, usize)) {
    assert!(
        applied > CASES / 2,
        "n = {n}: {applied} of {CASES} corrected"
    );
    assert!(outside > 0, "n = {n}: the kernel alone never left the band");
}

fn exact_state<const N: usize, const S: usize>(s: &BodyState<f64, N, S>) -> BodyState<Exact, N, S> {
    BodyState {
        spin: std::array::from_fn(|k| x(s.spin[k])),
        velocity: std::array::from_fn(|k| x(s.velocity[k])),
    }
}

fn exact_ball(b: &Ball<f64>) -> Ball<Exact> {
    Ball {
        inv_mass: x(b.inv_mass),
        radius: x(b.radius),
        gamma2: x(b.gamma2),
    }
}

/// The regime of case `case`: a scale of the velocities and spins (`1`, `10^-100`, `10^100`),
/// and a spread of the inverse masses (`10^-6` to `10^6` in the last quarter), so that the
/// cases cover the accuracy report's extreme scales and mass ratios as well as the typical
/// ones.
fn regime(case: usize) -> (f64, f64) {
    match case % 4 {
        0 => (1.0, 1.0),
        1 => (1e-100, 1.0),
        2 => (1e100, 1.0),
        _ => (1.0, 1e6),
    }
}

fn random_state<const N: usize, const S: usize>(
    rng: &mut ChaCha8Rng,
    scale: f64,
) -> BodyState<f64, N, S> {
    BodyState {
        spin: std::array::from_fn(|_| scale * rng.random_range(-1.0..1.0)),
        velocity: std::array::from_fn(|_| scale * rng.random_range(-1.0..1.0)),
    }
}

/// A unit normal rounded to `f64` (not exactly of length 1: its rounding is one of the
/// biases the correction removes).
fn random_normal<const N: usize>(rng: &mut ChaCha8Rng) -> [f64; N] {
    let v: [f64; N] = std::array::from_fn(|_| rng.random_range(-1.0..1.0));
    let norm = v.iter().map(|a| a * a).sum::<f64>().sqrt();
    v.map(|a| a / norm)
}

fn random_ball(rng: &mut ChaCha8Rng, n: usize, spread: f64) -> Ball<f64> {
    Ball {
        inv_mass: rng.random_range(0.1..10.0) * spread.powf(rng.random_range(-1.0..1.0)),
        radius: rng.random_range(0.01..3.0),
        gamma2: rng.random_range(0.0..2.0 / n as f64),
    }
}

/// The `E` norm of `a - b` (exact differences, then `f64`).
fn distance<const N: usize, const S: usize>(
    m: f64,
    ball: &Ball<f64>,
    a: &BodyState<f64, N, S>,
    b: &BodyState<Exact, N, S>,
) -> f64 {
    let zero = [0.0; N];
    let weights: Vec<f64> = terms(m, ball, a, &zero).map(|(c, _)| c).collect();
    let values = a.velocity.iter().chain(a.spin.iter());
    let exact = b.velocity.iter().chain(b.spin.iter());
    let sum: f64 = weights
        .iter()
        .zip(values.zip(exact))
        .map(|(c, (v, e))| c * (x(*v) - e).to_f64().powi(2))
        .sum();
    sum.sqrt()
}

fn fixed_case<const N: usize, const S: usize>() -> (usize, usize)
where
    Generated: Kernel<f64, N, S> + Kernel<Exact, N, S>,
{
    let mut rng = ChaCha8Rng::seed_from_u64(28 + N as u64);
    let (mut applied, mut outside) = (0, 0);
    for case in 0..CASES {
        let (scale, spread) = regime(case);
        let ball = random_ball(&mut rng, N, spread);
        let before = random_state::<N, S>(&mut rng, scale);
        let nu = random_normal::<N>(&mut rng);
        let out =
            <Generated as Kernel<f64, N, S>>::fixed(&nu, &1.0, &ball, &BodyState::zero(), &before);
        let corrected = fixed(&ball, &before, &out);
        applied += usize::from(corrected != out);
        let e_in = energy_exact(1.0, &ball, &before);
        let band = x(4.001 * U) * &e_in;
        let off = |s: &BodyState<f64, N, S>| (energy_exact(1.0, &ball, s) - &e_in).abs();
        outside += usize::from(off(&out) > band);
        assert!(
            off(&corrected) <= band,
            "n = {N}, case {case}: |E'' - E_in| = {:e} E_in, band {:e}",
            (off(&corrected) / &e_in).to_f64(),
            4.001 * U
        );
        // Against the exact map at the float inputs: no farther than the kernel, up to the
        // final rounding (`u |x*|_E`) and the exact map's own distance from the sphere (1 %
        // for the second-order terms).
        let exact = <Generated as Kernel<Exact, N, S>>::fixed(
            &nu.map(x),
            &x(1.0),
            &exact_ball(&ball),
            &BodyState::zero(),
            &exact_state(&before),
        );
        // The exact map need not be on the sphere the correction restores (the rounded
        // normal's length, the weight `gamma^2 R R` rounded): radially onto it, `x*` moves
        // by `|E(x*) - E_in| / (2 |x*|_E)`, which the bound allows for.
        let e_exact = energy_of_exact(1.0, &ball, &exact);
        let size = e_exact.to_f64().sqrt();
        let off_sphere = (&e_exact - &e_in).abs().to_f64() / (2.0 * size);
        let (d_out, d_corrected) = (
            distance(1.0, &ball, &out, &exact),
            distance(1.0, &ball, &corrected, &exact),
        );
        assert!(
            d_corrected <= 1.01 * (d_out + off_sphere + 2.0 * U * size),
            "n = {N}, case {case}: error {d_corrected:e} after the correction, {d_out:e} before (|x| {size:e}, off the sphere {off_sphere:e})"
        );
    }
    (applied, outside)
}

#[test]
fn fixed_restores_the_energy_to_the_final_rounding_and_does_not_lose_accuracy() {
    has_power(2, fixed_case::<2, 1>());
    has_power(3, fixed_case::<3, 3>());
}

fn free_case<const N: usize, const S: usize>() -> (usize, usize)
where
    Generated: Kernel<f64, N, S> + Kernel<Exact, N, S>,
{
    let mut rng = ChaCha8Rng::seed_from_u64(2800 + N as u64);
    let (mut applied, mut outside) = (0, 0);
    for case in 0..CASES {
        let (scale, spread) = regime(case);
        let (b1, b2) = (
            random_ball(&mut rng, N, spread),
            random_ball(&mut rng, N, spread),
        );
        let (s1, s2) = (
            random_state::<N, S>(&mut rng, scale),
            random_state::<N, S>(&mut rng, scale),
        );
        let nu = random_normal::<N>(&mut rng);
        let [o1, o2] = <Generated as Kernel<f64, N, S>>::free(&nu, &b1, &b2, &s1, &s2);
        let [c1, c2] = free(&b1, &b2, [&s1, &s2], [&o1, &o2]);
        applied += usize::from(c1 != o1 || c2 != o2);
        let (m1, m2) = (1.0 / b1.inv_mass, 1.0 / b2.inv_mass);
        let total = |a: &BodyState<f64, N, S>, b: &BodyState<f64, N, S>| {
            energy_exact(m1, &b1, a) + energy_exact(m2, &b2, b)
        };
        let e_in = total(&s1, &s2);
        let band = x(4.001 * U) * &e_in;
        outside += usize::from((total(&o1, &o2) - &e_in).abs() > band);
        let off = (total(&c1, &c2) - &e_in).abs();
        assert!(
            off <= band,
            "n = {N}, case {case}: |E'' - E_in| = {:e} E_in",
            (off / &e_in).to_f64()
        );
        // Against the exact map at the float inputs: the move is `|E_in - E_out| / (2
        // sqrt(E_rel))`, at most `sqrt(E / E_rel)` (<= 4) times the kernel's error plus the
        // exact map's own distance from the sphere; then one ulp per output.
        let exact = <Generated as Kernel<Exact, N, S>>::free(
            &nu.map(x),
            &exact_ball(&b1),
            &exact_ball(&b2),
            &exact_state(&s1),
            &exact_state(&s2),
        );
        let d = |a: &BodyState<f64, N, S>, b: &BodyState<f64, N, S>| {
            (distance(m1, &b1, a, &exact[0]).powi(2) + distance(m2, &b2, b, &exact[1]).powi(2))
                .sqrt()
        };
        let (d_out, d_corrected) = (d(&o1, &o2), d(&c1, &c2));
        let e_exact = energy_of_exact(m1, &b1, &exact[0]) + energy_of_exact(m2, &b2, &exact[1]);
        let v: [f64; N] = std::array::from_fn(|k| {
            (b2.inv_mass * o1.velocity[k] + b1.inv_mass * o2.velocity[k])
                / (b1.inv_mass + b2.inv_mass)
        });
        let e_rel: f64 = terms(m1, &b1, &o1, &v)
            .chain(terms(m2, &b2, &o2, &v))
            .map(|(c, y)| c * y * y)
            .sum();
        let size = e_exact.to_f64().sqrt();
        let ratio = (size * size / e_rel).sqrt();
        let off_sphere = (&e_exact - &e_in).abs().to_f64() / (2.0 * e_rel.sqrt());
        assert!(
            d_corrected <= 1.01 * (d_out + ratio * d_out + off_sphere + 2.0 * U * size),
            "n = {N}, case {case}: error {d_corrected:e} after the correction, {d_out:e} before (E / E_rel {:e})",
            ratio * ratio
        );
        // The momentum moves by at most the final rounding of the velocities (the move
        // itself changes it by `ds (P_out - M v)`, of order `u ds`).
        for k in 0..N {
            let p = |a: &BodyState<f64, N, S>, b: &BodyState<f64, N, S>| {
                x(m1) * x(a.velocity[k]) + x(m2) * x(b.velocity[k])
            };
            let moved = (p(&c1, &c2) - p(&o1, &o2)).abs().to_f64();
            let rounding = 2.001 * U * (m1 * c1.velocity[k].abs() + m2 * c2.velocity[k].abs());
            assert!(
                moved <= rounding,
                "n = {N}, case {case}, k = {k}: momentum moved {moved:e}, rounding {rounding:e}"
            );
        }
    }
    (applied, outside)
}

#[test]
fn free_restores_the_total_energy_keeps_the_momentum_and_moves_within_its_bound() {
    has_power(2, free_case::<2, 1>());
    has_power(3, free_case::<3, 3>());
}

#[test]
fn what_the_correction_leaves_alone() {
    let ball = Ball {
        inv_mass: 1.0,
        radius: 0.3,
        gamma2: 0.5,
    };
    let s = BodyState::<f64, 2, 1> {
        spin: [0.7],
        velocity: [0.3, -0.2],
    };
    // Already on its energy: ds = 0, the same bits.
    assert_eq!(fixed(&ball, &s, &s), s);
    // An energy change far beyond rounding (a dissipative law's): not touched.
    let slower = BodyState {
        spin: [0.7],
        velocity: [0.3, -0.1],
    };
    assert_eq!(fixed(&ball, &s, &slower), slower);
    // Not finite, or zero: not touched.
    let nan = BodyState {
        spin: [f64::NAN],
        velocity: [0.3, -0.2],
    };
    assert_eq!(fixed(&ball, &s, &nan).velocity, nan.velocity);
    let rest = BodyState::<f64, 2, 1>::zero();
    assert_eq!(fixed(&ball, &rest, &rest), rest);
    // Two bodies moving almost together (E / E_rel above MAX_REL_RATIO): not touched.
    let a = BodyState {
        spin: [0.0],
        velocity: [1.0, 0.0],
    };
    let b = BodyState {
        spin: [0.0],
        velocity: [1.0 + 1e-3, 0.0],
    };
    let nudged = BodyState {
        spin: [0.0],
        velocity: [1.0 + 1e-3 + 1e-15, 0.0],
    };
    assert_eq!(
        free(&ball, &ball, [&a, &b], [&a, &nudged]),
        [a.clone(), nudged.clone()]
    );
    // A point mass's spin carries no energy: left as it is.
    let point = Ball {
        inv_mass: 1.0,
        radius: 0.3,
        gamma2: 0.0,
    };
    let out = BodyState {
        spin: [0.7],
        velocity: [0.3 * (1.0 + 1e-15), -0.2],
    };
    let corrected = fixed(&point, &s, &out);
    assert_ne!(corrected.velocity, out.velocity);
    assert_eq!(corrected.spin, out.spin);
}

/// [`round_unbiased`] returns `x` or its neighbour on the side of `p`, the neighbour with
/// probability `q = |p| / gap`: over `10^5` salts the neighbour's count is binomial, mean
/// `10^5 q`, standard deviation `sqrt(10^5 q (1 - q))` (at most 158); the band is 5 of them.
/// The cases include sums that cross into the binade below (`-1 + 0.3 ulp(1)` is 0.6 of the
/// gap above `-1`). It is a function of its inputs (the same salt, the same bits).
#[test]
fn the_final_rounding_is_unbiased_and_a_function_of_its_inputs() {
    let ulp = f64::EPSILON;
    for (x, share) in [(1.0, 0.3), (1.5, 0.3), (-1.0, 0.3), (1.0, -0.3), (3.0, 0.1)] {
        let p = share * ulp;
        let other = toward(x, p > 0.0);
        let q = p.abs() / (other - x).abs();
        let mut moved = 0usize;
        for salt in 0..100_000u64 {
            let r = round_unbiased(x, p, salt);
            assert!(r == x || r == other, "{x} + {p}: {r}");
            assert_eq!(r.to_bits(), round_unbiased(x, p, salt).to_bits());
            moved += usize::from(r == other);
        }
        let (mean, sd) = (1e5 * q, (1e5 * q * (1.0 - q)).sqrt());
        assert!(
            (moved as f64 - mean).abs() <= 5.0 * sd,
            "{x} + {share} ulp: the neighbour {moved} times of 10^5, expected {mean}"
        );
    }
    // Exactly representable sums are returned as they are.
    assert_eq!(round_unbiased(1.0, 0.5, 7), 1.5);
    assert_eq!(round_unbiased(0.0, 0.0, 7), 0.0);
}
