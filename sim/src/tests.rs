//! The engine on small hand-made setups: when it stops by itself, boxes far larger than the
//! balls, and the absolute clock across re-basings.

use super::{Body, Contact, FixedBall, GenericKernels, NoContact, Setup, Simulation, Step};
use collision_core::{Ball, BodyState};

const DISK: Ball<f64> = Ball {
    inv_mass: 1.0,
    radius: 0.5,
    gamma2: 0.5,
};

fn disk(position: [f64; 2], velocity: [f64; 2]) -> Body<2, 1> {
    Body {
        species: 0,
        position,
        state: BodyState {
            spin: [0.0],
            velocity,
        },
    }
}

fn sim2(
    size: [f64; 2],
    periodic: [bool; 2],
    obstacles: Vec<FixedBall<2>>,
    bodies: Vec<Body<2, 1>>,
) -> Simulation<2, 1, GenericKernels<f64>> {
    let setup = Setup {
        size,
        periodic,
        species: vec![DISK],
        obstacles,
        bodies,
        orientation: false,
        table: crate::Table::boxed(),
    };
    Simulation::new(
        setup,
        GenericKernels {
            species: vec![DISK],
        },
    )
    .unwrap()
}

#[test]
fn one_disk_parallel_to_the_walls_stops_at_once() {
    // issue 16: periodic along x, walls along y, moving along x: it crossed cells forever.
    let mut sim = sim2(
        [10.0, 4.0],
        [true, false],
        vec![],
        vec![disk([1.0, 2.0], [1.0, 0.0])],
    );
    assert_eq!(sim.step(f64::INFINITY), Step::Never(NoContact::Separated));
    assert_eq!((sim.contacts(), sim.crossings()), (0, 0));
    // The same disk with a component towards a wall does touch it.
    let mut sim = sim2(
        [10.0, 4.0],
        [true, false],
        vec![],
        vec![disk([1.0, 2.0], [1.0, 1e-3])],
    );
    let Step::Contact(e) = sim.step(f64::INFINITY) else {
        panic!("a wall contact")
    };
    assert!(matches!(e.contact, Contact::Wall { axis: 1, .. }));
}

#[test]
fn disks_on_parallel_lines_are_decided_exactly() {
    // Along x at speeds 1 and -1, centres 1.01 apart across x (contact distance 1): never.
    let bodies = vec![disk([1.0, 2.0], [1.0, 0.0]), disk([5.0, 3.01], [-1.0, 0.0])];
    let mut sim = sim2([10.0, 10.0], [true, true], vec![], bodies);
    assert_eq!(sim.step(f64::INFINITY), Step::Never(NoContact::Separated));
    // 0.99 apart: they meet, through the periodic face or not.
    let bodies = vec![disk([1.0, 2.0], [1.0, 0.0]), disk([5.0, 2.99], [-1.0, 0.0])];
    let mut sim = sim2([10.0, 10.0], [true, true], vec![], bodies);
    assert!(matches!(sim.step(f64::INFINITY), Step::Contact(_)));
    // The perpendicular distance is the minimum image: 9.5 apart in a side of 10 is 0.5.
    let bodies = vec![disk([1.0, 0.25], [1.0, 0.0]), disk([5.0, 9.75], [0.0, 0.0])];
    let mut sim = sim2([10.0, 10.0], [true, true], vec![], bodies);
    assert!(matches!(sim.step(f64::INFINITY), Step::Contact(_)));
    // An obstacle off the line of flight.
    let obstacle = FixedBall {
        position: [5.0, 7.0],
        radius: 1.0,
    };
    let mut sim = sim2(
        [10.0, 10.0],
        [true, true],
        vec![obstacle],
        vec![disk([1.0, 2.0], [1.0, 0.0])],
    );
    assert_eq!(sim.step(f64::INFINITY), Step::Never(NoContact::Separated));
}

#[test]
fn balls_at_rest_stop_at_once() {
    let bodies = vec![disk([1.0, 2.0], [0.0, 0.0]), disk([5.0, 3.0], [0.0, 0.0])];
    let mut sim = sim2([10.0, 10.0], [false, true], vec![], bodies);
    assert_eq!(sim.step(f64::INFINITY), Step::Never(NoContact::AtRest));
    assert_eq!(sim.now(), 0.0);
    // With a time limit, the clock moves on to it.
    assert_eq!(sim.step(5.0), Step::Never(NoContact::AtRest));
    assert_eq!(sim.now(), 5.0);
}

