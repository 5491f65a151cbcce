//! `noslip simulate FILE`: run a scene, event by event.

use collision_core::sim::{GenericKernels, Setup, Simulation};
use collision_core::Generated;
use collision_core::Kernel;
use indicatif::{ProgressBar, ProgressStyle};
use noslip_codegen::scene::Scene;
use noslip_verify::report::write_atomic;
use noslip_verify::simulate::log::LogFile;
use noslip_verify::simulate::plot::{energy_svg, trajectories_svg};
use noslip_verify::simulate::run::{run, Limits, Summary};
use noslip_verify::simulate::setup::{f, setup};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

const LONG_ABOUT: &str = "\
Run a scene (TOML, see docs/scenes.md): an event-driven simulation of rigid balls with
no-slip collisions. Balls fly freely between events; at each ball-ball, ball-wall or
ball-obstacle contact the pair's state jumps by the no-slip map (the generated f64 kernels).
Contacts are found with a cell list and a priority queue; periodic axes use images.

Stops after --events contacts (at least 1) or at --time (positive and finite; default: the
scene's [simulation] values, else 100000 events). Prints a summary (events, events per
second, kinetic energy and the drift of energy, linear and angular momentum relative to the
start) and writes to --out: summary.json, energy.svg (energy drift over events) and, in 2D,
trajectories.svg (a few balls' paths, cut at periodic wraps and thinned, and the contact
points). --log writes every contact as a JSON line: time, kind, balls, normal, positions, pre
and post states; the log file appears complete at the end of the run or not at all (if it
cannot be written, the run still ends, prints and writes its summary, and exits 1).

