//! An adversarial search against the fast certified companions (`docs/accuracy.md`, "Fast
//! certified companions"): inputs built to stress the soundness argument of
//! `noslip_codegen::certify::fast` — subnormal and near-underflow entries, entries near the
//! floor `s`, huge entries near overflow, zero and negative `inv_mass` and `gamma2` (the
//! kernels are unchecked), divisors that cancel (`m_1 + m_2`, `1 + gamma2`, `D`), non-unit
//! normals, a NaN or an infinity in one entry, in `f64` and in `f32` (generated in `f32`,
//! subnormals included). Every case goes through `collide_certified_by(Companion::Fast, ..)`
//! (`free_fast`, and `fixed_fast` for an immovable body on either side) and is checked:
//!
//! - every output bit-identical to `collide_unchecked`'s (or both NaN);
//! - every bound `>= 0` or `+inf` (never NaN);
//! - a finite bound only on a finite output, and then `|computed - exact| <= bound` in exact
//!   rationals, `exact` the rational map on the given floats (`measure::exact_result`);
//! - where that map is undefined (a non-finite input the kernel reads, or an exact divisor
//!   that vanishes), every component of a body the call moves must have the bound `+inf`
//!   (an immovable body is returned as given, bound 0).
//!
//! Run (release; 300 000 cases per format take 33 s at n = 2, 160 s at n = 4, one core):
//!
//! ```text
//! FAST_ADVERSARIAL_CASES=100000 cargo test --release -p noslip-accuracy \
//!     --test fast_adversarial -- --ignored --nocapture
//! ```

use collision_core::certified::{collide_certified_by, CertifiedKernel, Certify, Companion};
use collision_core::exact::Relaxing;
use collision_core::{collide_unchecked, Ball, BodyState, Exact, Generated, Kernel, Scalar};
use noslip_accuracy::case::{flatten, Case};
use noslip_accuracy::measure::exact_result;
use num_traits::Signed;
use std::panic::{catch_unwind, AssertUnwindSafe};

/// splitmix64: a small deterministic generator.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn sign(&mut self) -> f64 {
        if self.next() & 1 == 0 {
            1.0
        } else {
            -1.0
        }
    }
    fn int(&mut self, lo: i32, hi: i32) -> i32 {
        lo + self.below((hi - lo + 1) as u64) as i32
    }
}

/// A float format the search draws in: `T` with its exponent range.
trait Format: Scalar + Certify + Copy + std::fmt::Debug {
    /// The exponents of the least normal and of the largest finite float.
    const EMIN: i32;
    const EMAX: i32;
    fn of(x: f64) -> Self;
    fn bits_eq(a: Self, b: Self) -> bool;
}

impl Format for f64 {
    const EMIN: i32 = -1022;
    const EMAX: i32 = 1023;
    fn of(x: f64) -> f64 {
        x
    }
    fn bits_eq(a: f64, b: f64) -> bool {
        a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
    }
}

impl Format for f32 {
    const EMIN: i32 = -126;
    const EMAX: i32 = 127;
    fn of(x: f64) -> f32 {
        x as f32
    }
    fn bits_eq(a: f32, b: f32) -> bool {
        a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
    }
}

/// `m 2^e`, `m` in `[1, 2)`, built without overflow or double rounding (`powi` of 2 is exact).
fn pow2(m: f64, e: i32) -> f64 {
    // Split the exponent so that no step overflows or underflows prematurely.
    let half = e / 2;
    m * 2f64.powi(half) * 2f64.powi(e - half)
}

