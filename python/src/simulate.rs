//! `noslip.simulate`: a run of a scene by the simulator (`noslip_sim::run::run`, as
//! `noslip simulate` runs it), its events log and energy samples as NumPy arrays.
//!
//! The events log is the simulator's own JSON-lines log (`noslip_sim::run::event_json`),
//! read back into columns: the same numbers, bit for bit (shortest round-trip text). The
//! boundary map is `noslip_sim::boundary_map::row` of each contact with an immovable body,
//! as `noslip simulate --boundary-map` writes it, in the CSV's columns. With `html`, the run
//! as the animation page of `noslip simulate --html` (`noslip_sim::animation`). With
//! `observables`, the rows of `noslip simulate --observables` (`noslip_sim::granular`).

use crate::error::{input_error, unsigned_opt};
use crate::scene::Scene;
use crate::signals::Signals;
use collision_core::{Generated, Kernel};
use log_columns::{log_bytes, Columns, LogColumns};
use noslip_sim::boundary_map::{self, Row};
use noslip_sim::granular::{self, Sampler};
use noslip_sim::pair_correlation::MAX_BINS;
use noslip_sim::pair_losses::is_count;
use noslip_sim::run::{check_time, run_watched, Limits, Summary, Trace};
use noslip_sim::setup::{f, setup};
use noslip_sim::{Conserving, Simulation};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

mod log_columns;

/// A finished run: the summary, the energy samples, the events log's columns (empty
/// without `log`) and the boundary map's rows (empty without `map`).
struct Run {
    summary: Summary,
    trace: Trace,
    columns: Columns,
    rows: Vec<Row>,
    html: Option<String>,
    /// The observables' columns (name, unit) and rows (none without `observables`).
    observables: (Vec<(String, String)>, Vec<granular::Row>),
    /// `g(r)` averaged over the rows, `(r, g)` per bin (none without `pair_correlation`).
    pair_correlation: Vec<[f64; 2]>,
    /// The self-diffusion blocks and the estimate (none without `self_diffusion`).
    self_diffusion: Option<Diffusion>,
}

/// The self-diffusion blocks `(start, end, D_b)` and the estimate `(D, s_D)`.
type Diffusion = (Vec<[f64; 3]>, (f64, f64));

/// What a run keeps of each contact, and at most how many contacts' worth.
#[derive(Clone, Copy)]
struct Keep {
    log: bool,
    map: bool,
    /// Record the animation page (bounded by its own caps, outside `max_memory`).
    html: bool,
    /// The most contacts whose records fit the memory cap (`u64::MAX` keeping nothing).
    contacts: u64,
    /// Sample the observables every this much simulated time.
    observables: Option<f64>,
    /// Sample `g(r)` up to this distance in this many bins at each row.
    pair_correlation: Option<(f64, usize)>,
    /// Estimate the self-diffusion coefficient in blocks of this length from this time.
    self_diffusion: Option<(f64, f64)>,
    /// The memory cap, in bytes, which the observables' rows share with the records.
    max_memory: u64,
    /// The bytes the records of a contact take ([`bytes_per_contact`]).
    per_contact: u64,
    /// Correct the no-slip contacts onto their energy ([`noslip_sim::Conserving`]).
    conserve_energy: bool,
}

/// The error of a run stopped at the memory cap (its text is replaced by [`simulate`]'s
/// message naming the argument).
const CAPPED: &str = "the records reached the memory cap";

/// The error of a run stopped by a signal (the handler's exception is raised instead).
const INTERRUPTED: &str = "interrupted";

