//! Lyapunov spectra of a one-ball table and a small gas: the symmetries the dynamics must
//! have, and the two methods (tangent space with QR; two trajectories) against each other.
//!
//! - **Sum 0**: every contact's tangent map and every flight have determinant 1 (the no-slip
//!   map is a linear isometry of the energy metric; the flight is a shear), so the sum of all
//!   exponents is a sum of `log |det| = 0` up to rounding: bounded by 1e-10 per unit time.
//! - **Pairing** `lambda_i = -lambda_{d+1-i}`: for the smooth table (Hamiltonian) a theorem;
//!   for the no-slip ones measured, within 4 standard errors plus the bias of the neutral
//!   directions (their growth is linear in time, so they converge like `log T / T`, not like
//!   the block error: 1% of `lambda_1` after these runs).
//! - **Zero exponents**: one ball in 2D has 3 (time shift, velocity scaling, and the middle of
//!   an odd-dimensional symmetric spectrum); a periodic gas in 2D has 6 (time shift, velocity
//!   scaling, 2 translations, 2 momenta).

use noslip_dynamics::lyapunov::{qr, two_trajectory, Options, Spectrum};
use noslip_dynamics::Law;
use noslip_scene::Scene;

const SINAI: &str = include_str!("../../scenes/sinai.toml");

const GAS: &str = r#"
dim = 2
[box]
size = [6, 6]
boundary = ["periodic", "periodic"]
[[species]]
mass = 1
radius = "1/2"
count = 8
[random]
seed = 2
speed = 1
spin = 1
"#;

fn run(text: &str, events: u64, law: Law, two: bool) -> Spectrum {
    let scene = Scene::from_toml(text, "test.toml").unwrap();
    let setup = noslip_sim::setup::setup::<2, 1>(&scene).unwrap();
    let options = Options {
        events,
        k: None,
        blocks: 10,
        seed: 7,
        law: Some(law),
        every: None,
    };
    if two {
        two_trajectory(
            setup,
            &Options {
                k: Some(1),
                ..options
            },
        )
        .unwrap()
    } else {
        qr(setup, &options).unwrap()
    }
}

/// Exponents below `fraction` of the largest in magnitude.
fn near_zero(s: &Spectrum, fraction: f64) -> usize {
    let top = s.per_time[0].value;
    s.per_time
        .iter()
        .filter(|e| e.value.abs() < fraction * top)
        .count()
}

/// `zero_below`: the fraction of `lambda_1` that separates the neutral exponents from the
/// rest. The Sinai table's spectrum is `lambda_1`, three exponents near 0 and `-lambda_1`
/// (any fraction up to 1/2 separates them: 1/100). The gas has small genuine exponents: its
/// measured spectrum has six of magnitude 2e-4 lambda_1 and the next at 5e-3 lambda_1 (0.0057
/// and -0.0038, at 6 standard errors), so the cut is 2e-3 lambda_1, a factor 10 from both.
fn check_symmetries(s: &Spectrum, zeros: usize, zero_below: f64) {
    let d = s.per_time.len();
    assert_eq!(d, s.dimension);
    assert!(s.sum.value.abs() < 1e-10, "sum {:?}", s.sum);
    let top = s.per_time[0].value;
    assert!(top > 0.1, "chaotic: {top}");
    for i in 0..d / 2 {
        let (a, b) = (s.per_time[i], s.per_time[d - 1 - i]);
        let slack = 4.0 * (a.error + b.error) + 0.01 * top;
        assert!((a.value + b.value).abs() < slack, "pair {i}: {a:?} {b:?}");
    }
    assert_eq!(near_zero(s, zero_below), zeros, "{:?}", s.per_time);
}

#[test]
fn sinai_spectra_are_symmetric_with_three_zeros() {
    for law in [Law::NoSlip, Law::Smooth] {
        let s = run(SINAI, 40_000, law, false);
        check_symmetries(&s, 3, 0.01);
    }
}

#[test]
fn periodic_gas_spectrum_is_symmetric_with_six_zeros() {
    let s = run(GAS, 40_000, Law::NoSlip, false);
    check_symmetries(&s, 6, 0.002);
}

/// The largest exponent by both methods: the difference within 3 combined standard errors.
#[test]
fn the_two_methods_agree_on_the_sinai_table_and_the_gas() {
    for (text, events) in [(SINAI, 20_000), (GAS, 20_000)] {
        let a = run(text, events, Law::NoSlip, false).per_time[0];
        let b = run(text, events, Law::NoSlip, true).per_time[0];
        let sigma = (a.error.powi(2) + b.error.powi(2)).sqrt();
        assert!(
            (a.value - b.value).abs() < 3.0 * sigma,
            "qr {a:?}, two-trajectory {b:?}"
        );
        assert!(
            a.value > 10.0 * sigma,
            "a measured, positive exponent: {a:?}"
        );
    }
}

