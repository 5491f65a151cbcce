//! The shipped tables (strip, wedge, sector, triangle, circle, Sinai's square, cube, sphere):
//! energy over 10^6 contacts, the ball inside the table after every event, corners and
//! grazing contacts, the wedge's escape, smooth contacts, and time reversal.

use collision_core::{Ball, BodyState, Generated, Kernel};
use noslip_scene::Scene;
use noslip_sim::setup::setup;
use noslip_sim::table::{Boundary, ContactKind, Shape, Table};
use noslip_sim::{Body, Contact, GenericKernels, NoContact, Setup, Simulation, Step};
use std::path::Path;

fn scene(name: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../scenes")
        .join(name);
    Scene::from_file(&path).unwrap_or_else(|e| panic!("{e}"))
}

fn simulation<const N: usize, const S: usize>(
    setup: Setup<N, S>,
) -> Simulation<N, S, GenericKernels<f64>>
where
    Generated: Kernel<f64, N, S>,
{
    let kernels = GenericKernels {
        species: setup.species.clone(),
    };
    Simulation::new(setup, kernels).unwrap()
}

fn norm<const N: usize>(x: &[f64; N]) -> f64 {
    x.iter().map(|v| v * v).sum::<f64>().sqrt()
}

/// The ball's gap to everything that bounds it now (boundaries, box walls, obstacles): the
/// least, which is `>= 0` while it is in the table.
fn least_gap<const N: usize, const S: usize>(
    sim: &Simulation<N, S, GenericKernels<f64>>,
    setup: &Setup<N, S>,
    i: usize,
) -> f64
where
    Generated: Kernel<f64, N, S>,
{
    let a = sim.position(i);
    let r = setup.species[sim.species_of(i)].radius;
    let mut gap = sim
        .table()
        .boundaries
        .iter()
        .map(|b| b.shape.gap(&a, r))
        .fold(f64::INFINITY, f64::min);
    if sim.table().boxed {
        for k in (0..N).filter(|&k| !setup.periodic[k]) {
            gap = gap.min(a[k] - r).min(setup.size[k] - r - a[k]);
        }
    }
    for o in &setup.obstacles {
        let d: [f64; N] = std::array::from_fn(|k| a[k] - o.position[k]);
        gap = gap.min(norm(&d) - o.radius - r);
    }
    gap
}

/// What a run of a table did.
#[derive(Debug)]
struct Run {
    contacts: u64,
    drift: f64,
    /// The least gap over every event, relative to the tolerance (>= -1 passes).
    worst: f64,
    end: Option<NoContact>,
}

/// Up to `events` contacts of the table `name`, checking after every one that every ball is
/// inside the table within `tol = 64 eps (L + |a|)` (`L` the table's length scale, `a` the
/// centre: the rounding of coordinates of that size, and of the local clock, which is re-based
/// before the fastest ball flies `CLOCK_CELLS` = 128 cell widths, at most `L` each here, so that
/// half an ulp of a local time moves a ball by at most `64 eps L`).
fn run<const N: usize, const S: usize>(name: &str, events: u64) -> Run
where
    Generated: Kernel<f64, N, S>,
{
    let scene = scene(name);
    let start: Setup<N, S> = setup(&scene).unwrap();
    let scale = start.size.iter().copied().fold(0.0, f64::max);
    let mut sim = simulation(start.clone());
    let e0 = sim.observables().energy;
    let mut worst = f64::INFINITY;
    let mut contacts = 0;
    let mut end = None;
    while contacts < events {
        match sim.step(f64::INFINITY) {
            Step::Contact(_) => contacts += 1,
            Step::Never(why) => {
                end = Some(why);
                break;
            }
            other => panic!("{name}: {other:?}"),
        }
        for i in 0..sim.len() {
            let tol = 64.0 * f64::EPSILON * (scale + norm(&sim.position(i)));
            worst = worst.min(least_gap(&sim, &start, i) / tol);
        }
    }
    let drift = (sim.observables().energy - e0) / e0;
    Run {
        contacts,
        drift,
        worst,
        end,
    }
}