fn run_dim<const N: usize, const S: usize>(
    scene: &noslip_scene::Scene,
    limits: &Limits,
    keep: Keep,
    signals: &Signals,
) -> Result<Run, RunError>
where
    Generated: Kernel<f64, N, S>,
{
    let fail = |e: String| RunError::Input(format!("{}: {e}", scene.origin));
    let setup = setup::<N, S>(scene).map_err(|e| fail(e.to_string()))?;
    let species = setup.species.clone();
    let names: Vec<String> = scene.species.iter().map(|s| s.name.clone()).collect();
    let kernels = Conserving::generic(species.clone(), keep.conserve_energy);
    let mut sim = Simulation::new(setup, kernels).map_err(|e| fail(e.to_string()))?;
    let mut lines = LogColumns::new(N, S);
    let writer: Option<&mut dyn std::io::Write> = if keep.log { Some(&mut lines) } else { None };
    let mut rows = Vec::new();
    let title = std::path::Path::new(&scene.origin)
        .file_name()
        .map_or(String::new(), |s| s.to_string_lossy().into_owned());
    let mut recorder = keep
        .html
        .then(|| noslip_sim::animation::Recorder::new(&sim, &species, &title));
    let mut sampler = keep
        .observables
        .map(|dt| Sampler::start(dt, &sim, &species).with_species_names(&names));
    if let Some((r_max, bins)) = keep.pair_correlation {
        sampler = sampler
            .map(|s| s.with_pair_correlation(r_max, bins))
            .transpose()
            .map_err(|e| RunError::Input(format!("pair_correlation: {e}")))?;
    }
    if let Some((block, from)) = keep.self_diffusion {
        sampler = sampler
            .map(|s| s.with_self_diffusion(block, from))
            .transpose()
            .map_err(|e| RunError::Input(format!("self_diffusion: {e}")))?;
    }
    // The sampler is told of contacts (the observer) and of kicks (the kick observer).
    let sampler = std::cell::RefCell::new(sampler);
    // The kicks kept in the log's columns, and the bytes each holds (every ball's velocity,
    // counted three times like the records).
    let kicked = std::cell::Cell::new(0u64);
    let kick_bytes = 3 * (8 * N * sim.len() + 24) as u64;
    // The contacts so far, and the records kept when the cap was passed: `(contacts, kicks)`
    // within it (the contact or the kick that passed it not counted).
    let contacts = std::cell::Cell::new(0u64);
    let capped = std::cell::Cell::new((0u64, 0u64));
    // The bytes the records hold with `c` contacts, `r` rows of observables and `k` kicks:
    // over the cap? Asked after every contact and every kick (a run with few contacts may
    // take many kicks).
    let over = |c: u64, r: u64, k: u64| {
        c.saturating_mul(keep.per_contact)
            .saturating_add(r.saturating_mul(observable_bytes(species.len())))
            .saturating_add(k.saturating_mul(kick_bytes))
            > keep.max_memory
    };
    let (mut summary, trace) = run_watched(
        &mut sim,
        &species,
        limits,
        writer,
        &mut |_| {},
        &mut |index, e, sim| {
            if keep.map {
                rows.extend(boundary_map::row(index, e, sim, &species));
            }
            if let Some(r) = &mut recorder {
                r.observe(index, e, sim, &species);
            }
            let samples = match sampler.borrow_mut().as_mut() {
                Some(s) => {
                    s.contact(e, sim, &species);
                    s.rows().len() as u64
                }
                None => 0,
            };
            contacts.set(index);
            if over(index, samples, kicked.get()) {
                capped.set((index - 1, kicked.get()));
                return Err(std::io::Error::other(CAPPED));
            }
            if signals.interrupted() {
                return Err(std::io::Error::other(INTERRUPTED));
            }
            Ok(())
        },
        &mut |k, _| {
            if let Some(s) = sampler.borrow_mut().as_mut() {
                s.kick(k);
            }
            if keep.log {
                kicked.set(kicked.get() + 1);
                let samples = sampler
                    .borrow()
                    .as_ref()
                    .map_or(0, |s| s.rows().len() as u64);
                if over(contacts.get(), samples, kicked.get()) {
                    capped.set((contacts.get(), kicked.get() - 1));
                    return Err(std::io::Error::other(CAPPED));
                }
            }
            Ok(())
        },
    )
    .map_err(|e| match e.to_string().as_str() {
        CAPPED => {
            let (contacts, kicks) = capped.get();
            RunError::Capped {
                time: sim.now(),
                contacts,
                kicks,
                kick_bytes,
            }
        }
        INTERRUPTED => RunError::Interrupted,
        _ => RunError::Input(format!("internal error: the log in memory failed: {e}")),
    })?;
    // A run that could not go on (a ball out of its container, an inelastic collapse, a gas
    // cooled out of the f64 range): an InputError with the CLI's message.
    if let Some(message) = summary.failure(scene) {
        return Err(fail(message));
    }
    summary.conserve_energy = keep.conserve_energy;
    let sampler = sampler.into_inner();
    Ok(Run {
        summary,
        trace,
        columns: lines.into_columns(),
        rows,
        html: recorder.map(|r| noslip_sim::animation_page::html(&r.finish(&sim))),
        pair_correlation: sampler
            .as_ref()
            .and_then(|s| s.pair_correlation())
            .map_or_else(Vec::new, |g| g.g()),
        self_diffusion: sampler.as_ref().and_then(|s| s.self_diffusion()).map(|d| {
            let blocks = d.blocks().iter().map(|b| [b.start, b.end, b.d]).collect();
            (blocks, d.estimate())
        }),
        observables: sampler.map_or_else(Default::default, |s| (s.columns(), s.rows().to_vec())),
    })
}

