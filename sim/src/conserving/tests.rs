//! The energy-conserving correction on the shipped one-ball tables ([`Conserving`],
//! issue 28 item 4): with it the energy has no drift per contact; without it the same runs
//! drift by the kernel's rounding bias (`docs/accuracy.md`, "An energy-conserving
//! correction", where the same statistic is quoted over `10^7` contacts).
//!
//! **The statistic.** Over `K` contacts the per-contact changes of `E = |u|^2 + g R^2 sum
//! U_ij^2` (double-double from the `f64` states, eps of `E_0`) are cut into `B = 40`
//! consecutive batches; `z` is their mean over the standard error of the batch means. The
//! batches absorb the correlation of neighbouring contacts, so with no bias `z` follows
//! Student's t with 39 degrees of freedom: `|z| > 4` has probability below `3e-4` per run.
//! The runs are deterministic (a scene fixes its start), so each assertion is a fixed
//! outcome; the band says how unlikely it would be for an unbiased map. The power: the
//! uncorrected kernel's bias on `disk_between_walls` and `sector` (`+0.008` and `+0.064` eps
//! per contact at `10^7`, standard deviations per contact of about 0.3 and 1.6 eps) puts
//! those runs 8 and 12 standard errors out at `K = 10^5`, so a correction that did nothing
//! would fail.

use super::Conserving;
use crate::setup::setup;
use crate::{GenericKernels, PairKernels, Simulation, Step};
use collision_core::conserve::weighted_squares;
use collision_core::{BodyState, Generated, Kernel};
use noslip_scene::Scene;

const CONTACTS: usize = 100_000;
const BATCHES: usize = 40;
const BAND: f64 = 4.0;

/// `z` of the module docs for `scene` run with `kernels`.
fn z<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(scene: &Scene, kernels: K) -> f64 {
    let setup = setup::<N, S>(scene).expect("valid scene");
    let ball = setup.species[setup.bodies[0].species].clone();
    let w = ball.gamma2 * ball.radius * ball.radius;
    let energy = |s: &BodyState<f64, N, S>| {
        let velocity = s.velocity.iter().map(|&x| (1.0, x));
        weighted_squares(velocity.chain(s.spin.iter().map(|&x| (w, x))))
    };
    let mut sim = Simulation::new(setup, kernels).expect("valid setup");
    let mut before = energy(sim.state(0));
    let scale = 1.0 / (before.0 * f64::EPSILON);
    let mut batches = [0.0; BATCHES];
    let mut k = 0;
    while k < CONTACTS {
        match sim.step(f64::INFINITY) {
            Step::Contact(_) => {}
            Step::Quiet { .. } => continue,
            other => panic!("{}: the run ended at contact {k}: {other:?}", scene.origin),
        }
        let after = energy(sim.state(0));
        batches[k * BATCHES / CONTACTS] += ((after.0 - before.0) + (after.1 - before.1)) * scale;
        before = after;
        k += 1;
    }
    let per = (CONTACTS / BATCHES) as f64;
    let means = batches.map(|b| b / per);
    let mean = means.iter().sum::<f64>() / BATCHES as f64;
    let var = means.iter().map(|m| (m - mean).powi(2)).sum::<f64>() / (BATCHES - 1) as f64;
    mean / (var / BATCHES as f64).sqrt()
}

/// `z` without and with the correction.
fn both<const N: usize, const S: usize>(text: &str, name: &str) -> (f64, f64)
where
    Generated: Kernel<f64, N, S>,
{
    let scene = Scene::from_toml(text, name).expect("valid scene");
    let species = setup::<N, S>(&scene).expect("valid scene").species;
    let generated = GenericKernels {
        species: species.clone(),
    };
    let conserving = Conserving::generic(species, true);
    (
        z::<N, S, _>(&scene, generated),
        z::<N, S, _>(&scene, conserving),
    )
}

#[test]
fn the_corrected_one_ball_tables_have_no_energy_drift_where_the_kernel_alone_has_one() {
    let tables = [
        (
            "disk_between_walls",
            include_str!("../../../scenes/disk_between_walls.toml"),
        ),
        ("sector", include_str!("../../../scenes/sector.toml")),
        ("sinai", include_str!("../../../scenes/sinai.toml")),
    ];
    for (name, text) in tables {
        let (plain, corrected) = both::<2, 1>(text, name);
        assert!(
            corrected.abs() <= BAND,
            "{name}: corrected, the energy drifts at {corrected:+.1} standard errors"
        );
        if name != "sinai" {
            assert!(
                plain.abs() > BAND,
                "{name}: the kernel alone is within the band ({plain:+.1}): the test has no power"
            );
        }
    }
    let (_, corrected) = both::<3, 3>(include_str!("../../../scenes/sphere3d.toml"), "sphere3d");
    assert!(
        corrected.abs() <= BAND,
        "sphere3d: corrected, the energy drifts at {corrected:+.1} standard errors"
    );
}
