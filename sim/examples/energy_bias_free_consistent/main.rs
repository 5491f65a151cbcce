//! The `free` kernel's energy bias and the consistent spin coefficient that removes it
//! (issue 28 item 4; `docs/accuracy.md`, "Energy bias", the `free` kernel): the experiment of
//! `energy_bias_free.rs` run with two hand-written forms of the map side by side
//! (`forms.rs`): `shipped` (the generated kernel's operations, checked against
//! `Generated::free` at every contact of the run) and `consistent` (ball 2's spin
//! coefficient from the identity `2 (w_1 + w_2) p_t + R_1 rho_1 + R_2 rho_2 = 2` with the
//! rounded `p_t^`, `rho_1^`).
//!
//! ```sh
//! cargo run --release -p noslip-sim --example energy_bias_free_consistent -- 400000
//! ```
//!
//! Argument: contacts per run (default 400 000). Balls: `g = 1/2`, masses 1 and 2, radii
//! `(1/4, 1/8)`, `(1/20, 3/10)`, `(1/10, 1/10)`; seeds 0, 1, 2; n = 2 and 3 (the settings of
//! `energy_bias_free.rs`, whose figures the `shipped` column reproduces digit for digit).
//! Per run and form: the mean change per contact of
//! `E = sum_b m_b (|u_b|^2 + g_b R_b^2 sum U_ij^2)` (double-double from the `f64` states,
//! eps of `E_0`), `z` = mean / standard error of 40 batch means (Student's t with 39 degrees
//! of freedom when there is no bias), and `pred`, the first-order prediction of the constants'
//! bias: the mean over the run's contacts of `2 p_t |t|^2 delta` with
//! `delta = 2 (w_1 + w_2) p_t^ + R_1 rho_1^ + R_2 rho_2^ - 2` of the form's coefficients,
//! evaluated exactly (`num-rational`); `delta` itself, in eps, goes to stderr.
//!
//! With `--rounded` (slow: exact rationals, about a minute per 10^6 contacts), a third map:
//! `rounded`, the correctly rounded map (the kernel's rational map evaluated in `Exact` on the
//! float inputs, each output rounded once to `f64`: the best any `f64` kernel of this map can
//! do), the reference for the residual that the consistent form leaves. With `--once FLAGS`
//! (`FLAGS` letters of `v`, `s`, `t`; as slow) instead the consistent form with those stages
//! rounded once (`once.rs`): which roundings leave the residual.

#[path = "forms.rs"]
mod forms;
#[path = "once.rs"]
mod once;

