//! The boundary (collision) map: one row per contact of a ball with an immovable body (a box
//! wall, an obstacle, a boundary of [`crate::table`]), in the coordinates billiard studies use.
//!
//! Conventions (`nu` is the event's unit normal, from the body to the ball's centre; `Q = a -
//! R nu` the contact point; in 2D `t = (nu_1, -nu_0)` is the tangent with the table on its
//! left, counterclockwise around a table, clockwise around an obstacle):
//!
//! - **coordinate**, 2D: the arc length along a flat boundary, `(Q - p) . t` from a wall's
//!   point `p` (box walls: from the origin, `Q . t`); around a polygon the arc length from its
//!   first vertex counterclockwise (an edge or a polygon table's wall: the arc to its start
//!   vertex plus the distance along it; a vertex: the arc to it); on a circle (container,
//!   obstacle) the angle `atan2` of `Q - c` about its centre, in `(-pi, pi]`. In nD: the
//!   distance `|Q - p|` of the contact point from a wall's point (box walls: `|Q|` with the
//!   wall's axis left out), and on a sphere the angle between `Q - c` and `e_0`, in `[0, pi]`.
//! - **incidence** (before) and **reflection** (after): 2D the signed angles `atan2(u . t,
//!   -u . nu)` and `atan2(u' . t, u' . nu)` from the normal, in `(-pi/2, pi/2)`; nD their
//!   sizes, `arccos(-u . nu / |u|)` and `arccos(u' . nu / |u'|)`, in `[0, pi/2]`.
//! - **normal velocity** `u . nu` before (negative; after, it is reversed exactly by both
//!   maps up to rounding).
//! - **tangential velocity**, before and after: 2D the signed `u . t`; nD the norm
//!   `|u - (u . nu) nu|`.
//! - **spin**, before and after: 2D the angular velocity `c` (`U = c J`, counterclockwise
//!   positive); nD the norm of the compact entries, `sqrt(sum_{i<j} U_ij^2)`.
//! - **scaled spin** `gamma R c = sqrt(2 lambda) c` (nD: times the norm): with it the energy
//!   is `m/2 (u_n^2 + u_t^2 + (gamma R c)^2)`, so the no-slip map acts on `(u_t, gamma R c)`
//!   as an orthogonal map (a reflection) and its invariant lines and circles show undistorted.

pub use crate::immovable::Body;
use crate::portrait::{Axes, Portrait};
use crate::run::contact_point;
use crate::table::{Shape, Table};
use crate::{Contact, Event, PairKernels, Simulation};
use std::io::{self, Write};

/// One row of the boundary map (see the module docs for each quantity).
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// The event's index in the run (1 for the first contact).
    pub event: u64,
    /// The time of the contact.
    pub time: f64,
    /// The ball.
    pub ball: usize,
    /// What it touched.
    pub body: Body,
    /// The contact point `Q`.
    pub point: Vec<f64>,
    /// The boundary coordinate.
    pub coordinate: f64,
    /// The angle of incidence (before).
    pub incidence: f64,
    /// The angle of reflection (after).
    pub reflection: f64,
    /// `u . nu` before.
    pub normal_velocity: f64,
    /// The tangential velocity before and after.
    pub tangential: [f64; 2],
    /// The spin before and after.
    pub spin: [f64; 2],
    /// `sqrt(2 lambda)` times the spin, before and after.
    pub scaled_spin: [f64; 2],
}

/// The CSV header for dimension `n`.
pub fn header(n: usize) -> String {
    let point: Vec<String> = (0..n).map(|k| format!("q{k}")).collect();
    format!(
        "event,time,ball,kind,id,{},coordinate,incidence,reflection,normal_velocity,\
         tangential_velocity,tangential_velocity_post,spin,spin_post,scaled_spin,scaled_spin_post",
        point.join(",")
    )
}

/// The CSV line of `row`.
pub fn line(row: &Row) -> String {
    let (kind, id) = row.body.kind_id();
    let mut s = format!("{},{:e},{},{kind},{id}", row.event, row.time, row.ball);
    for x in &row.point {
        s.push_str(&format!(",{x:e}"));
    }
    for x in [
        row.coordinate,
        row.incidence,
        row.reflection,
        row.normal_velocity,
        row.tangential[0],
        row.tangential[1],
        row.spin[0],
        row.spin[1],
        row.scaled_spin[0],
        row.scaled_spin[1],
    ] {
        s.push_str(&format!(",{x:e}"));
    }
    s
}

fn dot<const N: usize>(a: &[f64; N], b: &[f64; N]) -> f64 {
    (0..N).map(|k| a[k] * b[k]).sum()
}

