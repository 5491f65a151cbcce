//! Fuzz target `scene_toml`: the scene front end of `noslip simulate` and `noslip gen`.
//!
//! Any bytes are a scene file. The CLI reads it as UTF-8 (other bytes: exit 2), then:
//! - parse and validate (`Scene::from_toml`);
//! - `gen`: the pair set and the specialised module (`specialise::generate`: range checks of
//!   the folded constants, code generation, formatting), and the same in C and OpenCL C
//!   (`backend::generate_scene`), which must accept and refuse exactly the scenes Rust does;
//! - `simulate`: the f64 range checks, placement and setup (`simulate::setup::setup`), the
//!   engine's own setup checks (`Simulation::new`), and a short run through the CLI's run loop
//!   (`simulate::run::run`, at most [`EVENTS`] contacts, the scene's time limit if any, the
//!   events log and the boundary map written to sinks) and the pictures (`energy_svg`,
//!   `trajectories_svg` in 2D, each body's phase portraits).
//!
//! Bounded run: a scene with more than [`MAX_RUN_BALLS`] balls is validated and generated but
//! not placed or run (placement is O(N) and is exercised by smaller scenes; the fuzzer's
//! executions must stay in milliseconds). The run also stops at the simulated time in which
//! the fastest ball flies [`BOX_LENGTHS`] times the longest box side (the scene's own time
//! limit if earlier): a scene whose next contact is astronomically far (a flight almost
//! along a periodic corridor) would otherwise cross cells for a million box lengths before
//! the run loop gives up on it (`noslip_sim::run::MAX_QUIET_BOX_LENGTHS`; docs/reliability.md).
//!
//! Contract checked: no panic, abort, hang or unbounded memory; a refused scene is an error
//! (exit 2 in the CLI); an accepted run's energies, time and energy drifts are finite, and its time
//! is not negative.

#![no_main]

use collision_core::{Generated, Kernel};
use libfuzzer_sys::fuzz_target;
use noslip_codegen::backend::{generate_scene, Lang};
use noslip_codegen::specialise::generate;
use noslip_scene::Scene;
use noslip_sim::boundary_map::{self, BoundaryMap};
use noslip_sim::plot::{energy_svg, trajectories_svg, Table2d};
use noslip_sim::run::{run_observed, Limits};
use noslip_sim::setup::{f, setup};
use noslip_sim::{GenericKernels, Setup, Simulation};

/// Contacts per run, at most (the scene's own limit if lower).
const EVENTS: u64 = 300;
/// Scenes with more balls are not placed or run.
const MAX_RUN_BALLS: usize = 32;
/// Box lengths the fastest ball may fly in a run (two "no contact" notices, at 1000 and 2000).
const BOX_LENGTHS: f64 = 2500.0;
/// Thermostat intervals a run may last: every kick re-bases the clock and predicts every
/// ball again, so a driven scene with few contacts (two balls in a wide periodic box) would
/// otherwise take millions of kicks to reach the box-length bound (a fuzzer-found timeout,
/// `regressions/scene_toml/thermostat-timeout.toml`: 4 million kicks, a minute).
const KICKS: f64 = 1000.0;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return; // the CLI: "cannot read: stream did not contain valid UTF-8", exit 2
    };
    let Ok(scene) = Scene::from_toml(text, "fuzz.toml") else {
        return; // exit 2, "fuzz.toml: PLACE: MESSAGE"
    };
    // `gen`
    let set = scene.pairs();
    // Err: exit 2.
    let rust = generate(&set, "collision_core", "noslip_sim");
    // `gen --lang c|opencl --scene`: the same folded constants, so the same verdict.
    for lang in [Lang::C, Lang::OpenCl] {
        let other = generate_scene(lang, &set);
        assert_eq!(
            other.is_ok(),
            rust.is_ok(),
            "{} and Rust disagree: {:?} vs {:?}",
            lang.name(),
            other.err(),
            rust.as_ref().err()
        );
    }
    // `simulate`
    if scene.ball_count() <= MAX_RUN_BALLS {
        collision_core::with_dim!(
            scene.dim,
            |N, S| simulate::<N, S>(&scene),
            panic!("validation accepted dim = {}", scene.dim)
        )
    }
});

/// What `noslip simulate` does with an accepted scene, with a bounded run.
fn simulate<const N: usize, const S: usize>(scene: &Scene)
where
    Generated: Kernel<f64, N, S>,
{
    let Ok(setup): Result<Setup<N, S>, _> = setup::<N, S>(scene) else {
        return; // exit 2
    };
    let species = setup.species.clone();
    let table = Table2d::of(&setup);
    let size = setup.size;
    let kernels = GenericKernels {
        species: species.clone(),
    };
    let Ok(mut sim) = Simulation::new(setup, kernels) else {
        return; // exit 2
    };
    let speed = (0..sim.len())
        .map(|i| {
            sim.state(i)
                .velocity
                .iter()
                .map(|v| v * v)
                .sum::<f64>()
                .sqrt()
        })
        .fold(0.0, f64::max);
    let longest = size.iter().copied().fold(0.0, f64::max);
    let bound = (speed > 0.0).then(|| sim.now() + BOX_LENGTHS * longest / speed);
    let kicks = scene
        .thermostat
        .as_ref()
        .map(|t| sim.now() + KICKS * f(&t.interval));
    let bound = match (bound, kicks) {
        (Some(b), Some(k)) => Some(b.min(k)),
        (b, k) => b.or(k),
    };
    let time = match (scene.simulation.time.as_ref().map(f), bound) {
        (Some(t), Some(b)) => Some(t.min(b)),
        (t, b) => t.or(b),
    };
    let limits = Limits {
        events: Some(scene.simulation.events.unwrap_or(EVENTS).min(EVENTS)),
        time,
        samples: 2000,
        traced: if N == 2 { 12 } else { 0 },
        contact_points: if N == 2 { usize::MAX } else { 0 },
    };
    let mut log = std::io::sink();
    let mut map = BoundaryMap::new(std::io::sink(), N).expect("a sink cannot fail");
    let (summary, trace) = run_observed(
        &mut sim,
        &species,
        &limits,
        Some(&mut log),
        &mut |_| {},
        &mut |index, e, sim| match boundary_map::row(index, e, sim, &species) {
            Some(row) => map.push(&row),
            None => Ok(()),
        },
    )
    .expect("a sink cannot fail");
    for portrait in map.portraits(sim.table()) {
        portrait.svg("fuzz.toml").expect("a string cannot fail");
        portrait.png("fuzz.toml");
    }
    for (name, x) in [
        ("energy_start", summary.energy_start),
        ("energy_end", summary.energy_end),
        ("time", summary.time),
    ] {
        assert!(x.is_finite(), "{name} = {x} after an accepted scene");
    }
    assert!(summary.time >= 0.0, "time = {}", summary.time);
    assert!(
        summary.energy_drift.is_finite() && summary.energy_drift_max.is_finite(),
        "energy drift {} (max {}), energy {} -> {}",
        summary.energy_drift,
        summary.energy_drift_max,
        summary.energy_start,
        summary.energy_end
    );
    energy_svg("fuzz.toml: energy drift", &trace).expect("a string cannot fail");
    if N == 2 {
        trajectories_svg("fuzz.toml", &table, &trace).expect("a string cannot fail");
    }
}
