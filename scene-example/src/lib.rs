//! Kernels specialised to shipped scenes by `build.rs` (noslip-codegen's build-script API),
//! and a simulation setup for scenes with explicit balls only.

/// `scenes/disk_between_walls.toml`: ball-wall kernels for the two walls of axis 1.
pub mod disk_between_walls {
    include!(concat!(env!("OUT_DIR"), "/disk_between_walls.rs"));
}

/// `scenes/gas2d.toml`: ball-ball for species (0,0), (0,1), (1,1) and ball-wall.
pub mod gas2d {
    include!(concat!(env!("OUT_DIR"), "/gas2d.rs"));
}

/// `scenes/sinai.toml`: the ball-obstacle kernel.
pub mod sinai {
    include!(concat!(env!("OUT_DIR"), "/sinai.rs"));
}

use collision_core::sim::{Body, FixedBall, Setup};
use collision_core::{Ball, BodyState};
use noslip_codegen::scene::{Boundary, Scene};
use num_rational::BigRational;
use num_traits::ToPrimitive;

/// The nearest f64 of an exact scene number.
fn f(x: &BigRational) -> f64 {
    x.to_f64().unwrap_or(f64::NAN)
}

/// The kernels' `Ball` parameters of the scene's species, each constant mapped by `map`.
pub fn species_balls<T>(scene: &Scene, map: impl Fn(&BigRational) -> T) -> Vec<Ball<T>> {
    scene
        .species
        .iter()
        .map(|s| Ball {
            inv_mass: map(&s.inv_mass),
            radius: map(&s.radius),
            gamma2: map(&s.gamma2),
        })
        .collect()
}

/// The 2D setup of a scene whose balls are all explicit (no random placement).
pub fn explicit_setup(scene: &Scene) -> Setup<2, 1> {
    assert_eq!(scene.dim, 2);
    assert!(
        scene.species.iter().all(|s| s.count == 0),
        "explicit balls only"
    );
    let v = |x: &[BigRational]| [f(&x[0]), f(&x[1])];
    Setup {
        size: v(&scene.size),
        periodic: [0, 1].map(|k| scene.boundary[k] == Boundary::Periodic),
        species: species_balls(scene, f),
        obstacles: scene
            .obstacles
            .iter()
            .map(|o| FixedBall {
                position: v(&o.position),
                radius: f(&o.radius),
            })
            .collect(),
        bodies: scene
            .balls
            .iter()
            .map(|b| Body {
                species: b.species,
                position: v(&b.position),
                state: BodyState {
                    spin: [f(&b.spin[0])],
                    velocity: v(&b.velocity),
                },
            })
            .collect(),
        orientation: scene.simulation.orientation,
    }
}
