//! The table's boundaries besides the box: flat walls, spherical containers, 2D convex polygon
//! obstacles and the `[table]` conveniences (a convex polygon, a wedge) that expand to walls;
//! their exact validation, and whether a ball fits inside them.
//!
//! The boundaries are numbered in one list, [`crate::Scene::boundaries`], in this order:
//! `[[wall]]` in file order; the `[table]` walls (a polygon's edges from its first vertex, in
//! counterclockwise order; a wedge's two walls, first edge first); `[[container]]` in file
//! order; each `[[polygon]]` obstacle's edges then its vertices (counterclockwise from its
//! first vertex). That index is the boundary id of the simulator's events.

use crate::convex::{cross, strictly_convex, NotConvex};
use crate::ctx::Ctx;
use crate::number::show_q;
use crate::raw::{ContactKind, RawScene, RawWedge};
use crate::{Number, SceneError};
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive, Zero};

type Q = BigRational;

/// A point or vector, exact.
type Point = Vec<Q>;

/// A wall as `(point, normal, place)`.
type WallSpec = (Point, Point, String);

/// A polygon's vertices, counterclockwise.
type Polygon = Vec<Point>;

/// The geometry of one boundary, exact.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// The flat wall `(x - point) . normal = 0`; the table is where `(x - point) . normal >
    /// 0`. `normal` is nonzero, as given (not normalised).
    Wall {
        /// A point of the wall (a polygon table's wall: the start vertex of its edge).
        point: Vec<Q>,
        /// A nonzero normal into the table.
        normal: Vec<Q>,
    },
    /// The sphere `|x - centre| = radius`; the table is inside.
    Container {
        /// The centre.
        centre: Vec<Q>,
        /// The radius, `> 0`.
        radius: Q,
    },
    /// An edge of a 2D convex polygon obstacle, the segment from `from` to `to`; the table is
    /// on the side `normal` (outward from the obstacle, nonzero, not normalised) points to.
    Edge {
        /// The start vertex (counterclockwise).
        from: Vec<Q>,
        /// The end vertex.
        to: Vec<Q>,
        /// The outward normal `(to_1 - from_1, from_0 - to_0)`.
        normal: Vec<Q>,
    },
    /// A vertex of a 2D convex polygon obstacle: a point obstacle.
    Vertex {
        /// The vertex.
        point: Vec<Q>,
    },
}

/// One boundary of the table.
#[derive(Clone, Debug, PartialEq)]
pub struct TableBoundary {
    /// Its geometry.
    pub shape: Shape,
    /// No-slip or smooth.
    pub contact: ContactKind,
    /// Where the scene gives it (`wall[0]`, `table.polygon[2]`, `polygon[1].vertices[0]`),
    /// for messages.
    pub place: String,
    /// For a piece of a polygon: the polygon's index in [`crate::Scene::polygons`] and the
    /// index of the piece's (start) vertex there.
    pub polygon: Option<(usize, usize)>,
}

