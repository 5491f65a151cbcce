//! The granular observables of a driven gas (docs/granular.md, "A driven steady state"): the
//! displacements behind `msd` across the thermostat's kicks, and the injected energy's column
//! in the energy balance of every sample interval. Both against first principles: the
//! displacements against the balls' own positions in boxes where no position wraps, the
//! balance as the identity it is, to a rounding bound derived below.

use collision_core::{Generated, Kernel};
use noslip_scene::Scene;
use noslip_sim::displacement::Displacements;
use noslip_sim::granular::{Row, Sampler};
use noslip_sim::run::{run_watched, Limits, Summary};
use noslip_sim::setup::setup;
use noslip_sim::{Contact, GenericKernels, Simulation};

const EPS: f64 = f64::EPSILON;

/// What the checks of a run found.
struct Checked {
    summary: Summary,
    rows: Vec<Row>,
    /// Kicks done when each row was taken.
    kicks_at_row: Vec<u64>,
    /// The largest `|d_i - (x_i - x_i(0))|` over balls, components and checks, and the same
    /// over its bound.
    worst: f64,
    worst_ratio: f64,
    /// Checks of the displacements, and rows whose `msd` was checked.
    checks: u64,
}

/// Runs `text` to `until` through `run_watched`, a row every `every`, checking after every
/// contact and kick that each ball's displacement (`Displacements`, told of the contacts and
/// the kicks) is its move `x_i - x_i(0)` (the box's positions never wrap here: walls, or a
/// periodic box too wide for the run), and at each row that `msd` is the mean square of those
/// moves.
///
/// Rounding bound, per ball and component. The displacement adds one term `u (t - t_0)` per
/// flight; the engine's position moves its record once per flight end and per re-basing
/// (`sim.rebases()`), each move `x + u (t - t_0)` of a coordinate `|x| <= L` (the box's
/// longest side; no flight leaves the box, so `|u (t - t_0)| <= L` too) on a clock up to `T`
/// (the displacement's absolute time) with speeds up to `u_max`. Each such step rounds three
/// times (the time difference `eps T`, the product and the sum), so errs by at most
/// `eps (u_max T + 2 L)`; over the ball's `F_i` flights (contacts and kicks) on one side and
/// `F_i + R` moves on the other, twice that for the start: `(2 F_i + R + 2) eps (u_max T + 2 L)`.
fn checked(text: &str, every: f64, until: f64) -> Checked {
    let scene = Scene::from_toml(text, "t.toml").unwrap();
    collision_core::with_dim!(
        scene.dim,
        |N, S| checked_in::<N, S>(&scene, every, until),
        unreachable!()
    )
}

