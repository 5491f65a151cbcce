//! Periodic orbits of the boundary map of a one-ball table.
//!
//! **Newton's method** on `F(z) = P^K(z) - z` (positions compared by the minimum image on
//! periodic axes) with the exact derivative `DP^K - I` ([`section`]). `DP^K - I` is singular
//! in the neutral directions: the velocity scaling `(0, u, U)` (the map is homogeneous of
//! degree 1 in the velocities: `DP^K` has the eigenvalue 1 there), and, in tables with a
//! translation symmetry (a periodic axis parallel to the walls), translations. The step is
//! the least-squares one of least norm (SVD pseudo-inverse, singular values below
//! `1e-9 sigma_max` dropped), which moves nothing along the neutral directions; then the
//! start is put back on its boundary's contact surface and its energy is reset to the
//! start's (the velocity and spin scaled together): the energy is fixed.
//!
//! **Verdict** from the eigenvalues of the section map (the `2n + S - 1` eigenvalues of
//! `DP^K` other than the flow direction's 0): *hyperbolic* if one is off the unit circle by
//! more than [`STABILITY_TOL`]; else *elliptic* if one is non-real by more than it, else
//! *parabolic* (all at `+-1`); *undetermined* if the eigenvalue iteration did not converge
//! within its bound ([`poly::eigenvalues`]).
//!
//! **Exact**: for a rational table and a rational start on a flat wall, [`exact`] runs the
//! return map and its derivative in rationals and gives the characteristic polynomial of the
//! section map exactly.
//!
//! **A search** ([`search`]): the starts (given, a 2D grid, or the scene's ball), Newton
//! from each, the orbits merged, as `noslip orbits` and the Python package run it.

mod newton;
pub mod poly;
pub mod scene;
pub mod search;
pub mod section;

pub use newton::{newton, newton_within, section_eigenvalues, verdict, Budget};
pub use newton::{MAX_HALVINGS, SVD_SWEEPS};

use crate::dual::Dual;
use crate::geometry::dot;
use crate::table::{Boundary, NoHit, Table};
use collision_core::{Exact, Generated, Kernel, RefArith, Scalar};
use section::{return_map, Section};
use serde::Serialize;

/// The tolerance of the verdict: distance of an eigenvalue from the unit circle, or its
/// imaginary part.
pub const STABILITY_TOL: f64 = 1e-6;

/// Relative residual `|F| / (1 + |z|)` at which Newton stops.
pub const CONVERGED: f64 = 1e-12;

/// Newton iterations before a start is given up.
pub const MAX_ITERATIONS: usize = 40;

/// Linear stability of a periodic orbit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Verdict {
    /// All eigenvalues on the unit circle, some non-real.
    Elliptic,
    /// All eigenvalues at `+-1`.
    Parabolic,
    /// Some eigenvalue off the unit circle.
    Hyperbolic,
    /// The eigenvalues could not be computed: their iteration did not converge within its
    /// bound ([`poly::eigenvalues`]); the orbit itself converged.
    Undetermined,
}

/// A periodic orbit found by Newton's method.
#[derive(Clone, Debug, Serialize)]
pub struct Orbit {
    /// The boundaries touched, in order; the start is on the last.
    pub boundaries: Vec<usize>,
    /// The start `[x, u, U]` (a section state).
    pub start: Vec<f64>,
    /// The section states after each contact (the last is the start again).
    pub states: Vec<Vec<f64>>,
    /// `|P^K(z) - z| / (1 + |z|)` at the start.
    pub residual: f64,
    /// The residual before each Newton step, and at the end.
    pub residuals: Vec<f64>,
    /// Eigenvalues `(re, im)` of the section map (the flow direction's 0 removed); empty if
    /// they could not be computed ([`Verdict::Undetermined`]).
    pub eigenvalues: Vec<(f64, f64)>,
    /// The verdict.
    pub verdict: Verdict,
    /// How many starts converged to it.
    pub found_from: usize,
}

/// Why a start gave no orbit.
#[derive(Clone, Debug, PartialEq)]
pub enum Miss {
    /// A flight never met the table.
    NoHit(NoHit),
    /// Newton did not converge.
    NoConvergence {
        /// The last residual.
        residual: f64,
    },
    /// A step left the section (the velocity no longer points into the table).
    LeftSection,
    /// The search's budget of contacts ([`Budget`]) was spent before this start was done.
    Budget,
    /// Newton converged to a ball at rest (`|u|^2 <= RESTING E`, the energy all in the spin):
    /// a fixed point of the map in the limit of a vanishing flight, not an orbit.
    Resting,
}