/// One entry from a family chosen at random (in `T`).
fn entry<T: Format>(rng: &mut Rng, family: u64) -> f64 {
    let t = |x: f64| T::of(x).to_f64();
    let m = 1.0 + rng.unit();
    let s = rng.sign();
    match family {
        // Ordinary.
        0 => t(s * 2.0 * rng.unit()),
        // Subnormal.
        1 => t(s * pow2(m, rng.int(T::EMIN - 52, T::EMIN - 1))),
        // Near the least normal.
        2 => t(s * pow2(m, rng.int(T::EMIN - 3, T::EMIN + 40))),
        // Anywhere in the exponent range.
        3 => t(s * pow2(m, rng.int(T::EMIN - 20, T::EMAX))),
        // Near the floors the companions use (2^-340 .. 2^-60 in f64, scaled in f32).
        4 => {
            let (lo, hi) = if T::EMAX > 200 {
                (-420, -40)
            } else {
                (-60, -10)
            };
            let e = rng.int(lo, hi);
            // The power of two itself, or one ulp either side.
            let p = pow2(1.0, e);
            t(s * match rng.below(3) {
                0 => p,
                1 => p * (1.0 + f64::EPSILON),
                _ => p * (1.0 - f64::EPSILON / 2.0),
            })
        }
        // Huge.
        5 => t(s * pow2(m, rng.int(T::EMAX - 40, T::EMAX))),
        // Zero of either sign.
        6 => s * 0.0,
        // Powers of two and small integers (exact, often cancelling).
        7 => s * f64::from(rng.int(0, 4)) * 2f64.powi(rng.int(-3, 3)),
        _ => unreachable!(),
    }
}

/// One case: each input drawn from its own family (weighted towards the extreme ones), then
/// some of the structured cancellations.
fn draw<T: Format, const N: usize, const S: usize>(rng: &mut Rng) -> (Case<T, N, S>, &'static str) {
    let mode = rng.below(8);
    let pick = |rng: &mut Rng| -> f64 {
        let f = match mode {
            // One family for every entry.
            0 => 0,
            1..=3 => rng.below(8),
            // Mostly ordinary, one extreme entry here and there.
            _ => {
                if rng.below(6) == 0 {
                    1 + rng.below(7)
                } else {
                    0
                }
            }
        };
        entry::<T>(rng, f)
    };
    let mut v: Vec<f64> = (0..N + 6 + 2 * (S + N)).map(|_| pick(rng)).collect();
    // Layout: nu[N], balls (inv_mass, radius, gamma2) x 2, states (spin S, velocity N) x 2.
    let (nu0, b0, st0) = (0, N, N + 6);
    let inv = |k: usize| b0 + 3 * k;
    let rad = |k: usize| b0 + 3 * k + 1;
    let gam = |k: usize| b0 + 3 * k + 2;
    let mut family = "mixed";
    match rng.below(10) {
        // A unit normal (rounded) and physical balls: the documented regime, extreme states.
        0 | 1 => {
            let mut n: Vec<f64> = (0..N).map(|_| rng.sign() * rng.unit()).collect();
            let l = n.iter().map(|x| x * x).sum::<f64>().sqrt().max(1e-300);
            n.iter_mut().for_each(|x| *x = T::of(*x / l).to_f64());
            v[nu0..nu0 + N].copy_from_slice(&n);
            for k in 0..2 {
                v[inv(k)] = T::of(rng.unit() + 1e-3).to_f64();
                v[rad(k)] = T::of(rng.unit() + 1e-3).to_f64();
                v[gam(k)] = T::of(rng.unit() * 2.0 / 3.0).to_f64();
            }
            family = "physical balls";
        }
        // m_1 + m_2 cancelling (negative inverse mass, exactly or nearly).
        2 => {
            let w = v[inv(0)];
            v[inv(1)] = T::of(-w * (1.0 + f64::from(rng.int(-3, 3)) * 2f64.powi(rng.int(-60, -1))))
                .to_f64();
            family = "m1 + m2 cancels";
        }
        // 1 + gamma2 cancelling (fixed: `d = 1 + gamma2`), with an immovable body.
        3 => {
            let k = rng.below(2) as usize;
            v[inv(1 - k)] = 0.0;
            v[gam(k)] =
                T::of(-1.0 + f64::from(rng.int(-3, 3)) * 2f64.powi(rng.int(-60, -1))).to_f64();
            family = "1 + gamma2 cancels";
        }
        // `D = (1 + g1) w1 g2 + (1 + g2) g1 w2` cancelling: g2 chosen to zero it.
        4 => {
            let (w1, w2, g1) = (v[inv(0)], v[inv(1)], v[gam(0)]);
            let den = w1 * (1.0 + g1) + g1 * w2;
            if den != 0.0 && den.is_finite() {
                v[gam(1)] = T::of(-g1 * w2 / den).to_f64();
            }
            family = "D cancels";
        }
        // An immovable body on either side, otherwise as drawn.
        5 | 6 => {
            v[inv(rng.below(2) as usize)] = 0.0;
            family = "immovable";
        }
        // A NaN or an infinity in one entry.
        7 => {
            let k = rng.below(v.len() as u64) as usize;
            v[k] = match rng.below(3) {
                0 => f64::NAN,
                1 => f64::INFINITY,
                _ => f64::NEG_INFINITY,
            };
            family = "non-finite entry";
        }
        _ => {}
    }
    let x = |k: usize| T::of(v[k]);
    let ball = |k: usize| Ball {
        inv_mass: x(inv(k)),
        radius: x(rad(k)),
        gamma2: x(gam(k)),
    };
    let state = |k: usize| {
        let o = st0 + k * (S + N);
        BodyState {
            spin: std::array::from_fn(|i| x(o + i)),
            velocity: std::array::from_fn(|i| x(o + S + i)),
        }
    };
    (
        Case {
            nu: std::array::from_fn(|i| x(nu0 + i)),
            balls: [ball(0), ball(1)],
            states: [state(0), state(1)],
        },
        family,
    )
}

