//! The run loop of `noslip simulate`: steps the engine, writes the events log, samples the
//! energy drift and (for the picture) a few trajectories and the contact points, and tells
//! the caller how it goes ([`Progress`]).

use crate::dilute::out_of_reach;
use crate::thermostat::{Kick, Noise};
use crate::trace::{Tracer, CONTACT_DOTS};
use crate::{Contact, Event, PairKernels, Simulation, Step};
use collision_core::BodyState;
use serde_json::{json, Value};
use std::io::{self, Write};
use std::time::Instant;

pub use crate::no_contact::MAX_QUIET_BOX_LENGTHS;

/// What a run tells its caller as it goes (a progress bar, a notice).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Progress {
    /// This many contacts are done (every 4096).
    Events(u64),
    /// No contact while every moving ball travelled `box_lengths` box lengths, at simulated
    /// time `time` (the engine's [`Step::Quiet`]); the run goes on.
    Quiet {
        /// The distance every moving ball travelled since the last contact, in longest box
        /// sides.
        box_lengths: f64,
        /// The simulated time of the notice.
        time: f64,
    },
}

/// A run's time limit as the front ends take it (`noslip simulate --time`, Python's
/// `simulate(time=...)`): positive, finite and a normal f64, as the scene's `simulation.time`
/// (a subnormal time has lost its precision). The error is the message, without the option's
/// name.
pub fn check_time(t: f64) -> Result<f64, String> {
    if !(t > 0.0 && t.is_finite()) {
        return Err(format!("must be positive and finite, got {t}"));
    }
    if !t.is_normal() {
        return Err(format!(
            "{t:e} is not a normal f64 (the least is {:e})",
            f64::MIN_POSITIVE
        ));
    }
    Ok(t)
}

/// The balls' energies the drift samples may cost a contact, at most ([`Limits::samples`]):
/// samples are at least `balls / 8` contacts apart. A ball's energy is about 32
/// instructions (callgrind), a contact of a 3D gas about 10 000: so at most about 2.5 % of
/// a contact's instructions (docs/benchmarks.md, "What `noslip simulate` adds").
pub const SAMPLE_BALLS_PER_CONTACT: u64 = 8;

/// When to stop, and how much to record.
#[derive(Clone, Debug)]
pub struct Limits {
    /// Stop after this many contacts.
    pub events: Option<u64>,
    /// Stop at this simulated time.
    pub time: Option<f64>,
    /// Energy samples for the drift plot (at most). A sample reads every ball, so they are
    /// also at least `balls / `[`SAMPLE_BALLS_PER_CONTACT`] contacts apart: a large gas's
    /// samples then cost at most that many balls' energies a contact.
    pub samples: u64,
    /// Balls whose trajectories are recorded (2D picture).
    pub traced: usize,
    /// Contact points recorded (2D picture), at most; the picture keeps one per pixel and at
    /// most [`CONTACT_DOTS`].
    pub contact_points: usize,
}

/// Totals of a run. Drifts are relative to the start: `|E - E_0| / E_0` for energy,
/// `|p - p_0| / sum m |u|_0` for momentum, `|L - L_0| / sum m (|a| |u| + 2 lambda |U|)_0` for
/// angular momentum.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Summary {
    /// The dimension `n`.
    pub dim: usize,
    /// The number of balls.
    pub balls: usize,
    /// Contacts processed.
    pub events: u64,
    /// Ball-ball contacts among them.
    pub ball_ball: u64,
    /// Ball-wall contacts among them.
    pub ball_wall: u64,
    /// Ball-obstacle contacts among them.
    pub ball_obstacle: u64,
    /// Contacts with the table's other boundaries ([`crate::table`]) among them.
    pub ball_boundary: u64,
    /// Cell crossings processed.
    pub cell_crossings: u64,
    /// The simulated time at the end.
    pub time: f64,
    /// Wall-clock seconds the run took.
    pub seconds: f64,
    /// `events / seconds`.
    pub events_per_second: f64,
    /// Kinetic energy `E_0` at the start.
    pub energy_start: f64,
    /// Kinetic energy `E` at the end.
    pub energy_end: f64,
    /// `|E - E_0| / E_0` at the end of the run.
    pub energy_drift: f64,
    /// The largest `|E - E_0| / E_0` over the samples.
    pub energy_drift_max: f64,
    /// `|p - p_0| / sum m |u|_0` at the end of the run.
    pub momentum_drift: f64,
    /// `|L - L_0| / sum m (|a| |u| + 2 lambda |U|)_0` at the end of the run.
    pub angular_momentum_drift: f64,
    /// Why the run stopped before its limits: the engine found that no contact will happen
    /// again ([`crate::NoContact`]), or none came within [`MAX_QUIET_BOX_LENGTHS`].
    pub stopped: Option<String>,
    /// The ball that left the table through a container ([`crate::left_table`]), which ended
    /// the run: a failure, not an end (the front ends report it as an error naming the
    /// container, after writing what the run did up to it).
    pub left_table: Option<crate::LeftTable>,
    /// The contacts at one instant that did not end ([`crate::collapse`]), which ended the
    /// run: a failure, reported as [`Summary::left_table`] is.
    pub collapse: Option<crate::collapse::Collapse>,
    /// A ball whose speed fell below the f64 range ([`crate::speed_range`]), which ended the
    /// run: a failure, reported as [`Summary::left_table`] is.
    pub below_range: Option<crate::speed_range::BelowRange>,
    /// The thermostat's kicks applied ([`crate::thermostat`]; 0 without one).
    pub kicks: u64,
    /// The kinetic energy the kicks added, the sum of [`Simulation::kick`]'s returns (0
    /// without a thermostat): `energy_end = energy_start + energy_injected - (energy lost in
    /// contacts)`, to rounding.
    pub energy_injected: f64,
    /// Whether the no-slip contacts were corrected onto their balls' energy
    /// ([`crate::Conserving`]): set by the front end that chose the kernels (`false` from
    /// [`run`] itself).
    pub conserve_energy: bool,
}