/// The share of the energy (`|u|^2` against `|u|^2 + gamma^2 R^2 |U|^2`) at or below which
/// a converged state is a ball at rest ([`Miss::Resting`]): far below any orbit's, far above
/// rounding of a zero velocity.
pub const RESTING: f64 = 1e-12;

/// The gap of a centre at `x` from boundary `b`'s contact surface: `>= 0` in the table, 0 on
/// the surface. A wall: `(x - p) . n - r`; a sphere: `|x - c| - R - r`; a container:
/// `R - r - |x - c|` (minimum images on periodic axes); an edge: the distance from `x` to the
/// segment minus `r`.
pub fn gap<const N: usize>(table: &Table<f64, N>, b: usize, x: &[f64; N]) -> f64 {
    let r = table.ball.radius;
    match &table.boundaries[b] {
        Boundary::Wall { point, normal } => {
            let d: [f64; N] = std::array::from_fn(|k| x[k] - point[k]);
            dot(&d, normal) - r
        }
        Boundary::Sphere { centre, radius } => norm(&image(table, x, centre)) - radius - r,
        Boundary::Container { centre, radius } => radius - r - norm(&image(table, x, centre)),
        Boundary::Edge { from, to, .. } => {
            let e: [f64; N] = std::array::from_fn(|k| to[k] - from[k]);
            let d: [f64; N] = std::array::from_fn(|k| x[k] - from[k]);
            let s = (dot(&d, &e) / dot(&e, &e)).clamp(0.0, 1.0);
            let off: [f64; N] = std::array::from_fn(|k| d[k] - s * e[k]);
            norm(&off) - r
        }
    }
}

/// The boundary nearest to `x` (by `|g|`, the [`gap`] of the centre from its contact
/// surface), with `g`.
pub fn nearest<const N: usize>(table: &Table<f64, N>, x: &[f64; N]) -> (usize, f64) {
    (0..table.boundaries.len())
        .map(|b| (b, gap(table, b, x)))
        .min_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
        .expect("a table has a boundary")
}