/// Bytes one row of the observables holds with `species` species, counted three times like
/// the records (the vector's growth by doubling, then the arrays): the row and, in a mixture,
/// its per-species temperatures and `msd_cm_s` (24 bytes a species) and its per-pair losses
/// and contact counts (16 bytes a pair, `K (K + 1) / 2` pairs).
fn observable_bytes(species: usize) -> u64 {
    let extra = if species > 1 {
        24 * species + 16 * (species * (species + 1) / 2)
    } else {
        0
    };
    3 * (std::mem::size_of::<granular::Row>() + extra) as u64
}

/// The observables' rows as arrays under the CSV's column names
/// (`noslip_sim::granular::Sampler::columns`): `contacts` as integers, the rest as doubles.
fn observable_columns<'py>(
    py: Python<'py>,
    (columns, rows): &(Vec<(String, String)>, Vec<granular::Row>),
) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    let values: Vec<Vec<f64>> = rows.iter().map(granular::Row::values).collect();
    for (k, (name, _)) in columns.iter().enumerate() {
        if name == "contacts" {
            let v: Vec<i64> = rows.iter().map(|r| r.contacts as i64).collect();
            out.set_item(name, array(py, v, &[rows.len()])?)?;
        } else if is_count(name) {
            // A pair's contacts (`contacts_{a}-{b}`): exact as doubles below 2^53.
            let v: Vec<i64> = values.iter().map(|r| r[k] as i64).collect();
            out.set_item(name, array(py, v, &[rows.len()])?)?;
        } else {
            let v: Vec<f64> = values.iter().map(|r| r[k]).collect();
            out.set_item(name, array(py, v, &[rows.len()])?)?;
        }
    }
    Ok(out)
}

/// Why a run gave no result: bad input (the message), the memory cap reached at this
/// simulated time, or a signal handler's exception (Ctrl-C).
enum RunError {
    Input(String),
    Capped {
        time: f64,
        /// The contacts and kicks whose records fit.
        contacts: u64,
        kicks: u64,
        /// The bytes a kick's records count.
        kick_bytes: u64,
    },
    Interrupted,
}

/// Bytes one boundary map row holds while the run goes on and once it is turned into
/// arrays: the row (and its contact point's allocation), then `14 + n` columns of 8 bytes
/// and the `kind` text (a Python `str`, about 60 bytes).
fn map_bytes(n: usize) -> u64 {
    (std::mem::size_of::<Row>() + 8 * n + 32 + 8 * (14 + n) + 60) as u64
}

/// The memory kept per contact, with room for the vectors' growth (a vector grows by
/// doubling, so while it moves it holds up to three times its contents).
fn bytes_per_contact(n: usize, log: bool, map: bool) -> u64 {
    3 * (if log { log_bytes(n) } else { 0 } + if map { map_bytes(n) } else { 0 })
}

fn array<'py, T: numpy::Element>(
    py: Python<'py>,
    v: Vec<T>,
    shape: &[usize],
) -> PyResult<Bound<'py, PyAny>> {
    Ok(PyArray1::from_vec(py, v).reshape(shape)?.into_any())
}

/// One float column of the boundary map, read from a row.
type Field<'a> = dyn Fn(&Row) -> f64 + 'a;

/// The boundary map's rows as arrays under the CSV's column names
/// (`noslip_sim::boundary_map::header`): `kind` as text, the contact point as `q0`, `q1`, ...
fn map_columns<'py>(py: Python<'py>, rows: &[Row], n: usize) -> PyResult<Bound<'py, PyDict>> {
    let len = rows.len();
    let out = PyDict::new(py);
    let col = |f: &Field<'_>| rows.iter().map(f).collect::<Vec<f64>>();
    out.set_item(
        "event",
        array(py, rows.iter().map(|r| r.event).collect(), &[len])?,
    )?;
    out.set_item("time", array(py, col(&|r| r.time), &[len])?)?;
    out.set_item(
        "ball",
        array(py, rows.iter().map(|r| r.ball as i64).collect(), &[len])?,
    )?;
    let kinds: Vec<&str> = rows.iter().map(|r| r.body.kind_id().0).collect();
    out.set_item("kind", kinds)?;
    let ids: Vec<i64> = rows.iter().map(|r| r.body.kind_id().1 as i64).collect();
    out.set_item("id", array(py, ids, &[len])?)?;
    for k in 0..n {
        out.set_item(format!("q{k}"), array(py, col(&|r| r.point[k]), &[len])?)?;
    }
    let columns: [(&str, &Field<'_>); 10] = [
        ("coordinate", &|r| r.coordinate),
        ("incidence", &|r| r.incidence),
        ("reflection", &|r| r.reflection),
        ("normal_velocity", &|r| r.normal_velocity),
        ("tangential_velocity", &|r| r.tangential[0]),
        ("tangential_velocity_post", &|r| r.tangential[1]),
        ("spin", &|r| r.spin[0]),
        ("spin_post", &|r| r.spin[1]),
        ("scaled_spin", &|r| r.scaled_spin[0]),
        ("scaled_spin_post", &|r| r.scaled_spin[1]),
    ];
    for (name, f) in columns {
        out.set_item(name, array(py, col(f), &[len])?)?;
    }
    Ok(out)
}