fn checked_in<const N: usize, const S: usize>(scene: &Scene, every: f64, until: f64) -> Checked
where
    Generated: Kernel<f64, N, S>,
{
    let setup = setup::<N, S>(scene).unwrap();
    let species = setup.species.clone();
    let kernels = GenericKernels {
        species: species.clone(),
    };
    let mut sim = Simulation::new(setup, kernels).unwrap();
    let start: Vec<[f64; N]> = (0..sim.len()).map(|i| sim.position(i)).collect();
    let side = sim.box_size().iter().copied().fold(0.0, f64::max);
    let speed = |u: &[f64; N]| u.iter().map(|x| x * x).sum::<f64>().sqrt();
    let u_start = (0..sim.len())
        .map(|i| speed(&sim.state(i).velocity))
        .fold(0.0, f64::max);
    // Shared by the two observers: the sampler, the test's own displacements, the flights of
    // each ball, the kicks, the largest speed so far, and what was found.
    struct State<const N: usize> {
        sampler: Sampler,
        own: Displacements,
        flights: Vec<u64>,
        kicks: u64,
        kicks_at_row: Vec<u64>,
        u_max: f64,
        worst: f64,
        worst_ratio: f64,
        checks: u64,
    }
    let state = std::cell::RefCell::new(State::<N> {
        sampler: Sampler::start(every, &sim, &species),
        own: Displacements::start(&sim),
        flights: vec![0; sim.len()],
        kicks: 0,
        kicks_at_row: vec![0],
        u_max: u_start,
        worst: 0.0,
        worst_ratio: 0.0,
        checks: 0,
    });
    let check = |st: &mut State<N>, sim: &Simulation<N, S, GenericKernels<f64>>| {
        let d = st.own.now(sim);
        let t = sim.now();
        let mut square = 0.0;
        let mut bound_sum = 0.0;
        for (i, di) in d.iter().enumerate() {
            let x = sim.position(i);
            let factor = (2 * st.flights[i] + sim.rebases() + 2) as f64;
            let bound = factor * EPS * (st.u_max * t + 2.0 * side);
            for k in 0..N {
                let moved = x[k] - start[i][k];
                let off = (di[k] - moved).abs();
                assert!(
                    off <= bound,
                    "ball {i} axis {k} at t = {t}: displacement {} but moved {moved} \
                     (off by {off:e}, bound {bound:e})",
                    di[k]
                );
                st.worst = st.worst.max(off);
                st.worst_ratio = st.worst_ratio.max(off / bound);
                square += moved * moved;
                bound_sum += bound * (2.0 * moved.abs() + bound);
            }
        }
        st.checks += 1;
        (square / sim.len() as f64, bound_sum / sim.len() as f64)
    };
    let limits = Limits {
        events: None,
        time: Some(until),
        samples: 1,
        traced: 0,
        contact_points: 0,
    };
    let (summary, _) = run_watched(
        &mut sim,
        &species,
        &limits,
        None,
        &mut |_| {},
        &mut |_, e, sim| {
            let st = &mut *state.borrow_mut();
            let balls = match e.contact {
                Contact::Ball { i, j } => vec![i, j],
                Contact::Wall { i, .. }
                | Contact::Obstacle { i, .. }
                | Contact::Boundary { i, .. } => vec![i],
            };
            for (k, &i) in balls.iter().enumerate() {
                st.flights[i] += 1;
                st.u_max = st.u_max.max(speed(&e.post[k].velocity));
            }
            st.own.contact(e);
            let rows = st.sampler.rows().len();
            st.sampler.contact(e, sim, &species);
            let (msd, bound) = check(st, sim);
            if st.sampler.rows().len() > rows {
                let row = st.sampler.rows().last().unwrap();
                // `msd` over the moves, and the row's: the per-ball bound carried through the
                // squares (`|a^2 - b^2| <= b (2 |a| + b)`), plus the sums' own rounding
                // (`N_b n` additions of terms up to `msd N_b`, relative `N_b n eps`).
                let n_terms = (sim.len() * N) as f64;
                let allowed = bound + 2.0 * n_terms * EPS * msd.max(row.msd);
                assert!(
                    (row.msd - msd).abs() <= allowed,
                    "row at t = {}: msd {} against the moves' {msd} (allowed {allowed:e})",
                    row.time,
                    row.msd
                );
                st.kicks_at_row.push(st.kicks);
            }
            Ok(())
        },
        &mut |k, sim| {
            let st = &mut *state.borrow_mut();
            st.kicks += 1;
            assert_eq!(k.index, st.kicks);
            for (f, u) in st.flights.iter_mut().zip(&k.after) {
                *f += 1;
                st.u_max = st.u_max.max(speed(u));
            }
            st.own.kick(k);
            st.sampler.kick(k);
            check(st, sim);
            Ok(())
        },
    )
    .unwrap();
    let st = state.into_inner();
    Checked {
        summary,
        rows: st.sampler.rows().to_vec(),
        kicks_at_row: st.kicks_at_row,
        worst: st.worst,
        worst_ratio: st.worst_ratio,
        checks: st.checks,
    }
}

/// A driven gas of rough disks in a walled box with a rough obstacle (nothing wraps), `{box}`
/// the box's side, `{count}` balls.
const WALLED: &str = r#"
dim = 2
[box]
size = [{box}, {box}]
boundary = ["wall", "wall"]
contact = { e = "0.9", beta = "0.3" }
[[species]]
mass = 1
radius = "1/2"
count = {count}
[[obstacle]]
position = [6, 6]
radius = "3/2"
contact = { e = "0.8", beta = "0.5" }
[contact]
balls = { e = "0.9", beta = "0.4" }
tc = "1e-4"
[random]
seed = 3
velocities = "maxwellian"
[thermostat]
kind = "white-noise"
strength = "0.5"
interval = "0.1"
seed = 4
"#;