fn norm(d: &[f64]) -> f64 {
    d.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// `x - c` by the minimum image on periodic axes.
fn image<const N: usize>(table: &Table<f64, N>, x: &[f64; N], c: &[f64; N]) -> [f64; N] {
    std::array::from_fn(|k| {
        let d = x[k] - c[k];
        table.period[k].map_or(d, |l| d - l * (d / l).round())
    })
}

/// `x` moved onto boundary `b`'s contact surface (along its normal), and the normal there.
pub fn project<const N: usize>(
    table: &Table<f64, N>,
    b: usize,
    x: &[f64; N],
) -> ([f64; N], [f64; N]) {
    let r = table.ball.radius;
    let (y, nu): ([f64; N], [f64; N]) = match &table.boundaries[b] {
        Boundary::Wall { point, normal }
        | Boundary::Edge {
            from: point,
            normal,
            ..
        } => {
            let d: [f64; N] = std::array::from_fn(|k| x[k] - point[k]);
            let g = dot(&d, normal) - r;
            (std::array::from_fn(|k| x[k] - g * normal[k]), *normal)
        }
        Boundary::Sphere { centre, radius } | Boundary::Container { centre, radius } => {
            let inside = matches!(table.boundaries[b], Boundary::Container { .. });
            let d = image(table, x, centre);
            let l = norm(&d);
            let r_eff = if inside { radius - r } else { radius + r };
            let dir: [f64; N] = std::array::from_fn(|k| d[k] / l);
            let y: [f64; N] = std::array::from_fn(|k| x[k] - d[k] + r_eff * dir[k]);
            (y, if inside { dir.map(|v| -v) } else { dir })
        }
    };
    let wrapped = std::array::from_fn(|k| table.period[k].map_or(y[k], |l| y[k].rem_euclid(l)));
    (wrapped, nu)
}

/// The energy up to the factor `m/2`: `|u|^2 + gamma^2 R^2 sum_{i<j} U_ij^2`.
fn energy<const N: usize>(table: &Table<f64, N>, z: &[f64]) -> f64 {
    let g = table.ball.gamma2 * table.ball.radius * table.ball.radius;
    z[N..2 * N].iter().map(|x| x * x).sum::<f64>()
        + g * z[2 * N..].iter().map(|x| x * x).sum::<f64>()
}

/// `P^K(z) - z`, positions by the minimum image.
fn residual_vector<const N: usize>(table: &Table<f64, N>, end: &[f64], z: &[f64]) -> Vec<f64> {
    end.iter()
        .zip(z)
        .enumerate()
        .map(|(i, (a, b))| {
            let d = a - b;
            match table.period.get(i).copied().flatten() {
                Some(l) if i < N => d - l * (d / l).round(),
                _ => d,
            }
        })
        .collect()
}

/// Whether `z` is one of `orbit`'s section states (within `1e-7 (1 + |z|)`, positions by the
/// minimum image).
pub fn same_orbit<const N: usize>(table: &Table<f64, N>, orbit: &Orbit, z: &[f64]) -> bool {
    !orbit.boundaries.is_empty()
        && orbit
            .states
            .iter()
            .any(|s| norm(&residual_vector(table, s, z)) < 1e-7 * (1.0 + norm(z)))
}

/// Adds `orbit` to `found` unless it is already there (then counts the start).
pub fn merge<const N: usize>(table: &Table<f64, N>, found: &mut Vec<Orbit>, orbit: Orbit) {
    if let Some(o) = found.iter_mut().find(|o| {
        o.boundaries.len() == orbit.boundaries.len() && same_orbit(table, o, &orbit.start)
    }) {
        o.found_from += 1;
    } else {
        found.push(orbit);
    }
}

/// The exact return map of a rational start on a rational table.
#[derive(Clone, Debug, Serialize)]
pub struct ExactReturn {
    /// The boundaries touched.
    pub boundaries: Vec<usize>,
    /// Whether `P^K(z) = z` exactly.
    pub periodic: bool,
    /// `P^K(z)` as rationals.
    pub end: Vec<String>,
    /// The characteristic polynomial of the section map, `det(l I - DP^K) / l`, highest
    /// power first.
    pub charpoly: String,
    /// Its coefficients from the constant term up.
    pub coefficients: Vec<String>,
}

/// The return map of `z` and the characteristic polynomial of its linearisation, in exact
/// rationals; `None` where a contact time is irrational.
pub fn exact<const N: usize, const S: usize>(
    table: &Table<Exact, N>,
    z: &Section<Exact, N, S>,
    k: usize,
) -> Result<ExactReturn, NoHit>
where
    for<'a> &'a Exact: RefArith<Exact>,
    Generated: Kernel<Exact, N, S> + Kernel<Dual<Exact>, N, S>,
{
    let r = return_map(table, z, k)?;
    let end = r.states[k - 1].to_vec();
    let p = poly::charpoly(&r.columns);
    debug_assert!(
        num_traits::Zero::is_zero(&p[0]),
        "the flow direction's eigenvalue 0"
    );
    let section = poly::deflate_zero(&p);
    Ok(ExactReturn {
        boundaries: r.boundaries,
        periodic: end == z.to_vec(),
        end: end.iter().map(Scalar::show).collect(),
        charpoly: poly::show(&section),
        coefficients: section.iter().map(Scalar::show).collect(),
    })
}

/// Starts on a grid for a 2D table (`None` in other dimensions): on each boundary, `m`
/// points (along a wall within the `bounds` of the centre, or around a sphere), `m` outgoing
/// directions (angles to the normal in `(-pi/2, pi/2)`) and `m` spins (`gamma R c / |u|` in
/// `(-1, 1)`, `U = c J`), at unit speed.
pub fn grid<const N: usize>(
    table: &Table<f64, N>,
    bounds: &[(f64, f64); N],
    m: usize,
) -> Option<Vec<Vec<f64>>> {
    if N != 2 {
        return None;
    }
    let mid = |i: usize| (i as f64 + 0.5) / m as f64;
    let r = table.ball.radius;
    let gr = table.ball.gamma2.sqrt() * r;
    let mut out = Vec::new();
    for b in 0..table.boundaries.len() {
        let mut points: Vec<([f64; N], [f64; N])> = Vec::new();
        match &table.boundaries[b] {
            Boundary::Wall { point, normal } => {
                let tau = [-normal[1], normal[0]];
                let base = [point[0] + r * normal[0], point[1] + r * normal[1]];
                let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
                for k in 0..2 {
                    if tau[k].abs() > 1e-12 {
                        let a = (bounds[k].0 - base[k]) / tau[k];
                        let c = (bounds[k].1 - base[k]) / tau[k];
                        lo = lo.max(a.min(c));
                        hi = hi.min(a.max(c));
                    }
                }
                if lo.is_finite() && hi.is_finite() && lo < hi {
                    for i in 0..m {
                        let s = lo + (hi - lo) * mid(i);
                        let x = std::array::from_fn(|k| base[k] + s * tau[k]);
                        points.push((x, *normal));
                    }
                }
            }
            Boundary::Edge { from, to, normal } => {
                let base = [from[0] + r * normal[0], from[1] + r * normal[1]];
                for i in 0..m {
                    let s = mid(i);
                    let x = std::array::from_fn(|k| base[k] + s * (to[k] - from[k]));
                    points.push((x, *normal));
                }
            }
            Boundary::Sphere { centre, .. } | Boundary::Container { centre, .. } => {
                for i in 0..m {
                    let a = std::f64::consts::TAU * mid(i);
                    let dir = [a.cos(), a.sin()];
                    let guess = std::array::from_fn(|k| centre[k] + dir[k]);
                    points.push(project(table, b, &guess));
                }
            }
        }
        // Points of a wall's line outside the table (beyond a polygon's corner, outside a
        // container) are no starts.
        points.retain(|(x, _)| (0..table.boundaries.len()).all(|c| gap(table, c, x) >= -1e-9));
        for (x, nu) in points {
            let tau = [-nu[1], nu[0]];
            for j in 0..m {
                let phi = std::f64::consts::PI * (mid(j) - 0.5);
                let u = [
                    phi.cos() * nu[0] + phi.sin() * tau[0],
                    phi.cos() * nu[1] + phi.sin() * tau[1],
                ];
                for l in 0..m {
                    let c = (2.0 * mid(l) - 1.0) / gr;
                    out.push(vec![x[0], x[1], u[0], u[1], -c]);
                }
            }
        }
    }
    Some(out)
}

/// A rational start `[x, u, U]` put exactly on its nearest boundary (found in f64): along a
/// wall's rational normal, which is exact; on a sphere only if it lies on it already. `None`
/// if that is not possible in rationals, or the velocity does not point into the table.
#[allow(clippy::needless_range_loop)]
pub fn exact_start<const N: usize, const S: usize>(
    table: &Table<Exact, N>,
    z: &[Exact],
) -> Option<Section<Exact, N, S>> {
    let f = table.map(Scalar::to_f64);
    let xf: [f64; N] = std::array::from_fn(|k| z[k].to_f64());
    let (b, _) = nearest(&f, &xf);
    let mut s = Section::<Exact, N, S>::from_slice(z);
    let r = table.ball.radius.clone();
    let nu: [Exact; N] = match &table.boundaries[b] {
        Boundary::Wall { point, normal }
        | Boundary::Edge {
            from: point,
            normal,
            ..
        } => {
            let d: [Exact; N] = std::array::from_fn(|k| s.x[k].clone() - point[k].clone());
            let g = dot(&d, normal) - r;
            for k in 0..N {
                s.x[k] = s.x[k].clone() - g.clone() * normal[k].clone();
            }
            normal.clone()
        }
        Boundary::Sphere { centre, radius } | Boundary::Container { centre, radius } => {
            let inside = matches!(table.boundaries[b], Boundary::Container { .. });
            let shift: [Exact; N] = std::array::from_fn(|k| {
                let l = f.period[k].unwrap_or(0.0);
                let d = xf[k] - centre[k].to_f64();
                let n = if l > 0.0 { (d / l).round() as i64 } else { 0 };
                Exact::from_integer(n) * table.period[k].clone().unwrap_or_default()
            });
            let d: [Exact; N] =
                std::array::from_fn(|k| s.x[k].clone() - centre[k].clone() - shift[k].clone());
            let r_eff = if inside {
                radius.clone() - r
            } else {
                radius.clone() + r
            };
            if dot(&d, &d) != r_eff.clone() * r_eff.clone() {
                return None;
            }
            let sign = if inside {
                -Exact::from_integer(1)
            } else {
                Exact::from_integer(1)
            };
            std::array::from_fn(|k| sign.clone() * d[k].clone() / r_eff.clone())
        }
    };
    (dot(&s.state.velocity, &nu) > Exact::from_integer(0)).then_some(s)
}

/// The section state just after the first contact of a ball at `x` with `state` (the scene's
/// start as a start of the return map).
pub fn first_contact<const N: usize, const S: usize>(
    table: &Table<f64, N>,
    x: &[f64; N],
    state: &collision_core::BodyState<f64, N, S>,
) -> Result<Vec<f64>, NoHit>
where
    Generated: Kernel<f64, N, S>,
{
    let (hit, after) = table.step(x, state)?;
    Ok(Section {
        x: hit.position,
        state: after,
    }
    .to_vec())
}
