//! The homogeneous cooling state of rough balls by direct simulation Monte Carlo (DSMC) of
//! the homogeneous Boltzmann equation, written here without the engine: its own random
//! numbers, its own collision rule (angular velocity as a vector in 3D, the out-of-plane
//! component in 2D), no positions. It tells apart what the kinetic equation does from what
//! the engine does: where the engine's `T_rot / T_tr` departs from the Maxwellian
//! two-temperature theory (docs/granular.md), the Boltzmann equation's own homogeneous
//! cooling state departs the same way. And at `beta = -1` (smooth balls) its fourth cumulant
//! `a_2` against the Sonine theory (`scripts/sonine_cooling_a2.py`).
//!
//! `cargo test -p noslip-sim --test sim boltzmann:: -- --ignored --nocapture` (a few minutes).

use crate::common;
use common::dsmc::dsmc;
use common::{mean_se, two_temperature, T_5};

/// The DSMC's own check: elastic, perfectly rough balls (`e = beta = 1`, no energy lost)
/// share their energy equally, `T_rot / T_tr = 1`, from equal temperatures and stay there
/// (six seeds of 4000 particles, 40 collisions per particle after 10); `s < 0.004`.
#[test]
fn dsmc_of_elastic_perfectly_rough_balls_keeps_equipartition() {
    for dim in [2, 3] {
        let ratio: Vec<f64> = (0..6)
            .map(|seed| dsmc(dim, 1.0, 1.0, 4000, seed, 10.0, 40.0).0)
            .collect();
        let (mean, se) = mean_se(&ratio);
        eprintln!("DSMC {dim}D, e = beta = 1: {mean:.4} +- {se:.4} (6 seeds)");
        assert!(se < 0.004, "too noisy: {ratio:?}");
        assert!((mean - 1.0).abs() < T_5 * se, "{ratio:?}");
    }
}

/// The DSMC's mean of ratios against the Maxwellian two-temperature theory for the cases of
/// the first version of docs/granular.md's table over the roughness, six seeds of 4000
/// particles, the same settling (`|r - r_+| < 1e-3 r_+` by the theory, from `r = 1`) and
/// window (`60 / kappa` collisions per particle); checks only the power (`s < 0.004 r_+`).
/// The engine is held to the DSMC in `cooling_state.rs`.
#[test]
#[ignore]
fn dsmc_cooling_ratio_over_the_roughness() {
    for dim in [3, 2] {
        for (e, beta) in [
            (0.9, 1.0),
            (0.9, 0.9),
            (0.9, 0.5),
            (0.9, 0.0),
            (0.9, -0.5),
            (0.7, 0.9),
            (0.7, 0.5),
        ] {
            let theory = two_temperature(dim, e, beta, 2.0 / (dim as f64 + 2.0));
            let (skip, window) = (theory.settled(1.0, 1e-3), 60.0 / theory.rate());
            let ratio: Vec<f64> = (0..6)
                .map(|seed| dsmc(dim, e, beta, 4000, seed, skip, window).0)
                .collect();
            let (mean, se) = mean_se(&ratio);
            let r = theory.ratio();
            eprintln!(
                "DSMC {dim}D, e = {e}, beta = {beta}: {mean:.4} +- {se:.4} (6 seeds), theory \
                 {r:.4}, {:+.1} %, {:+.1} s",
                100.0 * (mean / r - 1.0),
                (mean - r) / se
            );
            assert!(se < 0.004 * r, "too noisy: {ratio:?}");
        }
    }
}

/// van Noije & Ernst's first Sonine approximation of the cooling state's `a_2`, smooth balls
/// in R^`d` (`scripts/sonine_cooling_a2.py` derives it from the collision integrals and checks
/// it exactly): `16 (1 - e) (1 - 2 e^2) / (9 + 24 d - e (41 - 8 d) + 30 (1 - e) e^2)`.
fn van_noije_ernst(d: usize, e: f64) -> f64 {
    let d = d as f64;
    16.0 * (1.0 - e) * (1.0 - 2.0 * e * e)
        / (9.0 + 24.0 * d - e * (41.0 - 8.0 * d) + 30.0 * (1.0 - e) * e * e)
}

/// The second Sonine approximation's `a_2` (`a_3` added, both to first order;
/// `scripts/sonine_cooling_a2.py`, exact rationals rounded to 6 decimals) at `(d, e)`.
const SECOND_SONINE_A2: [(usize, f64, f64); 4] = [
    (2, 0.5, 0.065_454),
    (2, 0.9, -0.029_671),
    (3, 0.5, 0.044_994),
    (3, 0.9, -0.015_662),
];

/// The fourth cumulant `a_2` of smooth inelastic balls' cooling state (`beta = -1`) by the
/// DSMC against its Sonine theory, `e = 0.5` and `0.9`, 2D and 3D: six seeds of 4000
/// particles, sampled over 100 collisions per particle after 20. The theory's accuracy is
/// taken as its last order's change (second minus first): the DSMC must lie within that plus
/// `t s` of the second order.
#[test]
#[ignore]
fn dsmc_cooling_a2_of_smooth_balls() {
    for (dim, e, second) in SECOND_SONINE_A2 {
        let a2: Vec<f64> = (0..6)
            .map(|seed| dsmc(dim, e, -1.0, 4000, seed, 20.0, 100.0).2)
            .collect();
        let (mean, se) = mean_se(&a2);
        let first = van_noije_ernst(dim, e);
        let order = (second - first).abs();
        eprintln!(
            "DSMC {dim}D smooth, e = {e}: a_2 = {mean:.5} +- {se:.5} (6 seeds); Sonine first \
             order {first:.5}, second {second:.5}; (DSMC - second) / s = {:+.1}",
            (mean - second) / se
        );
        assert!(se < 0.002, "too noisy: {a2:?}");
        assert!((mean - second).abs() < order + T_5 * se, "{a2:?}");
    }
}
