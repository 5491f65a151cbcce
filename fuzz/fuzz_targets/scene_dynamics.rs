//! Fuzz target `scene_dynamics`: the scene front end of `noslip lyapunov` and `noslip orbits`.
//!
//! Any bytes are a scene file (UTF-8 and [`Scene::from_toml`], as in `scene_toml`). An
//! accepted scene of at most [`MAX_BALLS`] balls then goes, as the commands take it, through:
//! - `lyapunov`: the QR method with the default `k` and interval, and the two-trajectory
//!   method, each for [`EVENTS`] contacts in [`BLOCKS`] blocks (`noslip_dynamics::lyapunov`);
//! - `orbits`: the search of period [`PERIOD`] on a grid of [`GRID`] starts per coordinate,
//!   bounded by [`MAX_CONTACTS`] contacts (`noslip_dynamics::orbits::search::search`; scenes
//!   of more than one ball are refused by it, as by the command).
//!
//! Contract checked: no panic, abort, hang or unbounded memory; a refusal is an error with a
//! message (exit 2 in the commands); an accepted spectrum's exponents, errors and sum are
//! finite, its interval at most a block, its `k` within the dimension; an accepted search
//! tried at most its starts, followed at most its bound of contacts, and its orbits' starts
//! and residuals are finite.

#![no_main]

use collision_core::{Exact, Generated, Kernel, DIMS};
use libfuzzer_sys::fuzz_target;
use noslip_dynamics::lyapunov::{qr, two_trajectory, Dim, Options, Spectrum};
use noslip_dynamics::orbits::search::{search, Search};
use noslip_dynamics::Dual;
use noslip_scene::Scene;
use noslip_sim::setup::setup;

/// Scenes with more balls are validated only (the engine's work per contact grows with the
/// balls; `scene_toml` places and runs the same scenes).
const MAX_BALLS: usize = 16;
/// Scenes with a box side longer than this many diameters of their smallest ball are not run
/// through `lyapunov`: a run with no contact in reach stops only after its balls fly a
/// million box lengths (the engine's rule, `noslip_sim::run`), and that costs the cells
/// crossed on the way, which grow with the box's size in diameters. Two balls in a box 400
/// diameters wide take 2 s a run in release, ten times that in this instrumented build,
/// which exceeds libFuzzer's timeout (`regressions/scene_dynamics/dilute-timeout.toml`, found by
/// CI). `scene_toml` runs such scenes under its own bound on the simulated time.
const MAX_BOX_DIAMETERS: f64 = 16.0;
/// Contacts of each Lyapunov run, and its blocks (the smallest run the rule takes is
/// `2 (blocks + 1)`).
const EVENTS: u64 = 48;
const BLOCKS: usize = 3;
/// The orbit search: period, starts per coordinate, and its bound of contacts.
const PERIOD: usize = 2;
const GRID: usize = 2;
const MAX_CONTACTS: u64 = 20_000;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(scene) = Scene::from_toml(text, "fuzz.toml") else {
        return;
    };
    if scene.ball_count() > MAX_BALLS {
        return;
    }
    assert!(
        DIMS.contains(&scene.dim),
        "validation accepted dim = {}",
        scene.dim
    );
    collision_core::with_dim!(
        scene.dim,
        |N, S| {
            lyapunov::<N, S>(&scene);
            orbits::<N, S>(&scene);
        },
        unreachable!("checked above")
    )
});

fn check(s: &Spectrum, dimension_cap: usize) {
    assert!(
        s.per_time.len() <= dimension_cap.max(1),
        "k = {}",
        s.per_time.len()
    );
    let block = (s.contacts - s.warmup) / BLOCKS as u64;
    assert!(
        s.every <= block.max(1),
        "every {} beyond a block of {block}",
        s.every
    );
    for e in s.per_time.iter().chain(&s.per_contact).chain([&s.sum]) {
        assert!(
            e.value.is_finite() && e.error.is_finite(),
            "{}: {e:?}",
            s.method
        );
    }
}

fn lyapunov<const N: usize, const S: usize>(scene: &Scene)
where
    Generated: Dim<N, S>,
{
    if let Ok(start) = setup::<N, S>(scene) {
        let diameter = start
            .species
            .iter()
            .map(|b| 2.0 * b.radius)
            .fold(f64::INFINITY, f64::min);
        if start.size.iter().any(|&l| l > MAX_BOX_DIAMETERS * diameter) {
            return;
        }
        let dimension = start.bodies.len() * (2 * N + S);
        let options = Options {
            events: EVENTS,
            k: None,
            blocks: BLOCKS,
            seed: 1,
            law: None,
            every: None,
        };
        match qr(start.clone(), &options) {
            Ok(s) => check(&s, dimension),
            Err(e) => assert!(!e.to_string().is_empty()),
        }
        let one = Options {
            k: Some(1),
            ..options
        };
        match two_trajectory(start, &one) {
            Ok(s) => check(&s, 1),
            Err(e) => assert!(!e.to_string().is_empty()),
        }
    }
}

fn orbits<const N: usize, const S: usize>(scene: &Scene)
where
    Generated: Kernel<f64, N, S> + Kernel<Dual<f64>, N, S>,
    Generated: Kernel<Exact, N, S> + Kernel<Dual<Exact>, N, S>,
{
    let ask = Search {
        period: PERIOD,
        from: Vec::new(),
        grid: Some(GRID),
        law: None,
        max_contacts: MAX_CONTACTS,
    };
    match search::<N, S>(scene, &ask) {
        Ok(report) => {
            assert!(
                report.tried <= report.starts,
                "{} of {}",
                report.tried,
                report.starts
            );
            assert!(
                report.contacts <= MAX_CONTACTS,
                "{} contacts",
                report.contacts
            );
            for o in &report.orbits {
                assert!(o.start.iter().all(|x| x.is_finite()), "{:?}", o.start);
                assert!(o.residual.is_finite(), "residual {}", o.residual);
            }
        }
        Err(e) => assert!(!e.message().is_empty()),
    }
}
