//! The kernels of `walton_box.toml` (a Walton law folded into every kind of kernel) against
//! the generic Walton kernels (`kernels::d2::walton`):
//!
//! - in exact rationals, equal at random points (the argument of `noslip gen --check`): the
//!   one square root is `Exact::sqrt_rounded` of the same rational on both sides;
//! - in `f64`, where the folded kernel takes the law's constants (`h_n = (1 + e)/2`, ...)
//!   rounded once from their exact values and the generic kernel computes them from `e`,
//!   `mu`, `beta0` rounded to `f64` (as the engines pass them), the two round differently:
//!   they are not compared bit for bit but each against the exact map at the same `f64`
//!   inputs and the exact law, within 64 eps in the max norm relative to the largest output
//!   component (the acceptance rule of `noslip report` for the `f64` kernels, whose Walton
//!   regimes measure at most 2.6 eps typical; docs/accuracy.md). The fraction of contacts
//!   with equal bits is printed (`--nocapture`) for docs/scenes.md.

use collision_core::{
    stereographic_normal, Ball, BodyState, Exact, Generated, Walton, WaltonKernel,
};
use noslip_scene::{ContactKind, Pair, Scene, WallSide};
use noslip_scene_example::walton_box;
use noslip_sim::setup::species_balls;
use noslip_sim::PairKernels;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn scene() -> noslip_scene::PairSet {
    let path = format!("{}/walton_box.toml", env!("CARGO_MANIFEST_DIR"));
    Scene::from_file(path.as_ref()).unwrap().pairs()
}

/// The exact law of `pair`'s kind in `set`.
fn law(set: &noslip_scene::PairSet, pair: Pair) -> Walton<Exact> {
    match set.laws.of(pair) {
        ContactKind::Walton { e, mu, beta0 } => Walton {
            e: Exact::from_fraction(e),
            mu: Exact::from_fraction(mu),
            beta0: Exact::from_fraction(beta0),
        },
        other => panic!("walton_box.toml: {other:?}"),
    }
}

/// `pair` by the generic Walton kernels (body 1 at rest for a wall or obstacle, as the
/// engines run them), in `T`.
fn generic<T: collision_core::ScalarRoot>(
    pair: Pair,
    balls: &[Ball<T>],
    law: &Walton<T>,
    nu: &[T; 2],
    states: &[BodyState<T, 2, 1>; 2],
) -> Vec<BodyState<T, 2, 1>>
where
    for<'a> &'a T: collision_core::RefArith<T>,
    Generated: WaltonKernel<T, 2, 1>,
{
    let (one, rest) = (T::one(), BodyState::zero());
    match pair {
        Pair::BallBall(a, b) => {
            Generated::walton_free(nu, &balls[a], &balls[b], law, &states[0], &states[1]).to_vec()
        }
        Pair::BallWall(s, axis, side) => {
            let sign = if side == WallSide::Upper { -1 } else { 1 };
            let wall = std::array::from_fn(|k| T::from_ratio(if k == axis { sign } else { 0 }, 1));
            vec![Generated::walton_fixed(
                &wall, &one, &balls[s], law, &rest, &states[1],
            )]
        }
        Pair::BallObstacle(s) => vec![Generated::walton_fixed(
            nu, &one, &balls[s], law, &rest, &states[1],
        )],
    }
}

/// `pair` by the scene's folded kernels, in `T`.
fn folded<T: Clone, K: PairKernels<T, 2, 1>>(
    kernels: &K,
    pair: Pair,
    nu: &[T; 2],
    states: &[BodyState<T, 2, 1>; 2],
) -> Vec<BodyState<T, 2, 1>> {
    match pair {
        Pair::BallBall(a, b) => kernels.ball_ball(a, b, nu, &states[0], &states[1]).to_vec(),
        Pair::BallWall(s, axis, side) => {
            vec![kernels.ball_wall(s, axis, side == WallSide::Upper, &states[1])]
        }
        Pair::BallObstacle(s) => vec![kernels.ball_obstacle(s, nu, &states[1])],
    }
}