/// In a walled box every contact and every kick keeps each ball's displacement equal to its
/// move from the start, to the rounding bound of [`checked`]; each row's `msd` is the mean
/// square of the moves. A kick not ended as a flight would be off by `|dv| (t - t_k)`, about
/// `0.5 sqrt(0.1) 0.1 = 0.016` after a tenth of a time unit, `10^10` times the bound.
#[test]
fn kicked_displacements_are_the_moves_in_a_walled_box() {
    let text = WALLED.replace("{box}", "12").replace("{count}", "40");
    let run = checked(&text, 1.0, 40.0);
    let s = &run.summary;
    eprintln!(
        "walled: {} contacts ({} ball-ball, {} wall, {} obstacle), {} kicks, {} checks, \
         worst {:e} ({:.2e} of its bound), final msd {}",
        s.events,
        s.ball_ball,
        s.ball_wall,
        s.ball_obstacle,
        s.kicks,
        run.checks,
        run.worst,
        run.worst_ratio,
        run.rows.last().unwrap().msd
    );
    assert_eq!(s.kicks, 400);
    assert!(
        s.ball_ball > 500 && s.ball_wall > 100 && s.ball_obstacle > 10,
        "{s:?}"
    );
    assert_eq!(run.checks, s.events + s.kicks);
    assert!(run.rows.len() >= 40 && run.rows.iter().all(|r| r.msd.is_finite()));
}

/// A periodic box so wide that no ball reaches a face in the run (checked: a wrap would put a
/// move off by a side, 400): two balls and the kicks alone, the displacement `sum of u dt`
/// over every kick's flight, against the positions.
#[test]
fn kicked_displacements_are_the_moves_in_a_wide_periodic_box() {
    let text = "dim = 3\n[box]\nsize = [400, 400, 400]\n\
                boundary = [\"periodic\", \"periodic\", \"periodic\"]\n\
                [[species]]\nmass = 1\nradius = \"1/2\"\n\
                [[ball]]\nspecies = 0\nposition = [150, 200, 200]\nvelocity = [1, 0, 0]\n\
                [[ball]]\nspecies = 0\nposition = [250, 200, 200]\nvelocity = [0, 1, 0]\n\
                [thermostat]\nkind = \"white-noise\"\nstrength = 1\ninterval = \"0.25\"\n\
                seed = 9\n";
    let run = checked(text, 5.0, 50.0);
    assert_eq!((run.summary.events, run.summary.kicks), (0, 200));
    assert_eq!(run.checks, 200);
    eprintln!(
        "periodic: worst {:e} ({:.2e} of its bound)",
        run.worst, run.worst_ratio
    );
}

