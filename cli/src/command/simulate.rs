//! `noslip simulate FILE`: run a scene, event by event.

use crate::exit::{self, Exit, Failure};
use crate::out::outln;
use crate::publish::Staging;
use collision_core::Generated;
use collision_core::Kernel;
use indicatif::{ProgressBar, ProgressStyle};
use noslip_columnar::events::{event_row, events_table, kick_rows};
use noslip_columnar::{self as columnar, is_parquet};
use noslip_scene::Scene;
use noslip_sim::animation::Recorder;
use noslip_sim::boundary_map::{self, BoundaryMap};
use noslip_sim::granular::Sampler;
use noslip_sim::log::LogFile;
use noslip_sim::plot::{energy_svg, trajectories_svg, Table2d};
use noslip_sim::run::{self, Limits, Progress, Summary};
use noslip_sim::setup::{f, setup};
use noslip_sim::{Conserving, Setup, Simulation};
use std::io::Write;
use std::path::{Path, PathBuf};

mod html;
mod paths;

pub use paths::check_limits;
use paths::{check_paths, same_dir, side_members};

pub(crate) const LONG_ABOUT: &str = "\
Run a scene (TOML, see docs/scenes.md): an event-driven simulation of rigid balls with
no-slip collisions. Balls fly freely between events; at each ball-ball, ball-wall or
ball-obstacle contact the pair's state jumps by its contact law: the no-slip map (the
generated f64 kernels, the default), the smooth one, or the rough-ball law { e, beta } of
granular gases, with the TC model against inelastic collapse (docs/granular.md).
Contacts are found with a cell list and a priority queue; periodic axes use images.

