//! A one-ball table in any scalar type: its boundaries, the next contact from a state, and
//! the boundary (collision) map. Generic over [`Root`], so a table of flat walls with
//! rational normals runs in exact rationals (its contact times are rational), and any table
//! in `f64`.
//!
//! The ball's centre moves on the table shrunk by its radius `r`: a wall `(x - p) . nu >= 0`
//! is touched at `(x - p) . nu = r`, a sphere obstacle of radius `R` at `|x - c| = R + r`, a
//! spherical container at `|x - c| = R - r`. Periodic axes wrap the centre into `[0, L)`;
//! sphere obstacles are tried at their images one box side away on each periodic axis, which
//! covers every flight up to the next face crossing (the centre stays in the box meanwhile).
//! Ties (a corner: two boundaries touched at the same time) go to the first boundary listed.
//! A grazing flight, tangent to a sphere's contact surface, is not a contact (it has measure
//! zero, and the tangent map divides by `u . nu = 0` there).

use crate::geometry::{dot, Geometry};
use crate::law::Law;
use crate::root::Root;
use collision_core::{Ball, BodyState, Generated, Kernel, RefArith};

/// A boundary of a one-ball table; `nu` at a contact points from the boundary towards the
/// ball's centre (into the table). A new kind is one variant and one arm in each method.
#[derive(Clone, Debug, PartialEq)]
pub enum Boundary<T, const N: usize> {
    /// The half-space `(x - point) . normal >= 0`, `normal` a unit vector into the table.
    Wall {
        /// A point of the wall.
        point: [T; N],
        /// The unit normal into the table.
        normal: [T; N],
    },
    /// A fixed ball obstacle: the ball stays outside.
    Sphere {
        /// The centre `c`.
        centre: [T; N],
        /// The radius `R`.
        radius: T,
    },
    /// A spherical container: the ball stays inside.
    Container {
        /// The centre `c`.
        centre: [T; N],
        /// The radius `R`.
        radius: T,
    },
    /// The segment from `from` to `to` (a 2D polygon obstacle's edge), the table on the side
    /// of the unit `normal`: touched at `(x - from) . normal = r` with the centre's foot on
    /// the segment, `0 <= (x - from) . (to - from) <= |to - from|^2`, approached from in
    /// front of its line (beyond its ends the obstacle's vertices, spheres of radius 0, take
    /// over).
    Edge {
        /// The start vertex.
        from: [T; N],
        /// The end vertex.
        to: [T; N],
        /// The unit normal out of the obstacle.
        normal: [T; N],
    },
}

/// The first contact of a flight.
#[derive(Clone, Debug, PartialEq)]
pub struct Hit<T, const N: usize> {
    /// The flight time to it (face crossings included).
    pub time: T,
    /// The index of the boundary touched.
    pub boundary: usize,
    /// The centre at the contact (wrapped into the box).
    pub position: [T; N],
    /// The unit normal from the boundary towards the centre.
    pub nu: [T; N],
}

/// Why a flight has no next contact in the arithmetic at hand.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum NoHit {
    /// No boundary is ever touched (or not within the crossing budget).
    Escapes,
    /// A contact time needs a square root the scalar type does not have (an exact table with
    /// a sphere).
    Irrational,
}

impl std::fmt::Display for NoHit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            NoHit::Escapes => {
                "its flight meets no boundary (it flies on for ever, or across more periodic \
                 cells than the search follows)"
            }
            NoHit::Irrational => {
                "its next contact time needs a square root that exact arithmetic does not have"
            }
        })
    }
}

impl<T: Root, const N: usize> Boundary<T, N> {
    /// The contact surface's [`Geometry`] for a ball of radius `r`.
    pub fn geometry(&self, r: &T) -> Geometry<T> {
        match self {
            Boundary::Wall { .. } | Boundary::Edge { .. } => Geometry::Flat,
            Boundary::Sphere { radius, .. } => Geometry::Convex {
                r_eff: radius.clone() + r.clone(),
            },
            Boundary::Container { radius, .. } => Geometry::Concave {
                r_eff: radius.clone() - r.clone(),
            },
        }
    }

