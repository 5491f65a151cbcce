//! From a validated scene (exact) to the engine's f64 setup: species, obstacles, the
//! explicit balls and the seeded random placement.

use crate::sample::Rng;
use collision_core::sim::{Body, FixedBall, Setup};
use collision_core::{Ball, BodyState};
use noslip_codegen::scene::{Boundary, Scene};
use num_rational::BigRational;
use num_traits::ToPrimitive;

/// The nearest f64 (scene numbers are validated finite rationals).
pub fn f(x: &BigRational) -> f64 {
    x.to_f64().unwrap_or(f64::NAN)
}

fn array<const M: usize>(v: &[BigRational]) -> [f64; M] {
    std::array::from_fn(|k| f(&v[k]))
}

/// Uniform in `[0, 1)`: the top 53 bits of a ChaCha8 word.
fn unit(rng: &mut Rng) -> f64 {
    (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// Squared distance with the minimum image on periodic axes.
fn distance2<const N: usize>(
    a: &[f64; N],
    b: &[f64; N],
    size: &[f64; N],
    periodic: &[bool; N],
) -> f64 {
    (0..N)
        .map(|k| {
            let mut d = (a[k] - b[k]).abs();
            if periodic[k] {
                d = d.min(size[k] - d);
            }
            d * d
        })
        .sum()
}

/// The kernels' `Ball` parameters of the scene's species, each constant mapped by `f`
/// (`f64` rounding for the simulator, `clone` for exact checks).
pub fn species_balls<T>(
    scene_species: &[noslip_codegen::scene::Species],
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

/// Attempts per randomly placed ball before the scene is declared too dense.
pub const ATTEMPTS: usize = 10_000;

/// The engine's setup for `scene` (whose `dim` must be `N`). Random balls: positions uniform
/// in the box (inside the walls), rejected while they overlap a placed ball or an obstacle;
/// velocity components uniform in `[-speed, speed]`, skew entries of `U` uniform in
/// `[-spin, spin]`; one ChaCha8 stream seeded with `random.seed`, species in order.
pub fn setup<const N: usize, const S: usize>(scene: &Scene) -> Result<Setup<N, S>, String> {
    assert_eq!(scene.dim, N, "scene dimension");
    let size: [f64; N] = array(&scene.size);
    let periodic: [bool; N] = std::array::from_fn(|k| scene.boundary[k] == Boundary::Periodic);
    let species: Vec<Ball<f64>> = scene
        .species
        .iter()
        .map(|s| Ball {
            inv_mass: f(&s.inv_mass),
            radius: f(&s.radius),
            gamma2: f(&s.gamma2),
        })
        .collect();
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
    let mut rng = Rng::new(scene.random.seed);
    let (speed, spin) = (f(&scene.random.speed), f(&scene.random.spin));
    for (k, sp) in scene.species.iter().enumerate() {
        let r = species[k].radius;
        for placed in 0..sp.count {
            let mut found = None;
            for _ in 0..ATTEMPTS {
                let p: [f64; N] = std::array::from_fn(|a| {
                    let (lo, hi) = if periodic[a] {
                        (0.0, size[a])
                    } else {
                        (r, size[a] - r)
                    };
                    lo + (hi - lo) * unit(&mut rng)
                });
                let clear_balls = bodies.iter().all(|b| {
                    let s = r + species[b.species].radius;
                    distance2(&p, &b.position, &size, &periodic) >= s * s
                });
                let clear = clear_balls
                    && obstacles.iter().all(|o| {
                        let s = r + o.radius;
                        distance2(&p, &o.position, &size, &periodic) >= s * s
                    });
                if clear {
                    found = Some(p);
                    break;
                }
            }
            let Some(position) = found else {
                return Err(format!(
                    "species[{k}].count: placed {placed} of {} balls, then {ATTEMPTS} random \
                     positions in a row overlapped: the box is too full for random placement",
                    sp.count
                ));
            };
            let mut uniform = |scale: f64| scale * (2.0 * unit(&mut rng) - 1.0);
            let velocity = std::array::from_fn(|_| uniform(speed));
            let spin = std::array::from_fn(|_| uniform(spin));
            bodies.push(Body {
                species: k,
                position,
                state: BodyState { spin, velocity },
            });
        }
    }
    Ok(Setup {
        size,
        periodic,
        species,
        obstacles,
        bodies,
        orientation: scene.simulation.orientation,
    })
}