/// The memory cap on a run's records when the caller gives none: 1 GiB.
pub const MAX_MEMORY: u64 = 1 << 30;

/// `time` as `noslip simulate --time` takes it ([`check_time`]).
fn time_of(t: f64) -> PyResult<f64> {
    check_time(t).map_err(|m| input_error(format!("time: {m}")))
}

/// Run ``scene`` to ``events`` contacts or simulated ``time`` (the scene's ``[simulation]``
/// defaults, else 100000 contacts); keep the events log when ``log``, the boundary map when
/// ``boundary_map``, their memory at most ``max_memory`` bytes (refused up front when ``events``
/// is known, else the run stops with an error at the cap). Returns a dict: ``summary`` (JSON
/// text of the simulator's summary), ``energy`` (event counts and relative drifts of the
/// samples), ``events`` (the log's columns as arrays), ``boundary_map``, ``html`` (the
/// animation page with ``html``, else None), ``observables`` (with ``observables`` the
/// sampling interval, the rows' columns as arrays; else empty).
#[pyfunction]
#[pyo3(signature = (scene, events, time, log, boundary_map, max_memory, html=false, observables=None, pair_correlation=None, pair_bins=None, self_diffusion=None, self_diffusion_from=0.0, conserve_energy=false))]
#[allow(clippy::too_many_arguments)]
pub fn simulate<'py>(
    py: Python<'py>,
    scene: &Bound<'py, Scene>,
    events: Option<Bound<'py, PyAny>>,
    time: Option<f64>,
    log: bool,
    boundary_map: bool,
    max_memory: Option<Bound<'py, PyAny>>,
    html: bool,
    observables: Option<f64>,
    pair_correlation: Option<f64>,
    pair_bins: Option<Bound<'py, PyAny>>,
    self_diffusion: Option<f64>,
    self_diffusion_from: f64,
    conserve_energy: bool,
) -> PyResult<Bound<'py, PyDict>> {
    // Read as `usize` (an `i32` let -1 through to a panic), its range checked here (2^30 bins
    // asked for 8 GiB).
    let pair_bins =
        unsigned_opt::<usize>(pair_bins.as_ref(), "pair_bins", 1, MAX_BINS)?.unwrap_or(100);
    if !(1..=MAX_BINS).contains(&pair_bins) {
        return Err(input_error(format!(
            "pair_bins: must be an integer in 1..={MAX_BINS}, got {pair_bins}"
        )));
    }
    if pair_correlation.is_some() && observables.is_none() {
        return Err(input_error(
            "pair_correlation: g(r) is sampled at the observables' rows: give observables too",
        ));
    }
    if self_diffusion.is_some() && observables.is_none() {
        return Err(input_error(
            "self_diffusion: the displacements are sampled at the observables' rows: give \
             observables too",
        ));
    }
    if let Some(dt) = observables.filter(|dt| !(*dt > 0.0 && dt.is_finite())) {
        return Err(input_error(format!(
            "observables: the interval must be positive and finite, got {dt}"
        )));
    }
    let events = unsigned_opt(events.as_ref(), "events", 1, u64::MAX)?;
    let time = time.map(time_of).transpose()?;
    let max_memory =
        unsigned_opt(max_memory.as_ref(), "max_memory", 0, u64::MAX)?.unwrap_or(MAX_MEMORY);
    if events == Some(0) {
        return Err(input_error(
            "events: must be at least 1 (a run of no contacts has nothing to report)",
        ));
    }
    let scene = &scene.get().inner;
    let n = scene.dim;
    let given_events = events.is_some();
    let mut events = events.or(scene.simulation.events);
    let time = time.or(scene.simulation.time.as_ref().map(f));
    if events.is_none() && time.is_none() {
        events = Some(100_000);
    }
    let per_contact = bytes_per_contact(n, log, boundary_map);
    let keep = Keep {
        log,
        map: boundary_map,
        html,
        contacts: max_memory.checked_div(per_contact).unwrap_or(u64::MAX),
        observables,
        pair_correlation: pair_correlation.map(|r| (r, pair_bins)),
        self_diffusion: self_diffusion.map(|b| (b, self_diffusion_from)),
        max_memory,
        per_contact,
        conserve_energy,
    };
    let kept = || {
        [("log", log), ("boundary_map", boundary_map)]
            .iter()
            .filter(|k| k.1)
            .map(|k| format!("{}=True", k.0))
            .chain(observables.map(|dt| format!("observables={dt:?}")))
            .collect::<Vec<_>>()
            .join(" and ")
    };
    if let Some(e) = events.filter(|&e| e > keep.contacts) {
        let name = if given_events {
            "events"
        } else {
            "events (the scene's simulation.events)"
        };
        return Err(input_error(format!(
            "{name}: {e} contacts with {} would keep up to {} bytes ({per_contact} a contact \
             in {n}D), beyond max_memory = {max_memory} bytes: at most {} contacts; ask for \
             fewer, keep less, or raise max_memory",
            kept(),
            u128::from(e) * u128::from(per_contact),
            keep.contacts
        )));
    }
    let limits = Limits {
        events,
        time,
        samples: 2000,
        traced: 0,
        contact_points: 0,
    };
    // Asked after each contact; the clock is read every 1024 contacts (under a
    // millisecond of work).
    let signals = Signals::new(1024);
    let done = py.detach(|| {
        collision_core::with_dim!(
            n,
            |N, S| run_dim::<N, S>(scene, &limits, keep, &signals),
            Err(RunError::Input(format!(
                "{}: dimension {n} has no kernels",
                scene.origin
            )))
        )
    });
    if let Some(e) = signals.raised() {
        return Err(e);
    }
    let done = done.map_err(|e| match e {
        RunError::Interrupted => input_error("internal error: interrupted without a signal"),
        RunError::Input(m) => input_error(m),
        RunError::Capped {
            time: t,
            contacts,
            kicks,
            kick_bytes,
        } => input_error(format!(
            "time: the run to t = {} with {} reached max_memory = {max_memory} bytes after \
             {contacts} contacts{}, at t = {t} ({per_contact} bytes a contact{} in {n}D); give \
             events (up to {}), keep less, or raise max_memory",
            time.map_or("(none)".into(), |t| format!("{t:e}")),
            kept(),
            if kicks > 0 {
                format!(" and {kicks} kicks")
            } else {
                String::new()
            },
            if kicks > 0 {
                format!(", {kick_bytes} a kick")
            } else {
                String::new()
            },
            keep.contacts
        )),
    })?;
    let ev = done.columns.into_dict(py, n, done.summary.balls)?;
    let (sample_events, drift): (Vec<u64>, Vec<f64>) = done.trace.energy.iter().copied().unzip();
    let samples = sample_events.len();
    let energy = PyDict::new(py);
    energy.set_item("events", array(py, sample_events, &[samples])?)?;
    energy.set_item("drift", array(py, drift, &[samples])?)?;
    let out = PyDict::new(py);
    out.set_item(
        "summary",
        serde_json::to_string(&done.summary)
            .map_err(|e| input_error(format!("internal error: {e}")))?,
    )?;
    out.set_item("energy", energy)?;
    out.set_item("events", ev)?;
    out.set_item("boundary_map", map_columns(py, &done.rows, n)?)?;
    out.set_item("html", done.html)?;
    out.set_item("observables", observable_columns(py, &done.observables)?)?;
    let g = PyDict::new(py);
    let bins = done.pair_correlation.len();
    g.set_item(
        "r",
        array(
            py,
            done.pair_correlation.iter().map(|b| b[0]).collect(),
            &[bins],
        )?,
    )?;
    g.set_item(
        "g",
        array(
            py,
            done.pair_correlation.iter().map(|b| b[1]).collect(),
            &[bins],
        )?,
    )?;
    out.set_item("pair_correlation", g)?;
    let d = PyDict::new(py);
    if let Some((blocks, (mean, se))) = done.self_diffusion {
        let k = blocks.len();
        for (c, name) in ["start", "end", "D"].into_iter().enumerate() {
            d.set_item(
                name,
                array(py, blocks.iter().map(|b| b[c]).collect(), &[k])?,
            )?;
        }
        d.set_item("mean", mean)?;
        d.set_item("standard_error", se)?;
    }
    out.set_item("self_diffusion", d)?;
    Ok(out)
}