fn norm<const N: usize>(a: &[f64; N]) -> f64 {
    dot(a, a).sqrt()
}

/// The coordinate of the contact point `q` (normal `nu`) on `body`.
fn coordinate<const N: usize>(
    table: &Table<N>,
    obstacles: &[crate::FixedBall<N>],
    body: Body,
    q: &[f64; N],
    nu: &[f64; N],
) -> f64 {
    let t = |nu: &[f64; N]| -> [f64; N] { std::array::from_fn(|k| [nu[1], -nu[0]][k.min(1)]) };
    let sub = |a: &[f64; N], b: &[f64; N]| -> [f64; N] { std::array::from_fn(|k| a[k] - b[k]) };
    let angle = |d: [f64; N]| {
        if N == 2 {
            d[1].atan2(d[0])
        } else {
            (d[0] / norm(&d)).clamp(-1.0, 1.0).acos()
        }
    };
    match body {
        Body::BoxWall(axis, _) => {
            if N == 2 {
                dot(q, &t(nu))
            } else {
                let d: [f64; N] = std::array::from_fn(|k| if k == axis { 0.0 } else { q[k] });
                norm(&d)
            }
        }
        Body::Obstacle(o) => angle(sub(q, &obstacles[o].position)),
        Body::Boundary(b) => {
            let boundary = &table.boundaries[b];
            match &boundary.shape {
                Shape::Wall { point, .. } => {
                    if N == 2 {
                        boundary.arc + dot(&sub(q, point), &t(nu))
                    } else {
                        norm(&sub(q, point))
                    }
                }
                Shape::Edge { from, .. } => boundary.arc + norm(&sub(q, from)),
                Shape::Sphere { radius, .. } if *radius == 0.0 => boundary.arc,
                Shape::Sphere { centre, .. } | Shape::Container { centre, .. } => {
                    angle(sub(q, centre))
                }
            }
        }
    }
}

/// The boundary-map row of event `e` (the `index`-th contact), or `None` for two balls.
pub fn row<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
    index: u64,
    e: &Event<N, S>,
    sim: &Simulation<N, S, K>,
    species: &[collision_core::Ball<f64>],
) -> Option<Row> {
    let (i, body) = match e.contact {
        Contact::Ball { .. } => return None,
        Contact::Wall { i, axis, upper } => (i, Body::BoxWall(axis, upper)),
        Contact::Obstacle { i, obstacle } => (i, Body::Obstacle(obstacle)),
        Contact::Boundary { i, boundary } => (i, Body::Boundary(boundary)),
    };
    let ball = &species[sim.species_of(i)];
    let q = contact_point(e, species, sim);
    let nu = &e.nu;
    let (pre, post) = (&e.pre[0], &e.post[0]);
    let t: [f64; N] = std::array::from_fn(|k| [nu[1], -nu[0]][k.min(1)]);
    let (un, un_post) = (dot(&pre.velocity, nu), dot(&post.velocity, nu));
    let tangential = |u: &[f64; N], un: f64| {
        if N == 2 {
            dot(u, &t)
        } else {
            let w: [f64; N] = std::array::from_fn(|k| u[k] - un * nu[k]);
            norm(&w)
        }
    };
    let spin = |s: &[f64; S]| {
        if N == 2 {
            -s[0]
        } else {
            s.iter().map(|x| x * x).sum::<f64>().sqrt()
        }
    };
    let (ut, ut_post) = (
        tangential(&pre.velocity, un),
        tangential(&post.velocity, un_post),
    );
    let angle = |ut: f64, un: f64, u: &[f64; N]| {
        if N == 2 {
            ut.atan2(un)
        } else {
            (un / norm(u)).clamp(-1.0, 1.0).acos()
        }
    };
    let (c, c_post) = (spin(&pre.spin), spin(&post.spin));
    let scale = (2.0 * ball.lambda()).sqrt();
    Some(Row {
        event: index,
        time: e.time,
        ball: i,
        body,
        point: q.to_vec(),
        coordinate: coordinate(sim.table(), sim.obstacles(), body, &q, nu),
        incidence: angle(ut, -un, &pre.velocity),
        reflection: angle(ut_post, un_post, &post.velocity),
        normal_velocity: un,
        tangential: [ut, ut_post],
        spin: [c, c_post],
        scaled_spin: [scale * c, scale * c_post],
    })
}

/// The most points kept per body for the phase portraits (the CSV has every row).
pub const PORTRAIT_POINTS: usize = 200_000;

