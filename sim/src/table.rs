//! The table's boundaries besides the box: their geometry in f64, contact times, contact
//! normals, and the contact kinds.
//!
//! A table is the box of [`crate::Setup`] (axis-aligned; walled or periodic axes; or no box
//! at all, [`Table::boxed`] false) with fixed ball obstacles ([`crate::FixedBall`]), and
//! the boundaries of [`Table::boundaries`]: flat walls, spherical containers, spheres seen
//! from outside (a polygon obstacle's vertex is one of radius 0) and 2D polygon-obstacle edges.
//! Boundary `b` is index `b` of that list, the id of [`crate::Contact::Boundary`]; the scene's
//! order is given in `noslip_scene::table`.
//!
//! **The contact law.** Every boundary is immovable and at rest, so a no-slip contact is the
//! generated `fixed` map ([`crate::PairKernels::ball_obstacle`]) with the local unit normal
//! `nu` (from the boundary to the ball's centre) at the contact point, and a smooth one the
//! specular map ([`crate::smooth`]). The curvature of the boundary does not enter: the map
//! acts on velocities at one instant, and it depends on the geometry only through the
//! contact point `Q = a - R nu` (on the ball) and the normal there. The no-slip subspace is
//! `{u + U (Q - a) = 0}` at `Q`, the energy is that of the ball, and neither involves the
//! boundary's shape beyond `nu`: a wall, a container and an obstacle touching the ball at
//! the same point with the same normal give the same post-state (tested exactly in
//! `sim/src/table_tests.rs`). Curvature matters for the flight between contacts and for the
//! derivative of the return map, not for the jump.

pub use crate::law::ContactKind;
use crate::normal::unit;
use crate::predict::contact_time;

/// The geometry of one boundary, in f64. Normals are unit vectors.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape<const N: usize> {
    /// The flat wall `(x - point) . normal = 0`; the table is where `(x - point) . normal
    /// >= 0`. A ball of radius `R` touches it when `(a - point) . normal = R`.
    Wall {
        /// A point of the wall.
        point: [f64; N],
        /// The unit normal into the table.
        normal: [f64; N],
    },
    /// The sphere `|x - centre| = radius` with the table inside: a ball touches it when
    /// `|a - centre| = radius - R`.
    Container {
        /// The centre.
        centre: [f64; N],
        /// The radius.
        radius: f64,
    },
    /// A sphere seen from outside (radius 0: a point, a polygon obstacle's vertex): a ball
    /// touches it when `|a - centre| = radius + R`.
    Sphere {
        /// The centre.
        centre: [f64; N],
        /// The radius, `>= 0`.
        radius: f64,
    },
    /// The segment from `from` to `to` of a 2D polygon obstacle, the table on the side of
    /// `normal`: a ball touches it when `(a - from) . normal = R` with the foot of its centre
    /// on the segment (beyond its ends the vertices, [`Shape::Sphere`] of radius 0, take over).
    Edge {
        /// The start vertex.
        from: [f64; N],
        /// The end vertex.
        to: [f64; N],
        /// The unit normal out of the obstacle.
        normal: [f64; N],
    },
}

/// The local geometry of a contact, as the derivative of the dynamics needs it: the jump map
/// does not depend on it (module docs), the flight between contacts does.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Geometry {
    /// A flat wall (a box wall, a [`Shape::Wall`], a [`Shape::Edge`]).
    Flat,
    /// A sphere of `radius` (0: a point) touched from outside: [`Shape::Sphere`], a
    /// [`crate::FixedBall`] obstacle.
    Outside {
        /// The sphere's radius.
        radius: f64,
    },
    /// A sphere of `radius` touched from inside: [`Shape::Container`].
    Inside {
        /// The sphere's radius.
        radius: f64,
    },
    /// Two balls.
    Pair,
}

/// One boundary: its shape, its contact kind, and its 2D boundary coordinate's origin.
#[derive(Clone, Debug, PartialEq)]
pub struct Boundary<const N: usize> {
    /// The geometry.
    pub shape: Shape<N>,
    /// No-slip (the `fixed` kernel) or smooth (specular).
    pub contact: ContactKind,
    /// The boundary coordinate (arc length) of the piece's start when it is a piece of a
    /// polygon (the polygon's arc length from its first vertex to the start of this edge, or
    /// to this vertex); 0 otherwise.
    pub arc: f64,
}