use collision_core::{Ball, BodyState, Exact, Generated, Kernel};
use forms::{two_prod, two_sum, Form, Pair};
use num_rational::BigRational;
use num_traits::ToPrimitive;
use once::Once;
use rand::{Rng as _, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Batches of the standard error.
const BATCHES: usize = 40;

/// `E` of the two bodies in double-double, weights `m_b` and `m_b g_b R_b^2` (`w`).
fn energy<const N: usize, const S: usize>(
    m: [f64; 2],
    w: [f64; 2],
    s: &[BodyState<f64, N, S>; 2],
) -> (f64, f64) {
    let mut terms = Vec::new();
    for b in 0..2 {
        for &x in &s[b].velocity {
            terms.push((m[b], x));
        }
        for &x in &s[b].spin {
            terms.push((m[b] * w[b], x));
        }
    }
    terms.into_iter().fold((0.0, 0.0), |(hi, lo), (c, x)| {
        let (sq, sq_lo) = two_prod(x, x);
        let (a, a_lo) = two_prod(c, sq);
        let (s, e) = two_sum(hi, a);
        (s, lo + e + a_lo + c * sq_lo)
    })
}

/// `delta = 2 (w_1 + w_2) p_t^ + R_1 rho_1^ + R_2 rho_2^ - 2` of a form's coefficients, exactly
/// (`rho_2^` = `head + tail` for the consistent form).
fn identity_defect(pair: &Pair, balls: &[Ball<f64>; 2]) -> f64 {
    let q = |x: f64| BigRational::from_float(x).expect("finite");
    let k = &pair.shipped;
    let rho2 = match pair.form {
        Form::Shipped => q(k.rho[1]),
        Form::Consistent => q(pair.rho2_pair.0) + q(pair.rho2_pair.1),
    };
    let sum = (q(k.two_w[0]) + q(k.two_w[1])) * q(k.p_t)
        + q(balls[0].radius) * q(k.rho[0])
        + q(balls[1].radius) * rho2
        - q(2.0);
    sum.to_f64().expect("finite")
}

/// One run's figures.
struct Figures {
    mean: f64,
    se: f64,
    pred: f64,
    mismatches: usize,
}

/// The kernel's rational map on the float inputs, each output rounded once.
fn correctly_rounded<const N: usize, const S: usize>(
    nu: &[f64; N],
    balls: &[Ball<f64>; 2],
    s: &[BodyState<f64, N, S>; 2],
) -> [BodyState<f64, N, S>; 2]
where
    Generated: Kernel<Exact, N, S>,
{
    let x = |v: f64| Exact::from_float(v).expect("finite");
    let nu: [Exact; N] = std::array::from_fn(|k| x(nu[k]));
    let ball = |b: &Ball<f64>| Ball {
        inv_mass: x(b.inv_mass),
        radius: x(b.radius),
        gamma2: x(b.gamma2),
    };
    let state = |b: &BodyState<f64, N, S>| BodyState::<Exact, N, S> {
        spin: std::array::from_fn(|k| x(b.spin[k])),
        velocity: std::array::from_fn(|k| x(b.velocity[k])),
    };
    let after = <Generated as Kernel<Exact, N, S>>::free(
        &nu,
        &ball(&balls[0]),
        &ball(&balls[1]),
        &state(&s[0]),
        &state(&s[1]),
    );
    after.map(|b| BodyState {
        spin: std::array::from_fn(|k| b.spin[k].to_f64()),
        velocity: std::array::from_fn(|k| b.velocity[k].to_f64()),
    })
}

/// The map of a run.
#[derive(Clone, Copy, Debug)]
enum Map {
    /// A hand-written form (`forms.rs`).
    Hand(Form),
    /// The correctly rounded map.
    Rounded,
    /// The consistent form with stages rounded once.
    Once(Once),
}

/// Mean change of `E` per contact (eps of `E_0`), its batch-means standard error and the
/// first-order prediction, as in `energy_bias_free.rs`; the shipped form compared with
/// `Generated::free` at every contact.
fn run<const N: usize, const S: usize>(
    balls: &[Ball<f64>; 2],
    map: Map,
    seed: u64,
    contacts: usize,
) -> Figures
where
    Generated: Kernel<f64, N, S> + Kernel<Exact, N, S>,
{
    let form = match map {
        Map::Hand(form) => form,
        // The prediction for the rounded map is that of exact coefficients: 0.
        Map::Rounded | Map::Once(_) => Form::Consistent,
    };
    let pair = Pair::new(&balls[0], &balls[1], form);
    let delta = match map {
        Map::Hand(_) | Map::Once(_) => identity_defect(&pair, balls),
        Map::Rounded => 0.0,
    };
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
    let mut batches = vec![0.0; BATCHES];
    let (mut pred, mut mismatches) = (0.0, 0);
    for i in 0..contacts {
        let axis = rng.random_range(0..N);
        let du = s[1].velocity[axis] - s[0].velocity[axis];
        let side = if du < 0.0 { 1.0 } else { -1.0 };
        let nu: [f64; N] = std::array::from_fn(|k| if k == axis { side } else { 0.0 });
        let next = match map {
            Map::Hand(_) => pair.collide(&nu, &balls[0], &balls[1], &s[0], &s[1]),
            Map::Rounded => correctly_rounded(&nu, balls, &s),
            Map::Once(once) => once::collide(&pair, once, &nu, balls, &s),
        };
        if matches!(map, Map::Hand(Form::Shipped)) {
            let want: [BodyState<f64, N, S>; 2] =
                <Generated as Kernel<f64, N, S>>::free(&nu, &balls[0], &balls[1], &s[0], &s[1]);
            let bits = |b: &[BodyState<f64, N, S>; 2]| -> Vec<u64> {
                b.iter()
                    .flat_map(|x| x.velocity.iter().chain(&x.spin).map(|v| v.to_bits()))
                    .collect()
            };
            mismatches += usize::from(bits(&next) != bits(&want));
        }
        // The slip before the contact (the axis is exact: t is du minus its normal part and
        // minus c = (R_1 U_1 + R_2 U_2) nu), for the prediction 2 p_t |t|^2 delta.
        let t2: f64 = (0..N)
            .filter(|&k| k != axis)
            .map(|k| {
                let dk = s[1].velocity[k] - s[0].velocity[k];
                let ck: f64 = forms::skew_pairs(N)
                    .iter()
                    .enumerate()
                    .map(|(e, &(a, b))| {
                        let wv = s[0].spin[e] * balls[0].radius + s[1].spin[e] * balls[1].radius;
                        if a == k && b == axis {
                            wv * side
                        } else if b == k && a == axis {
                            -wv * side
                        } else {
                            0.0
                        }
                    })
                    .sum();
                (dk - ck).powi(2)
            })
            .sum();
        pred += 2.0 * pair.shipped.p_t * t2 * delta * scale;
        s = next;
        let after = energy(m, w, &s);
        batches[i * BATCHES / contacts] += ((after.0 - before.0) + (after.1 - before.1)) * scale;
        before = after;
    }
    let per = (contacts / BATCHES) as f64;
    let means: Vec<f64> = batches.iter().map(|b| b / per).collect();
    let mean = means.iter().sum::<f64>() / BATCHES as f64;
    let var = means.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (BATCHES - 1) as f64;
    Figures {
        mean,
        se: (var / BATCHES as f64).sqrt(),
        pred: pred / contacts as f64,
        mismatches,
    }
}

fn main() {
    let mut contacts = 400_000;
    let mut third: Option<Map> = None;
    let mut label = String::from("rounded");
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        if a == "--rounded" {
            third = Some(Map::Rounded);
            continue;
        }
        if a == "--once" {
            let flags = args.next().unwrap_or_default();
            match Once::parse(&flags) {
                Some(once) if !flags.is_empty() => {
                    third = Some(Map::Once(once));
                    label = format!("once {flags}");
                }
                _ => {
                    eprintln!("--once: expected letters of v, s, t, got {flags:?}");
                    std::process::exit(2);
                }
            }
            continue;
        }
        match a.parse() {
            Ok(c) if c >= BATCHES => contacts = c,
            _ => {
                eprintln!(
                    "contacts: expected an integer >= {BATCHES}, --rounded or --once FLAGS, got {a:?}"
                );
                std::process::exit(2);
            }
        }
    }
    let mut mismatches = 0;
    let extra = match third {
        None => String::new(),
        Some(_) => format!(" {label} mean | se | z |"),
    };
    let extra_rule = if third.is_some() {
        "---:|---:|---:|"
    } else {
        ""
    };
    println!(
        "| R_1, R_2 | seed | n | shipped mean | z | pred | consistent mean | se | z | pred |{extra}"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|{extra_rule}");
    for (r1, r2) in [(0.25, 0.125), (0.05, 0.3), (0.1, 0.1)] {
        let b = |r: f64, im: f64| Ball {
            inv_mass: im,
            radius: r,
            gamma2: 0.5,
        };
        let balls = [b(r1, 1.0), b(r2, 0.5)];
        for form in [Form::Shipped, Form::Consistent] {
            let pair = Pair::new(&balls[0], &balls[1], form);
            eprintln!(
                "R = ({r1}, {r2}) {form:?}: delta = {:+.3e} eps",
                identity_defect(&pair, &balls) / f64::EPSILON
            );
        }
        for seed in 0..3u64 {
            let row = |n: usize, a: Figures, c: Figures, r: Option<Figures>| {
                let extra = r.map_or(String::new(), |r| {
                    format!(" {:+.5} | {:.5} | {:+.1} |", r.mean, r.se, r.mean / r.se)
                });
                println!(
                    "| ({r1}, {r2}) | {seed} | {n} | {:+.5} | {:+.1} | {:+.5} | {:+.5} | {:.5} | {:+.1} | {:+.1e} |{extra}",
                    a.mean,
                    a.mean / a.se,
                    a.pred,
                    c.mean,
                    c.se,
                    c.mean / c.se,
                    c.pred
                );
            };
            let a = run::<2, 1>(&balls, Map::Hand(Form::Shipped), seed, contacts);
            let c = run::<2, 1>(&balls, Map::Hand(Form::Consistent), seed, contacts);
            let r = third.map(|map| run::<2, 1>(&balls, map, seed, contacts));
            mismatches += a.mismatches;
            row(2, a, c, r);
            let a = run::<3, 3>(&balls, Map::Hand(Form::Shipped), seed, contacts);
            let c = run::<3, 3>(&balls, Map::Hand(Form::Consistent), seed, contacts);
            let r = third.map(|map| run::<3, 3>(&balls, map, seed, contacts));
            mismatches += a.mismatches;
            row(3, a, c, r);
        }
    }
    if mismatches > 0 {
        eprintln!("the shipped form differs from Generated::free at {mismatches} contacts");
        std::process::exit(1);
    }
}