/// Each contact rounds the energy of the ball a few times: `|E - E_0| / E_0 <= 8 k eps`
/// after `k` contacts even if every error had the same sign (the same bound as the gases';
/// the one-ball tables drifted linearly, by about 0.2 eps per contact, until the `fixed`
/// kernel's spin coefficient was derived from its velocity coefficient: docs/tables.md,
/// "Energy and the table, over 10^6 contacts").
fn check(name: &str, r: &Run, events: u64) {
    eprintln!("{name}: {r:?}");
    assert!(r.worst >= -1.0, "{name}: the ball left the table: {r:?}");
    assert!(
        r.drift.abs() <= 8.0 * r.contacts as f64 * f64::EPSILON,
        "{name}: energy drift {r:?}"
    );
    if name != "wedge.toml" {
        assert_eq!(r.contacts, events, "{name}: {r:?}");
    }
}

#[test]
fn shipped_tables_keep_energy_and_the_ball_over_a_million_contacts() {
    let m = 1_000_000;
    for name in [
        "strip.toml",
        "sector.toml",
        "triangle.toml",
        "circle.toml",
        "sinai_square.toml",
    ] {
        check(name, &run::<2, 1>(name, m), m);
    }
    check("cube3d.toml", &run::<3, 3>("cube3d.toml", m), m);
    check("sphere3d.toml", &run::<3, 3>("sphere3d.toml", m), m);
    // The open wedge: finitely many contacts, then the ball escapes.
    let r = run::<2, 1>("wedge.toml", m);
    check("wedge.toml", &r, m);
    assert!(r.contacts >= 2 && r.contacts < 100, "{r:?}");
    assert_eq!(r.end, Some(NoContact::Escaped));
}

const DISK: Ball<f64> = Ball {
    inv_mass: 1.0,
    radius: 0.125,
    gamma2: 0.5,
};

fn wall(point: [f64; 2], normal: [f64; 2], contact: ContactKind) -> Boundary<2> {
    Boundary {
        shape: Shape::Wall { point, normal },
        contact,
        arc: 0.0,
    }
}

fn one_disk(
    boundaries: Vec<Boundary<2>>,
    position: [f64; 2],
    velocity: [f64; 2],
    spin: f64,
) -> Setup<2, 1> {
    Setup {
        size: [4.0, 4.0],
        periodic: [false; 2],
        species: vec![DISK],
        obstacles: vec![],
        bodies: vec![Body {
            species: 0,
            position,
            state: BodyState {
                spin: [spin],
                velocity,
            },
        }],
        orientation: false,
        table: Table {
            boxed: false,
            boundaries,
            ..Table::boxed()
        },
    }
}

/// The unit square `[0, 1]^2` as four walls.
fn square(contact: ContactKind) -> Vec<Boundary<2>> {
    vec![
        wall([0.0, 0.0], [0.0, 1.0], contact),
        wall([1.0, 0.0], [-1.0, 0.0], contact),
        wall([1.0, 1.0], [0.0, -1.0], contact),
        wall([0.0, 1.0], [1.0, 0.0], contact),
    ]
}

/// Up to `events` contacts; every one at a time no earlier than the last, the ball inside
/// within `64 eps`; the contacts, and how the run ended.
fn contacts_of(
    setup: Setup<2, 1>,
    events: u64,
) -> (Vec<noslip_sim::Event<2, 1>>, Option<NoContact>) {
    let mut sim = simulation(setup.clone());
    let mut out: Vec<noslip_sim::Event<2, 1>> = Vec::new();
    while (out.len() as u64) < events {
        match sim.step(f64::INFINITY) {
            Step::Contact(e) => {
                if let Some(last) = out.last() {
                    assert!(e.time >= last.time);
                }
                assert!(least_gap(&sim, &setup, 0) >= -64.0 * f64::EPSILON * 4.0);
                out.push(e);
            }
            Step::Never(why) => return (out, Some(why)),
            other => panic!("{other:?}"),
        }
    }
    (out, None)
}