#[test]
fn a_closed_orbit_that_misses_stops_at_once() {
    // Velocity (1, 1) in a periodic square of side 10: the orbit is the line x - y = 0 (mod
    // 10), closed after two box traversals; the obstacle at x - y = 5 stays
    // 5/sqrt(2) - 1.5 > 0 away, so no contact can ever happen.
    let obstacle = FixedBall {
        position: [7.5, 2.5],
        radius: 1.0,
    };
    let mut sim = sim2(
        [10.0, 10.0],
        [true, true],
        vec![obstacle.clone()],
        vec![disk([1.0, 1.0], [1.0, 1.0])],
    );
    assert_eq!(sim.step(f64::INFINITY), Step::Never(NoContact::Separated));
    assert_eq!((sim.contacts(), sim.crossings()), (0, 0));
    // The same closed orbit, moved so that it passes the obstacle at 1.4 < 1.5: it touches.
    let mut sim = sim2(
        [10.0, 10.0],
        [true, true],
        vec![obstacle],
        vec![disk([1.0, 1.0 + 5.0 - 1.4 * 2f64.sqrt()], [1.0, 1.0])],
    );
    assert!(matches!(sim.step(f64::INFINITY), Step::Contact(_)));
}

#[test]
fn a_flight_along_a_corridor_is_noticed_and_goes_on_to_its_contact() {
    // Sinai's table (unit square, obstacle of radius 0.3 at the centre, disk of radius 0.05)
    // with the disk just above the obstacle's band, moving almost along the corridor
    // y in (0.85, 1.15): it leaves the corridor after 0.3 / 2.2e-4 ~ 1360 time units, about
    // 1350 box lengths, and then meets an obstacle. The run reports the quiet stretch and
    // must not stop there (a stop at 1000 box lengths cut a Sinai run short).
    let small = Ball {
        radius: 0.05,
        ..DISK
    };
    let setup = Setup {
        size: [1.0, 1.0],
        periodic: [true, true],
        species: vec![small.clone()],
        obstacles: vec![FixedBall {
            position: [0.5, 0.5],
            radius: 0.3,
        }],
        bodies: vec![disk([0.49, 0.8501], [-0.99165, 2.2077e-4])],
        orientation: false,
        table: crate::Table::boxed(),
    };
    let mut sim = Simulation::new(
        setup,
        GenericKernels {
            species: vec![small],
        },
    )
    .unwrap();
    let mut notices = Vec::new();
    let contact = loop {
        match sim.step(f64::INFINITY) {
            Step::Quiet { box_lengths } => notices.push(box_lengths),
            Step::Contact(e) => break e,
            other => panic!("the corridor ends in a contact, got {other:?}"),
        }
    };
    assert!(!notices.is_empty() && notices[0] >= super::no_contact::QUIET_BOX_LENGTHS);
    assert!(
        (1200.0..1500.0).contains(&contact.time),
        "contact at t = {}",
        contact.time
    );
}

/// A deterministic spread of points in `[lo, hi)^N` (a Weyl sequence), `count` of them.
fn spread<const N: usize>(count: usize, lo: f64, hi: f64) -> Vec<[f64; N]> {
    (1..=count)
        .map(|i| {
            std::array::from_fn(|k| {
                let alpha = (2.0 + k as f64).sqrt().fract();
                lo + (hi - lo) * (i as f64 * alpha).fract()
            })
        })
        .collect()
}