/// What the search saw in one dimension and format.
#[derive(Default, Debug)]
struct Seen {
    cases: usize,
    /// Components with a finite bound checked against the exact error.
    checked: usize,
    /// Components with a `+inf` bound.
    infinite: usize,
    /// Cases whose exact map is undefined (a non-finite input, a vanishing exact divisor).
    undefined: usize,
    /// ... of which with a finite bound on some component of a movable body (a failure).
    undefined_finite: usize,
    /// Cases with a non-finite entry only where the kernel does not read it (checked).
    unread: usize,
    /// A few of those, to read.
    undefined_examples: Vec<String>,
    /// Largest `|computed - exact| / bound` over checked components with a positive bound.
    worst: f64,
    /// Failures (bound below the error, a NaN bound, a differing output).
    failures: Vec<String>,
}

/// Check one companion call: `out` bit-identical to `plain`, every bound `>= 0` or `+inf`, a
/// finite bound only on a finite output, and (where `exact` is known) `|out - exact| <= bound`
/// in exact rationals. `moves(k)`: whether component `k` belongs to a body the call moves.
#[allow(clippy::too_many_arguments)]
fn verify<T: Format>(
    seen: &mut Seen,
    what: &dyn Fn() -> String,
    out: &[T],
    bound: &[T],
    plain: &[T],
    exact: Option<&[Exact]>,
    moves: &dyn Fn(usize) -> bool,
) {
    let fail = |seen: &mut Seen, msg: String| {
        if seen.failures.len() < 20 {
            seen.failures.push(format!("{} {msg}", what()));
        }
    };
    for k in 0..out.len() {
        let b = bound[k].to_f64();
        if !T::bits_eq(out[k], plain[k]) {
            fail(
                seen,
                format!(
                    "component {k} {:?} differs from plain {:?}",
                    out[k], plain[k]
                ),
            );
        }
        if b.is_nan() || b < 0.0 {
            fail(seen, format!("component {k} has the bound {b}"));
        }
        if moves(k) && b.is_finite() && !out[k].to_f64().is_finite() {
            fail(
                seen,
                format!("component {k} is {:?} with the finite bound {b:e}", out[k]),
            );
        }
    }
    let Some(exact) = exact else {
        seen.undefined += 1;
        if (0..out.len()).any(|k| moves(k) && bound[k].to_f64().is_finite()) {
            seen.undefined_finite += 1;
            if seen.undefined_examples.len() < 5 {
                let e = format!("out {out:?} bound {bound:?} {}", what());
                seen.undefined_examples.push(e);
            }
            fail(
                seen,
                format!("a finite bound {bound:?} where the exact map is undefined"),
            );
        }
        return;
    };
    for k in 0..out.len() {
        let b = bound[k].to_f64();
        if !b.is_finite() {
            seen.infinite += 1;
            continue;
        }
        let Some(y) = Exact::from_float(out[k].to_f64()) else {
            continue; // a failure above, or an immovable body's non-finite entry
        };
        seen.checked += 1;
        let err = (y - &exact[k]).abs();
        if err > Exact::from_float(b).expect("finite") {
            fail(
                seen,
                format!(
                    "component {k} computed {:e} exact {:e}: error {:e} above the bound {b:e}",
                    out[k].to_f64(),
                    exact[k].to_f64(),
                    err.to_f64()
                ),
            );
        } else if b > 0.0 {
            seen.worst = seen.worst.max(err.to_f64() / b);
        }
    }
}

