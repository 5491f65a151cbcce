//! The table's next contact, checked by hand-computed flights.

use super::*;
use collision_core::{Exact, Scalar, State2};

fn q(n: i64, d: i64) -> Exact {
    Exact::from_ratio(n, d)
}

fn disk() -> Ball<Exact> {
    Ball {
        inv_mass: q(1, 1),
        radius: q(1, 2),
        gamma2: q(1, 2),
    }
}

/// A wall tilted to nu = (3/5, 4/5) through the origin: from (3, 4) (distance 5) moving with
/// (-3, -4)/5 at unit speed, the centre touches at distance r = 1/2 after t = 9/2.
#[test]
fn tilted_wall_contact_is_exact() {
    let table = Table {
        boundaries: vec![Boundary::Wall {
            point: [q(0, 1), q(0, 1)],
            normal: [q(3, 5), q(4, 5)],
        }],
        period: [None, None],
        ball: disk(),
        laws: vec![Law::NoSlip],
    };
    let hit = table
        .next_hit(&[q(3, 1), q(4, 1)], &[q(-3, 5), q(-4, 5)])
        .unwrap();
    assert_eq!(hit.time, q(9, 2));
    assert_eq!(hit.position, [q(3, 10), q(2, 5)]);
    assert_eq!(hit.nu, [q(3, 5), q(4, 5)]);
    // Moving away: never.
    assert_eq!(
        table.next_hit(&[q(3, 1), q(4, 1)], &[q(1, 1), q(0, 1)]),
        Err(NoHit::Escapes)
    );
}

/// A periodic unit square with a disk obstacle (the Sinai table): a flight that wraps across
/// the face x = 1 meets the obstacle's image... here the obstacle itself after one wrap: from
/// (9/10, 1/2) moving +x, the centre wraps to x = 0 at t = 1/10 and touches the obstacle
/// (centre (1/2, 1/2), R_eff = 3/10 + 1/20 = 7/20) at x = 1/2 - 7/20 = 3/20: t = 1/10 + 3/20.
#[test]
fn periodic_flight_wraps_and_meets_the_obstacle() {
    let table = Table {
        boundaries: vec![Boundary::Sphere {
            centre: [q(1, 2), q(1, 2)],
            radius: q(3, 10),
        }],
        period: [Some(q(1, 1)), Some(q(1, 1))],
        ball: Ball {
            radius: q(1, 20),
            ..disk()
        },
        laws: vec![Law::NoSlip],
    };
    let hit = table
        .next_hit(&[q(9, 10), q(1, 2)], &[q(1, 1), q(0, 1)])
        .unwrap();
    assert_eq!(hit.time, q(1, 4));
    assert_eq!(hit.position, [q(3, 20), q(1, 2)]);
    assert_eq!(hit.nu, [q(-1, 1), q(0, 1)]);
    // A grazing-free flight along y = 0 misses every image: it escapes (in the budget).
    let f = table.map(|x| x.to_f64());
    assert_eq!(f.next_hit(&[0.0, 0.0], &[1.0, 0.0]), Err(NoHit::Escapes));
    // An irrational contact time cannot be found exactly.
    assert_eq!(
        table
            .next_hit(&[q(0, 1), q(1, 2)], &[q(1, 1), q(1, 3)])
            .map(|h| h.time),
        Err(NoHit::Irrational)
    );
    assert!(f.next_hit(&[0.0, 0.5], &[1.0, 1.0 / 3.0]).is_ok());
}

/// Inside a circle of radius 3 (R_eff = 5/2), a chord from the centre along (0, 1) ends at
/// y = 5/2; the no-slip step then reverses the normal velocity.
#[test]
fn container_chord_and_step() {
    let table = Table {
        boundaries: vec![Boundary::Container {
            centre: [q(0, 1), q(0, 1)],
            radius: q(3, 1),
        }],
        period: [None, None],
        ball: disk(),
        laws: vec![Law::NoSlip],
    };
    let s = State2::from_scalar_spin(q(0, 1), [q(0, 1), q(2, 1)]);
    let (hit, after) = table.step(&[q(0, 1), q(0, 1)], &s).unwrap();
    assert_eq!(
        (hit.time, hit.position.clone()),
        (q(5, 4), [q(0, 1), q(5, 2)])
    );
    assert_eq!(hit.nu, [q(0, 1), q(-1, 1)]);
    assert_eq!(after.velocity, [q(0, 1), q(-2, 1)]);
}

