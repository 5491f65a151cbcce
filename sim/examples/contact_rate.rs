//! Contacts per second of the engine on shipped scenes (generic kernels, no log, no
//! observables): `cargo run --release -p noslip-sim --example contact_rate -- [CONTACTS]
//! [RUNS] [SCENE...]` prints, per scene, the median over RUNS (default 5) of contacts per
//! second of this thread's CPU time (Linux `/proc/thread-self/schedstat`, steadier than the
//! wall clock on a shared machine; the wall clock elsewhere) over CONTACTS contacts (default
//! 10^6; fewer if the run ends). It uses
//! only the API that predates the tables (issue 12), so the same file measures the engine
//! before and after that change (docs/tables.md, "Speed").

use collision_core::{Generated, Kernel};
use noslip_scene::Scene;
use noslip_sim::setup::setup;
use noslip_sim::{GenericKernels, Simulation, Step};
use std::path::Path;
use std::time::Instant;

/// Seconds of CPU time this thread has run (Linux), or of wall clock since `start`.
fn seconds(start: &Instant) -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .map_or_else(|| start.elapsed().as_secs_f64(), |ns| ns * 1e-9)
}

/// Contacts per second of one run of `scene` for up to `contacts` contacts, and the contacts.
fn rate<const N: usize, const S: usize>(scene: &Scene, contacts: u64) -> (f64, u64)
where
    Generated: Kernel<f64, N, S>,
{
    let start = setup::<N, S>(scene).expect("a shipped scene");
    let kernels = GenericKernels {
        species: start.species.clone(),
    };
    let mut sim = Simulation::new(start, kernels).expect("a valid setup");
    let clock = Instant::now();
    let t0 = seconds(&clock);
    let mut done = 0;
    while done < contacts {
        match sim.step(f64::INFINITY) {
            Step::Contact(_) => done += 1,
            Step::Quiet { .. } => {}
            _ => break,
        }
    }
    (done as f64 / (seconds(&clock) - t0), done)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let contacts: u64 = args
        .first()
        .map_or(1_000_000, |a| a.parse().expect("CONTACTS"));
    let runs: usize = args.get(1).map_or(5, |a| a.parse().expect("RUNS"));
    let default = ["disk_between_walls", "sinai", "gas2d", "gas3d"];
    let names: Vec<String> = if args.len() > 2 {
        args[2..].to_vec()
    } else {
        default.iter().map(|s| s.to_string()).collect()
    };
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    for name in names {
        let scene = Scene::from_file(&root.join(format!("{name}.toml"))).expect("scene");
        let mut rates = Vec::new();
        let mut done = 0;
        for _ in 0..runs {
            let (r, d) = collision_core::with_dim!(
                scene.dim,
                |N, S| rate::<N, S>(&scene, contacts),
                unreachable!()
            );
            rates.push(r);
            done = d;
        }
        rates.sort_by(f64::total_cmp);
        println!(
            "{name}: {done} contacts, median {:.0} contacts per CPU second (min {:.0}, max {:.0}, {runs} runs)",
            rates[runs / 2],
            rates[0],
            rates[runs - 1]
        );
    }
}