/// A container, with smooth contacts: the circular billiard is integrable (the angular
/// momentum about the centre, hence the chord length, is conserved with the speed), so every
/// tangent vector grows at most linearly in time and every exponent is 0. Over a finite run
/// linear growth shows as `ln(T / T_w) / (T - T_w)` (the measured part runs from the warm-up's
/// end `T_w` to `T`); every flight has the same length, so `T / T_w` is `contacts / warmup`.
/// Each exponent is at most that (5% for the linear growth's constant term at `T_w`) in
/// size, and the sum is 0 to rounding (1e-12 per unit time). The contact kind comes from the
/// scene (`contact = "smooth"` on the container), no override.
#[test]
fn smooth_circle_is_integrable_all_exponents_vanish() {
    let text = include_str!("../../scenes/circle.toml")
        .replace("radius = 1\n", "radius = 1\ncontact = \"smooth\"\n");
    let scene = Scene::from_toml(&text, "circle.toml").unwrap();
    let setup = noslip_sim::setup::setup::<2, 1>(&scene).unwrap();
    let s = qr(
        setup,
        &Options {
            events: 200_000,
            k: None,
            blocks: 10,
            seed: 7,
            law: None,
            every: None,
        },
    )
    .unwrap();
    let linear = (s.contacts as f64 / s.warmup as f64).ln() / s.time;
    for e in &s.per_time {
        assert!(e.value.abs() <= 1.05 * linear, "{e:?} vs {linear}: {s:?}");
    }
    assert!(s.sum.value.abs() < 1e-12, "{s:?}");
    // The largest is the linear growth's, not a smaller rate: the bound is the right one.
    assert!(s.per_time[0].value > 0.8 * linear, "{s:?}");
}

/// Issue 26: a run of few contacts for its balls (gas2d with `--events 200` renormalised
/// every 187 contacts, 10 blocks of 18) left blocks without a re-orthonormalisation: their
/// estimates were 0/0 and every error bar printed `± NaN`. The default interval is now
/// shortened to a block, and a longer `every` asked for is refused.
#[test]
fn every_block_gets_a_renormalisation_and_every_error_is_finite() {
    // 80 disks: default intervals 20 (QR) and 40 (two trajectories); blocks of 18 contacts.
    let text = GAS
        .replace("size = [6, 6]", "size = [30, 30]")
        .replace("count = 8", "count = 80");
    let scene = Scene::from_toml(&text, "test.toml").unwrap();
    let options = Options {
        events: 200,
        k: Some(4),
        blocks: 10,
        seed: 7,
        law: Some(Law::NoSlip),
        every: None,
    };
    let setup = || noslip_sim::setup::setup::<2, 1>(&scene).unwrap();
    let two = Options {
        k: Some(1),
        ..options
    };
    for s in [
        qr(setup(), &options).unwrap(),
        two_trajectory(setup(), &two).unwrap(),
    ] {
        assert!(s.every <= 18, "{}: every {}", s.method, s.every);
        for e in s.per_time.iter().chain(&s.per_contact).chain([&s.sum]) {
            assert!(
                e.value.is_finite() && e.error.is_finite(),
                "{}: {e:?}",
                s.method
            );
            assert!(e.error > 0.0, "{}: {e:?}", s.method);
        }
    }
    let long = Options {
        every: Some(19),
        ..options
    };
    let e = qr(setup(), &long).unwrap_err();
    assert!(e.to_string().starts_with("--every: 19 contacts"), "{e}");
    assert!(e.to_string().contains("at most 18"), "{e}");
    assert!(qr(
        setup(),
        &Options {
            every: Some(18),
            ..options
        }
    )
    .is_ok());
}

/// The fuzzer's hang (CI, 2026-12-03): a ball flying almost along a corridor of a periodic
/// Sinai table, its next contact `0.3 / 2.2e-12` time units (about `10^11` box lengths) away.
/// `simulate` stopped such a run after [`noslip_sim::run::MAX_QUIET_BOX_LENGTHS`] box lengths;
/// `lyapunov` waited for the contact. Both methods now stop by the same rule, with its
/// reason. (The reach is `2^20` crossings of the box, well under a second.)
#[test]
fn a_corridor_flight_stops_both_methods_at_the_reach_of_simulate() {
    let text = r#"
dim = 2
[box]
size = [1, 1]
boundary = ["periodic", "periodic"]
[[species]]
mass = 1
radius = "1/20"
[[ball]]
species = 0
position = ["0.49", "0.8501"]
velocity = ["-0.99165", "2.2074e-12"]
[[obstacle]]
position = ["1/2", "1/2"]
radius = "3/10"
"#;
    let scene = Scene::from_toml(text, "corridor.toml").unwrap();
    let options = Options {
        events: 48,
        k: None,
        blocks: 3,
        seed: 1,
        law: None,
        every: None,
    };
    let setup = || noslip_sim::setup::setup::<2, 1>(&scene).unwrap();
    let two = Options {
        k: Some(1),
        ..options
    };
    for e in [
        qr(setup(), &options).unwrap_err(),
        two_trajectory(setup(), &two).unwrap_err(),
    ] {
        let e = e.to_string();
        assert!(
            e.starts_with(
                "the run stopped: no contact while every moving ball travelled 1048576 box lengths"
            ),
            "{e}"
        );
        assert!(e.contains("out of reach"), "{e}");
    }
}