#[test]
fn huge_boxes_need_memory_for_the_balls_only() {
    // issue 16: 10 balls in a 6D periodic box of side 1e6 overflowed the cell count
    // (index out of bounds); 100 disks in a 1e5 x 1e5 box allocated 60 GB.
    let ball = Ball {
        inv_mass: 1.0,
        radius: 0.5,
        gamma2: 1.0 / 3.0,
    };
    let bodies: Vec<Body<6, 15>> = spread::<6>(10, 0.0, 1e6)
        .into_iter()
        .zip(spread::<6>(10, -1.0, 1.0))
        .map(|(position, velocity)| Body {
            species: 0,
            position,
            state: BodyState {
                spin: [0.0; 15],
                velocity,
            },
        })
        .collect();
    let setup = Setup {
        size: [1e6; 6],
        periodic: [true; 6],
        species: vec![ball.clone()],
        obstacles: vec![],
        bodies,
        orientation: false,
        table: crate::Table::boxed(),
    };
    let mut sim = Simulation::new(
        setup,
        GenericKernels {
            species: vec![ball],
        },
    )
    .unwrap();
    assert_eq!(sim.step(100.0), Step::Until);
    assert!(sim.cells() <= 40, "{}", sim.cells());

    let bodies = spread::<2>(100, 1.0, 1e5 - 1.0)
        .into_iter()
        .zip(spread::<2>(100, -1.0, 1.0))
        .map(|(p, v)| disk(p, v))
        .collect();
    let mut sim = sim2([1e5, 1e5], [false, false], vec![], bodies);
    assert!(sim.cells() <= 400, "{}", sim.cells());
    // Each disk reaches a wall (the nearest is at most 5e4 away at speed >= 1e-2 or so).
    for _ in 0..100 {
        assert!(matches!(sim.step(f64::INFINITY), Step::Contact(_)));
    }
}

#[test]
fn orientations_follow_the_spin_across_crossings_and_rebasings() {
    // Nearly the closed orbit of `a_closed_orbit_that_misses_stops_at_once`, spinning: the
    // direction (1, 1 + 2^-13) does not close within 64 box traversals, so the engine cannot
    // decide that it never meets the obstacle and keeps flying; by T = 5000 it has drifted
    // 5000 2^-13 / sqrt(2) = 0.43 across, less than its 2.03 clearance, so no contact.
    // The compact entry U_01 = 0.3 is U = c J with c = -0.3, so A(T) is the rotation by
    // -0.3 T.
    // Up to T = 5000 there are 2000 cell crossings (2 x 2 cells of side 5), which move no
    // record, and a rebase every 128 x 5 / sqrt(2) = 453: 11 rebases, each adding its flight
    // time to the orientation's unapplied time, then one exponential of the sum: the angle is
    // rounded by about 0.3 x 5000 x 12 eps < 4e-12, the rotation by a few eps; 1e-10 is
    // allowed.
    let obstacle = FixedBall {
        position: [7.5, 2.5],
        radius: 1.0,
    };
    let mut body = disk([1.0, 1.0], [1.0, 1.0 + 2f64.powi(-13)]);
    body.state.spin = [0.3];
    let setup = Setup {
        size: [10.0, 10.0],
        periodic: [true, true],
        species: vec![DISK],
        obstacles: vec![obstacle],
        bodies: vec![body],
        orientation: true,
        table: crate::Table::boxed(),
    };
    let kernels = GenericKernels {
        species: vec![DISK],
    };
    let mut sim = Simulation::new(setup, kernels).unwrap();
    let t = 5000.0;
    assert_eq!(sim.step(t), Step::Until);
    assert!(sim.rebases() >= 10 && sim.crossings() >= 1000);
    assert!(sim.rebases() + sim.crossings() < 4000);
    let a = sim.orientation(0).unwrap();
    let (s, c) = (0.3 * t).sin_cos();
    let want = [[c, s], [-s, c]];
    for (row, want_row) in a.iter().zip(&want) {
        for (x, y) in row.iter().zip(want_row) {
            assert!((x - y).abs() < 1e-10, "{a:?} against {want:?}");
        }
    }
}

#[test]
fn contact_times_stay_absolute_across_rebasings() {
    // A disk bouncing along y between walls 3 apart (centre range [0.5, 3.5]) at speed 1: the
    // k-th contact is at 1.5 + 3 (k - 1), exactly representable, and the local clock is
    // re-based each 128 cell widths (2 x 2 cells) travelled, at local time 256: over 3 x 10^5
    // more than 1000 times, each moving the record to a time between two contacts.
    let mut sim = sim2(
        [4.0, 4.0],
        [true, false],
        vec![],
        vec![disk([2.0, 2.0], [0.0, 1.0])],
    );
    for k in 1..=100_000u64 {
        let Step::Contact(e) = sim.step(f64::INFINITY) else {
            panic!("contact {k}")
        };
        assert_eq!(e.time, 1.5 + 3.0 * (k - 1) as f64, "contact {k}");
    }
    assert!(sim.rebases() > 1_000, "{}", sim.rebases());
}

