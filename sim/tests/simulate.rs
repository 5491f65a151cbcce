//! The simulator on the shipped scenes: energy conservation over 10^6 events, and the
//! two-wall scene's events log against the disk-on-wall matrix of docs/derivation.md §11, exactly.

use collision_core::Ball;
use noslip_scene::Scene;
use noslip_sim::run::{run, Limits, Progress, Summary, Trace, MAX_QUIET_BOX_LENGTHS};
use noslip_sim::setup::setup;
use noslip_sim::trace::{CONTACT_DOTS, PATH_BUDGET, PICTURE, PIECE_COST};
use noslip_sim::{GenericKernels, Simulation};
use num_rational::BigRational;
use num_traits::{ToPrimitive, Zero};
use serde_json::Value;
use std::path::Path;

fn scene(name: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../scenes")
        .join(name);
    Scene::from_file(&path).expect("shipped scene is valid")
}

fn limits(events: u64) -> Limits {
    Limits {
        events: Some(events),
        time: None,
        samples: 100,
        traced: 0,
        contact_points: 0,
    }
}

/// Every contact changes the total energy by a few roundings of the energy of the pair, at
/// most `8 eps E`; so after `k` contacts `|E - E_0| / E_0 <= 8 k eps` even if every error had
/// the same sign (they do not: the observed drift is a random walk, far smaller).
fn energy_bound(events: u64) -> f64 {
    8.0 * events as f64 * f64::EPSILON
}

/// The simulation of `scene` (placed as `noslip simulate` places it) on the generic kernels,
/// and its species.
fn simulation<const N: usize, const S: usize>(
    scene: &Scene,
) -> (Simulation<N, S, GenericKernels<f64>>, Vec<Ball<f64>>)
where
    collision_core::Generated: collision_core::Kernel<f64, N, S>,
{
    let setup = setup::<N, S>(scene).expect("placement succeeds");
    let species = setup.species.clone();
    let kernels = GenericKernels {
        species: species.clone(),
    };
    (Simulation::new(setup, kernels).unwrap(), species)
}

/// Run the shipped scene `name` for `events` contacts on the generic kernels.
fn simulate<const N: usize, const S: usize>(
    name: &str,
    events: u64,
    log: Option<&mut dyn std::io::Write>,
) -> (Scene, Summary, Trace)
where
    collision_core::Generated: collision_core::Kernel<f64, N, S>,
{
    let scene = scene(name);
    let (mut sim, species) = simulation::<N, S>(&scene);
    let (summary, trace) = run(&mut sim, &species, &limits(events), log, &mut |_| {}).unwrap();
    (scene, summary, trace)
}

fn drift_over<const N: usize, const S: usize>(name: &str, events: u64)
where
    collision_core::Generated: collision_core::Kernel<f64, N, S>,
{
    let (_, summary, trace) = simulate::<N, S>(name, events, None);
    assert_eq!(summary.events, events, "{name}: the gas keeps colliding");
    assert!(
        summary.ball_ball > events / 2,
        "{name}: mostly ball-ball contacts"
    );
    let bound = energy_bound(events);
    assert!(
        summary.energy_drift_max <= bound,
        "{name}: energy drift {} over {events} events exceeds {bound}",
        summary.energy_drift_max
    );
    assert_eq!(trace.energy.len(), 101);
}

#[test]
fn energy_drift_gas2d_over_a_million_events() {
    drift_over::<2, 1>("gas2d.toml", 1_000_000);
}

#[test]
fn energy_drift_gas3d_over_a_million_events() {
    drift_over::<3, 3>("gas3d.toml", 1_000_000);
}

#[test]
fn periodic_gas_conserves_momentum() {
    // gas3d is periodic on every axis with no obstacles: only ball-ball contacts, which
    // conserve m_1 u_1 + m_2 u_2 exactly in exact arithmetic; in f64 each contact adds a few
    // roundings of the pair's momentum, bounded like the energy.
    let (_, summary, _) = simulate::<3, 3>("gas3d.toml", 100_000, None);
    assert_eq!(summary.ball_wall + summary.ball_obstacle, 0);
    assert!(
        summary.momentum_drift <= energy_bound(100_000),
        "{}",
        summary.momentum_drift
    );
}

