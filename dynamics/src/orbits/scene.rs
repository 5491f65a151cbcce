//! A scene with one ball as a [`Table`]: walls at `0` and `L_k` on each walled axis, sphere
//! obstacles, periodic axes; kept exact (the scene's rationals).

use crate::law::Law;
use crate::table::{Boundary, Table};
use collision_core::{Ball, BodyState, Exact};
use noslip_scene::{Boundary as Axis, Scene};
use num_traits::{One, Zero};

/// The scene's table and its ball's start `(x, state)`; an error names the place.
#[allow(clippy::type_complexity)]
pub fn table<const N: usize, const S: usize>(
    scene: &Scene,
    law: Law,
) -> Result<(Table<Exact, N>, [Exact; N], BodyState<Exact, N, S>), String> {
    let balls: usize = scene.balls_per_species().iter().sum();
    if balls != 1 || scene.balls.len() != 1 {
        return Err(format!(
            "{}: a one-ball table is needed (one [[ball]], no species count), found {balls} balls",
            scene.origin
        ));
    }
    let mut boundaries = Vec::new();
    for (k, axis) in scene.boundary.iter().enumerate() {
        if *axis == Axis::Wall {
            let e = |s: i64| -> [Exact; N] {
                std::array::from_fn(|a| {
                    if a == k {
                        Exact::from_integer(s)
                    } else {
                        Exact::zero()
                    }
                })
            };
            let mut far = e(0);
            far[k] = Exact::from_fraction(&scene.size[k]);
            boundaries.push(Boundary::Wall {
                point: e(0),
                normal: e(1),
            });
            boundaries.push(Boundary::Wall {
                point: far,
                normal: e(-1),
            });
        }
    }
    for o in &scene.obstacles {
        boundaries.push(Boundary::Sphere {
            centre: std::array::from_fn(|k| Exact::from_fraction(&o.position[k])),
            radius: Exact::from_fraction(&o.radius),
        });
    }
    let spec = &scene.balls[0];
    let species = &scene.species[spec.species];
    let table = Table {
        boundaries,
        period: std::array::from_fn(|k| {
            (scene.boundary[k] == Axis::Periodic).then(|| Exact::from_fraction(&scene.size[k]))
        }),
        ball: Ball {
            inv_mass: Exact::one() / Exact::from_fraction(&species.mass),
            radius: Exact::from_fraction(&species.radius),
            gamma2: Exact::from_fraction(&species.gamma2),
        },
        law,
    };
    let x = std::array::from_fn(|k| Exact::from_fraction(&spec.position[k]));
    let state = BodyState {
        velocity: std::array::from_fn(|k| Exact::from_fraction(&spec.velocity[k])),
        spin: std::array::from_fn(|k| Exact::from_fraction(&spec.spin[k])),
    };
    Ok((table, x, state))
}