/// Writes the CSV as the run goes, and keeps each body's points (up to [`PORTRAIT_POINTS`])
/// for its phase portraits: `(coordinate, reflection)` and `(tangential_post,
/// scaled_spin_post)`, the outgoing state. (A Parquet boundary map is written beside one
/// whose CSV goes to `io::sink()`: the `noslip-columnar` crate.)
pub struct BoundaryMap<W: Write> {
    out: W,
    /// Per body, the points of both portraits (the first [`PORTRAIT_POINTS`]).
    pub points: std::collections::BTreeMap<Body, Vec<[f64; 4]>>,
    /// Per body, its contacts (all of them, drawn or not).
    pub counts: std::collections::BTreeMap<Body, u64>,
}

impl<W: Write> BoundaryMap<W> {
    /// Start the CSV (its header) for dimension `n`.
    pub fn new(mut out: W, n: usize) -> io::Result<Self> {
        writeln!(out, "{}", header(n))?;
        Ok(BoundaryMap {
            out,
            points: Default::default(),
            counts: Default::default(),
        })
    }

    /// Write `row` and keep its portrait points.
    pub fn push(&mut self, row: &Row) -> io::Result<()> {
        writeln!(self.out, "{}", line(row))?;
        *self.counts.entry(row.body).or_default() += 1;
        let points = self.points.entry(row.body).or_default();
        if points.len() < PORTRAIT_POINTS {
            points.push([
                row.coordinate,
                row.reflection,
                row.tangential[1],
                row.scaled_spin[1],
            ]);
        }
        Ok(())
    }

    /// Each body's portraits so far, its axes as `table` has it.
    pub fn portraits<const N: usize>(&self, table: &Table<N>) -> Vec<Portrait> {
        self.points
            .iter()
            .map(|(&body, points)| Portrait {
                body,
                axes: Axes::of(table, body),
                count: self.counts.get(&body).copied().unwrap_or(0),
                points: points.clone(),
            })
            .collect()
    }

    /// The writer, flushed.
    pub fn finish(mut self) -> io::Result<W> {
        self.out.flush()?;
        Ok(self.out)
    }
}