impl Summary {
    /// Why the run could not go on, if so: a ball that left its table (the container named by
    /// its key in `scene`, [`crate::left_table`]), an inelastic collapse
    /// ([`crate::collapse`]) or a gas cooled out of the f64 range ([`crate::speed_range`]).
    /// The front ends report it as an error (exit 2, a Python `InputError`) after what the run
    /// did up to it.
    pub fn failure(&self, scene: &noslip_scene::Scene) -> Option<String> {
        let left = self
            .left_table
            .as_ref()
            .map(|left| left.message(&scene.boundaries[left.boundary].place));
        left.or_else(|| self.collapse.as_ref().map(ToString::to_string))
            .or_else(|| self.below_range.as_ref().map(ToString::to_string))
    }
}

/// What the pictures need (bounded whatever the number of events; see [`crate::trace`]).
#[derive(Clone, Debug, Default)]
pub struct Trace {
    /// `(events, (E - E_0) / E_0)`.
    pub energy: Vec<(u64, f64)>,
    /// Per traced ball, polylines of its centre (first two coordinates, from the table's
    /// [`crate::Table::origin`]), cut at periodic wraps and thinned to half a pixel.
    pub paths: Vec<Vec<Vec<[f64; 2]>>>,
    /// The time up to which the paths are drawn.
    pub paths_until: f64,
    /// Contact points (first two coordinates), one per picture pixel.
    pub contacts: Vec<[f64; 2]>,
}

fn state_json<const N: usize, const S: usize>(s: &BodyState<f64, N, S>) -> Value {
    json!({"spin": s.spin.to_vec(), "velocity": s.velocity.to_vec()})
}

/// One events-log line.
pub fn event_json<const N: usize, const S: usize>(index: u64, e: &Event<N, S>) -> Value {
    let (kind, who, n) = match e.contact {
        Contact::Ball { i, j } => ("ball-ball", json!({"balls": [i, j]}), 2),
        Contact::Wall { i, axis, upper } => (
            "ball-wall",
            json!({"balls": [i], "axis": axis, "side": if upper { "upper" } else { "lower" }}),
            1,
        ),
        Contact::Obstacle { i, obstacle } => (
            "ball-obstacle",
            json!({"balls": [i], "obstacle": obstacle}),
            1,
        ),
        Contact::Boundary { i, boundary } => (
            "ball-boundary",
            json!({"balls": [i], "boundary": boundary}),
            1,
        ),
    };
    let mut v = json!({
        "event": index,
        "time": e.time,
        "kind": kind,
        "nu": e.nu.to_vec(),
        "positions": e.position[..n].iter().map(|p| p.to_vec()).collect::<Vec<_>>(),
        "pre": e.pre[..n].iter().map(state_json).collect::<Vec<_>>(),
        "post": e.post[..n].iter().map(state_json).collect::<Vec<_>>(),
    });
    if let (Value::Object(m), Value::Object(w)) = (&mut v, who) {
        m.extend(w);
    }
    v
}