pub(crate) fn dot(a: &[Q], b: &[Q]) -> Q {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn sub(a: &[Q], b: &[Q]) -> Vec<Q> {
    a.iter().zip(b).map(|(x, y)| x - y).collect()
}

/// The vertices of a strictly convex polygon, counterclockwise: refused (naming `place`) with
/// fewer than 3 vertices, no area, a turn that is not strictly left (a repeated or collinear
/// vertex, a dent) or edges that turn more than once around (self-intersecting), in `O(m)`
/// ([`crate::convex`]).
fn convex(ctx: &Ctx, place: &str, raw: &[Vec<Number>]) -> Result<Vec<Vec<Q>>, SceneError> {
    if raw.len() < 3 {
        return Err(ctx.err(
            place,
            format!("a polygon needs at least 3 vertices, got {}", raw.len()),
        ));
    }
    let mut v = Vec::new();
    for (k, p) in raw.iter().enumerate() {
        v.push(ctx.vector(&format!("{place}[{k}]"), p, 2)?);
    }
    let m = v.len();
    let area2: Q = (0..m).map(|k| cross(&v[k], &v[(k + 1) % m])).sum();
    if area2.is_zero() {
        return Err(ctx.err(place, "the polygon has no area"));
    }
    if area2.is_negative() {
        // Counterclockwise from the same first vertex.
        v[1..].reverse();
    }
    match strictly_convex(&v) {
        Ok(()) => {}
        Err(NotConvex::Turn(k)) => {
            let (a, b, p) = (&v[k], &v[(k + 1) % m], &v[(k + 2) % m]);
            return Err(ctx.err(
                place,
                format!(
                    "not strictly convex: vertex ({}, {}) is not strictly inside the line of \
                     the edge from ({}, {}) to ({}, {}) (vertices must be the corners of a \
                     convex polygon, in order, none repeated or on a line with two others)",
                    p[0], p[1], a[0], a[1], b[0], b[1]
                ),
            ));
        }
        Err(NotConvex::Winds(w)) => {
            return Err(ctx.err(
                place,
                format!(
                    "not strictly convex: every turn goes the same way but the edges turn {w} \
                     times around (the polygon crosses itself, like a pentagram)"
                ),
            ));
        }
    }
    Ok(v)
}

fn nonzero(ctx: &Ctx, place: &str, v: &[Q]) -> Result<(), SceneError> {
    if v.iter().all(Zero::is_zero) {
        return Err(ctx.err(place, "must be a nonzero vector"));
    }
    Ok(())
}

/// The two walls of a wedge: `(point, normal, place)`.
fn wedge(ctx: &Ctx, w: &RawWedge) -> Result<Vec<WallSpec>, SceneError> {
    let corner = ctx.vector("table.wedge.corner", &w.corner, 2)?;
    let (d1, d2) = match (&w.directions, &w.angle_degrees) {
        (Some(d), None) => {
            if d.len() != 2 {
                return Err(ctx.err(
                    "table.wedge.directions",
                    format!("needs two directions, got {}", d.len()),
                ));
            }
            let d1 = ctx.vector("table.wedge.directions[0]", &d[0], 2)?;
            let d2 = ctx.vector("table.wedge.directions[1]", &d[1], 2)?;
            nonzero(ctx, "table.wedge.directions[0]", &d1)?;
            nonzero(ctx, "table.wedge.directions[1]", &d2)?;
            if !cross(&d1, &d2).is_positive() {
                return Err(ctx.err(
                    "table.wedge.directions",
                    "the second direction must be strictly counterclockwise from the first, \
                     by less than 180 degrees (the wedge must be convex)",
                ));
            }
            (d1, d2)
        }
        (None, Some(a)) => {
            let deg = a.0.to_f64().unwrap_or(f64::NAN);
            if !(a.0.is_positive() && deg < 180.0) {
                return Err(ctx.err(
                    "table.wedge.angle_degrees",
                    format!("must be in (0, 180), got {}", show_q(&a.0)),
                ));
            }
            let rad = deg.to_radians();
            let exact = |x: f64| Q::from_float(x).unwrap_or_else(Q::zero);
            let one = Q::from_integer(1.into());
            (
                vec![one, Q::zero()],
                vec![exact(rad.cos()), exact(rad.sin())],
            )
        }
        _ => {
            return Err(ctx.err(
                "table.wedge",
                "give exactly one of directions and angle_degrees",
            ))
        }
    };
    // Inward normals: left of d1 (counterclockwise from it), right of d2.
    let n1 = vec![-d1[1].clone(), d1[0].clone()];
    let n2 = vec![d2[1].clone(), -d2[0].clone()];
    Ok(vec![
        (corner.clone(), n1, "table.wedge.directions[0]".into()),
        (corner, n2, "table.wedge.directions[1]".into()),
    ])
}

/// The boundaries of `raw` besides the box, validated exactly, and the polygons (counter-
/// clockwise) their pieces refer to. `boxed_periodic`: the box has a periodic axis (the
/// boundaries are then refused: they would need their periodic images).
pub(crate) fn boundaries(
    raw: &RawScene,
    origin: &str,
    boxed_periodic: bool,
) -> Result<(Vec<TableBoundary>, Vec<Polygon>), SceneError> {
    let ctx = Ctx { origin };
    let n = raw.dim;
    let mut out = Vec::new();
    let mut polygons = Vec::new();
    let first = if !raw.wall.is_empty() {
        Some("wall[0]")
    } else if raw.table.is_some() {
        Some("table")
    } else if !raw.container.is_empty() {
        Some("container[0]")
    } else if !raw.polygon.is_empty() {
        Some("polygon[0]")
    } else {
        None
    };
    if let (Some(place), true) = (first, boxed_periodic) {
        return Err(ctx.err(
            place,
            "walls, containers, polygons and [table] need a box without periodic axes (or no \
             [box] at all): they have no periodic images",
        ));
    }
    for (i, w) in raw.wall.iter().enumerate() {
        let at = format!("wall[{i}]");
        let point = ctx.vector(&format!("{at}.point"), &w.point, n)?;
        let normal = ctx.vector(&format!("{at}.normal"), &w.normal, n)?;
        nonzero(&ctx, &format!("{at}.normal"), &normal)?;
        out.push(TableBoundary {
            shape: Shape::Wall { point, normal },
            contact: ctx.contact(&format!("{at}.contact"), &w.contact)?,
            place: at,
            polygon: None,
        });
    }
    if let Some(t) = &raw.table {
        if n != 2 {
            return Err(ctx.err(
                "table",
                format!("a polygon or wedge table is 2D; dim = {n}"),
            ));
        }
        let contact = ctx.contact("table.contact", &t.contact)?;
        match (&t.polygon, &t.wedge) {
            (Some(p), None) => {
                let v = convex(&ctx, "table.polygon", p)?;
                let g = polygons.len();
                for k in 0..v.len() {
                    let e = sub(&v[(k + 1) % v.len()], &v[k]);
                    out.push(TableBoundary {
                        shape: Shape::Wall {
                            point: v[k].clone(),
                            normal: vec![-e[1].clone(), e[0].clone()],
                        },
                        contact: contact.clone(),
                        place: format!("table.polygon[{k}]"),
                        polygon: Some((g, k)),
                    });
                }
                polygons.push(v);
            }
            (None, Some(w)) => {
                for (point, normal, place) in wedge(&ctx, w)? {
                    out.push(TableBoundary {
                        shape: Shape::Wall { point, normal },
                        contact: contact.clone(),
                        place,
                        polygon: None,
                    });
                }
            }
            _ => {
                return Err(ctx.err("table", "give exactly one of polygon and [table.wedge]"));
            }
        }
    }
    for (i, c) in raw.container.iter().enumerate() {
        let at = format!("container[{i}]");
        let centre = ctx.vector(&format!("{at}.centre"), &c.centre, n)?;
        if !c.radius.0.is_positive() {
            return Err(ctx.err(
                format!("{at}.radius"),
                format!("must be positive, got {}", show_q(&c.radius.0)),
            ));
        }
        let contact = ctx.contact(&format!("{at}.contact"), &c.contact)?;
        // e as the engine takes it: an `e` that rounds to 0 in f64 is 0 there.
        if contact.e().to_f64().is_none_or(|e| e == 0.0) {
            // noslip_sim::left_table: after a slanted contact at e = 0 the ball moves along
            // the wall's tangent, out of the container.
            return Err(ctx.err(
                format!("{at}.contact.e"),
                "must be > 0 on a container (and not round to 0 in f64): at e = 0 a ball \
                 leaves its first slanted contact along the wall's tangent, out of the \
                 container (the true motion slides along the concave wall, which an \
                 event-driven run cannot follow); use e > 0 with [contact] tc (the TC model)",
            ));
        }
        out.push(TableBoundary {
            shape: Shape::Container {
                centre,
                radius: c.radius.0.clone(),
            },
            contact,
            place: at,
            polygon: None,
        });
    }
    for (i, p) in raw.polygon.iter().enumerate() {
        let at = format!("polygon[{i}]");
        if n != 2 {
            return Err(ctx.err(at, format!("a polygon obstacle is 2D; dim = {n}")));
        }
        let v = convex(&ctx, &format!("{at}.vertices"), &p.vertices)?;
        let g = polygons.len();
        let m = v.len();
        let contact = ctx.contact(&format!("{at}.contact"), &p.contact)?;
        for k in 0..m {
            let (a, b) = (&v[k], &v[(k + 1) % m]);
            let e = sub(b, a);
            out.push(TableBoundary {
                shape: Shape::Edge {
                    from: a.clone(),
                    to: b.clone(),
                    normal: vec![e[1].clone(), -e[0].clone()],
                },
                contact: contact.clone(),
                place: format!("{at}.vertices[{k}]"),
                polygon: Some((g, k)),
            });
        }
        for (k, point) in v.iter().enumerate() {
            out.push(TableBoundary {
                shape: Shape::Vertex {
                    point: point.clone(),
                },
                contact: contact.clone(),
                place: format!("{at}.vertices[{k}]"),
                polygon: Some((g, k)),
            });
        }
        polygons.push(v);
    }
    Ok((out, polygons))
}

/// Why a ball of radius `r` at `a` does not fit inside boundary `b`, if it does not: it is
/// outside, cut (it overlaps the boundary), or the container is too small. Exact.
pub(crate) fn misfit(b: &TableBoundary, a: &[Q], r: &Q) -> Option<String> {
    match &b.shape {
        Shape::Wall { point, normal } => {
            let s = dot(&sub(a, point), normal);
            let n2 = dot(normal, normal);
            if s.is_negative() {
                Some(format!("outside the table: behind {}", b.place))
            } else if &s * &s < r * r * n2 {
                Some(format!(
                    "cut by {}: the centre is closer than R = {r} to the wall",
                    b.place
                ))
            } else {
                None
            }
        }
        Shape::Container { centre, radius } => {
            if radius <= r {
                return Some(format!(
                    "{} is too small: its radius {radius} is not larger than R = {r}",
                    b.place
                ));
            }
            let d = sub(a, centre);
            let room = radius - r;
            (dot(&d, &d) > &room * &room).then(|| {
                format!(
                    "outside the table or cut by {}: |x - centre| > {radius} - R",
                    b.place
                )
            })
        }
        Shape::Vertex { point } => {
            let d = sub(a, point);
            (dot(&d, &d) < r * r).then(|| format!("overlaps the vertex {}", b.place))
        }
        Shape::Edge { from, to, .. } => {
            let e = sub(to, from);
            let t = dot(&sub(a, from), &e) / dot(&e, &e);
            let t = t.max(Q::zero()).min(Q::from_integer(1.into()));
            let foot: Vec<Q> = from.iter().zip(&e).map(|(x, y)| x + &t * y).collect();
            let d = sub(a, &foot);
            (dot(&d, &d) < r * r).then(|| format!("overlaps the polygon edge {}", b.place))
        }
    }
}

/// Whether `a` is inside the convex polygon `v` (counterclockwise), closed.
pub(crate) fn inside_polygon(v: &[Vec<Q>], a: &[Q]) -> bool {
    let m = v.len();
    (0..m).all(|k| !cross(&sub(&v[(k + 1) % m], &v[k]), &sub(a, &v[k])).is_negative())
}

/// Whether a ball of radius `r` at `a` with velocity `u` touches container `b` from inside and
/// moves along it (`|a - c| = radius - r`, `(a - c) . u = 0`, `u != 0`): its straight flight
/// leaves the container at second order, a degenerate graze. Exact.
pub(crate) fn grazes_inside(b: &TableBoundary, a: &[Q], r: &Q, u: &[Q]) -> bool {
    match &b.shape {
        Shape::Container { centre, radius } => {
            let d = sub(a, centre);
            let room = radius - r;
            dot(&d, &d) == &room * &room && dot(&d, u).is_zero() && u.iter().any(|x| !x.is_zero())
        }
        _ => false,
    }
}