/// The energy balance of every sample interval, `E_b - E_a = (injected_b - injected_a) -
/// sum_kinds (lost_b - lost_a)`, from the rows alone. Rounding (as the whole run's balance in
/// `driven.rs`, per interval): each of the interval's `C` contacts' losses within
/// `64 eps E_max` and each of its `K` kicks' gains within `(16 + 2 N_b) eps E_max`; the two
/// rows' energies within `20 N_b eps E_max` each; and the running totals, each addition
/// rounding by half an ulp of a total up to `W` (the largest of the run's totals: injected or a
/// kind's loss), `(C + K) eps W`, and the differences and the sum over the kinds `10 eps W`.
#[test]
fn every_interval_balances_the_injected_and_the_lost_energy() {
    let text = WALLED.replace("{box}", "12").replace("{count}", "40");
    let run = checked(&text, 0.5, 40.0);
    let balls = 40.0;
    let e_max = 2.0 * run.rows.iter().map(|r| r.energy).fold(0.0, f64::max);
    let last = run.rows.last().unwrap();
    let w = last.lost.iter().copied().fold(last.injected, f64::max);
    assert!(last.injected > 2.0 * run.rows[0].energy, "{last:?}");
    let (mut worst, mut intervals) = (0.0f64, 0);
    for (pair, kicks) in run.rows.windows(2).zip(run.kicks_at_row.windows(2)) {
        let (a, b) = (&pair[0], &pair[1]);
        let c = (b.contacts - a.contacts) as f64;
        let k = (kicks[1] - kicks[0]) as f64;
        let lost: f64 = (0..4).map(|kind| b.lost[kind] - a.lost[kind]).sum();
        let off = (b.energy - a.energy) - ((b.injected - a.injected) - lost);
        let bound = (64.0 * c + (16.0 + 2.0 * balls) * k + 40.0 * balls) * EPS * e_max
            + (c + k + 10.0) * EPS * w;
        assert!(
            off.abs() <= bound,
            "rows at t = {} and {}: off by {off:e} > {bound:e}",
            a.time,
            b.time
        );
        worst = worst.max(off.abs() / bound);
        intervals += 1;
        // The thermostat and the contacts both act in every interval.
        assert!(k > 0.0 && c > 0.0 && b.injected > a.injected);
    }
    assert!(intervals >= 79, "{intervals}");
    eprintln!("{intervals} intervals balanced, worst at {worst:.2e} of its bound");
}

/// A driven run's events log is complete: from the start's velocities, each contact line's
/// `post` velocities (of its balls) and each kick line's `velocities` (of every ball), in the
/// log's order, replay every ball's velocity at the end bit for bit (the log's numbers are
/// the f64 values in shortest round-trip form). A log without the kicks would leave every
/// velocity off by the kicks' sum since the ball's last contact.
#[test]
fn a_driven_log_replays_every_velocity() {
    let text = WALLED.replace("{box}", "12").replace("{count}", "40");
    let scene = Scene::from_toml(&text, "t.toml").unwrap();
    let setup = setup::<2, 1>(&scene).unwrap();
    let species = setup.species.clone();
    let kernels = GenericKernels {
        species: species.clone(),
    };
    let mut sim = Simulation::new(setup, kernels).unwrap();
    let mut velocities: Vec<[f64; 2]> = (0..sim.len()).map(|i| sim.state(i).velocity).collect();
    let limits = Limits {
        events: None,
        time: Some(10.0),
        samples: 1,
        traced: 0,
        contact_points: 0,
    };
    let mut log = Vec::new();
    let (summary, _) = run_watched(
        &mut sim,
        &species,
        &limits,
        Some(&mut log),
        &mut |_| {},
        &mut |_, _, _| Ok(()),
        &mut |_, _| Ok(()),
    )
    .unwrap();
    let pair = |v: &serde_json::Value| [0, 1].map(|k| v[k].as_f64().unwrap());
    let (mut contacts, mut kicks, mut last) = (0, 0, 0.0);
    for line in String::from_utf8(log).unwrap().lines() {
        let v: serde_json::Value = serde_json::from_str(line).unwrap();
        let time = v["time"].as_f64().unwrap();
        assert!(time >= last, "the log is in time order");
        last = time;
        if let Some(k) = v.get("kick") {
            kicks += 1;
            assert_eq!(k.as_u64(), Some(kicks));
            let after = v["velocities"].as_array().unwrap();
            assert_eq!(after.len(), velocities.len());
            for (u, a) in velocities.iter_mut().zip(after) {
                *u = pair(a);
            }
        } else {
            contacts += 1;
            for (k, b) in v["balls"].as_array().unwrap().iter().enumerate() {
                velocities[b.as_u64().unwrap() as usize] = pair(&v["post"][k]["velocity"]);
            }
        }
    }
    assert_eq!((contacts, kicks), (summary.events, summary.kicks));
    assert!(kicks == 100 && contacts > 100, "{summary:?}");
    for (i, u) in velocities.iter().enumerate() {
        let want = sim.state(i).velocity;
        assert_eq!(u.map(f64::to_bits), want.map(f64::to_bits), "ball {i}");
    }
}