Stops after --events contacts (at least 1) or at --time (positive and finite; default: the
scene's [simulation] values, else 100000 events). Prints a summary (events, events per
second, kinetic energy and the drift of energy, linear and angular momentum relative to the
start) and writes to --out, published as one set (the whole directory is replaced at once;
a non-empty directory noslip did not make is refused): summary.json, energy.svg (energy
drift over events: at most 2000 samples, at least balls/8 contacts apart), with
--observables DT observables.csv and observables.parquet (granular temperatures, collision
frequency, pressure, a2 and energy lost per contact kind every DT,
in a mixture also per pair of species with the pair's contacts, lost_ball_ball_A-B and
contacts_A-B; the same numbers; docs/granular.md), observables.svg (the temperatures against time) and
observables-pressure.svg, -a2.svg, -msd.svg (with --pair-correlation also
pair-correlation.csv, .parquet, .svg; with --self-diffusion self-diffusion.csv) and, in 2D,
trajectories.svg (a few balls' paths, cut at periodic wraps
and thinned, and the contact points). --log and --boundary-map belong to the set: a file
directly in --out is one of its files; a file elsewhere is published in it as events.jsonl
or boundary-map.csv, the file becoming a link to it (so it always shows the log of the
set in --out, and a kill at any moment leaves the log and the set of one run). Missing
parent directories of --out and of these files are created, as mkdir -p would; a path that
is a directory (or --out itself) is refused.
--boundary-map FILE writes the boundary map as CSV (one row per contact with an immovable
body: event, time, ball, kind, id, contact point, boundary coordinate, angles of incidence
and reflection, normal velocity, tangential velocity and spin before and after, scaled spin;
see docs/tables.md), complete or absent like the log, and into --out each body's phase
portraits, portrait-KIND-ID.svg and .png (Birkhoff coordinates: coordinate against the sine
of the angle of reflection; tangential velocity against scaled spin gamma R c; after each
contact; titled, with axes, units and a legend; the SVG's scatter an embedded image). --log writes every contact as a JSON line: time, kind, balls, normal, positions, pre
and post states; the log appears complete at the end of the run or not at all (if it
cannot be written, the run still ends, prints and writes its summary, and exits 1; so for
--boundary-map and --html).
A --log or --boundary-map FILE whose extension is .parquet is written as Apache Parquet
instead (the same fields as typed columns, units in the metadata key noslip.units; see
docs/scenes.md); outside --out it is published as events.parquet or boundary-map.parquet.
--html FILE writes the run as an animation: one self-contained HTML page (no network) that
plays the balls with a mark showing each one's spin, trails, the time, play/pause and a
slider, and for a one-ball table the phase portrait with the current contact highlighted;
2D, and the first three coordinates projected beyond; frames and balls capped so the page
stays under about 2 MB (docs/animation.md). It belongs to the set as --log does (outside
--out it is published as animation.html).

A scene whose numbers leave the f64 range the engine needs (see docs/scenes.md, \"The
scene in f64\") is refused with exit code 2, naming the field.";

/// The arguments of `noslip simulate`.
#[derive(clap::Args)]
#[command(long_about = LONG_ABOUT, after_long_help = exit::help(CODES))]
pub struct Args {
    /// The scene file.
    pub file: PathBuf,
    /// Stop after this many contacts (at least 1).
    #[arg(long)]
    events: Option<u64>,
    /// Stop at this simulated time (positive and finite).
    #[arg(long, allow_negative_numbers = true)]
    time: Option<f64>,
    /// Write every contact as a JSON line to this file (Parquet if it ends in .parquet).
    #[arg(long)]
    log: Option<PathBuf>,
    /// Write the boundary map to this CSV (or .parquet) file (one row per contact with a wall, container,
    /// obstacle or other boundary; docs/tables.md), and each boundary's phase portraits to
    /// --out as portrait-KIND-ID.svg and .png.
    #[arg(long, value_name = "FILE")]
    boundary_map: Option<PathBuf>,
    /// Write the run as an animation, one self-contained HTML page (docs/animation.md).
    #[arg(long, value_name = "FILE")]
    html: Option<PathBuf>,
    /// Sample the granular-gas observables every DT of simulated time (translational and
    /// rotational temperatures, collision frequency, energy lost per contact kind and, in a
    /// mixture, per pair of species A-B with its contacts: lost_ball_ball_A-B, contacts_A-B) into
    /// --out as observables.csv, units in its header, and observables.parquet, units in its
    /// metadata, with plots: observables.svg (temperatures), observables-pressure.svg,
    /// observables-a2.svg and observables-msd.svg (docs/granular.md).
    #[arg(long, value_name = "DT", allow_negative_numbers = true)]
    observables: Option<f64>,
    /// With --observables: also sample the pair correlation g(r) of the centres at every
    /// row, r in [0, R_MAX] (at most half the box's shortest side) in --pair-bins bins, and
    /// write its average over the rows to --out as pair-correlation.csv, .parquet and .svg (a
    /// periodic box without obstacles or boundaries only; docs/granular.md).
    #[arg(
        long,
        value_name = "R_MAX",
        requires = "observables",
        allow_negative_numbers = true
    )]
    pair_correlation: Option<f64>,
    /// The bins of --pair-correlation.
    #[arg(
        long,
        value_name = "BINS",
        default_value_t = 100,
        requires = "pair_correlation"
    )]
    pair_bins: usize,
    /// With --observables: estimate the self-diffusion coefficient D from the mean square
    /// displacement about the centre of mass, in blocks of BLOCK of simulated time
    /// (each its own time origin; D_b the slope over the block's last four fifths / 2n; at least 4
    /// sampling intervals), writing the blocks to --out as self-diffusion.csv and D with its
    /// standard error over the blocks on stdout (docs/granular.md).
    #[arg(
        long,
        value_name = "BLOCK",
        requires = "observables",
        allow_negative_numbers = true
    )]
    self_diffusion: Option<f64>,
    /// The start of --self-diffusion's first block (the first row at or after it).
    #[arg(
        long,
        value_name = "T0",
        default_value_t = 0.0,
        requires = "self_diffusion",
        allow_negative_numbers = true
    )]
    self_diffusion_from: f64,
    /// Directory for summary.json and the SVG pictures (default out/simulate/SCENE).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
    /// Correct every no-slip contact onto the energy its balls had before it (docs/accuracy.md,
    /// "An energy-conserving correction"): the energy then random-walks instead of drifting
    /// by the kernels' rounding bias. Contacts differ from the uncorrected run's by an ulp or
    /// two; rough and Walton contacts are left as their law gives them.
    #[arg(long)]
    conserve_energy: bool,
}