/// One events-log line for a thermostat's kick: `{"kick": k, "time": t_k, "velocities":
/// [u'_0, u'_1, ...], "energy_injected": dE}`, every ball's velocity after the kick in ball
/// order (spins are not kicked), so that the log with the start replays every velocity.
pub fn kick_json<const N: usize>(k: &Kick<N>) -> Value {
    json!({
        "kick": k.index,
        "time": k.time,
        "velocities": k.after.iter().map(|u| u.to_vec()).collect::<Vec<_>>(),
        "energy_injected": k.injected,
    })
}

fn scales<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
    sim: &Simulation<N, S, K>,
    species: &[collision_core::Ball<f64>],
) -> (f64, f64) {
    let (mut p, mut l) = (0.0, 0.0);
    for i in 0..sim.len() {
        let b = &species[sim.species_of(i)];
        let m = 1.0 / b.inv_mass;
        let s = sim.state(i);
        p += m * norm(s.velocity.iter().copied());
        let position = sim.position(i);
        l += m
            * (norm(position.iter().copied()) * norm(s.velocity.iter().copied())
                + 2.0 * b.lambda() * norm(s.spin.iter().copied()));
    }
    (p.max(f64::MIN_POSITIVE), l.max(f64::MIN_POSITIVE))
}

/// `|v|`, its squares taken of the entries over the largest magnitude, so that no square
/// overflows or leaves the normal range (a momentum of `10^160`, or of `10^-170`).
fn norm(v: impl Iterator<Item = f64> + Clone) -> f64 {
    let big = v.clone().fold(0.0, |m: f64, x| m.max(x.abs()));
    if big == 0.0 || !big.is_finite() {
        return big;
    }
    big * v.map(|x| (x / big) * (x / big)).sum::<f64>().sqrt()
}

/// `|a - b|` ([`norm`]).
fn distance(a: &[f64], b: &[f64]) -> f64 {
    norm(a.iter().zip(b).map(|(x, y)| x - y))
}

/// Run `sim` to the limits; log each contact to `log` (JSON lines) if given.
pub fn run<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
    sim: &mut Simulation<N, S, K>,
    species: &[collision_core::Ball<f64>],
    limits: &Limits,
    log: Option<&mut dyn Write>,
    progress: &mut dyn FnMut(Progress),
) -> io::Result<(Summary, Trace)> {
    run_observed(sim, species, limits, log, progress, &mut |_, _, _| Ok(()))
}

/// Why a run that has had no contact while every moving ball travelled `box_lengths` box
/// lengths (a [`Step::Quiet`] notice) should stop now, or `None` to go on: the reach
/// [`MAX_QUIET_BOX_LENGTHS`] is spent, or the periodic gas is so dilute that kinetic theory
/// expects no contact within it ([`out_of_reach`]). Every command that runs the engine to a
/// count of contacts (`simulate`, `lyapunov`) stops by this one rule.
pub fn quiet_stop<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
    sim: &Simulation<N, S, K>,
    species: &[collision_core::Ball<f64>],
    box_lengths: f64,
) -> Option<String> {
    if box_lengths >= MAX_QUIET_BOX_LENGTHS {
        return Some(format!(
            "no contact while every moving ball travelled {box_lengths:.0} box lengths \
             (t = {:.6e}): a next contact, if there is one, is out of reach of the run (it \
             stops after {MAX_QUIET_BOX_LENGTHS:.0e} box lengths without a contact, with or \
             without --time: stepping cell by cell to a contact that far off would take too \
             long)",
            sim.now()
        ));
    }
    out_of_reach(sim, species, box_lengths).map(|far| {
        format!(
            "no contact while every moving ball travelled {box_lengths:.0} box lengths \
             (t = {:.6e}), and this periodic gas is so dilute that kinetic theory expects at \
             most {:.1e} contacts per unit time, {:.1e} before every moving ball has travelled \
             {MAX_QUIET_BOX_LENGTHS:.0e} box lengths: a next contact, if there is one, is out \
             of reach of the run (it stops here with or without --time)",
            sim.now(),
            far.rate,
            far.expected
        )
    })
}

/// What [`run_observed`] calls after each contact: `(index, event, simulation)`.
pub type Observer<'a, const N: usize, const S: usize, K> =
    dyn FnMut(u64, &Event<N, S>, &Simulation<N, S, K>) -> io::Result<()> + 'a;

/// What [`run_watched`] calls after each thermostat kick: `(kick, simulation)`, the simulation
/// after the kick.
pub type KickObserver<'a, const N: usize, const S: usize, K> =
    dyn FnMut(&Kick<N>, &Simulation<N, S, K>) -> io::Result<()> + 'a;

