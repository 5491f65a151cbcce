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
                        Exact::from_integer(s.into())
                    } else {
                        Exact::zero()
                    }
                })
            };
            let mut far = e(0);
            far[k] = scene.size[k].clone();
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
            centre: std::array::from_fn(|k| o.position[k].clone()),
            radius: o.radius.clone(),
        });
    }
    let spec = &scene.balls[0];
    let species = &scene.species[spec.species];
    let table = Table {
        boundaries,
        period: std::array::from_fn(|k| {
            (scene.boundary[k] == Axis::Periodic).then(|| scene.size[k].clone())
        }),
        ball: Ball {
            inv_mass: Exact::one() / species.mass.clone(),
            radius: species.radius.clone(),
            gamma2: species.gamma2.clone(),
        },
        law,
    };
    let x = std::array::from_fn(|k| spec.position[k].clone());
    let state = BodyState {
        velocity: std::array::from_fn(|k| spec.velocity[k].clone()),
        spin: std::array::from_fn(|k| spec.spin[k].clone()),
    };
    Ok((table, x, state))
}
