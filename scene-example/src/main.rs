//! Run a 2D scene on the kernels specialised to it by `build.rs`:
//! `cargo run --release -p noslip-scene-example -- scenes/gas2d.toml 1000000`.

use noslip_scene::Scene;
use noslip_scene_example::{disk_between_walls, gas2d, kernels_fit, sinai, COMPILED};
use noslip_sim::setup::setup;
use noslip_sim::{PairKernels, Simulation, Step};
use std::io::{ErrorKind, Write};
use std::process::ExitCode;
use std::time::Instant;

const USAGE: &str = "\
Usage: noslip-scene-example [SCENE] [EVENTS]

Run a 2D scene on the kernels that build.rs specialised to it: SCENE is one of the shipped
scenes scenes/disk_between_walls.toml, scenes/gas2d.toml, scenes/sinai.toml (default
scenes/sinai.toml), or a file with the same name, species and walls. Random balls are placed
by noslip simulate's rule. Stops after EVENTS contacts (default 1000000) and prints the
contacts per second and the relative energy drift.

Exit codes: 0 success; 1 stdout could not be written; 2 bad input or usage.";

/// A run's result line.
fn run<K: PairKernels<f64, 2, 1>>(
    scene: &Scene,
    kernels: K,
    events: u64,
) -> Result<String, String> {
    let mut sim = Simulation::new(setup::<2, 1>(scene)?, kernels).map_err(|e| e.to_string())?;
    let e0 = sim.observables().energy;
    let clock = Instant::now();
    let mut done = 0;
    while done < events {
        match sim.step(f64::INFINITY) {
            Step::Contact(_) => done += 1,
            // A long stretch without contact: a notice, the run goes on.
            Step::Quiet { .. } => {}
            _ => break,
        }
    }
    let s = clock.elapsed().as_secs_f64();
    let drift = (sim.observables().energy - e0) / e0;
    Ok(format!(
        "{done} contacts in {s:.3} s ({:.0}/s), energy drift {drift:.3e}",
        done as f64 / s
    ))
}

/// The arguments: `Ok(None)` for `--help`.
fn parse(args: &[String]) -> Result<Option<(String, u64)>, String> {
    let mut positional = Vec::new();
    for a in args {
        match a.as_str() {
            "-h" | "--help" => return Ok(None),
            a if a.starts_with('-') && a.len() > 1 => {
                return Err(format!("unknown option {a:?} (see --help)"))
            }
            a => positional.push(a),
        }
    }
    if positional.len() > 2 {
        return Err(format!(
            "at most SCENE and EVENTS, got {} arguments (see --help)",
            positional.len()
        ));
    }
    let path = positional
        .first()
        .unwrap_or(&"scenes/sinai.toml")
        .to_string();
    let events = match positional.get(1) {
        None => 1_000_000,
        Some(n) => n
            .parse()
            .map_err(|_| format!("EVENTS: {n:?} is not a count of contacts"))?,
    };
    Ok(Some((path, events)))
}

fn main_result() -> Result<Option<String>, String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some((path, events)) = parse(&args)? else {
        return Ok(None);
    };
    let scene = Scene::from_file(path.as_ref()).map_err(|e| e.to_string())?;
    let set = scene.pairs();
    let names = COMPILED.map(|(name, _)| name).join(", ");
    let compiled = COMPILED
        .iter()
        .find(|(name, _)| *name == set.name)
        .ok_or_else(|| {
            format!(
                "{path}: scene {}: this example compiles specialised kernels for {names} only \
                 (build.rs); run other scenes with `noslip simulate`",
                set.name
            )
        })?;
    let compiled_set = Scene::from_toml(compiled.1, &format!("{}.toml", compiled.0))
        .map_err(|e| e.to_string())?
        .pairs();
    if !kernels_fit(&compiled_set, &set) {
        return Err(format!(
            "{path}: its species or walls differ from scenes/{}.toml, whose kernels are \
             compiled here: specialised kernels fit only their own constants",
            set.name
        ));
    }
    let line = match set.name.as_str() {
        "sinai" => run(&scene, sinai::Kernels, events),
        "disk_between_walls" => run(&scene, disk_between_walls::Kernels, events),
        "gas2d" => run(&scene, gas2d::Kernels, events),
        other => unreachable!("{other} is in COMPILED"),
    }
    .map_err(|e| format!("{path}: {e}"))?;
    Ok(Some(line))
}

fn main() -> ExitCode {
    let text = match main_result() {
        Ok(Some(line)) => line,
        Ok(None) => USAGE.to_string(),
        Err(e) => {
            let _ = writeln!(std::io::stderr(), "error: {e}");
            return ExitCode::from(2);
        }
    };
    match writeln!(std::io::stdout(), "{text}") {
        Err(e) if e.kind() != ErrorKind::BrokenPipe => {
            let _ = writeln!(std::io::stderr(), "error: cannot write to stdout: {e}");
            ExitCode::from(1)
        }
        _ => ExitCode::SUCCESS,
    }
}