/// [`run`], calling `observe(index, event, sim)` after each contact (the boundary map's
/// writer, [`crate::boundary_map`]); its error ends the run. Kicks are not observed
/// ([`run_watched`] observes them too).
pub fn run_observed<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
    sim: &mut Simulation<N, S, K>,
    species: &[collision_core::Ball<f64>],
    limits: &Limits,
    log: Option<&mut dyn Write>,
    progress: &mut dyn FnMut(Progress),
    observe: &mut Observer<'_, N, S, K>,
) -> io::Result<(Summary, Trace)> {
    run_watched(sim, species, limits, log, progress, observe, &mut |_, _| {
        Ok(())
    })
}

/// [`run_observed`], also calling `on_kick(kick, sim)` after each kick of the thermostat
/// ([`Kick`]: what the granular observables' displacements and injected energy need,
/// [`crate::granular::Sampler::kick`]); its error ends the run. The log, if given, holds a
/// line for each kick between the contacts' ([`kick_json`]).
pub fn run_watched<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
    sim: &mut Simulation<N, S, K>,
    species: &[collision_core::Ball<f64>],
    limits: &Limits,
    mut log: Option<&mut dyn Write>,
    progress: &mut dyn FnMut(Progress),
    observe: &mut Observer<'_, N, S, K>,
    on_kick: &mut KickObserver<'_, N, S, K>,
) -> io::Result<(Summary, Trace)> {
    let start = sim.observables();
    let (p_scale, l_scale) = scales(sim, species);
    let events = limits.events.unwrap_or(u64::MAX);
    let until = limits.time.unwrap_or(f64::INFINITY);
    let every = (events.min(1 << 40) / limits.samples.max(1))
        .max(sim.len() as u64 / SAMPLE_BALLS_PER_CONTACT)
        .max(1);
    let traced = limits.traced.min(sim.len());
    let size = sim.box_size();
    let two = |x: &[f64; N]| [x[0], x[1]];
    // Points in the picture's frame: from the table's origin (0 with a box).
    let origin = sim.table().origin;
    let at = |x: &[f64; N]| [x[0] - origin[0], x[1] - origin[1]];
    let start_points: Vec<([f64; 2], [f64; 2])> = (0..traced)
        .map(|i| (at(&sim.position(i)), two(&sim.state(i).velocity)))
        .collect();
    let mut tracer = Tracer::new(two(&size), sim.now(), &start_points);
    let mut samples = vec![(0, 0.0)];
    let mut kinds = [0u64; 4];
    let mut drift_max: f64 = 0.0;
    let clock = Instant::now();
    let mut done = 0u64;
    let mut stopped = None;
    let mut left_table = None;
    let mut streak = crate::collapse::Streak::default();
    let mut collapse = None;
    let mut below_range = None;
    let mut noise = sim.table().thermostat.map(Noise::new);
    let mut injected = 0.0;
    while done < events {
        // The engine steps to the next kick (if it comes by `until`), then the kick is applied.
        let kick_at = noise.as_ref().map(Noise::next_time).filter(|&t| t <= until);
        let step = sim.step(kick_at.unwrap_or(until));
        // A kick is due. After `Never` too if the run has a time limit (kicks set balls at
        // rest or apart moving); without one it stops there, as a run without kicks (a lone
        // ball would be kicked forever).
        let due = match step {
            Step::Until => true,
            Step::Never(_) => until.is_finite(),
            _ => false,
        };
        if let (Some(noise), Some(_), true) = (&mut noise, kick_at, due) {
            let k = kick(sim, species, noise, &mut tracer, traced, &at);
            injected += k.injected;
            if let Some(w) = log.as_deref_mut() {
                writeln!(w, "{}", kick_json(&k))?;
            }
            on_kick(&k, sim)?;
            continue;
        }
        let e = match step {
            Step::Contact(e) => e,
            Step::Until => break,
            Step::Never(why) => {
                stopped = Some(why.to_string());
                break;
            }
            Step::LeftTable(left) => {
                stopped = Some(left.to_string());
                left_table = Some(left);
                break;
            }
            Step::Quiet { box_lengths } => {
                if let Some(why) = quiet_stop(sim, species, box_lengths) {
                    stopped = Some(why);
                    break;
                }
                progress(Progress::Quiet {
                    box_lengths,
                    time: sim.now(),
                });
                continue;
            }
        };
        done += 1;
        let collapsed = streak.record(&e);
        let (k, balls) = match e.contact {
            Contact::Ball { i, j } => (0, [i, j]),
            Contact::Wall { i, .. } => (1, [i, i]),
            Contact::Obstacle { i, .. } => (2, [i, i]),
            Contact::Boundary { i, .. } => (3, [i, i]),
        };
        kinds[k] += 1;
        if let Some(w) = log.as_deref_mut() {
            writeln!(w, "{}", event_json(done, &e))?;
        }
        observe(done, &e, sim)?;
        for (slot, &b) in balls.iter().enumerate() {
            if b < traced && (slot == 0 || balls[1] != balls[0]) {
                tracer.flight(
                    b,
                    e.time,
                    at(&e.position[slot]),
                    two(&e.post[slot].velocity),
                );
            }
        }
        if tracer.contacts.len() < limits.contact_points.min(CONTACT_DOTS) {
            tracer.contact(at(&contact_point(&e, species, sim)));
        }
        if done % every == 0 {
            let energy = sim.energy();
            let drift = (energy - start.energy) / start.energy;
            drift_max = drift_max.max(drift.abs());
            samples.push((done, drift));
        }
        if done % 4096 == 0 {
            progress(Progress::Events(done));
        }
        if let Some(c) = collapsed {
            stopped = Some(c.to_string());
            collapse = Some(c);
            break;
        }
        if let Some(b) = crate::speed_range::below_range(&e) {
            stopped = Some(b.to_string());
            below_range = Some(b);
            break;
        }
    }
    let seconds = clock.elapsed().as_secs_f64();
    let ends: Vec<[f64; 2]> = (0..traced).map(|i| at(&sim.position(i))).collect();
    tracer.finish(sim.now(), &ends);
    let trace = Trace {
        energy: samples,
        paths: tracer.paths,
        paths_until: tracer.until,
        contacts: tracer.contacts,
    };
    let end = sim.observables();
    let drift = (end.energy - start.energy) / start.energy;
    drift_max = drift_max.max(drift.abs());
    let summary = Summary {
        dim: N,
        balls: sim.len(),
        events: done,
        ball_ball: kinds[0],
        ball_wall: kinds[1],
        ball_obstacle: kinds[2],
        ball_boundary: kinds[3],
        cell_crossings: sim.crossings(),
        time: sim.now(),
        seconds,
        events_per_second: done as f64 / seconds.max(1e-9),
        energy_start: start.energy,
        energy_end: end.energy,
        energy_drift: drift.abs(),
        energy_drift_max: drift_max,
        momentum_drift: distance(&end.momentum, &start.momentum) / p_scale,
        angular_momentum_drift: distance(&end.angular_momentum, &start.angular_momentum) / l_scale,
        stopped,
        left_table,
        collapse,
        below_range,
        kicks: noise.as_ref().map_or(0, Noise::done),
        energy_injected: injected,
        conserve_energy: false,
    };
    Ok((summary, trace))
}