/// Whether every input of `case` is finite.
fn finite<T: Format, const N: usize, const S: usize>(case: &Case<T, N, S>) -> bool {
    flatten(&case.states)
        .iter()
        .chain(&case.nu)
        .chain(
            case.balls
                .iter()
                .flat_map(|b| [&b.inv_mass, &b.radius, &b.gamma2]),
        )
        .all(|x| x.to_f64().is_finite())
}

/// `f` in exact arithmetic, `None` where it is undefined (an exact division by zero panics).
fn exactly<R>(f: impl FnOnce() -> R) -> Option<R> {
    catch_unwind(AssertUnwindSafe(f)).ok()
}

fn run<T: Format, const N: usize, const S: usize>(cases: usize, seed: u64) -> [Seen; 2]
where
    Generated:
        Kernel<T, N, S> + Kernel<collision_core::ExactRelaxed, N, S> + CertifiedKernel<T, N, S>,
    Relaxing: Kernel<Exact, N, S>,
{
    let mut rng = Rng(seed);
    let [mut seen, mut direct] = [Seen::default(), Seen::default()];
    let per_body = S + N;
    for _ in 0..cases {
        let (case, family) = draw::<T, N, S>(&mut rng);
        let what = || format!("n = {N} {} [{family}] {case:?}", T::NAME);
        // Through the dispatcher.
        seen.cases += 1;
        let (out, bound) = collide_certified_by(
            Companion::Fast,
            &case.nu,
            case.ball_refs(),
            case.state_refs(),
        );
        let plain = collide_unchecked(&case.nu, case.ball_refs(), case.state_refs());
        let (out, bound, plain) = (flatten(&out), flatten(&bound), flatten(&plain));
        // An immovable body is returned as given, bound 0 (exact whatever it holds).
        let moves = |k: usize| !case.balls[k / per_body].is_immovable();
        // With one body immovable, `fixed_fast` reads neither the movable body's `inv_mass`
        // nor the immovable body's `gamma2`: a non-finite entry there is replaced by 1/2, the
        // companion run again (same outputs and bounds, bit for bit) and the exact map taken
        // on that case.
        let mut exact_on = case.clone();
        if !finite(&case) {
            if let Some(still) = (0..2).find(|&k| case.balls[k].is_immovable()) {
                let half = T::of(0.5);
                let fix = |x: &mut T| {
                    if !x.to_f64().is_finite() {
                        *x = half;
                    }
                };
                fix(&mut exact_on.balls[still].gamma2);
                fix(&mut exact_on.balls[1 - still].inv_mass);
                let (o, b) = collide_certified_by(
                    Companion::Fast,
                    &exact_on.nu,
                    exact_on.ball_refs(),
                    exact_on.state_refs(),
                );
                let same = |x: &[T], y: &[T]| x.iter().zip(y).all(|(a, b)| T::bits_eq(*a, *b));
                if !same(&flatten(&o), &out) || !same(&flatten(&b), &bound) {
                    exact_on = case.clone();
                } else if finite(&exact_on) {
                    seen.unread += 1;
                }
            }
        }
        let exact = if finite(&exact_on) {
            let e = exact_on.to_exact();
            exactly(|| flatten(&exact_result(&e)))
        } else {
            None
        };
        verify(
            &mut seen,
            &what,
            &out,
            &bound,
            &plain,
            exact.as_deref(),
            &moves,
        );
        // The kernels directly, on every finite case: `free_fast` whatever the inverse masses
        // (zero included), and `fixed_fast` with body 1's radius and state.
        if !finite(&case) {
            continue;
        }
        direct.cases += 1;
        let e = case.to_exact();
        let (b1, b2) = (&case.balls[0], &case.balls[1]);
        let (s1, s2) = (&case.states[0], &case.states[1]);
        let (out, bound) = <Generated as CertifiedKernel<T, N, S>>::free(
            Companion::Fast,
            &case.nu,
            b1,
            b2,
            s1,
            s2,
        );
        let plain = <Generated as Kernel<T, N, S>>::free(&case.nu, b1, b2, s1, s2);
        let exact = exactly(|| {
            flatten(&<Relaxing as Kernel<Exact, N, S>>::free(
                &e.nu,
                &e.balls[0],
                &e.balls[1],
                &e.states[0],
                &e.states[1],
            ))
        });
        let what_free = || format!("free_fast: {}", what());
        let (out, bound, plain) = (flatten(&out), flatten(&bound), flatten(&plain));
        verify(
            &mut direct,
            &what_free,
            &out,
            &bound,
            &plain,
            exact.as_deref(),
            &|_| true,
        );
        let (out, bound) = <Generated as CertifiedKernel<T, N, S>>::fixed(
            Companion::Fast,
            &case.nu,
            &b1.radius,
            b2,
            s1,
            s2,
        );
        let plain = <Generated as Kernel<T, N, S>>::fixed(&case.nu, &b1.radius, b2, s1, s2);
        let exact = exactly(|| {
            let o = <Relaxing as Kernel<Exact, N, S>>::fixed(
                &e.nu,
                &e.balls[0].radius,
                &e.balls[1],
                &e.states[0],
                &e.states[1],
            );
            o.spin
                .iter()
                .chain(&o.velocity)
                .cloned()
                .collect::<Vec<Exact>>()
        });
        let flat = |o: &BodyState<T, N, S>| -> Vec<T> {
            o.spin.iter().chain(&o.velocity).copied().collect()
        };
        let what_fixed = || format!("fixed_fast: {}", what());
        let (out, bound, plain) = (flat(&out), flat(&bound), flat(&plain));
        verify(
            &mut direct,
            &what_fixed,
            &out,
            &bound,
            &plain,
            exact.as_deref(),
            &|_| true,
        );
    }
    [seen, direct]
}

