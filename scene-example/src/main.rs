//! Run a 2D scene with explicit balls on its specialised kernels:
//! `cargo run --release -p noslip-scene-example -- scenes/sinai.toml 1000000`.

use collision_core::sim::{PairKernels, Simulation, Step};
use noslip_codegen::scene::Scene;
use noslip_scene_example::{disk_between_walls, explicit_setup, sinai};
use std::time::Instant;

fn run<K: PairKernels<f64, 2, 1>>(scene: &Scene, kernels: K, events: u64) {
    let mut sim = Simulation::new(explicit_setup(scene), kernels).expect("a valid setup");
    let e0 = sim.observables().energy;
    let clock = Instant::now();
    let mut done = 0;
    while done < events && matches!(sim.step(f64::INFINITY), Step::Contact(_)) {
        done += 1;
    }
    let s = clock.elapsed().as_secs_f64();
    let drift = (sim.observables().energy - e0) / e0;
    println!(
        "{done} contacts in {s:.3} s ({:.0}/s), energy drift {drift:.3e}",
        done as f64 / s
    );
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let path = args.get(1).map_or("scenes/sinai.toml", String::as_str);
    let events = args
        .get(2)
        .and_then(|n| n.parse().ok())
        .unwrap_or(1_000_000);
    let scene = Scene::from_file(path.as_ref()).unwrap_or_else(|e| {
        eprintln!("error: {e}");
        std::process::exit(2)
    });
    match scene.pairs().name.as_str() {
        "sinai" => run(&scene, sinai::Kernels, events),
        "disk_between_walls" => run(&scene, disk_between_walls::Kernels, events),
        other => {
            eprintln!("error: no specialised kernels compiled for scene {other}");
            std::process::exit(2)
        }
    }
}