A scene whose numbers leave the f64 range the engine needs (see docs/scenes.md, \"The
scene in f64\") is refused with exit code 2, naming the field.";

#[derive(clap::Args)]
#[command(long_about = LONG_ABOUT, after_long_help = super::EXIT_CODES)]
pub struct Args {
    /// The scene file.
    file: PathBuf,
    /// Stop after this many contacts (at least 1).
    #[arg(long)]
    events: Option<u64>,
    /// Stop at this simulated time (positive and finite).
    #[arg(long, allow_negative_numbers = true)]
    time: Option<f64>,
    /// Write every contact as a JSON line to this file.
    #[arg(long)]
    log: Option<PathBuf>,
    /// Directory for summary.json and the SVG pictures (default out/simulate/SCENE).
    #[arg(long)]
    out: Option<PathBuf>,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

fn print_summary(s: &Summary) {
    println!(
        "{} contacts ({} ball-ball, {} ball-wall, {} ball-obstacle), {} cell crossings, t = {:.6}",
        s.events, s.ball_ball, s.ball_wall, s.ball_obstacle, s.cell_crossings, s.time
    );
    println!(
        "{:.3} s wall clock, {:.0} events/s, {} balls in R^{}",
        s.seconds, s.events_per_second, s.balls, s.dim
    );
    println!(
        "energy {:.17e} -> {:.17e}: drift {:.3e} (max over samples {:.3e})",
        s.energy_start, s.energy_end, s.energy_drift, s.energy_drift_max
    );
    println!(
        "momentum drift {:.3e}, angular momentum drift {:.3e} (relative; conserved only without walls/obstacles, angular also without periodic wrapping)",
        s.momentum_drift, s.angular_momentum_drift
    );
    if let Some(why) = &s.stopped {
        println!("stopped: {why}");
    }
}

fn simulate<const N: usize, const S: usize>(scene: &Scene, args: &Args) -> Result<(), (u8, String)>
where
    Generated: Kernel<f64, N, S>,
{
    let setup: Setup<N, S> =
        setup::<N, S>(scene).map_err(|e| (2, format!("{}: {e}", scene.origin)))?;
    let species = setup.species.clone();
    let obstacles: Vec<([f64; 2], f64)> = setup
        .obstacles
        .iter()
        .map(|o| ([o.position[0], o.position[1]], o.radius))
        .collect();
    let (size, periodic) = (setup.size, setup.periodic);
    let kernels = GenericKernels {
        species: species.clone(),
    };
    let mut sim =
        Simulation::new(setup, kernels).map_err(|e| (2, format!("{}: {e}", scene.origin)))?;
    let mut events = args.events.or(scene.simulation.events);
    let time = args.time.or(scene.simulation.time.as_ref().map(f));
    if events.is_none() && time.is_none() {
        events = Some(100_000);
    }
    let limits = Limits {
        events,
        time,
        samples: 2000,
        traced: if N == 2 { 12 } else { 0 },
        contact_points: if N == 2 { usize::MAX } else { 0 },
    };
    let out = args.out.clone().unwrap_or_else(|| {
        let stem = Path::new(&scene.origin)
            .file_stem()
            .map_or("scene".into(), |s| s.to_string_lossy().into_owned());
        PathBuf::from("out/simulate").join(stem)
    });
    let mut log = match &args.log {
        Some(p) => Some(
            LogFile::create(p).map_err(|e| (1, format!("cannot write {}: {e}", p.display())))?,
        ),
        None => None,
    };
    let progress = (!args.quiet).then(|| {
        let pb = ProgressBar::new(events.unwrap_or(0));
        pb.set_style(
            ProgressStyle::with_template("{bar:40} {pos}/{len} contacts, {per_sec}, eta {eta}")
                .expect("valid template"),
        );
        pb
    });
    let (summary, trace) = run(
        &mut sim,
        &species,
        &limits,
        log.as_mut().map(|w| w as &mut dyn Write),
        progress.as_ref(),
    )
    .map_err(|e| (1, format!("cannot write the events log: {e}")))?;
    if let Some(pb) = progress {
        pb.finish_and_clear();
    }
    // The log is complete or absent; its failure does not stop the summary and pictures.
    let log_failed = match (log, &args.log) {
        (Some(log), Some(p)) => log.finish().err().map(|e| {
            (
                1u8,
                format!(
                    "cannot write the events log {}: {e} (no log was left; the summary was written)",
                    p.display()
                ),
            )
        }),
        _ => None,
    };
    print_summary(&summary);
    let write = |name: &str, r: std::io::Result<()>| {
        r.map_err(|e| {
            (
                1u8,
                format!("cannot write {}: {e}", out.join(name).display()),
            )
        })
    };
    let json = serde_json::to_string_pretty(&summary).expect("summary serialises");
    write(
        "summary.json",
        write_atomic(&out.join("summary.json"), &(json + "\n")),
    )?;
    let title = Path::new(&scene.origin)
        .file_name()
        .map_or(String::new(), |s| s.to_string_lossy().into_owned());
    write(
        "energy.svg",
        energy_svg(
            &out.join("energy.svg"),
            &format!("{title}: energy drift"),
            &trace,
        ),
    )?;
    if N == 2 {
        let size2 = [size[0], size[1]];
        let balls = trace.paths.len();
        write(
            "trajectories.svg",
            trajectories_svg(
                &out.join("trajectories.svg"),
                &format!(
                    "{title}: {balls} ball{} up to t = {:.6}, {} contact points",
                    if balls == 1 { "" } else { "s" },
                    trace.paths_until,
                    trace.contacts.len()
                ),
                size2,
                [periodic[0], periodic[1]],
                &obstacles,
                &trace,
            ),
        )?;
    }
    println!("wrote {}", out.display());
    log_failed.map_or(Ok(()), Err)
}

/// `--time` and `--events` as the scene file has them: a positive finite time, at least one
/// contact.
fn check_limits(args: &Args) -> Result<(), String> {
    if let Some(t) = args.time {
        if !(t > 0.0 && t.is_finite()) {
            return Err(format!("--time: must be positive and finite, got {t}"));
        }
    }
    if args.events == Some(0) {
        return Err(
            "--events: must be at least 1 (a run of no contacts has nothing to report)".into(),
        );
    }
    Ok(())
}

pub fn run_cmd(args: &Args) -> ExitCode {
    if let Err(e) = check_limits(args) {
        return super::fail(2, &e);
    }
    let scene = match Scene::from_file(&args.file) {
        Ok(s) => s,
        Err(e) => return super::fail(2, &e.to_string()),
    };
    match super::with_dim!(scene.dim, simulate(&scene, args)) {
        Ok(()) => ExitCode::SUCCESS,
        Err((code, m)) => super::fail(code, &m),
    }
}