fn report<T: Format, const N: usize, const S: usize>(cases: usize, seed: u64) -> Vec<String>
where
    Generated:
        Kernel<T, N, S> + Kernel<collision_core::ExactRelaxed, N, S> + CertifiedKernel<T, N, S>,
    Relaxing: Kernel<Exact, N, S>,
{
    let start = std::time::Instant::now();
    let seens = run::<T, N, S>(cases, seed);
    let took = start.elapsed().as_secs_f64();
    let mut failures = Vec::new();
    for (how, seen) in ["collide_certified_by", "free_fast + fixed_fast"]
        .iter()
        .zip(seens)
    {
        println!(
            "n = {N} {} {how}: cases {} checked components {} inf {} non-finite but unread {} undefined {} (with a finite bound {}) worst error/bound {:.3e} failures {} ({took:.1} s both)",
            T::NAME,
            seen.cases,
            seen.checked,
            seen.infinite,
            seen.unread,
            seen.undefined,
            seen.undefined_finite,
            seen.worst,
            seen.failures.len(),
        );
        for f in &seen.undefined_examples {
            println!("  undefined exact, finite bound: {f}");
        }
        for f in &seen.failures {
            println!("  FAIL {f}");
        }
        failures.extend(seen.failures);
    }
    failures
}

/// The search: `FAST_ADVERSARIAL_CASES` cases (default 20 000) per dimension 2..=6 and format.
#[test]
#[ignore = "an adversarial search, minutes in release; see the module docs for the command"]
fn fast_companions_survive_an_adversarial_search() {
    let cases: usize = std::env::var("FAST_ADVERSARIAL_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(20_000);
    let dims: Vec<usize> = std::env::var("FAST_ADVERSARIAL_DIMS")
        .ok()
        .map(|s| s.split(',').filter_map(|x| x.parse().ok()).collect())
        .unwrap_or_else(|| vec![2, 3, 4, 5, 6]);
    // Exact division by zero panics inside `exact_result`: keep those quiet.
    std::panic::set_hook(Box::new(|_| {}));
    let mut failures = Vec::new();
    for &n in &dims {
        let seed = 0x5eed_0000 + n as u64;
        failures.extend(match n {
            2 => [
                report::<f64, 2, 1>(cases, seed),
                report::<f32, 2, 1>(cases, !seed),
            ]
            .concat(),
            3 => [
                report::<f64, 3, 3>(cases, seed),
                report::<f32, 3, 3>(cases, !seed),
            ]
            .concat(),
            4 => [
                report::<f64, 4, 6>(cases, seed),
                report::<f32, 4, 6>(cases, !seed),
            ]
            .concat(),
            5 => [
                report::<f64, 5, 10>(cases, seed),
                report::<f32, 5, 10>(cases, !seed),
            ]
            .concat(),
            6 => [
                report::<f64, 6, 15>(cases, seed),
                report::<f32, 6, 15>(cases, !seed),
            ]
            .concat(),
            _ => panic!("FAST_ADVERSARIAL_DIMS: dimension {n} is not one of 2..=6"),
        });
    }
    let _ = std::panic::take_hook();
    assert!(
        failures.is_empty(),
        "{} failures: {failures:#?}",
        failures.len()
    );
}

/// The check itself can fail: a bound below the error, a NaN bound, a differing output, a
/// finite bound on an infinite output and a finite bound where the exact map is undefined
/// are each reported (quick; the search above is the ignored test).
#[test]
fn the_check_reports_each_kind_of_failure() {
    let exact = [Exact::from_float(1.0).expect("finite")];
    let what = || "unit".to_string();
    let cases: [(f64, f64, f64, Option<&[Exact]>); 5] = [
        (1.5, 0.25, 1.5, Some(&exact)),     // error 0.5 above the bound 0.25
        (1.0, f64::NAN, 1.0, Some(&exact)), // a NaN bound
        (1.0, 0.0, 2.0, Some(&exact)),      // not the plain kernel's output
        (f64::INFINITY, 1.0, f64::INFINITY, None), // a finite bound on an infinite output
        (1.0, 1.0, 1.0, None),              // a finite bound, exact undefined
    ];
    for (out, bound, plain, exact) in cases {
        let mut seen = Seen::default();
        verify(&mut seen, &what, &[out], &[bound], &[plain], exact, &|_| {
            true
        });
        assert!(!seen.failures.is_empty(), "{out} {bound} {plain} passed");
    }
    let mut seen = Seen::default();
    verify(
        &mut seen,
        &what,
        &[1.25],
        &[0.25],
        &[1.25],
        Some(&exact),
        &|_| true,
    );
    assert!(seen.failures.is_empty(), "{:?}", seen.failures);
}
