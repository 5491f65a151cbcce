//! `noslip simulate FILE`: run a scene, event by event.

use super::exit::{self, Exit, Failure};
use super::out::outln;
use collision_core::sim::{GenericKernels, Setup, Simulation};
use collision_core::Generated;
use collision_core::Kernel;
use indicatif::{ProgressBar, ProgressStyle};
use noslip_codegen::scene::Scene;
use noslip_verify::report::write_atomic;
use noslip_verify::simulate::plot::{energy_svg, trajectories_svg};
use noslip_verify::simulate::run::{run, Limits, Summary};
use noslip_verify::simulate::setup::{f, setup};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

const LONG_ABOUT: &str = "\
Run a scene (TOML, see docs/scenes.md): an event-driven simulation of rigid balls with
no-slip collisions. Balls fly freely between events; at each ball-ball, ball-wall or
ball-obstacle contact the pair's state jumps by the no-slip map (the generated f64 kernels).
Contacts are found with a cell list and a priority queue; periodic axes use images.

Stops after --events contacts or at --time (default: the scene's [simulation] values, else
100000 events). Prints a summary (events, events per second, kinetic energy and the drift of
energy, linear and angular momentum relative to the start) and writes to --out:
summary.json, energy.svg (energy drift over events) and, in 2D, trajectories.svg (a few
balls' paths and the contact points). --log writes every contact as a JSON line: time, kind,
balls, normal, positions, pre and post states.";

#[derive(clap::Args)]
#[command(long_about = LONG_ABOUT, after_long_help = exit::help(CODES))]
pub struct Args {
    /// The scene file.
    file: PathBuf,
    /// Stop after this many contacts.
    #[arg(long)]
    events: Option<u64>,
    /// Stop at this simulated time.
    #[arg(long)]
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

/// What `simulate` can return.
pub const CODES: &[Exit] = &[Exit::Success, Exit::OutputFailed, Exit::BadInput];

/// The summary on stdout (after the files are written: a failing stdout loses nothing).
fn print_summary(s: &Summary) -> Result<(), Failure> {
    outln!(
        "{} contacts ({} ball-ball, {} ball-wall, {} ball-obstacle), {} cell crossings, t = {:.6}",
        s.events,
        s.ball_ball,
        s.ball_wall,
        s.ball_obstacle,
        s.cell_crossings,
        s.time
    )?;
    outln!(
        "{:.3} s wall clock, {:.0} events/s, {} balls in R^{}",
        s.seconds,
        s.events_per_second,
        s.balls,
        s.dim
    )?;
    outln!(
        "energy {:.17e} -> {:.17e}: drift {:.3e} (max over samples {:.3e})",
        s.energy_start,
        s.energy_end,
        s.energy_drift,
        s.energy_drift_max
    )?;
    outln!(
        "momentum drift {:.3e}, angular momentum drift {:.3e} (relative; conserved only without walls/obstacles, angular also without periodic wrapping)",
        s.momentum_drift, s.angular_momentum_drift
    )
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
    let size = setup.size;
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
        traced: 12,
        contact_points: 20_000,
    };
    let out = args.out.clone().unwrap_or_else(|| {
        let stem = Path::new(&scene.origin)
            .file_stem()
            .map_or("scene".into(), |s| s.to_string_lossy().into_owned());
        PathBuf::from("out/simulate").join(stem)
    });
    let mut log = match &args.log {
        Some(p) => {
            Some(BufWriter::new(std::fs::File::create(p).map_err(|e| {
                (1, format!("cannot write {}: {e}", p.display()))
            })?))
        }
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
    if let Some(mut w) = log {
        w.flush()
            .map_err(|e| (1, format!("cannot write the events log: {e}")))?;
    }
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
        write(
            "trajectories.svg",
            trajectories_svg(
                &out.join("trajectories.svg"),
                &format!("{title}: trajectories and contact points"),
                size2,
                &obstacles,
                &trace,
            ),
        )?;
    }
    print_summary(&summary).map_err(|f| (f.exit.code(), f.message))?;
    outln!("wrote {}", out.display()).map_err(|f| (f.exit.code(), f.message))?;
    Ok(())
}

pub fn run_cmd(args: &Args) -> ExitCode {
    let scene = match Scene::from_file(&args.file) {
        Ok(s) => s,
        Err(e) => return exit::finish(Err(Failure::bad_input(e.to_string()))),
    };
    exit::finish(
        super::with_dim!(scene.dim, simulate(&scene, args))
            .map(|()| Exit::Success)
            .map_err(|(code, m)| {
                let exit = if code == 2 {
                    Exit::BadInput
                } else {
                    Exit::OutputFailed
                };
                Failure::new(exit, m)
            }),
    )
}
