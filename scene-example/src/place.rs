//! The 2D setup of a scene: its explicit balls, then each species' `count` balls placed at
//! random by the rule of `noslip simulate` (`verify/src/simulate/setup.rs`): positions
//! uniform in the box (inside the walls), rejected while they overlap a placed ball or an
//! obstacle (at most [`ATTEMPTS`] tries per ball); velocity components uniform in
//! `[-speed, speed]`, the spin `U_12` uniform in `[-spin, spin]`; one ChaCha8 stream seeded
//! with `random.seed`, species in order.

use collision_core::sim::{Body, FixedBall, Setup};
use collision_core::BodyState;
use noslip_codegen::scene::{Boundary, Scene};
use num_rational::BigRational;
use num_traits::ToPrimitive;
use rand::RngCore;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// Random positions tried per ball before placement gives up.
pub const ATTEMPTS: usize = 10_000;

/// The nearest f64 of an exact scene number.
pub(crate) fn f(x: &BigRational) -> f64 {
    x.to_f64().unwrap_or(f64::NAN)
}

fn pair(x: &[BigRational]) -> [f64; 2] {
    [f(&x[0]), f(&x[1])]
}

/// Uniform in `[0, 1)`: the top 53 bits of a ChaCha8 word.
fn unit(rng: &mut ChaCha8Rng) -> f64 {
    (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// Squared distance, with the minimum image on periodic axes.
fn distance2(a: &[f64; 2], b: &[f64; 2], size: &[f64; 2], periodic: &[bool; 2]) -> f64 {
    (0..2)
        .map(|k| {
            let mut d = (a[k] - b[k]).abs();
            if periodic[k] {
                d = d.min(size[k] - d);
            }
            d * d
        })
        .sum()
}

/// The engine's setup of the 2D `scene`; an error names the species whose balls do not fit.
pub fn setup(scene: &Scene) -> Result<Setup<2, 1>, String> {
    if scene.dim != 2 {
        return Err(format!(
            "dim: this example runs 2D scenes, got {}",
            scene.dim
        ));
    }
    let size = pair(&scene.size);
    let periodic = [0, 1].map(|k| scene.boundary[k] == Boundary::Periodic);
    let species = crate::species_balls(scene, f);
    let obstacles: Vec<FixedBall<2>> = scene
        .obstacles
        .iter()
        .map(|o| FixedBall {
            position: pair(&o.position),
            radius: f(&o.radius),
        })
        .collect();
    let mut bodies: Vec<Body<2, 1>> = scene
        .balls
        .iter()
        .map(|b| Body {
            species: b.species,
            position: pair(&b.position),
            state: BodyState {
                spin: [f(&b.spin[0])],
                velocity: pair(&b.velocity),
            },
        })
        .collect();
    let mut rng = ChaCha8Rng::seed_from_u64(scene.random.seed);
    let (speed, spin) = (f(&scene.random.speed), f(&scene.random.spin));
    for (k, sp) in scene.species.iter().enumerate() {
        let r = species[k].radius;
        for placed in 0..sp.count {
            let mut found = None;
            for _ in 0..ATTEMPTS {
                let p: [f64; 2] = std::array::from_fn(|a| {
                    let (lo, hi) = if periodic[a] {
                        (0.0, size[a])
                    } else {
                        (r, size[a] - r)
                    };
                    lo + (hi - lo) * unit(&mut rng)
                });
                let clear = bodies.iter().all(|b| {
                    let s = r + species[b.species].radius;
                    distance2(&p, &b.position, &size, &periodic) >= s * s
                }) && obstacles.iter().all(|o| {
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
            let velocity = [uniform(speed), uniform(speed)];
            let spin = [uniform(spin)];
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