/// The boundaries besides the box, and the contact kinds of the rest.
#[derive(Clone, Debug, PartialEq)]
pub struct Table<const N: usize> {
    /// Whether the box of [`crate::Setup`] bounds the table. Without a box, its `size` is only
    /// the table's length scale (for the engine's clock and notices), no axis is walled or
    /// periodic, and the engine checks every pair of balls and every boundary at each
    /// prediction (one cell).
    pub boxed: bool,
    /// The boundaries, by id.
    pub boundaries: Vec<Boundary<N>>,
    /// The contact kind of each [`crate::Setup::obstacles`] entry (missing entries: no-slip).
    pub obstacle_contact: Vec<ContactKind>,
    /// The contact kind of every ball-ball pair of species not in [`Table::pair_contact`].
    pub ball_contact: ContactKind,
    /// The ball-ball laws per pair of species (a scene's `[[contact.pair]]`); empty: every
    /// pair has [`Table::ball_contact`]. [`Table::ball_law`] reads both.
    pub pair_contact: crate::species_laws::SpeciesLaws,
    /// The contact kind of the box walls.
    pub box_contact: ContactKind,
    /// The TC model's contact duration `t_c` ([`crate::law::tc_law`]); 0: none.
    pub tc: f64,
    /// The lower corner of the region the pictures show, `[origin, origin + size]` (`size`
    /// of [`crate::Setup`]): 0 with a box.
    pub origin: [f64; N],
    /// The white-noise thermostat's kicks ([`crate::thermostat`]), applied by the run loop
    /// ([`crate::run::run_observed`]); `None`: no forcing.
    pub thermostat: Option<crate::thermostat::Thermostat>,
}

impl<const N: usize> Table<N> {
    /// The box alone, every contact no-slip.
    pub fn boxed() -> Self {
        Table {
            boxed: true,
            boundaries: Vec::new(),
            obstacle_contact: Vec::new(),
            ball_contact: ContactKind::NoSlip,
            pair_contact: Default::default(),
            box_contact: ContactKind::NoSlip,
            tc: 0.0,
            origin: [0.0; N],
            thermostat: None,
        }
    }

    /// The contact kind of balls of species `a` and `b` (either order): the pair's in
    /// [`Table::pair_contact`], else [`Table::ball_contact`].
    #[inline]
    pub fn ball_law(&self, a: usize, b: usize) -> ContactKind {
        self.pair_contact.get(a, b).unwrap_or(self.ball_contact)
    }

    /// Obstacle `o`'s contact kind.
    pub fn obstacle(&self, o: usize) -> ContactKind {
        self.obstacle_contact.get(o).copied().unwrap_or_default()
    }
}

fn dot<const N: usize>(a: &[f64; N], b: &[f64; N]) -> f64 {
    (0..N).map(|k| a[k] * b[k]).sum()
}

fn sub<const N: usize>(a: &[f64; N], b: &[f64; N]) -> [f64; N] {
    std::array::from_fn(|k| a[k] - b[k])
}

impl<const N: usize> Shape<N> {
    /// The local geometry of a contact with this shape.
    pub fn geometry(&self) -> Geometry {
        match self {
            Shape::Wall { .. } | Shape::Edge { .. } => Geometry::Flat,
            Shape::Sphere { radius, .. } => Geometry::Outside { radius: *radius },
            Shape::Container { radius, .. } => Geometry::Inside { radius: *radius },
        }
    }

    /// Whether a ball that just touched this shape cannot touch it again before its velocity
    /// changes by another contact: the set of centres that touch it is convex seen from the
    /// ball (flat walls, spheres and edges from outside), so the distance to it along a
    /// straight flight is convex in time and, once growing, never shrinks again. Not so for a
    /// container (the next contact is the other end of the chord).
    pub fn convex_from_outside(&self) -> bool {
        !matches!(self, Shape::Container { .. })
    }