/// What `simulate` can return.
pub const CODES: &[Exit] = &[Exit::Success, Exit::OutputFailed, Exit::BadInput];

/// The summary on stdout (after the files are written: a failing stdout loses nothing).
fn print_summary(s: &Summary) -> Result<(), Failure> {
    outln!(
        "{} contacts ({} ball-ball, {} ball-wall, {} ball-obstacle, {} ball-boundary), {} cell crossings, t = {:.6}",
        s.events,
        s.ball_ball,
        s.ball_wall,
        s.ball_obstacle,
        s.ball_boundary,
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
    )?;
    if s.kicks > 0 {
        outln!(
            "thermostat: {} kicks added energy {:.17e}",
            s.kicks,
            s.energy_injected
        )?;
    }
    if let Some(why) = &s.stopped {
        outln!("stopped: {why}")?;
    }
    Ok(())
}

fn simulate<const N: usize, const S: usize>(scene: &Scene, args: &Args) -> Result<(), Failure>
where
    Generated: Kernel<f64, N, S>,
{
    let setup: Setup<N, S> =
        setup::<N, S>(scene).map_err(|e| Failure::bad_input(format!("{}: {e}", scene.origin)))?;
    let species = setup.species.clone();
    let names: Vec<String> = scene.species.iter().map(|s| s.name.clone()).collect();
    let table = Table2d::of(&setup);
    let kernels = Conserving::generic(species.clone(), args.conserve_energy);
    let mut sim = Simulation::new(setup, kernels)
        .map_err(|e| Failure::bad_input(format!("{}: {e}", scene.origin)))?;
    let mut sampler = match args.observables {
        Some(dt) if !(dt > 0.0 && dt.is_finite()) => {
            return Err(Failure::bad_input(format!(
                "--observables: the interval must be positive and finite, got {dt}"
            )))
        }
        Some(dt) => Some(Sampler::start(dt, &sim, &species).with_species_names(&names)),
        None => None,
    };
    if let Some(r_max) = args.pair_correlation {
        // `requires = "observables"`: the sampler is there.
        sampler = sampler
            .map(|s| s.with_pair_correlation(r_max, args.pair_bins))
            .transpose()
            .map_err(|e| Failure::bad_input(format!("--pair-correlation: {e}")))?;
    }
    if let Some(block) = args.self_diffusion {
        sampler = sampler
            .map(|s| s.with_self_diffusion(block, args.self_diffusion_from))
            .transpose()
            .map_err(|e| Failure::bad_input(format!("--self-diffusion: {e}")))?;
    }
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
    // The output set is staged before the run, so that a refused --out costs no run. The log
    // and the boundary map are members of the set, published with it: `--log OUT/NAME` as
    // NAME, a file outside --out as a link to its member (`publish::link`).
    let members = side_members(args, &out)?;
    let html_member = match &args.html {
        Some(p) => Some(html::member(args, p, &out, &members)?),
        None => None,
    };
    let mut set = Staging::new(&out).map_err(|e| crate::exit::publish_failure(&e))?;
    let mut open = |p: &PathBuf, member: &Option<String>| {
        let at = match member {
            Some(m) if same_dir(p.parent(), &out) => set.path(m),
            Some(m) => set
                .side(p, m)
                .map_err(|e| crate::exit::publish_failure(&e))?,
            None => p.clone(),
        };
        LogFile::create(&at)
            .map_err(|e| Failure::output(format!("cannot write {}: {e}", p.display())))
    };
    // A `.parquet` log or map is a Parquet table written into the same atomic file.
    let mut log = match &args.log {
        Some(p) => Some(open(p, &members[0])?),
        None => None,
    };
    let events_parquet = match (&args.log, &mut log) {
        (Some(p), log @ Some(_)) if is_parquet(p) => Some(
            events_table(log.take().expect("matched Some"), N)
                .map_err(|e| Failure::output(format!("cannot write {}: {e}", p.display())))?,
        ),
        _ => None,
    };
    let (mut map, mut map_parquet) = match &args.boundary_map {
        Some(p) => {
            let file = open(p, &members[1])?;
            let cannot =
                |e: std::io::Error| Failure::output(format!("cannot write {}: {e}", p.display()));
            if is_parquet(p) {
                (
                    Some(BoundaryMap::new(Side::Sink, N).map_err(cannot)?),
                    Some(columnar::boundary_map::table(file, N).map_err(cannot)?),
                )
            } else {
                (
                    Some(BoundaryMap::new(Side::File(file), N).map_err(cannot)?),
                    None,
                )
            }
        }
        None => (None, None),
    };
    let progress = (!args.quiet).then(|| {
        let pb = ProgressBar::new(events.unwrap_or(0));
        pb.set_style(
            ProgressStyle::with_template("{bar:40} {pos}/{len} contacts, {per_sec}, eta {eta}")
                .expect("valid template"),
        );
        pb
    });
    let mut report = |p: Progress| match p {
        Progress::Events(done) => {
            if let Some(pb) = &progress {
                pb.set_position(done);
            }
        }
        Progress::Quiet { box_lengths, time } => {
            // A notice on stderr (never a panic if stderr is gone); the run goes on.
            let _ = writeln!(
                std::io::stderr(),
                "notice: no contact while every moving ball travelled {box_lengths:.0} box \
                 lengths (t = {time:.6e}); contacts may be rare here: the run goes on (--time \
                 bounds it)"
            );
        }
        _ => {}
    };
    let title = Path::new(&scene.origin)
        .file_name()
        .map_or(String::new(), |s| s.to_string_lossy().into_owned());
    let mut recorder = args
        .html
        .as_ref()
        .map(|_| Recorder::new(&sim, &species, &title));
    // The sampler is told of contacts (the observer) and of kicks (the kick observer).
    let sampler = std::cell::RefCell::new(sampler);
    // So is the Parquet log (a kick's rows among the contacts').
    let events_parquet = std::cell::RefCell::new(events_parquet);
    let (mut summary, trace) = run::run_watched(
        &mut sim,
        &species,
        &limits,
        log.as_mut().map(|w| w as &mut dyn Write),
        &mut report,
        &mut |index, e, sim| {
            if let Some(r) = &mut recorder {
                r.observe(index, e, sim, &species);
            }
            if let Some(s) = sampler.borrow_mut().as_mut() {
                s.contact(e, sim, &species);
            }
            if let Some(table) = events_parquet.borrow_mut().as_mut() {
                table.push(&event_row(index, e))?;
            }
            if let Some(row) = map
                .as_ref()
                .and_then(|_| boundary_map::row(index, e, sim, &species))
            {
                map.as_mut().expect("checked").push(&row)?;
                if let Some(table) = &mut map_parquet {
                    table.push(&columnar::boundary_map::cells(&row))?;
                }
            }
            Ok(())
        },
        &mut |k, _| {
            if let Some(s) = sampler.borrow_mut().as_mut() {
                s.kick(k);
            }
            if let Some(table) = events_parquet.borrow_mut().as_mut() {
                for row in kick_rows(k, S) {
                    table.push(&row)?;
                }
            }
            Ok(())
        },
    )
    .map_err(|e| Failure::output(format!("cannot write the events log: {e}")))?;
    // A run that could not go on (`Summary::failure`) is a failure (exit 2), reported after
    // the outputs of the run up to it are published.
    let failure = summary.failure(scene);
    if let Some(message) = &failure {
        summary.stopped = Some(message.clone());
    }
    let events_parquet = events_parquet.into_inner();
    let sampler = sampler.into_inner();
    if let Some(pb) = progress {
        pb.finish_and_clear();
    }
    // The log is complete or absent; its failure does not stop the summary and pictures.
    let log_done = match (log, events_parquet) {
        (Some(log), _) => Some(log.finish()),
        (None, Some(table)) => Some(table.finish().and_then(LogFile::finish)),
        (None, None) => None,
    };
    let log_failed = match (log_done, &args.log) {
        (Some(Err(e)), Some(p)) => Some(Failure::output(format!(
            "cannot write the events log {}: {e} (no log was left; the summary was written)",
            p.display()
        ))),
        _ => None,
    };
    let mut portraits = Vec::new();
    let map_done = map.map(|map| {
        portraits = map.portraits(sim.table());
        let file = map.finish().and_then(Side::finish);
        match map_parquet {
            Some(table) => file.and(table.finish().and_then(LogFile::finish)),
            None => file,
        }
    });
    let map_failed = match (map_done, &args.boundary_map) {
        (Some(Err(e)), Some(p)) => Some(Failure::output(format!(
            "cannot write the boundary map {}: {e} (none was left; the summary was written)",
            p.display()
        ))),
        _ => None,
    };
    let staged = |r: std::io::Result<String>, name: &str| {
        r.map_err(|e| Failure::output(format!("cannot draw {name}: {e}")))
    };
    summary.conserve_energy = args.conserve_energy;
    let json = serde_json::to_string_pretty(&summary).expect("summary serialises") + "\n";
    set.write("summary.json", json.as_bytes())
        .map_err(|e| crate::exit::publish_failure(&e))?;
    if let Some(s) = &sampler {
        set.write("observables.csv", s.csv().as_bytes())
            .map_err(|e| crate::exit::publish_failure(&e))?;
        let table = columnar::observables::parquet(s, N, Vec::new())
            .map_err(|e| Failure::output(format!("cannot write observables.parquet: {e}")))?;
        set.write("observables.parquet", &table)
            .map_err(|e| crate::exit::publish_failure(&e))?;
        let svg = staged(
            noslip_sim::granular_plot::temperatures_svg(&title, s),
            "observables.svg",
        )?;
        set.write("observables.svg", svg.as_bytes())
            .map_err(|e| crate::exit::publish_failure(&e))?;
        use noslip_sim::observables_plot as plot;
        let charts = [
            ("observables-pressure.svg", plot::pressure_svg(&title, s)),
            ("observables-a2.svg", plot::a2_svg(&title, s)),
            ("observables-msd.svg", plot::msd_svg(&title, s)),
        ];
        for (name, svg) in charts {
            let svg = staged(svg, name)?;
            set.write(name, svg.as_bytes())
                .map_err(|e| crate::exit::publish_failure(&e))?;
        }
        if let Some(g) = s.pair_correlation() {
            set.write("pair-correlation.csv", g.csv().as_bytes())
                .map_err(|e| crate::exit::publish_failure(&e))?;
            let table = columnar::observables::pair_correlation(g, N, Vec::new()).map_err(|e| {
                Failure::output(format!("cannot write pair-correlation.parquet: {e}"))
            })?;
            set.write("pair-correlation.parquet", &table)
                .map_err(|e| crate::exit::publish_failure(&e))?;
            let svg = staged(
                plot::pair_correlation_svg(&title, g),
                "pair-correlation.svg",
            )?;
            set.write("pair-correlation.svg", svg.as_bytes())
                .map_err(|e| crate::exit::publish_failure(&e))?;
        }
        if let Some(d) = s.self_diffusion() {
            set.write("self-diffusion.csv", d.csv().as_bytes())
                .map_err(|e| crate::exit::publish_failure(&e))?;
        }
    }
    let energy = staged(
        energy_svg(&format!("{title}: energy drift"), &trace),
        "energy.svg",
    )?;
    set.write("energy.svg", energy.as_bytes())
        .map_err(|e| crate::exit::publish_failure(&e))?;
    if N == 2 {
        let balls = trace.paths.len();
        let picture = staged(
            trajectories_svg(
                &format!(
                    "{title}: {balls} ball{} up to t = {:.6}, {} contact points",
                    if balls == 1 { "" } else { "s" },
                    trace.paths_until,
                    trace.contacts.len()
                ),
                &table,
                &trace,
            ),
            "trajectories.svg",
        )?;
        set.write("trajectories.svg", picture.as_bytes())
            .map_err(|e| crate::exit::publish_failure(&e))?;
    }
    for portrait in &portraits {
        let (kind, id) = portrait.body.kind_id();
        let name = format!("portrait-{kind}-{id}");
        let svg = staged(portrait.svg(&title), &format!("{name}.svg"))?;
        set.write(&format!("{name}.svg"), svg.as_bytes())
            .map_err(|e| crate::exit::publish_failure(&e))?;
        set.write(&format!("{name}.png"), &portrait.png(&title))
            .map_err(|e| crate::exit::publish_failure(&e))?;
    }
    let html_failed = match (recorder, &args.html, &html_member) {
        (Some(r), Some(p), Some(m)) => {
            let page = noslip_sim::animation_page::html(&r.finish(&sim));
            html::publish(&mut set, p, m, &page)?
        }
        _ => None,
    };
    set.commit().map_err(|e| crate::exit::publish_failure(&e))?;
    print_summary(&summary)?;
    if let Some(d) = sampler.as_ref().and_then(|s| s.self_diffusion()) {
        let (mean, se) = d.estimate();
        outln!(
            "self-diffusion: D = {mean:.6e} +- {se:.2e} [L^2 T^-1] ({} blocks of {} from {}; blocks in self-diffusion.csv)",
            d.blocks().len(),
            d.block(),
            d.from()
        )?;
    }
    outln!("wrote {}", out.display())?;
    let failed = failure.map(|m| Failure::bad_input(format!("{}: {m}", scene.origin)));
    failed
        .or(log_failed)
        .or(map_failed)
        .or(html_failed)
        .map_or(Ok(()), Err)
}

