//! From a validated scene (exact) to the engine's f64 setup: the range checks
//! ([`crate::range`]), species, obstacles, the explicit balls and the seeded random placement
//! ([`crate::place`]).

use crate::cover::Cover;
use crate::lattice::{self, Shuffle};
use crate::law::ContactKind;
use crate::normal::unit;
use crate::place::Cells;
use crate::range::{check_scene, check_start};
use crate::sequential::{Batch, Region};
use crate::table::{Boundary as TableBoundary, Shape, Table};
use crate::{Body, FixedBall, Setup};
use collision_core::rng::Rng;
use collision_core::{Ball, BodyState};
use noslip_scene::{Boundary, Placement, Scene};
use num_rational::BigRational;
use num_traits::Zero;

pub use crate::extent::{extent, extent_dyn};
pub use crate::nearest::f;

fn array<const M: usize>(v: &[BigRational]) -> [f64; M] {
    std::array::from_fn(|k| f(&v[k]))
}

/// A unit normal from the scene's nonzero `normal`: its components rounded once when it is
/// already a unit vector in exact rationals, else `n / |n|` in f64 (each component one
/// rounding of the quotient by the accurate norm) of `n` first scaled exactly by a power of
/// two, [`binary_scaled`], so that its largest component is in `[1/2, 2)`: a normal of any
/// magnitude the scene can write (`1e-300`, `1e200`: `|n|^2` would underflow to 0 or
/// overflow) gives the same unit vector, and a normal of moderate size the same bits as
/// without the scaling (scaling by `2^s` commutes with every rounding in the normal range).
fn unit_normal<const N: usize>(normal: &[BigRational]) -> [f64; N] {
    let n2: BigRational = normal.iter().map(|x| x * x).sum();
    if n2 == BigRational::from_integer(1.into()) {
        array(normal)
    } else {
        unit(array(&binary_scaled(normal)))
    }
}

/// `v 2^-E`, exactly, with `E` the largest `bits(p) - bits(q)` over `v`'s nonzero components
/// `p/q`, so that the largest `|v_k| 2^-E` is in `[1/2, 2)`; `v` itself if it is zero.
fn binary_scaled(v: &[BigRational]) -> Vec<BigRational> {
    let exponent = |x: &BigRational| x.numer().bits() as i64 - x.denom().bits() as i64;
    let Some(e) = v.iter().filter(|x| !x.is_zero()).map(exponent).max() else {
        return v.to_vec();
    };
    let shift = e.unsigned_abs() as usize;
    v.iter()
        .map(|x| {
            if e >= 0 {
                BigRational::new(x.numer().clone(), x.denom() << shift)
            } else {
                BigRational::new(x.numer() << shift, x.denom().clone())
            }
        })
        .collect()
}

fn length(a: &[BigRational], b: &[BigRational]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| f(&(x - y)).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// The table's boundaries in f64 (boundary ids as in the scene), the obstacles' contact kinds
/// and the box's presence.
pub fn table<const N: usize>(scene: &Scene) -> Table<N> {
    // Per polygon, the arc length up to each vertex: `arcs[g][k] = sum_{j < k} |v_{j+1} -
    // v_j|`, summed from the first vertex in order (linear in the vertices; the same sums
    // as one per piece).
    let arcs: Vec<Vec<f64>> = scene
        .polygons
        .iter()
        .map(|v| {
            // -0.0: the empty sum as f64's `Sum` gives it, which the boundary map has
            // printed for a polygon's first vertex.
            let mut arc = -0.0;
            let mut out = vec![arc];
            for j in 0..v.len() - 1 {
                arc += length(&v[j], &v[j + 1]);
                out.push(arc);
            }
            out
        })
        .collect();
    let boundaries = scene
        .boundaries
        .iter()
        .map(|b| {
            let shape = match &b.shape {
                noslip_scene::Shape::Wall { point, normal } => Shape::Wall {
                    point: array(point),
                    normal: unit_normal(normal),
                },
                noslip_scene::Shape::Container { centre, radius } => Shape::Container {
                    centre: array(centre),
                    radius: f(radius),
                },
                noslip_scene::Shape::Edge { from, to, normal } => Shape::Edge {
                    from: array(from),
                    to: array(to),
                    normal: unit_normal(normal),
                },
                noslip_scene::Shape::Vertex { point } => Shape::Sphere {
                    centre: array(point),
                    radius: 0.0,
                },
            };
            // The arc length of the polygon up to the piece's start vertex.
            let arc = b.polygon.map_or(0.0, |(g, k)| arcs[g][k]);
            TableBoundary {
                shape,
                contact: ContactKind::from(&b.contact),
                arc,
            }
        })
        .collect();
    Table {
        boxed: !scene.size.is_empty(),
        boundaries,
        obstacle_contact: scene
            .obstacles
            .iter()
            .map(|o| ContactKind::from(&o.contact))
            .collect(),
        ball_contact: ContactKind::from(&scene.ball_contact),
        // Only a scene that lists pairs gets the table (the rest look up nothing).
        pair_contact: if scene.pair_contacts.is_empty() {
            Default::default()
        } else {
            crate::species_laws::SpeciesLaws::new(scene.species.len(), |a, b| {
                ContactKind::from(scene.ball_law(a, b))
            })
        },
        box_contact: ContactKind::from(&scene.box_contact),
        tc: scene.tc.as_ref().map_or(0.0, f),
        origin: extent::<N>(scene).0,
        thermostat: scene
            .thermostat
            .as_ref()
            .map(|t| crate::thermostat::Thermostat {
                strength: f(&t.strength),
                interval: f(&t.interval),
                seed: t.seed,
            }),
    }
}

/// Whether `p` (its first two coordinates) is inside the counterclockwise convex polygon `v`.
fn inside_polygon<const N: usize>(v: &[[f64; 2]], p: &[f64; N]) -> bool {
    let m = v.len();
    (0..m).all(|k| {
        let (a, b) = (v[k], v[(k + 1) % m]);
        (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]) >= 0.0
    })
}