/// A disk aimed exactly at a corner of the square along the diagonal touches both walls at
/// the same instant: two contacts at one time, then on. Smooth, it comes straight back along
/// the diagonal (each wall reverses one component); no-slip, it goes on bouncing. Neither
/// loops at the corner: time moves on.
#[test]
fn a_disk_aimed_into_a_corner_touches_both_walls_and_leaves() {
    let (events, end) = contacts_of(
        one_disk(square(ContactKind::Smooth), [0.5, 0.5], [1.0, 1.0], 0.0),
        4,
    );
    assert_eq!(end, None);
    // Corner (1, 1) at t = 0.375: both walls at that instant, in some order.
    assert_eq!(events[0].time, events[1].time);
    assert_eq!(events[0].time, 0.375);
    let walls = [events[0].contact, events[1].contact];
    assert!(
        walls.contains(&Contact::Boundary { i: 0, boundary: 1 }),
        "{walls:?}"
    );
    assert!(
        walls.contains(&Contact::Boundary { i: 0, boundary: 2 }),
        "{walls:?}"
    );
    assert_eq!(events[1].post[0].velocity, [-1.0, -1.0]);
    // Then the opposite corner, 0.75 later.
    assert_eq!(events[2].time, 1.125);
    assert_eq!(events[3].post[0].velocity, [1.0, 1.0]);
    // No-slip with spin: 10^4 contacts, time moving on, never a corner loop.
    let (events, end) = contacts_of(
        one_disk(square(ContactKind::NoSlip), [0.5, 0.5], [1.0, 1.0], 3.0),
        10_000,
    );
    assert_eq!((events.len(), end), (10_000, None));
    let same_time = events.windows(3).filter(|w| w[0].time == w[2].time).count();
    assert_eq!(same_time, 0, "three contacts at one instant");
}

/// A disk aimed at the apex of a smooth wedge of angle `theta` along its bisector makes at
/// most `ceil(pi / theta)` contacts (unfold the wedge: a straight line crosses at most that
/// many copies of it) and escapes; a no-slip one also escapes after finitely many.
#[test]
fn a_disk_aimed_at_a_wedge_apex_escapes() {
    for degrees in [90.0f64, 60.0, 45.0, 30.0, 10.0] {
        let theta = degrees.to_radians();
        let walls = |contact| {
            vec![
                wall([0.0, 0.0], [0.0, 1.0], contact),
                wall([0.0, 0.0], [theta.sin(), -theta.cos()], contact),
            ]
        };
        let bisector = [(theta / 2.0).cos(), (theta / 2.0).sin()];
        let start = bisector.map(|x| 3.0 * x);
        let v = bisector.map(|x| -x);
        let (events, end) = contacts_of(one_disk(walls(ContactKind::Smooth), start, v, 0.0), 1000);
        assert_eq!(end, Some(NoContact::Escaped), "{degrees}");
        let bound = (std::f64::consts::PI / theta - 1e-9).ceil() as usize;
        assert!(
            events.len() <= bound,
            "{degrees}: {} > {bound}",
            events.len()
        );
        assert!(!events.is_empty());
        let (events, end) = contacts_of(one_disk(walls(ContactKind::NoSlip), start, v, 2.0), 1000);
        assert_eq!(end, Some(NoContact::Escaped), "{degrees}: {}", events.len());
    }
}

/// Grazing: a disk touching the floor of a strip and moving along it never touches it (no
/// contact, and it flies off along the strip); one passing tangent to a disk obstacle touches
/// it once with zero normal velocity and flies on.
#[test]
fn grazing_disks_do_not_loop() {
    let strip = vec![
        wall([0.0, 0.0], [0.0, 1.0], ContactKind::NoSlip),
        wall([0.0, 1.0], [0.0, -1.0], ContactKind::NoSlip),
    ];
    let (events, end) = contacts_of(one_disk(strip, [0.5, DISK.radius], [1.0, 0.0], 1.0), 10);
    assert_eq!((events.len(), end), (0, Some(NoContact::Escaped)));
    let post = vec![Boundary {
        shape: Shape::Sphere {
            centre: [2.0, 0.0],
            radius: 0.5,
        },
        contact: ContactKind::NoSlip,
        arc: 0.0,
    }];
    let (events, end) = contacts_of(
        one_disk(post, [0.0, 0.5 + DISK.radius], [1.0, 0.0], 1.0),
        10,
    );
    assert_eq!((events.len(), end), (1, Some(NoContact::Escaped)));
    let e = &events[0];
    let un: f64 = (0..2).map(|k| e.pre[0].velocity[k] * e.nu[k]).sum();
    assert!(un.abs() < 1e-15, "{un}");
    // The no-slip map still turns spin into tangential velocity at a graze.
    assert_ne!(e.post[0], e.pre[0]);
}