/// Where a CSV boundary map's text goes: its file, or nowhere (a Parquet map keeps the
/// [`BoundaryMap`] only for its portraits).
enum Side {
    File(LogFile),
    Sink,
}

impl Side {
    /// Publish the file (see [`LogFile::finish`]).
    fn finish(self) -> std::io::Result<()> {
        match self {
            Side::File(f) => f.finish(),
            Side::Sink => Ok(()),
        }
    }
}

impl Write for Side {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        match self {
            Side::File(f) => f.write(buf),
            Side::Sink => Ok(buf.len()),
        }
    }

    fn flush(&mut self) -> std::io::Result<()> {
        match self {
            Side::File(f) => f.flush(),
            Side::Sink => Ok(()),
        }
    }
}

/// Check the limits and the output paths, read the scene, run it and publish its outputs.
pub fn run(args: &Args) -> Result<Exit, Failure> {
    check_limits(args)?;
    check_paths(args)?;
    let scene = Scene::from_file(&args.file).map_err(|e| Failure::bad_input(e.to_string()))?;
    collision_core::with_dim!(
        scene.dim,
        |N, S| simulate::<N, S>(&scene, args),
        unreachable!("scene validation keeps dim in {:?}", collision_core::DIMS)
    )?;
    Ok(Exit::Success)
}
