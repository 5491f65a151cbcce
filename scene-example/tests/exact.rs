//! The compiled specialised kernels, instantiated with exact rationals, equal the generic
//! kernels run with the same species constants, at random exact points (see
//! `noslip gen --check` for the argument that this proves the identity).

use collision_core::{stereographic_normal, BodyState, Exact};
use noslip_scene::Pair;
use noslip_scene::{Scene, WallSide};
use noslip_scene_example::{disk_between_walls, gas2d, sinai};
use noslip_sim::setup::species_balls;
use noslip_sim::{GenericKernels, PairKernels};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn check<K: PairKernels<Exact, 2, 1>>(scene: &str, kernels: K) {
    let path = format!("{}/../scenes/{scene}", env!("CARGO_MANIFEST_DIR"));
    let scene = Scene::from_file(path.as_ref()).unwrap();
    let generic = GenericKernels {
        species: species_balls(&scene.species, Exact::from_fraction),
    };
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mut q = || {
        Exact::from_integer(rng.random_range(-1000..=1000))
            / Exact::from_integer(rng.random_range(1..=97))
    };
    let set = scene.pairs();
    assert!(!set.all().is_empty());
    for pair in set.all() {
        for _ in 0..8 {
            let nu: [Exact; 2] = stereographic_normal(&[q()]).try_into().unwrap();
            let s1 = BodyState {
                spin: [q()],
                velocity: [q(), q()],
            };
            let s2 = BodyState {
                spin: [q()],
                velocity: [q(), q()],
            };
            let (got, want) = match pair {
                Pair::BallBall(a, b) => (
                    kernels.ball_ball(a, b, &nu, &s1, &s2).to_vec(),
                    generic.ball_ball(a, b, &nu, &s1, &s2).to_vec(),
                ),
                Pair::BallWall(s, k, side) => {
                    let up = side == WallSide::Upper;
                    (
                        vec![kernels.ball_wall(s, k, up, &s2)],
                        vec![generic.ball_wall(s, k, up, &s2)],
                    )
                }
                Pair::BallObstacle(s) => (
                    vec![kernels.ball_obstacle(s, &nu, &s2)],
                    vec![generic.ball_obstacle(s, &nu, &s2)],
                ),
            };
            assert_eq!(got, want, "{pair:?}");
            if let Pair::BallBall(a, b) = pair {
                // The dispatch swaps species for (b, a).
                let swapped = kernels.ball_ball(b, a, &nu, &s1, &s2).to_vec();
                assert_eq!(swapped, generic.ball_ball(b, a, &nu, &s1, &s2).to_vec());
            }
        }
    }
}

#[test]
fn specialised_equals_generic_exactly() {
    check("gas2d.toml", gas2d::Kernels);
    check("sinai.toml", sinai::Kernels);
    check("disk_between_walls.toml", disk_between_walls::Kernels);
}