/// The portraits of every body of a run of `setup` (generic kernels) for `events` contacts
/// (fewer if the run ends): what `noslip simulate --boundary-map` draws, without the CSV. The
/// docs' pictures come from here (`examples/table_portraits.rs`).
pub fn portraits<const N: usize, const S: usize>(
    setup: crate::Setup<N, S>,
    events: u64,
) -> io::Result<Vec<Portrait>>
where
    collision_core::Generated: collision_core::Kernel<f64, N, S>,
{
    let species = setup.species.clone();
    let kernels = crate::GenericKernels {
        species: species.clone(),
    };
    let mut sim = Simulation::new(setup, kernels).map_err(io::Error::other)?;
    let mut map = BoundaryMap::new(io::sink(), N)?;
    let limits = crate::run::Limits {
        events: Some(events),
        time: None,
        samples: 1,
        traced: 0,
        contact_points: 0,
    };
    crate::run::run_observed(
        &mut sim,
        &species,
        &limits,
        None,
        &mut |_| {},
        &mut |index, e, sim| match row(index, e, sim, &species) {
            Some(r) => map.push(&r),
            None => Ok(()),
        },
    )?;
    Ok(map.portraits(sim.table()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::{Boundary, ContactKind, Shape};
    use crate::{GenericKernels, Setup, Step};
    use collision_core::{Ball, BodyState};

    const DISK: Ball<f64> = Ball {
        inv_mass: 1.0,
        radius: 0.25,
        gamma2: 0.5,
    };

    /// The rows of the first `k` contacts of one disk (spin `c`) in a table of `boundaries`.
    fn rows(boundaries: Vec<Boundary<2>>, a: [f64; 2], u: [f64; 2], c: f64, k: usize) -> Vec<Row> {
        let setup = Setup {
            size: [4.0, 4.0],
            periodic: [false; 2],
            species: vec![DISK],
            obstacles: vec![],
            bodies: vec![crate::Body {
                species: 0,
                position: a,
                state: BodyState {
                    spin: [-c],
                    velocity: u,
                },
            }],
            orientation: false,
            table: Table {
                boxed: false,
                boundaries,
                ..Table::boxed()
            },
        };
        let species = vec![DISK];
        let mut sim = Simulation::new(
            setup,
            GenericKernels {
                species: species.clone(),
            },
        )
        .unwrap();
        (1..=k as u64)
            .map(|index| match sim.step(f64::INFINITY) {
                Step::Contact(e) => row(index, &e, &sim, &species).unwrap(),
                other => panic!("{other:?}"),
            })
            .collect()
    }

    fn floor(contact: ContactKind) -> Boundary<2> {
        Boundary {
            shape: Shape::Wall {
                point: [1.0, 0.0],
                normal: [0.0, 1.0],
            },
            contact,
            arc: 0.0,
        }
    }

    #[test]
    fn a_floor_contact_in_the_map_coordinates() {
        // From (0, 1) with u = (1, -3): the centre reaches y = R at t = 0.25, x = 0.25, the
        // contact point (0.25, 0); coordinate (Q - p) . t = 0.25 - 1 along t = (1, 0).
        for contact in [ContactKind::Smooth, ContactKind::NoSlip] {
            let r = &rows(vec![floor(contact)], [0.0, 1.0], [1.0, -3.0], 2.0, 1)[0];
            assert_eq!((r.event, r.time, r.body), (1, 0.25, Body::Boundary(0)));
            assert_eq!(r.point, [0.25, 0.0]);
            assert_eq!(r.coordinate, -0.75);
            assert_eq!(r.normal_velocity, -3.0);
            assert_eq!(r.incidence, 1f64.atan2(3.0));
            assert_eq!((r.tangential[0], r.spin[0]), (1.0, 2.0));
            // gamma R = sqrt(2 lambda) = sqrt(1/2) / 4.
            let scale = (2.0 * DISK.lambda()).sqrt();
            assert_eq!(r.scaled_spin[0], scale * 2.0);
            // The invariant circle: u_t^2 + (gamma R c)^2 is kept by both maps (energy, with
            // u_n only reversed), up to rounding.
            let circle = |k: usize| r.tangential[k].powi(2) + r.scaled_spin[k].powi(2);
            assert!((circle(1) - circle(0)).abs() <= 4.0 * f64::EPSILON * circle(0));
            match contact {
                // Specular: the angle of reflection is the angle of incidence, spin kept.
                ContactKind::Smooth => {
                    assert_eq!(r.reflection, r.incidence);
                    assert_eq!(r.spin[1], r.spin[0]);
                }
                // No-slip: the contact point's tangential velocity reverses (the mean state
                // rolls). It is u_t + R c: U (Q - a) = c J (-R nu) = R c t.
                ContactKind::NoSlip => {
                    let slip = |k: usize| r.tangential[k] + DISK.radius * r.spin[k];
                    assert!((slip(1) + slip(0)).abs() <= 8.0 * f64::EPSILON);
                    assert_ne!(r.reflection, r.incidence);
                }
                ContactKind::Rough { .. } | ContactKind::Walton { .. } => {
                    unreachable!("only the two kinds above are run")
                }
            }
        }
    }

    #[test]
    fn polygon_and_circle_coordinates() {
        // A unit square table as four walls with their polygon arcs: a disk sent to the
        // right wall (arc 1) meets it at height 0.5: coordinate 1.5.
        let wall = |point: [f64; 2], normal: [f64; 2], arc: f64| Boundary {
            shape: Shape::Wall { point, normal },
            contact: ContactKind::Smooth,
            arc,
        };
        let square = vec![
            wall([0.0, 0.0], [0.0, 1.0], 0.0),
            wall([1.0, 0.0], [-1.0, 0.0], 1.0),
            wall([1.0, 1.0], [0.0, -1.0], 2.0),
            wall([0.0, 1.0], [1.0, 0.0], 3.0),
        ];
        let r = rows(square, [0.5, 0.5], [1.0, 0.0], 0.0, 2);
        assert_eq!((r[0].body, r[0].coordinate), (Body::Boundary(1), 1.5));
        // Back to the left wall, at height 0.5 going down from (0, 1): 3 + 0.5.
        assert_eq!((r[1].body, r[1].coordinate), (Body::Boundary(3), 3.5));
        // A container of radius 1 about (0, 0): sent up the y axis, the contact point is at
        // angle pi/2.
        let circle = vec![Boundary {
            shape: Shape::Container {
                centre: [0.0, 0.0],
                radius: 1.0,
            },
            contact: ContactKind::NoSlip,
            arc: 0.0,
        }];
        let r = &rows(circle, [0.0, 0.0], [0.0, 1.0], 0.0, 1)[0];
        assert_eq!(r.coordinate, std::f64::consts::FRAC_PI_2);
        assert_eq!((r.normal_velocity, r.incidence), (-1.0, 0.0));
    }

    #[test]
    fn the_csv_has_one_field_per_header_column() {
        let r = &rows(
            vec![floor(ContactKind::NoSlip)],
            [0.0, 1.0],
            [1.0, -3.0],
            2.0,
            1,
        )[0];
        assert_eq!(line(r).split(',').count(), header(2).split(',').count());
        assert!(line(r).starts_with("1,2.5e-1,0,boundary,0,2.5e-1,0e0,-7.5e-1,"));
    }
}