/// The kernels' `Ball` parameters of the scene's species, each constant mapped by `f`
/// (`f64` rounding for the simulator, `clone` for exact checks).
pub fn species_balls<T>(
    scene_species: &[noslip_scene::Species],
    f: impl Fn(&BigRational) -> T,
) -> Vec<Ball<T>> {
    scene_species
        .iter()
        .map(|s| Ball {
            inv_mass: f(&s.inv_mass),
            radius: f(&s.radius),
            gamma2: f(&s.gamma2),
        })
        .collect()
}

/// Attempts in a row for one randomly placed ball before the scene is declared too dense.
pub const ATTEMPTS: usize = 10_000;

/// Attempts per randomly placed ball on average (over all placed so far, plus [`ATTEMPTS`])
/// before the scene is declared too dense: near the jamming packing every ball takes longer,
/// and this bounds the whole placement to `O(N)` attempts.
pub const AVERAGE_ATTEMPTS: usize = 1_000;

/// The packing fraction at which random sequential placement of equal balls in R^n saturates,
/// about `(0.202 + 0.974 n) / 2^n` (the fit of Torquato, Uche and Stillinger, Phys. Rev. E 74,
/// 061308 (2006), for n = 2..6): 0.54, 0.39, 0.26, 0.16, 0.09. Placement slows down well
/// before it.
pub fn saturation(n: usize) -> f64 {
    (0.202048 + 0.973872 * n as f64) / (1u64 << n) as f64
}

/// `log` of the volume of the unit ball in R^n, `pi^(n/2) / Gamma(n/2 + 1)`.
pub(crate) fn log_unit_ball(n: usize) -> f64 {
    // Gamma(n/2 + 1) by its recurrence from Gamma(1) = 1 or Gamma(3/2) = sqrt(pi)/2.
    let pi = std::f64::consts::PI;
    let mut gamma = if n % 2 == 0 { 1.0 } else { pi.sqrt() / 2.0 };
    let mut x = if n % 2 == 0 { 1.0 } else { 1.5 };
    while x < n as f64 / 2.0 + 1.0 {
        gamma *= x;
        x += 1.0;
    }
    n as f64 / 2.0 * pi.ln() - gamma.ln()
}

/// The fraction of the box's volume that the scene's balls fill (computed in logarithms, so
/// it does not overflow).
pub fn volume_fraction(scene: &Scene) -> f64 {
    let n = scene.dim;
    let log_box: f64 = scene.size.iter().map(|l| f(l).ln()).sum();
    scene
        .balls_per_species()
        .iter()
        .zip(&scene.species)
        .filter(|(&count, _)| count > 0)
        .map(|(&count, s)| {
            ((count as f64).ln() + log_unit_ball(n) + n as f64 * f(&s.radius).ln() - log_box).exp()
        })
        .sum()
}