/// Grazing inside a circular container. Nearly tangent (the normal velocity 1e-3 of the
/// speed, outward): the whispering-gallery orbit, many short chords at positive intervals,
/// inside the table. Exactly tangent while touching (a state scenes refuse: the straight
/// flight leaves the container at second order): one grazing contact, no repeat at the same
/// instant (which would loop forever), and the run stops there with the disk leaving the
/// table ([`Step::LeftTable`], `noslip_sim::left_table`; it used to fly off and end the
/// run with the false note that the table is unbounded).
#[test]
fn grazing_inside_a_container_moves_on() {
    let circle = vec![Boundary {
        shape: Shape::Container {
            centre: [0.0, 0.0],
            radius: 1.0,
        },
        contact: ContactKind::NoSlip,
        arc: 0.0,
    }];
    let rho = 1.0 - DISK.radius;
    let (events, end) = contacts_of(
        one_disk(circle.clone(), [rho - 1e-9, 0.0], [1e-3, 1.0], 0.0),
        1000,
    );
    assert_eq!((events.len(), end), (1000, None));
    let t = events.last().unwrap().time;
    assert!(t > 1e-3, "the clock stalls at {t}");
    let mut sim = simulation(one_disk(circle, [rho, 0.0], [0.0, 1.0], 1.0));
    assert!(matches!(sim.step(f64::INFINITY), Step::Contact(_)));
    let left = noslip_sim::LeftTable {
        ball: 0,
        boundary: 0,
        time: 0.0,
        outward_speed: 0.0,
    };
    assert_eq!(sim.step(f64::INFINITY), Step::LeftTable(left));
    // Stepping again says it again: the run cannot go on.
    assert_eq!(sim.step(f64::INFINITY), Step::LeftTable(left));
}

/// Time reversal of a no-slip table: `k` contacts forward, velocities and spins negated, `k`
/// back: the start again, within the divergence of a twin started `2^-30` away times `64 k
/// eps / 2^-30` (the argument of sim/tests/contacts.rs, `time_reversal_returns_to_the_start`).
#[test]
fn time_reversal_in_no_slip_tables() {
    reversal("circle.toml", 1000);
    reversal("triangle.toml", 1000);
    // Sinai's square is chaotic: few contacts before a 2^-30 perturbation grows to O(1).
    reversal("sinai_square.toml", 20);
}

fn reversal(name: &str, k: u64) {
    let start: Setup<2, 1> = setup(&scene(name)).unwrap();
    let go = |s: Setup<2, 1>| -> (Setup<2, 1>, f64) {
        let mut sim = simulation(s.clone());
        for _ in 0..k {
            assert!(matches!(sim.step(f64::INFINITY), Step::Contact(_)));
        }
        let mut end = s;
        end.bodies[0].position = sim.position(0);
        end.bodies[0].state = sim.state(0).clone();
        (end, sim.now())
    };
    let reverse = |mut s: Setup<2, 1>| {
        let b = &mut s.bodies[0];
        b.state.velocity = b.state.velocity.map(|x| -x);
        b.state.spin = b.state.spin.map(|x| -x);
        s
    };
    let distance = |a: &Setup<2, 1>, b: &Setup<2, 1>| {
        let (x, y) = (&a.bodies[0], &b.bodies[0]);
        let d = (0..2)
            .map(|k| (x.position[k] - y.position[k]).abs())
            .chain((0..2).map(|k| (x.state.velocity[k] - y.state.velocity[k]).abs()))
            .chain([(x.state.spin[0] - y.state.spin[0]).abs()]);
        d.fold(0.0, f64::max)
    };
    let (there, t) = go(start.clone());
    let mut sim = simulation(reverse(there.clone()));
    for _ in 0..k {
        assert!(matches!(sim.step(f64::INFINITY), Step::Contact(_)));
    }
    // Back at time t after the last contact (the first flight, undone).
    assert_eq!(sim.step(t), Step::Until);
    let mut back = start.clone();
    back.bodies[0].position = sim.position(0);
    back.bodies[0].state = sim.state(0).clone();
    let error = distance(&start, &reverse(back));
    let mut twin = start.clone();
    twin.bodies[0].position[0] += 2f64.powi(-30);
    let divergence = distance(&there, &go(twin).0);
    let bound = divergence * 64.0 * k as f64 * f64::EPSILON / 2f64.powi(-30);
    eprintln!("{name}: reversal error {error:.3e}, twin {divergence:.3e}, bound {bound:.3e}");
    assert!(divergence <= 1e-3 && error <= bound);
}