    /// The time `t > 0` (or `t >= 0` while approaching) at which a centre at `x` moving with
    /// `u` touches this boundary (the sphere's centre shifted by `shift`), and the normal there.
    fn contact(&self, x: &[T; N], u: &[T; N], r: &T, shift: &[T; N]) -> Result<Option<T>, NoHit> {
        match self {
            Boundary::Wall { point, normal } => {
                let un = dot(u, normal);
                if un >= T::zero() {
                    return Ok(None);
                }
                let d: [T; N] = std::array::from_fn(|k| x[k].clone() - point[k].clone());
                let t = (r.clone() - dot(&d, normal)) / un;
                Ok(Some(if t < T::zero() { T::zero() } else { t }))
            }
            Boundary::Edge { from, to, normal } => {
                let un = dot(u, normal);
                let d: [T; N] = std::array::from_fn(|k| x[k].clone() - from[k].clone());
                let depth = dot(&d, normal);
                if un >= T::zero() || depth < T::zero() {
                    return Ok(None);
                }
                let t = (r.clone() - depth) / un;
                let t = if t < T::zero() { T::zero() } else { t };
                let e: [T; N] = std::array::from_fn(|k| to[k].clone() - from[k].clone());
                let q: [T; N] = std::array::from_fn(|k| d[k].clone() + t.clone() * u[k].clone());
                let s = dot(&q, &e);
                Ok((s >= T::zero() && s <= dot(&e, &e)).then_some(t))
            }
            Boundary::Sphere { centre, radius } | Boundary::Container { centre, radius } => {
                let inside = matches!(self, Boundary::Container { .. });
                let r_eff = if inside {
                    radius.clone() - r.clone()
                } else {
                    radius.clone() + r.clone()
                };
                let d: [T; N] =
                    std::array::from_fn(|k| x[k].clone() - centre[k].clone() - shift[k].clone());
                let a = dot(u, u);
                let b = dot(&d, u);
                let c = dot(&d, &d) - r_eff.clone() * r_eff;
                if a.is_zero() {
                    return Ok(None);
                }
                let disc = b.clone() * b.clone() - a.clone() * c.clone();
                // A grazing flight (disc = 0: tangent to the contact surface, u . nu = 0 there)
                // is not a contact: it has measure zero, and the tangent map is singular at it.
                if disc <= T::zero() {
                    return Ok(None);
                }
                if inside {
                    // The later root of |d + t u| = R_eff, from inside (c <= 0).
                    let s = disc.root().ok_or(NoHit::Irrational)?;
                    let t = (s - b) / a;
                    Ok((t > T::zero()).then_some(t))
                } else {
                    if b >= T::zero() {
                        return Ok(None);
                    }
                    if c <= T::zero() {
                        return Ok(Some(T::zero()));
                    }
                    let s = disc.root().ok_or(NoHit::Irrational)?;
                    Ok(Some(c / (s - b)))
                }
            }
        }
    }

    /// The unit normal towards the centre `x` in contact (the sphere shifted by `shift`).
    fn normal(&self, x: &[T; N], r: &T, shift: &[T; N]) -> [T; N] {
        match self {
            Boundary::Wall { normal, .. } | Boundary::Edge { normal, .. } => normal.clone(),
            Boundary::Sphere { centre, radius } => {
                let r_eff = radius.clone() + r.clone();
                std::array::from_fn(|k| {
                    (x[k].clone() - centre[k].clone() - shift[k].clone()) / r_eff.clone()
                })
            }
            Boundary::Container { centre, radius } => {
                let r_eff = radius.clone() - r.clone();
                std::array::from_fn(|k| (centre[k].clone() - x[k].clone()) / r_eff.clone())
            }
        }
    }
}