/// The engine's setup for `scene` (whose `dim` must be `N`), after the range checks of
/// [`crate::range`]. Random balls: positions uniform in the box (inside the walls), rejected
/// while they are not inside the table's other boundaries (a gap below 0, or a centre inside a
/// polygon obstacle; checked against every boundary)
/// or overlap a placed ball or an obstacle (found with a [`Cells`] grid, so each test
/// visits only the cells around the candidate, after the [`Cover`] of wholly excluded voxels
/// and with the draws made a batch ahead, [`crate::sequential`]: neither changes which
/// centre is kept), at most [`ATTEMPTS`] times in a row and
/// [`AVERAGE_ATTEMPTS`] per ball overall; balls that would fill more than the box are refused
/// before any attempt. With `random.placement = "lattice"` the centres are instead sites of
/// the widest [`crate::lattice`] with enough sites clear of the table's boundaries, the
/// obstacles and the explicit balls (for the largest radius), taken in a seeded random order
/// ([`lattice::Shuffle`]); a count the densest such lattice cannot hold is refused. Then
/// velocity components uniform in `[-speed, speed]`, skew entries of `U` uniform in `[-spin,
/// spin]` (or, with `random.velocities = "maxwellian"`, normal at `random.temperature` in
/// every degree of freedom, [`crate::maxwell`]); one ChaCha8 stream seeded with
/// `random.seed`, species in order. Errors are
/// `field: message`.
pub fn setup<const N: usize, const S: usize>(scene: &Scene) -> Result<Setup<N, S>, String> {
    assert_eq!(scene.dim, N, "scene dimension");
    let scales = check_scene(scene)?;
    let (_, size) = extent::<N>(scene);
    let periodic: [bool; N] =
        std::array::from_fn(|k| scene.boundary.get(k) == Some(&Boundary::Periodic));
    let table = table::<N>(scene);
    let species = species_balls(&scene.species, f);
    let obstacles: Vec<FixedBall<N>> = scene
        .obstacles
        .iter()
        .map(|o| FixedBall {
            position: array(&o.position),
            radius: f(&o.radius),
        })
        .collect();
    let mut bodies: Vec<Body<N, S>> = scene
        .balls
        .iter()
        .map(|b| Body {
            species: b.species,
            position: array(&b.position),
            state: BodyState {
                spin: array(&b.spin),
                velocity: array(&b.velocity),
            },
        })
        .collect();
    let fraction = volume_fraction(scene);
    // Without a box (no random balls then) there is no box volume to fill: the explicit balls
    // were checked exactly against the table and each other.
    if fraction > 1.0 && !scene.size.is_empty() {
        let k = (0..scene.species.len())
            .rev()
            .find(|&k| scene.species[k].count > 0)
            .unwrap_or(0);
        return Err(format!(
            "species[{k}].count: the balls would fill {fraction:.3} times the box's volume: \
             they cannot fit"
        ));
    }
    let per_species = scene.balls_per_species();
    let r_max = (0..species.len())
        .filter(|&k| per_species[k] > 0)
        .map(|k| species[k].radius)
        .fold(0.0, f64::max);
    // Room for every ball at once (at most `noslip_scene::MAX_BALLS`), not grown by copies.
    bodies.reserve_exact(scene.ball_count() - bodies.len());
    let mut balls = Cells::new(size, periodic, 2.0 * r_max, scene.ball_count());
    for b in &bodies {
        balls.insert(&b.position, species[b.species].radius);
    }
    let obstacle_max = obstacles.iter().map(|o| o.radius).fold(0.0, f64::max);
    let mut fixed = Cells::new(size, periodic, r_max + obstacle_max, obstacles.len());
    for o in &obstacles {
        fixed.insert(&o.position, o.radius);
    }
    // The voxels every random candidate of radius at least `r_min` in them would overlap.
    let random_count: usize = scene.species.iter().map(|s| s.count).sum();
    let r_min = (0..species.len())
        .filter(|&k| scene.species[k].count > 0)
        .map(|k| species[k].radius)
        .fold(f64::INFINITY, f64::min);
    let mut cover = match scene.random.placement {
        Placement::Random => Cover::new(size, periodic, 2.0 * r_min, random_count),
        Placement::Lattice => Cover::new(size, periodic, 0.0, 0),
    };
    for b in &bodies {
        cover.mark(&b.position, r_min + species[b.species].radius);
    }
    for o in &obstacles {
        cover.mark(&o.position, r_min + o.radius);
    }
    let mut unmarked: Option<([f64; N], f64)> = None;
    // The polygon obstacles (their edges' gaps say nothing of a centre deep inside).
    let mut polygons: Vec<Vec<[f64; 2]>> = Vec::new();
    let mut seen = Vec::new();
    for b in &scene.boundaries {
        if let (noslip_scene::Shape::Edge { .. }, Some((g, _))) = (&b.shape, b.polygon) {
            if !seen.contains(&g) {
                seen.push(g);
                polygons.push(
                    scene.polygons[g]
                        .iter()
                        .map(|v| [f(&v[0]), f(&v[1])])
                        .collect(),
                );
            }
        }
    }
    let mut rng = Rng::new(scene.random.seed);
    let (speed, spin) = (f(&scene.random.speed), f(&scene.random.spin));
    let temperature = scene.random.temperature.as_ref().map(f);
    // The tests of a centre `p` of radius `r`: inside the table's other boundaries, outside
    // the polygon obstacles, clear of the obstacles and (`clear_balls`) of the placed balls.
    let in_table = |p: &[f64; N], r: f64| {
        table.boundaries.iter().all(|b| b.shape.gap(p, r) >= 0.0)
            && !polygons.iter().any(|v| inside_polygon(v, p))
            && fixed.clear_of(p, r)
    };
    let last = (0..scene.species.len())
        .rev()
        .find(|&k| scene.species[k].count > 0)
        .unwrap_or(0);
    // The lattice start: the widest lattice with enough sites clear of everything placed,
    // its sites drawn in a seeded random order.
    let mut sites = match scene.random.placement {
        Placement::Lattice if random_count > 0 => {
            let usable = |p: &[f64; N]| in_table(p, r_max) && balls.clear_of(p, r_max);
            let all_usable = bodies.is_empty()
                && obstacles.is_empty()
                && table.boundaries.is_empty()
                && polygons.is_empty();
            let lattice = lattice::start(&size, &periodic, r_max, random_count, all_usable, usable)
                .map_err(|why| format!("species[{last}].count: {why}"))?;
            Some((lattice, Shuffle::new()))
        }
        _ => None,
    };
    let (mut attempts, mut placed_random) = (0usize, 0usize);
    // Draws made ahead for the next ball: as many as the last one took (a draw made ahead of
    // the kept one is wasted).
    let (mut ahead, mut batch) = (1, Batch::default());
    let too_full = |k: usize, placed: usize, why: String| {
        format!(
            "species[{k}].count: placed {placed} of {} balls, then {why}: the box is too full \
             for random placement (the balls would fill {fraction:.3} of it; random sequential \
             placement of equal balls saturates near {:.2} in {N}D; [random] placement = \
             \"lattice\" reaches denser packings)",
            scene.species[k].count,
            saturation(N)
        )
    };
    for (k, sp) in scene.species.iter().enumerate() {
        let r = species[k].radius;
        for placed in 0..sp.count {
            let position = if let Some((lattice, shuffle)) = &mut sites {
                // Every usable site is clear of the lattice's other sites by construction
                // (`crate::lattice`); the test is repeated with this ball's radius.
                let mut found = None;
                while let Some(g) = shuffle.draw(&mut rng, lattice.points()) {
                    let Some(index) = lattice.site(g) else {
                        continue;
                    };
                    let p = lattice.position(&index);
                    if in_table(&p, r_max) && balls.clear_of(&p, r_max) {
                        found = Some(p);
                        break;
                    }
                }
                found.ok_or_else(|| {
                    format!(
                        "species[{k}].count: placed {placed} of {} balls, then the lattice ran \
                         out of clear sites",
                        sp.count
                    )
                })?
            } else {
                if attempts > AVERAGE_ATTEMPTS * placed_random + ATTEMPTS {
                    let why = format!("{attempts} attempts (over {AVERAGE_ATTEMPTS} per ball)");
                    return Err(too_full(k, placed, why));
                }
                let region = Region {
                    size,
                    periodic,
                    cover: &cover,
                    balls: &balls,
                    inside: &in_table,
                };
                let (found, spent) = region.draw(&mut batch, &mut rng, r, ATTEMPTS, ahead);
                attempts += spent;
                ahead = spent;
                let Some(position) = found else {
                    let why = format!("{ATTEMPTS} random positions in a row overlapped");
                    return Err(too_full(k, placed, why));
                };
                position
            };
            placed_random += 1;
            let (velocity, spin) = match temperature {
                Some(t) => crate::maxwell::draw(&mut rng, &species[k], t),
                None => {
                    let mut uniform = |scale: f64| scale * rng.uniform(-1.0, 1.0);
                    let velocity = std::array::from_fn(|_| uniform(speed));
                    (velocity, std::array::from_fn(|_| uniform(spin)))
                }
            };
            balls.insert(&position, r);
            // The cover marks a ball once the next one is drawn: its words are fetched now,
            // and the draws meanwhile are tested in full where it would have covered them.
            if let Some((p, e)) = unmarked.replace((position, r_min + r)) {
                cover.mark(&p, e);
            }
            cover.prefetch_around(&position, r_min + r);
            bodies.push(Body {
                species: k,
                position,
                state: BodyState { spin, velocity },
            });
        }
    }
    let setup = Setup {
        size,
        periodic,
        species,
        obstacles,
        bodies,
        orientation: scene.simulation.orientation,
        table,
    };
    check_start(&scales, &setup)?;
    Ok(setup)
}

#[cfg(test)]
#[path = "setup_tests.rs"]
mod tests;