/// The portraits docs/tables.md shows are what the code draws now: each shipped table's
/// pictures regenerated (the same run as `examples/table_portraits.rs`) equal the files in
/// docs/tables/ byte for byte, and there is no other file there.
#[test]
fn the_docs_portraits_are_what_the_code_draws() {
    use noslip_sim::boundary_map::portraits;
    use noslip_sim::portrait::{DOCS_EVENTS, DOCS_TABLES};
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/tables");
    let mut expected = Vec::new();
    for name in DOCS_TABLES {
        let scene = scene(&format!("{name}.toml"));
        let portraits = collision_core::with_dim!(
            scene.dim,
            |N, S| portraits::<N, S>(setup::<N, S>(&scene).unwrap(), DOCS_EVENTS).unwrap(),
            unreachable!()
        );
        for portrait in portraits {
            let (kind, id) = portrait.body.kind_id();
            let file = format!("{name}-{kind}-{id}.png");
            let shipped = std::fs::read(dir.join(&file)).unwrap_or_else(|e| {
                panic!("{file}: {e} (cargo run --release -p noslip-sim --example table_portraits)")
            });
            assert!(
                shipped == portrait.png(&format!("{name}.toml")),
                "{file} is stale: cargo run --release -p noslip-sim --example table_portraits"
            );
            expected.push(file);
        }
    }
    let mut present: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".png"))
        .collect();
    present.sort();
    expected.sort();
    assert_eq!(present, expected);
}

/// Random placement inside a table (a box with a circular container and a triangular
/// obstacle inside it): every ball inside the container, outside the triangle (also deep
/// inside it, where the edges' gaps alone would not see it) and the other balls; then a
/// smooth gas there: ball-ball contacts keep the spins, energy is kept (`8 k eps`), and every
/// ball stays in the table after every contact.
#[test]
fn random_balls_are_placed_inside_the_table_and_a_smooth_gas_keeps_it() {
    let text = "dim = 2\n[box]\nsize = [4, 4]\nboundary = [\"wall\", \"wall\"]\n\
                [[container]]\ncentre = [2, 2]\nradius = 2\n\
                [[polygon]]\nvertices = [[1, 1], [3, 1], [2, 3]]\n\
                [[species]]\nmass = 1\nradius = \"1/10\"\ncount = 100\n\
                [contact]\nballs = \"smooth\"\n[random]\nseed = 5\nspin = 1\n";
    let scene = Scene::from_toml(text, "t.toml").unwrap();
    let start: Setup<2, 1> = setup(&scene).unwrap();
    let inside_triangle = |p: &[f64; 2]| {
        let v = [[1.0, 1.0], [3.0, 1.0], [2.0, 3.0]];
        (0..3).all(|k| {
            let (a, b): ([f64; 2], [f64; 2]) = (v[k], v[(k + 1) % 3]);
            (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]) >= 0.0
        })
    };
    for b in &start.bodies {
        let d = ((b.position[0] - 2.0).powi(2) + (b.position[1] - 2.0).powi(2)).sqrt();
        assert!(d <= 2.0 - 0.1, "{:?}", b.position);
        assert!(!inside_triangle(&b.position), "{:?}", b.position);
    }
    let mut sim = simulation(start.clone());
    let e0 = sim.observables().energy;
    let (mut pairs, mut k) = (0, 0u64);
    while k < 20_000 {
        let Step::Contact(e) = sim.step(f64::INFINITY) else {
            panic!("the gas keeps colliding")
        };
        k += 1;
        if let Contact::Ball { .. } = e.contact {
            pairs += 1;
            assert_eq!(
                [&e.post[0].spin, &e.post[1].spin],
                [&e.pre[0].spin, &e.pre[1].spin]
            );
        }
        for i in 0..sim.len() {
            let gap = least_gap(&sim, &start, i);
            assert!(gap >= -64.0 * f64::EPSILON * 8.0, "ball {i}: {gap}");
            assert!(!inside_triangle(&[sim.position(i)[0], sim.position(i)[1]]));
        }
    }
    assert!(pairs > 1000, "{pairs} ball-ball contacts");
    // Time moves on (a ball behind one polygon edge's line once took it at t = 0, forever).
    assert!(sim.now() > 1.0, "the clock stalls at {}", sim.now());
    let drift = (sim.observables().energy - e0) / e0;
    assert!(drift.abs() <= 8.0 * k as f64 * f64::EPSILON, "{drift}");
}