/// A one-ball table.
#[derive(Clone, Debug, PartialEq)]
pub struct Table<T, const N: usize> {
    /// The boundaries, by index.
    pub boundaries: Vec<Boundary<T, N>>,
    /// Per axis: `Some(L)` for a periodic axis of side `L`.
    pub period: [Option<T>; N],
    /// The ball's parameters.
    pub ball: Ball<T>,
    /// The law of the contact with each boundary, by index (as long as
    /// [`Table::boundaries`]).
    pub laws: Vec<Law>,
}

/// Face crossings a flight may take before it is declared escaping.
pub const MAX_CROSSINGS: usize = 100_000;

impl<T: Clone, const N: usize> Table<T, N> {
    /// The same table with every number mapped by `f` (exact to `f64`, or to dual numbers).
    pub fn map<U>(&self, f: impl Fn(&T) -> U) -> Table<U, N> {
        let v = |a: &[T; N]| -> [U; N] { std::array::from_fn(|k| f(&a[k])) };
        Table {
            boundaries: self
                .boundaries
                .iter()
                .map(|b| match b {
                    Boundary::Wall { point, normal } => Boundary::Wall {
                        point: v(point),
                        normal: v(normal),
                    },
                    Boundary::Sphere { centre, radius } => Boundary::Sphere {
                        centre: v(centre),
                        radius: f(radius),
                    },
                    Boundary::Container { centre, radius } => Boundary::Container {
                        centre: v(centre),
                        radius: f(radius),
                    },
                    Boundary::Edge { from, to, normal } => Boundary::Edge {
                        from: v(from),
                        to: v(to),
                        normal: v(normal),
                    },
                })
                .collect(),
            period: std::array::from_fn(|k| self.period[k].as_ref().map(&f)),
            ball: Ball {
                inv_mass: f(&self.ball.inv_mass),
                radius: f(&self.ball.radius),
                gamma2: f(&self.ball.gamma2),
            },
            laws: self.laws.clone(),
        }
    }
}

impl<T: Root, const N: usize> Table<T, N> {
    /// The first contact of the centre at `x` (in the box) moving with `u`.
    pub fn next_hit(&self, x: &[T; N], u: &[T; N]) -> Result<Hit<T, N>, NoHit> {
        let shifts = self.shifts();
        let images: Vec<Vec<usize>> = self
            .boundaries
            .iter()
            .map(|boundary| match boundary {
                Boundary::Sphere { centre, radius } => (0..shifts.len())
                    .filter(|&s| self.may_meet_the_box(centre, radius, &shifts[s]))
                    .collect(),
                _ => vec![0],
            })
            .collect();
        self.next_hit_among(x, u, &shifts, &images)
    }