    /// The time `t >= 0` at which a ball of radius `r` at `a` moving with velocity `v` first
    /// touches this shape, or `None` if it never does. A ball that overlaps by rounding while
    /// moving in is touching now (`t = 0`).
    ///
    /// - wall / edge: `(a + t v - p) . n = r`: `t = s / (-v . n)`, `s = (a - p) . n - r`, for
    ///   `v . n < 0` (an edge: only from in front of its line, `(a - p) . n >= 0`, and if the
    ///   centre's foot at `t` is on the segment);
    /// - sphere from outside: [`contact_time`] with `sigma = r + radius`;
    /// - container: the later root of `|a + t v - c|^2 = (radius - r)^2`, `t = -c' / (b +
    ///   sqrt(b^2 - |v|^2 c'))` for `b = (a - c) . v > 0` and `(-b + sqrt(..)) / |v|^2`
    ///   otherwise (no cancellation), `c' = |a - c|^2 - (radius - r)^2`.
    pub fn contact_time(&self, a: &[f64; N], v: &[f64; N], r: f64) -> Option<f64> {
        match self {
            Shape::Wall { point, normal } => {
                let vn = dot(v, normal);
                (vn < 0.0).then(|| ((dot(&sub(a, point), normal) - r) / -vn).max(0.0))
            }
            Shape::Edge { from, to, normal } => {
                let vn = dot(v, normal);
                let depth = dot(&sub(a, from), normal);
                // Behind the edge's line the centre is in front of another edge of the convex
                // obstacle (or inside it), and cannot reach this edge's face.
                if vn >= 0.0 || depth < 0.0 {
                    return None;
                }
                let t = ((depth - r) / -vn).max(0.0);
                let e = sub(to, from);
                let q: [f64; N] = std::array::from_fn(|k| a[k] + t * v[k] - from[k]);
                let s = dot(&q, &e) / dot(&e, &e);
                (0.0..=1.0).contains(&s).then_some(t)
            }
            Shape::Sphere { centre, radius } => {
                let d = sub(centre, a);
                let dv = v.map(|x| -x);
                contact_time(&d, &dv, r + radius)
            }
            Shape::Container { centre, radius } => {
                let d = sub(a, centre);
                let vv = dot(v, v);
                if vv == 0.0 {
                    return None;
                }
                let b = dot(&d, v);
                let rho = radius - r;
                let c = dot(&d, &d) - rho * rho;
                if c >= 0.0 && b >= 0.0 {
                    return Some(0.0);
                }
                let disc = (b * b - vv * c).max(0.0);
                let t = if b > 0.0 {
                    -c / (b + disc.sqrt())
                } else {
                    (disc.sqrt() - b) / vv
                };
                Some(t.max(0.0))
            }
        }
    }

    /// The unit contact normal `nu` from this shape to the centre `a` of a ball touching it:
    /// a wall's or edge's normal, `(a - c) / |a - c|` for a sphere, `(c - a) / |c - a|` for a
    /// container.
    pub fn normal(&self, a: &[f64; N]) -> [f64; N] {
        match self {
            Shape::Wall { normal, .. } | Shape::Edge { normal, .. } => *normal,
            Shape::Sphere { centre, .. } => unit(sub(a, centre)),
            Shape::Container { centre, .. } => unit(sub(centre, a)),
        }
    }

    /// The gap between a ball of radius `r` at `a` and this shape: `>= 0` when the ball is in
    /// the table (0: touching), negative when it overlaps. Wall: `(a - p) . n - r`; container:
    /// `radius - r - |a - c|`; sphere: `|a - c| - radius - r`; edge: the distance from `a` to
    /// the segment minus `r` (a centre inside a polygon obstacle is the scene's to refuse).
    pub fn gap(&self, a: &[f64; N], r: f64) -> f64 {
        let norm = |x: &[f64; N]| dot(x, x).sqrt();
        match self {
            Shape::Wall { point, normal } => dot(&sub(a, point), normal) - r,
            Shape::Container { centre, radius } => radius - r - norm(&sub(a, centre)),
            Shape::Sphere { centre, radius } => norm(&sub(a, centre)) - radius - r,
            Shape::Edge { from, to, .. } => {
                let e = sub(to, from);
                // An edge shorter than f64 can square (its ends a few ulps apart) is its start.
                let ee = dot(&e, &e);
                let s = if ee > 0.0 {
                    (dot(&sub(a, from), &e) / ee).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let foot: [f64; N] = std::array::from_fn(|k| from[k] + s * e[k]);
                norm(&sub(a, &foot)) - r
            }
        }
    }
}
