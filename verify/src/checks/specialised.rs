//! Specialised kernels (a scene's species constants folded in) against the generic map with
//! the same constants, exactly.
//!
//! Each specialised kernel's DAG is evaluated in exact rationals at random points (random
//! exactly unit normals, random states with entries from `S = {1..2^20}`) and must equal the
//! compiled generic kernel run with the species' `Ball` parameters (and, for walls and
//! obstacles, body 1 at rest with the wall's normal). Both sides are rational functions of the
//! point of low degree, so equality at random points is the Schwartz-Zippel argument of
//! `noslip verify`; with it, every identity verified for the generic kernels holds for the
//! specialised ones.

use crate::sample::{element, normal};
use crate::under_test::input_values;
use collision_core::rng::Rng;
use collision_core::{Ball, BodyState, Exact, Generated, Kernel};
use noslip_codegen::specialise;
use noslip_scene::Pair;
use noslip_scene::{PairSet, WallSide};
use noslip_sim::setup::species_balls;
use noslip_sim::{GenericKernels, PairKernels};

/// The outcome for one pair kind.
#[derive(Clone, Debug)]
pub struct PairCheck {
    /// The pair kind compared.
    pub pair: Pair,
    /// Random points compared.
    pub points: usize,
    /// Points where the two differ (0 when the check passes).
    pub mismatches: usize,
}

fn state<const N: usize, const S: usize>(rng: &mut Rng) -> BodyState<Exact, N, S> {
    BodyState {
        spin: std::array::from_fn(|_| element(rng)),
        velocity: std::array::from_fn(|_| element(rng)),
    }
}

/// Compare every pair kind of `set` at `points` random points.
pub fn check<const N: usize, const S: usize>(
    set: &PairSet,
    points: usize,
    seed: u64,
) -> Vec<PairCheck>
where
    Generated: Kernel<Exact, N, S> + Kernel<collision_core::ExactRelaxed, N, S>,
{
    assert_eq!(set.dim, N);
    let balls: Vec<Ball<Exact>> = species_balls(&set.species, Exact::from_fraction);
    let generic = GenericKernels {
        species: balls.clone(),
    };
    let mut rng = Rng::new(seed);
    set.all()
        .into_iter()
        .map(|pair| {
            let kernel = specialise::build(set, pair);
            let mut mismatches = 0;
            for _ in 0..points {
                let nu = normal::<N>(&mut rng);
                let states = [state::<N, S>(&mut rng), state::<N, S>(&mut rng)];
                let inputs = input_values(&nu, [&balls[0], &balls[0]], [&states[0], &states[1]]);
                let values = kernel
                    .graph
                    .eval_all(&|name| inputs.get(name).cloned(), &|_, _, _| None)
                    .expect("specialised kernels have constant, non-zero denominators");
                let read = |o: &noslip_codegen::model::BodyOutput| BodyState::<Exact, N, S> {
                    spin: std::array::from_fn(|k| values[o.spin[k].0 as usize].clone()),
                    velocity: std::array::from_fn(|k| values[o.velocity[k].0 as usize].clone()),
                };
                let got: Vec<BodyState<Exact, N, S>> = kernel.outputs.iter().map(read).collect();
                let want: Vec<BodyState<Exact, N, S>> = match pair {
                    Pair::BallBall(a, b) => generic
                        .ball_ball(a, b, &nu, &states[0], &states[1])
                        .to_vec(),
                    Pair::BallWall(s, axis, side) => {
                        vec![generic.ball_wall(s, axis, side == WallSide::Upper, &states[1])]
                    }
                    Pair::BallObstacle(s) => vec![generic.ball_obstacle(s, &nu, &states[1])],
                };
                if got != want {
                    mismatches += 1;
                }
            }
            PairCheck {
                pair,
                points,
                mismatches,
            }
        })
        .collect()
}