/// A flight tangent to a sphere's contact surface (R_eff = 4 + 1 = 5, passing at distance 5)
/// is not a contact, in exact arithmetic (no division by `u . nu = 0` follows); one passing
/// at 49/10 is.
#[test]
fn grazing_flights_are_not_contacts() {
    let table = Table {
        boundaries: vec![Boundary::Sphere {
            centre: [q(0, 1), q(0, 1)],
            radius: q(4, 1),
        }],
        period: [None, None],
        ball: Ball {
            radius: q(1, 1),
            ..disk()
        },
        laws: vec![Law::NoSlip],
    };
    assert_eq!(
        table.next_hit(&[q(-10, 1), q(5, 1)], &[q(1, 1), q(0, 1)]),
        Err(NoHit::Escapes)
    );
    // At height 3 the contact is at (-4, 3), t = 6 (a rational root).
    assert_eq!(
        table
            .next_hit(&[q(-10, 1), q(3, 1)], &[q(1, 1), q(0, 1)])
            .unwrap()
            .time,
        q(6, 1)
    );
}

/// A polygon obstacle's edge from (0, 0) to (2, 0), the table above (nu = (0, 1)), r = 1/2:
/// from (1, 3) moving straight down the centre touches at y = 1/2 after t = 5/2, exactly;
/// from (3, 3) (its foot beyond the edge's end) and from below the edge's line it never
/// touches the edge itself (the vertices, spheres of radius 0, would).
#[test]
fn edge_is_touched_only_over_the_segment_from_in_front() {
    let table = Table {
        boundaries: vec![Boundary::Edge {
            from: [q(0, 1), q(0, 1)],
            to: [q(2, 1), q(0, 1)],
            normal: [q(0, 1), q(1, 1)],
        }],
        period: [None, None],
        ball: disk(),
        laws: vec![Law::NoSlip],
    };
    let down = [q(0, 1), q(-1, 1)];
    let hit = table.next_hit(&[q(1, 1), q(3, 1)], &down).unwrap();
    assert_eq!(hit.time, q(5, 2));
    assert_eq!(hit.position, [q(1, 1), q(1, 2)]);
    assert_eq!(hit.nu, [q(0, 1), q(1, 1)]);
    assert_eq!(
        table.next_hit(&[q(3, 1), q(3, 1)], &down),
        Err(NoHit::Escapes)
    );
    assert_eq!(
        table.next_hit(&[q(1, 1), q(-1, 1)], &[q(0, 1), q(1, 1)]),
        Err(NoHit::Escapes)
    );
}

/// The images [`Table::next_hit`] leaves out (`may_meet_the_box`) change no hit: on random
/// Sinai tables in 2D and 3D (an obstacle anywhere in the unit periodic box, near its faces
/// and corners too, so that shifted images are met), random flights from outside every
/// image end at the same contact, bit for bit, as when every image is tried at every face.
#[test]
fn a_flight_meets_the_same_images_as_among_all_of_them() {
    fn check<const N: usize>(seed: u64) -> (usize, usize) {
        let mut state = seed;
        let mut next = move || {
            // xorshift64*, uniform in [0, 1).
            state ^= state >> 12;
            state ^= state << 25;
            state ^= state >> 27;
            (state.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
        };
        let (mut flights, mut kept_one) = (0, 0);
        for _ in 0..300 {
            let centre: [f64; N] = std::array::from_fn(|_| next());
            let table = Table {
                boundaries: vec![Boundary::Sphere {
                    centre,
                    radius: 0.05 + 0.35 * next(),
                }],
                period: [Some(1.0); N],
                ball: Ball {
                    inv_mass: 1.0,
                    radius: 0.05,
                    gamma2: 0.5,
                },
                laws: vec![Law::NoSlip],
            };
            let shifts = table.shifts();
            let all = vec![(0..shifts.len()).collect::<Vec<_>>()];
            let Boundary::Sphere { radius, .. } = table.boundaries[0] else {
                unreachable!()
            };
            let kept = (0..shifts.len())
                .filter(|&s| table.may_meet_the_box(&centre, &radius, &shifts[s]))
                .count();
            kept_one += usize::from(kept == 1);
            for _ in 0..10 {
                let x: [f64; N] = std::array::from_fn(|_| next());
                let clear = shifts.iter().all(|s| {
                    let d2: f64 = (0..N).map(|k| (x[k] - centre[k] - s[k]).powi(2)).sum();
                    d2.sqrt() > radius + 0.05
                });
                if !clear {
                    continue;
                }
                let u: [f64; N] = std::array::from_fn(|_| 2.0 * next() - 1.0);
                let among_all = table.next_hit_among(&x, &u, &shifts, &all);
                assert_eq!(
                    table.next_hit(&x, &u),
                    among_all,
                    "{table:?} from {x:?} with {u:?}"
                );
                flights += usize::from(among_all.is_ok());
            }
        }
        (flights, kept_one)
    }
    let (flights2, one2) = check::<2>(0x9e37_79b9_7f4a_7c15);
    let (flights3, one3) = check::<3>(0xd1b5_4a32_d192_ed03);
    // Most starts are clear of the obstacle and meet it; tables whose obstacle stays clear of
    // every face keep one image (an obstacle of R + r < 1/2 centred far enough inside).
    assert!(flights2 > 1000 && flights3 > 1000, "{flights2} {flights3}");
    assert!(one2 > 10 && one3 > 10, "{one2} {one3}");
}