#[test]
fn prefetching_changes_no_event() {
    // The prefetching scan (large cell lists) and the plain one read the same cells in the
    // same order: the same events, bit for bit (`{:?}` prints every f64 exactly), with ball
    // and obstacle partners, periodic images and walls.
    let run = |prefetch: bool| {
        let bodies: Vec<Body<2, 1>> = (0..400)
            .zip(spread::<2>(400, -1.0, 1.0))
            .map(|(b, v)| disk([(2 * (b % 20) + 1) as f64, (2 * (b / 20) + 1) as f64], v))
            .collect();
        let obstacles = (0..10)
            .map(|o| FixedBall {
                position: [(4 * o + 2) as f64, (2 * o + 2) as f64],
                radius: 0.3,
            })
            .collect();
        let mut sim = sim2([40.0, 40.0], [true, false], obstacles, bodies);
        sim.set_prefetch(prefetch);
        (0..6000)
            .map(|_| match sim.step(f64::INFINITY) {
                Step::Contact(e) => format!("{e:?}"),
                other => panic!("{other:?}"),
            })
            .collect::<Vec<String>>()
    };
    let plain = run(false);
    assert!(plain.iter().any(|e| e.contains("Obstacle")));
    assert!(plain.iter().any(|e| e.contains("Wall")));
    assert_eq!(plain, run(true));
}

#[test]
fn prefetching_changes_no_event_in_3d() {
    // In 3D the look-ahead takes a crossing's layer (9 cells) and leaves a full scan (27
    // cells) to the scan's own prefetch (`engine/ahead.rs`): both, with the lanes of the
    // gathered scan (no obstacles), periodic images and walls, give the plain run's events
    // bit for bit.
    let run = |prefetch: bool| {
        let ball = Ball {
            inv_mass: 1.0,
            radius: 0.5,
            gamma2: 0.4,
        };
        let bodies: Vec<Body<3, 3>> = (0..512)
            .zip(spread::<3>(512, -1.0, 1.0))
            .map(|(b, velocity)| Body {
                species: 0,
                position: std::array::from_fn(|k| (2 * ((b >> (3 * k)) % 8) + 1) as f64),
                state: BodyState {
                    spin: [0.0; 3],
                    velocity,
                },
            })
            .collect();
        let setup = Setup {
            size: [16.0; 3],
            periodic: [true, false, true],
            species: vec![ball.clone()],
            obstacles: vec![],
            bodies,
            orientation: false,
            table: crate::Table::boxed(),
        };
        let kernels = GenericKernels {
            species: vec![ball],
        };
        let mut sim = Simulation::new(setup, kernels).unwrap();
        sim.set_prefetch(prefetch);
        let events = (0..5000)
            .map(|_| match sim.step(f64::INFINITY) {
                Step::Contact(e) => format!("{e:?}"),
                other => panic!("{other:?}"),
            })
            .collect::<Vec<String>>();
        (events, sim.crossings())
    };
    let (plain, crossings) = run(false);
    assert!(plain.iter().any(|e| e.contains("Wall")));
    assert!(crossings > 5000, "{crossings}");
    assert_eq!(plain, run(true).0);
}

#[test]
fn the_energy_alone_is_the_observables_energy_bit_for_bit() {
    // `energy` skips the positions, not a term: along a run of spinning disks of unequal
    // speeds, its bits are those of `observables().energy` at every sampled contact.
    let bodies: Vec<Body<2, 1>> = (0..100)
        .zip(spread::<2>(100, -1.0, 1.0))
        .map(|(b, v)| Body {
            state: BodyState {
                spin: [v[0] - 0.3 * v[1]],
                velocity: v,
            },
            ..disk([(2 * (b % 10) + 1) as f64, (2 * (b / 10) + 1) as f64], v)
        })
        .collect();
    let mut sim = sim2([20.0, 20.0], [true, true], vec![], bodies);
    for k in 0..2000 {
        let Step::Contact(_) = sim.step(f64::INFINITY) else {
            panic!("contact {k}")
        };
        if k % 100 == 0 {
            let (alone, all) = (sim.energy(), sim.observables().energy);
            assert_eq!(alone.to_bits(), all.to_bits(), "contact {k}");
            assert!(alone > 0.0);
        }
    }
}