fn exact(v: &Value) -> BigRational {
    BigRational::from_float(v.as_f64().expect("a number")).expect("finite")
}

fn q(p: i64, d: i64) -> BigRational {
    BigRational::new(p.into(), d.into())
}

/// The disk on a wall of docs/derivation.md §11 (m_1 = inf) in coordinates `(g R c, u . tau, u . nu)` with
/// `U = c J`, `tau = -J nu`: `c+ = -(1-g^2)/(1+g^2) c - 2/(R (1+g^2)) u_tau`,
/// `u_tau+ = -2 g^2 R/(1+g^2) c + (1-g^2)/(1+g^2) u_tau`, `u_nu+ = -u_nu`. Returns
/// `(spin entry U_01 = -c, velocity)`.
fn disk_on_wall(
    g2: &BigRational,
    r: &BigRational,
    nu: [BigRational; 2],
    spin: &BigRational,
    u: [BigRational; 2],
) -> (BigRational, [BigRational; 2]) {
    let one = q(1, 1);
    let c = -spin.clone();
    let tau = [nu[1].clone(), -nu[0].clone()];
    let ut = &u[0] * &tau[0] + &u[1] * &tau[1];
    let un = &u[0] * &nu[0] + &u[1] * &nu[1];
    let den = &one + g2;
    let c2 = -(&one - g2) / &den * &c - q(2, 1) / (r * &den) * &ut;
    let ut2 = -(q(2, 1) * g2 * r) / &den * &c + (&one - g2) / &den * &ut;
    let un2 = -un;
    let v = [
        &ut2 * &tau[0] + &un2 * &nu[0],
        &ut2 * &tau[1] + &un2 * &nu[1],
    ];
    (-c2, v)
}

#[test]
fn two_wall_log_is_the_exact_disk_on_wall_map() {
    let mut log = Vec::new();
    let (scene, summary, _) = simulate::<2, 1>("disk_between_walls.toml", 200, Some(&mut log));
    let sp = &scene.species[0];
    let (g2, r) = (sp.gamma2.clone(), sp.radius.clone());
    assert_eq!((g2.clone(), r.clone()), (q(1, 2), q(1, 2)));
    assert_eq!(summary.ball_wall, 200);
    let lines: Vec<Value> = String::from_utf8(log)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 200);
    let mut previous: Option<Value> = None;
    for line in &lines {
        assert_eq!(line["kind"], "ball-wall");
        let nu = [exact(&line["nu"][0]), exact(&line["nu"][1])];
        // The walls are those of axis 1: nu = +e_1 (lower) or -e_1 (upper).
        assert!(nu[0].is_zero());
        let (pre, post) = (&line["pre"][0], &line["post"][0]);
        let u = [exact(&pre["velocity"][0]), exact(&pre["velocity"][1])];
        let (spin, v) = disk_on_wall(&g2, &r, nu, &exact(&pre["spin"][0]), u);
        // The f64 kernel rounds ~10 operations on numbers of size <= |state|: within
        // 16 eps max|state| of the exact map.
        let scale = [&pre["spin"][0], &pre["velocity"][0], &pre["velocity"][1]]
            .iter()
            .map(|x| x.as_f64().unwrap().abs())
            .fold(0.0, f64::max);
        let tol = 16.0 * f64::EPSILON * scale;
        for (want, got) in [
            (spin, &post["spin"][0]),
            (v[0].clone(), &post["velocity"][0]),
            (v[1].clone(), &post["velocity"][1]),
        ] {
            let err = (want.to_f64().unwrap() - got.as_f64().unwrap()).abs();
            assert!(err <= tol, "event {}: error {err} > {tol}", line["event"]);
        }
        // Free flight changes no velocity: each contact starts from the last one's result.
        if let Some(p) = &previous {
            assert_eq!(p["post"][0], line["pre"][0]);
        }
        previous = Some(line.clone());
    }
}