/// Applies `noise`'s next kick to `sim` ([`Simulation::kick`]) and restarts the traced balls'
/// paths with their new velocities; returns the kick as applied.
fn kick<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
    sim: &mut Simulation<N, S, K>,
    species: &[collision_core::Ball<f64>],
    noise: &mut Noise,
    tracer: &mut Tracer,
    traced: usize,
    at: &dyn Fn(&[f64; N]) -> [f64; 2],
) -> Kick<N> {
    let inv_mass: Vec<f64> = (0..sim.len())
        .map(|i| species[sim.species_of(i)].inv_mass)
        .collect();
    let velocities = |sim: &Simulation<N, S, K>| -> Vec<[f64; N]> {
        (0..sim.len()).map(|i| sim.state(i).velocity).collect()
    };
    let before = velocities(sim);
    let dv = noise.kick::<N>(&inv_mass);
    let injected = sim.kick(&dv);
    for b in 0..traced {
        let u = sim.state(b).velocity;
        tracer.flight(b, sim.now(), at(&sim.position(b)), [u[0], u[1]]);
    }
    Kick {
        index: noise.done(),
        time: sim.now(),
        before,
        after: velocities(sim),
        injected,
    }
}

/// The contact point `Q`: `a_i + R_i nu` for two balls, `a - R nu` for a ball on a wall, an
/// obstacle or a boundary (nu points from it to the ball).
pub fn contact_point<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
    e: &Event<N, S>,
    species: &[collision_core::Ball<f64>],
    sim: &Simulation<N, S, K>,
) -> [f64; N] {
    let (i, sign) = match e.contact {
        Contact::Ball { i, .. } => (i, 1.0),
        Contact::Wall { i, .. } | Contact::Obstacle { i, .. } | Contact::Boundary { i, .. } => {
            (i, -1.0)
        }
    };
    let r = species[sim.species_of(i)].radius;
    std::array::from_fn(|k| e.position[0][k] + sign * r * e.nu[k])
}
