//! The event log of a shipped scene on stdout, one JSON line per contact (the lines of
//! `noslip simulate`'s events.jsonl): `cargo run --release -p noslip-sim --example event_log
//! -- SCENE [CONTACTS]`. Two builds of the engine print the same lines when they compute the
//! same contacts (issue 15 compares the engine before and after its event queue changed).

use collision_core::{Generated, Kernel};
use noslip_scene::Scene;
use noslip_sim::run::event_json;
use noslip_sim::setup::setup;
use noslip_sim::{GenericKernels, Simulation, Step};
use std::io::Write;
use std::path::Path;

fn log<const N: usize, const S: usize>(scene: &Scene, contacts: u64)
where
    Generated: Kernel<f64, N, S>,
{
    let start = setup::<N, S>(scene).expect("a shipped scene");
    let kernels = GenericKernels {
        species: start.species.clone(),
    };
    let mut sim = Simulation::new(start, kernels).expect("a valid setup");
    let out = std::io::stdout();
    let mut out = std::io::BufWriter::new(out.lock());
    let mut done = 0;
    while done < contacts {
        match sim.step(f64::INFINITY) {
            Step::Contact(e) => {
                done += 1;
                writeln!(out, "{}", event_json(done, &e)).expect("stdout");
            }
            Step::Quiet { .. } => {}
            _ => break,
        }
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let name = args.first().expect("SCENE");
    let contacts: u64 = args.get(1).map_or(10_000, |a| a.parse().expect("CONTACTS"));
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    let scene = Scene::from_file(&root.join(format!("{name}.toml"))).expect("scene");
    collision_core::with_dim!(
        scene.dim,
        |N, S| log::<N, S>(&scene, contacts),
        unreachable!()
    );
}