    /// [`Table::next_hit`] with boundary `b` met only at its images `shifts[s]`, `s` in
    /// `images[b]`: face after face, the earliest contact within the box, else the next
    /// periodic face (at most [`MAX_CROSSINGS`] of them).
    fn next_hit_among(
        &self,
        x: &[T; N],
        u: &[T; N],
        shifts: &[[T; N]],
        images: &[Vec<usize>],
    ) -> Result<Hit<T, N>, NoHit> {
        let r = &self.ball.radius;
        let mut x = x.clone();
        let mut elapsed = T::zero();
        for _ in 0..MAX_CROSSINGS {
            let mut best: Option<(T, usize, usize)> = None;
            for (b, boundary) in self.boundaries.iter().enumerate() {
                for &s in &images[b] {
                    if let Some(t) = boundary.contact(&x, u, r, &shifts[s])? {
                        if best.as_ref().is_none_or(|(bt, _, _)| t < *bt) {
                            best = Some((t, b, s));
                        }
                    }
                }
            }
            // The next periodic face.
            let mut face: Option<(T, usize)> = None;
            for (k, p) in self.period.iter().enumerate() {
                let Some(l) = p else { continue };
                let t = if u[k] > T::zero() {
                    (l.clone() - x[k].clone()) / u[k].clone()
                } else if u[k] < T::zero() {
                    -x[k].clone() / u[k].clone()
                } else {
                    continue;
                };
                if face.as_ref().is_none_or(|(ft, _)| t < *ft) {
                    face = Some((t, k));
                }
            }
            match (best, face) {
                (Some((t, b, s)), f) if f.as_ref().is_none_or(|(ft, _)| t <= *ft) => {
                    let position: [T; N] =
                        std::array::from_fn(|k| x[k].clone() + t.clone() * u[k].clone());
                    let nu = self.boundaries[b].normal(&position, r, &shifts[s]);
                    return Ok(Hit {
                        time: elapsed + t,
                        boundary: b,
                        position,
                        nu,
                    });
                }
                (_, Some((t, k))) => {
                    for a in 0..N {
                        x[a] = x[a].clone() + t.clone() * u[a].clone();
                    }
                    let l = self.period[k].clone().expect("periodic axis");
                    x[k] = if u[k] > T::zero() { T::zero() } else { l };
                    elapsed += t;
                }
                _ => return Err(NoHit::Escapes),
            }
        }
        Err(NoHit::Escapes)
    }

    /// Whether the image `centre + shift` of a sphere obstacle of radius `radius` can be met
    /// by a centre in the box: on every periodic axis `k`, the interval `c_k + s_k -+ (R + r)`
    /// reaches `[0, L_k]` widened by `L_k 2^-20` on each side (far beyond the rounding of
    /// a float table). An image that fails this on some axis is met, if at all, only outside
    /// the box, so after the flight's next face: it never beats the face, and leaving it out
    /// changes no hit (the test `a_flight_meets_the_same_images_as_among_all_of_them`). In a
    /// Sinai table whose obstacle stays clear of the box's faces, only the unshifted one is
    /// left, instead of `3^p` images for `p` periodic axes at every crossing.
    fn may_meet_the_box(&self, centre: &[T; N], radius: &T, shift: &[T; N]) -> bool {
        let reach = radius.clone() + self.ball.radius.clone();
        (0..N).all(|k| {
            let Some(l) = &self.period[k] else {
                return true;
            };
            let margin = l.clone() * T::from_ratio(1, 1 << 20);
            let c = centre[k].clone() + shift[k].clone();
            c.clone() + reach.clone() >= -margin.clone() && c - reach.clone() <= l.clone() + margin
        })
    }

    /// Shifts of sphere obstacles: zero first, then each combination of `-L, 0, L` on the
    /// periodic axes.
    fn shifts(&self) -> Vec<[T; N]> {
        let mut out = vec![std::array::from_fn(|_| T::zero())];
        for k in 0..N {
            let Some(l) = &self.period[k] else { continue };
            let mut more = Vec::new();
            for s in &out {
                for sign in [T::one(), -T::one()] {
                    let mut t: [T; N] = s.clone();
                    t[k] = sign * l.clone();
                    more.push(t);
                }
            }
            out.extend(more);
        }
        out
    }

    /// One step of the boundary map: from a centre `x` and state just after a contact (or
    /// anywhere in the table) to the next contact; returns the hit and the state after it.
    pub fn step<const S: usize>(
        &self,
        x: &[T; N],
        state: &BodyState<T, N, S>,
    ) -> Result<(Hit<T, N>, BodyState<T, N, S>), NoHit>
    where
        for<'a> &'a T: RefArith<T>,
        Generated: Kernel<T, N, S>,
    {
        let hit = self.next_hit(x, &state.velocity)?;
        let after = self.laws[hit.boundary].boundary(&hit.nu, &self.ball, state);
        Ok((hit, after))
    }
}

#[cfg(test)]
#[path = "table_tests.rs"]
mod tests;