fn components<T: Clone>(states: &[BodyState<T, 2, 1>]) -> Vec<T> {
    states
        .iter()
        .flat_map(|s| s.spin.iter().chain(&s.velocity).cloned())
        .collect()
}

#[test]
fn folded_walton_kernels_equal_the_generic_ones_exactly() {
    let set = scene();
    let balls = species_balls(&set.species, Exact::from_fraction);
    let mut rng = ChaCha8Rng::seed_from_u64(27);
    let mut q = || {
        Exact::from_integer(rng.random_range(-1000..=1000))
            / Exact::from_integer(rng.random_range(1..=97))
    };
    assert_eq!(set.all().len(), 4);
    for pair in set.all() {
        for _ in 0..16 {
            let nu: [Exact; 2] = stereographic_normal(&[q()]).try_into().unwrap();
            let state = |q: &mut dyn FnMut() -> Exact| BodyState {
                spin: [q()],
                velocity: [q(), q()],
            };
            let states = [state(&mut q), state(&mut q)];
            let want = generic(pair, &balls, &law(&set, pair), &nu, &states);
            let got = folded(&walton_box::Kernels, pair, &nu, &states);
            assert_eq!(got, want, "{pair:?}");
        }
    }
}

#[test]
fn folded_walton_kernels_agree_with_the_generic_ones_in_f64_within_the_report_rule() {
    let set = scene();
    let exact_balls = species_balls(&set.species, Exact::from_fraction);
    let balls = species_balls(&set.species, |x| Exact::from_fraction(x).to_f64());
    let mut rng = ChaCha8Rng::seed_from_u64(2027);
    let eps = f64::EPSILON;
    for pair in set.all() {
        let exact_law = law(&set, pair);
        let law64 = Walton {
            e: exact_law.e.to_f64(),
            mu: exact_law.mu.to_f64(),
            beta0: exact_law.beta0.to_f64(),
        };
        let (mut same, mut worst) = (0, [0.0f64; 2]);
        let points = 500;
        for _ in 0..points {
            let angle: f64 = rng.random_range(0.0..std::f64::consts::TAU);
            let nu = [angle.cos(), angle.sin()];
            let mut v = || rng.random_range(-1.0..1.0);
            let states = [0, 1].map(|_| BodyState {
                spin: [v()],
                velocity: [v(), v()],
            });
            let exact = |x: &f64| Exact::from_float(*x).unwrap();
            let truth = components(&generic(
                pair,
                &exact_balls,
                &exact_law,
                &nu.each_ref().map(exact),
                &states.each_ref().map(|s| BodyState {
                    spin: s.spin.each_ref().map(exact),
                    velocity: s.velocity.each_ref().map(exact),
                }),
            ));
            let scale = truth.iter().map(|x| x.to_f64().abs()).fold(0.0, f64::max);
            let got = [
                components(&folded(&walton_box::Kernels, pair, &nu, &states)),
                components(&generic(pair, &balls, &law64, &nu, &states)),
            ];
            if got[0]
                .iter()
                .zip(&got[1])
                .all(|(a, b)| a.to_bits() == b.to_bits())
            {
                same += 1;
            }
            for (w, g) in worst.iter_mut().zip(&got) {
                let err = g
                    .iter()
                    .zip(&truth)
                    .map(|(x, t)| (&exact(x) - t).to_f64().abs())
                    .fold(0.0, f64::max);
                *w = w.max(err / scale / eps);
            }
        }
        println!(
            "{}: {same} of {points} contacts the same bits; largest error folded {:.2} eps, generic {:.2} eps",
            pair.fn_name(),
            worst[0],
            worst[1]
        );
        assert!(worst[0] <= 64.0 && worst[1] <= 64.0, "{pair:?}: {worst:?}");
    }
}