/// Run the shipped 2D scene `name` for `events` contacts, tracing `traced` balls and every
/// contact point the picture keeps.
fn traced(name: &str, events: u64, traced: usize) -> Trace {
    let scene = scene(name);
    let (mut sim, species) = simulation::<2, 1>(&scene);
    let limits = Limits {
        events: Some(events),
        time: None,
        samples: 100,
        traced,
        contact_points: usize::MAX,
    };
    run(&mut sim, &species, &limits, None, &mut |_| {})
        .unwrap()
        .1
}

/// The distance from `c` to the segment from `a` to `b`.
fn segment_distance(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    let (d, e) = ([b[0] - a[0], b[1] - a[1]], [c[0] - a[0], c[1] - a[1]]);
    let len2 = d[0] * d[0] + d[1] * d[1];
    let s = if len2 > 0.0 {
        ((e[0] * d[0] + e[1] * d[1]) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (e[0] - s * d[0]).hypot(e[1] - s * d[1])
}

#[test]
fn sinai_paths_are_cut_at_wraps_and_never_cross_the_obstacle() {
    // The disk's centre keeps a distance >= R + R_obstacle from the obstacle's centre, and
    // stays in the unit square once wrapped. A drawn segment is within half a pixel of the
    // path (the thinning), so it must keep that clearance less half a pixel; a chord across a
    // wrap (the old picture) passes through the obstacle.
    let scene = scene("sinai.toml");
    let centre = [
        scene.obstacles[0].position[0].to_f64().unwrap(),
        scene.obstacles[0].position[1].to_f64().unwrap(),
    ];
    let clearance = (&scene.obstacles[0].radius + &scene.species[0].radius)
        .to_f64()
        .unwrap();
    let half_pixel = 0.5 / PICTURE;
    let trace = traced("sinai.toml", 3000, 1);
    let pieces = &trace.paths[0];
    assert!(
        pieces.len() > 100,
        "the path wraps: {} pieces",
        pieces.len()
    );
    let mut segments = 0;
    for piece in pieces {
        for p in piece {
            assert!(
                p.iter().all(|x| (-1e-12..=1.0 + 1e-12).contains(x)),
                "{p:?} outside the box"
            );
        }
        for w in piece.windows(2) {
            let d = segment_distance(w[0], w[1], centre);
            assert!(
                d >= clearance - half_pixel - 1e-12,
                "segment {w:?} passes {d} from the obstacle's centre (clearance {clearance})"
            );
            segments += 1;
        }
    }
    assert!(segments > 100, "{segments} segments");
}

#[test]
fn traces_stay_bounded_at_many_events() {
    // 10^6 Sinai contacts used to keep 10^6 path points (1.56 GB at 10^7 contacts): the
    // thinned paths, the contact points and the energy samples must stay within their budgets
    // whatever the number of events.
    for (name, events, balls) in [("sinai.toml", 1_000_000, 12), ("gas2d.toml", 100_000, 12)] {
        let trace = traced(name, events, balls);
        let points: usize = trace.paths.iter().flatten().map(Vec::len).sum();
        let pieces: usize = trace.paths.iter().map(Vec::len).sum();
        let cost = points + PIECE_COST * pieces;
        assert!(
            cost <= PATH_BUDGET + PIECE_COST + 1,
            "{name}: {points} points, {pieces} pieces"
        );
        assert!(
            trace.contacts.len() <= CONTACT_DOTS,
            "{name}: {} contacts",
            trace.contacts.len()
        );
        assert!(
            trace.energy.len() <= 101,
            "{name}: {} energy samples",
            trace.energy.len()
        );
    }
}

/// Found by the fuzz target `scene_toml` (fuzz/regressions/scene_toml/corridor-timeout.toml):
/// one disk flying almost exactly along a corridor of a periodic Sinai-like table, its next
/// contact some 1e49 time units away. With an event limit and no time limit the run crossed
/// cells for ever; it must end by itself once no contact came within
/// `MAX_QUIET_BOX_LENGTHS`, saying why, with the clock and energy intact.
#[test]
fn a_contact_out_of_reach_ends_the_run() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../fuzz/regressions/scene_toml/corridor-timeout.toml");
    let scene = Scene::from_file(&path).expect("a valid scene");
    let (mut sim, species) = simulation::<2, 1>(&scene);
    let mut notices = 0;
    let (summary, _) = run(&mut sim, &species, &limits(10), None, &mut |p| {
        if let Progress::Quiet { .. } = p {
            notices += 1;
        }
    })
    .unwrap();
    assert_eq!(summary.events, 0);
    let why = summary.stopped.expect("the run says why it stopped");
    assert!(why.contains("out of reach"), "{why}");
    // The notices at 1000, 2000, .. 512 000 box lengths came first; the speed is 0.99165 and
    // the longest side 2, so the clock stands at about 1.024e6 * 2 / 0.99165.
    assert_eq!(notices, 10);
    let expected = MAX_QUIET_BOX_LENGTHS * 2.0 / 0.99165;
    assert!(
        summary.time >= expected && summary.time < 1.1 * expected,
        "t = {}",
        summary.time
    );
    assert_eq!(summary.energy_end, summary.energy_start);
}

/// Issue 26, item 12: ten balls of radius 1 in a 6D periodic box of side 10^6 (mean free path
/// about 10^26 box lengths) ran for hours on the way to the stop at `MAX_QUIET_BOX_LENGTHS`
/// (about 1000 box lengths a second). Kinetic theory puts any contact out of reach, so the run
/// stops at the first quiet notice, 1000 box lengths, saying why.
#[test]
fn a_dilute_gas_stops_at_the_first_notice() {
    let size = ["1000000"; 6].join(", ");
    let boundary = ["\"periodic\""; 6].join(", ");
    let scene = Scene::from_toml(
        &format!(
            "dim = 6\n[box]\nsize = [{size}]\nboundary = [{boundary}]\n[[species]]\nmass = 1\n\
             radius = 1\ncount = 10\n[random]\nseed = 1\n"
        ),
        "dilute.toml",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let (mut sim, species) = simulation::<6, 15>(&scene);
    let rate = noslip_sim::dilute::contact_rate(&sim, &species).expect("all periodic");
    let mut notices = 0;
    let (summary, _) = run(&mut sim, &species, &limits(100), None, &mut |p| {
        if let Progress::Quiet { .. } = p {
            notices += 1;
        }
    })
    .unwrap();
    assert_eq!((summary.events, notices), (0, 0));
    let why = summary.stopped.expect("the run says why it stopped");
    assert!(
        why.contains("kinetic theory") && why.contains("out of reach"),
        "{why}"
    );
    // At most c_5 2^5 (N - 1) sum |u_i| / V per unit time: below 1e-28 for speeds below 1.
    assert!(rate > 0.0 && rate < 1e-28, "{rate:e}");
}

/// The Sinai table and a dense gas are far from the rule: they expect many contacts per box
/// length, so their quiet flights still run to the full reach (the corridor above).
#[test]
fn dense_tables_expect_contacts_within_reach() {
    for (name, dim) in [("sinai.toml", 2), ("gas6d.toml", 6)] {
        let scene = scene(name);
        let expected = if dim == 2 {
            let (sim, species) = simulation::<2, 1>(&scene);
            noslip_sim::dilute::out_of_reach(&sim, &species, 1000.0)
        } else {
            let (sim, species) = simulation::<6, 15>(&scene);
            noslip_sim::dilute::out_of_reach(&sim, &species, 1000.0)
        };
        assert_eq!(expected, None, "{name}");
    }
}
