//! Specialised kernels (a scene's species constants and contact laws folded in) against the
//! generic map with the same constants, exactly: the no-slip kernels, or for a pair kind with
//! a rough law `(e, beta)` the generic rough kernels with the same exact `e` and `beta`, with
//! a Walton law `(e, mu, beta0)` the generic Walton kernels with the same exact law.
//!
//! A Walton kernel's one square root (of `rho = C / L` while the contact slides) is of the
//! contact's own numbers: both sides take it as `Exact::sqrt_rounded` does (exact when
//! rational, else truncated to 256 bits), a function of the rational under the root alone,
//! and the folded DAG computes the same rational there; so the two sides are equal exactly at
//! every point, sliding or sticking, a rational root or not.
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
use collision_core::{
    Ball, BodyState, Exact, Generated, Kernel, Restitution, RoughKernel, Walton, WaltonKernel,
};
use noslip_codegen::specialise;
use noslip_scene::Pair;
use noslip_scene::{ContactKind, PairSet, WallSide};
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

/// A pair's generic kernel as the engines run it: ball-ball the `free` map; a wall or
/// obstacle the `fixed` map with body 1 at rest (radius 1: it multiplies a zero spin) and the
/// wall's normal `+-e_axis` or the given `nu`.
fn as_engines<const N: usize, const S: usize>(
    pair: Pair,
    balls: &[Ball<Exact>],
    nu: &[Exact; N],
    states: &[BodyState<Exact, N, S>; 2],
    free: impl Fn(
        &[Exact; N],
        &Ball<Exact>,
        &Ball<Exact>,
        &BodyState<Exact, N, S>,
        &BodyState<Exact, N, S>,
    ) -> [BodyState<Exact, N, S>; 2],
    fixed: impl Fn(
        &[Exact; N],
        &Exact,
        &Ball<Exact>,
        &BodyState<Exact, N, S>,
        &BodyState<Exact, N, S>,
    ) -> BodyState<Exact, N, S>,
) -> Vec<BodyState<Exact, N, S>> {
    let (one, rest) = (Exact::from_integer(1), BodyState::zero());
    match pair {
        Pair::BallBall(a, b) => free(nu, &balls[a], &balls[b], &states[0], &states[1]).to_vec(),
        Pair::BallWall(s, axis, side) => {
            let sign = if side == WallSide::Upper { -1 } else { 1 };
            let wall =
                std::array::from_fn(|k| Exact::from_integer(if k == axis { sign } else { 0 }));
            vec![fixed(&wall, &one, &balls[s], &rest, &states[1])]
        }
        Pair::BallObstacle(s) => vec![fixed(nu, &one, &balls[s], &rest, &states[1])],
    }
}

/// The generic rough kernels under `law` for `pair`, as the engines run them ([`as_engines`]).
fn rough<const N: usize, const S: usize>(
    pair: Pair,
    balls: &[Ball<Exact>],
    law: &Restitution<Exact>,
    nu: &[Exact; N],
    states: &[BodyState<Exact, N, S>; 2],
) -> Vec<BodyState<Exact, N, S>>
where
    Generated: RoughKernel<Exact, N, S>,
{
    as_engines(
        pair,
        balls,
        nu,
        states,
        |nu, b1, b2, s1, s2| Generated::rough_free(nu, b1, b2, law, s1, s2),
        |nu, r1, b2, s1, s2| Generated::rough_fixed(nu, r1, b2, law, s1, s2),
    )
}

/// The generic Walton kernels under `law` for `pair`, as [`rough`] runs the rough ones.
fn walton<const N: usize, const S: usize>(
    pair: Pair,
    balls: &[Ball<Exact>],
    law: &Walton<Exact>,
    nu: &[Exact; N],
    states: &[BodyState<Exact, N, S>; 2],
) -> Vec<BodyState<Exact, N, S>>
where
    Generated: WaltonKernel<Exact, N, S>,
{
    as_engines(
        pair,
        balls,
        nu,
        states,
        |nu, b1, b2, s1, s2| Generated::walton_free(nu, b1, b2, law, s1, s2),
        |nu, r1, b2, s1, s2| Generated::walton_fixed(nu, r1, b2, law, s1, s2),
    )
}

/// Compare every pair kind of `set` at `points` random points.
pub fn check<const N: usize, const S: usize>(
    set: &PairSet,
    points: usize,
    seed: u64,
) -> Vec<PairCheck>
where
    Generated: Kernel<Exact, N, S>
        + Kernel<collision_core::ExactRelaxed, N, S>
        + RoughKernel<Exact, N, S>
        + WaltonKernel<Exact, N, S>,
{
    compare::<N, S>(set, set, points, seed)
}

/// [`check`] of the kernels specialised to `set` against the generic kernels under the laws
/// of `reference` (the same set but for its laws, in the tests).
fn compare<const N: usize, const S: usize>(
    set: &PairSet,
    reference: &PairSet,
    points: usize,
    seed: u64,
) -> Vec<PairCheck>
where
    Generated: Kernel<Exact, N, S>
        + Kernel<collision_core::ExactRelaxed, N, S>
        + RoughKernel<Exact, N, S>
        + WaltonKernel<Exact, N, S>,
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
                    .eval_all_rooted(
                        &|name| inputs.get(name).cloned(),
                        &|_, _, _| None,
                        &|x: &Exact| Some(x.sqrt_rounded()),
                    )
                    .expect("specialised kernels have constant, non-zero denominators");
                let read = |o: &noslip_codegen::model::BodyOutput| BodyState::<Exact, N, S> {
                    spin: std::array::from_fn(|k| values[o.spin[k].0 as usize].clone()),
                    velocity: std::array::from_fn(|k| values[o.velocity[k].0 as usize].clone()),
                };
                let got: Vec<BodyState<Exact, N, S>> = kernel.outputs.iter().map(read).collect();
                let want: Vec<BodyState<Exact, N, S>> = match reference.laws.of(pair) {
                    ContactKind::Rough { e, beta } => {
                        let law = Restitution {
                            e: Exact::from_fraction(&e),
                            beta: Exact::from_fraction(&beta),
                        };
                        rough(pair, &balls, &law, &nu, &states)
                    }
                    ContactKind::Walton { e, mu, beta0 } => {
                        let law = Walton {
                            e: Exact::from_fraction(&e),
                            mu: Exact::from_fraction(&mu),
                            beta0: Exact::from_fraction(&beta0),
                        };
                        walton(pair, &balls, &law, &nu, &states)
                    }
                    _ => match pair {
                        Pair::BallBall(a, b) => generic
                            .ball_ball(a, b, &nu, &states[0], &states[1])
                            .to_vec(),
                        Pair::BallWall(s, axis, side) => {
                            vec![generic.ball_wall(s, axis, side == WallSide::Upper, &states[1])]
                        }
                        Pair::BallObstacle(s) => vec![generic.ball_obstacle(s, &nu, &states[1])],
                    },
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

#[cfg(test)]
mod tests {
    use super::*;
    use noslip_scene::Scene;

    /// A 2D box with rough walls, a rough obstacle and rough ball-ball contacts: all three
    /// kinds of kernel with a rough law folded in.
    const ROUGH: &str = r#"
dim = 2
[box]
size = [10, 10]
boundary = ["wall", "periodic"]
contact = { e = "0.8", beta = "-1/3" }
[[species]]
mass = 1
radius = "1/2"
gamma2 = "1/2"
count = 3
[[obstacle]]
position = [5, 5]
radius = 1
contact = { e = "0.8", beta = "-1/3" }
[contact]
balls = { e = "0.9", beta = "1/2" }
"#;

    /// The same box under Walton laws: a small `mu` (most contacts slide) on the walls and the
    /// obstacle, a large one (most stick) between the balls.
    const WALTON: &str = r#"
dim = 2
[box]
size = [10, 10]
boundary = ["wall", "periodic"]
contact = { e = "0.8", mu = "1/10", beta0 = "1/2" }
[[species]]
mass = 1
radius = "1/2"
gamma2 = "1/2"
count = 3
[[obstacle]]
position = [5, 5]
radius = 1
contact = { e = "0.8", mu = "1/10", beta0 = "1/2" }
[contact]
balls = { e = "0.9", mu = "3", beta0 = "-1/3" }
"#;

    #[test]
    fn walton_kernels_equal_the_generic_walton_kernels_and_a_wrong_law_is_caught() {
        let set = Scene::from_toml(WALTON, "walton.toml").unwrap().pairs();
        assert!(matches!(set.laws.ball, ContactKind::Walton { .. }));
        assert!(matches!(set.laws.wall, ContactKind::Walton { .. }));
        assert!(matches!(set.laws.fixed, ContactKind::Walton { .. }));
        let results = check::<2, 1>(&set, 8, 1);
        assert_eq!(results.len(), 4); // ball-ball, two walls, obstacle
        assert!(results.iter().all(|r| r.mismatches == 0), "{results:?}");
        // Against another mu (which changes the sliding contacts only) some points differ,
        // against the rough law with beta = beta0 (the sticking branch) too, at the sliding ones.
        for law in [
            |l: &ContactKind| match l {
                ContactKind::Walton { e, beta0, .. } => ContactKind::Walton {
                    e: e.clone(),
                    mu: "1/7".parse().unwrap(),
                    beta0: beta0.clone(),
                },
                _ => unreachable!(),
            },
            |l: &ContactKind| match l {
                ContactKind::Walton { e, beta0, .. } => ContactKind::Rough {
                    e: e.clone(),
                    beta: beta0.clone(),
                },
                _ => unreachable!(),
            },
        ] {
            let mut other = set.clone();
            other.laws = noslip_scene::PairLaws {
                ball: law(&set.laws.ball),
                wall: law(&set.laws.wall),
                fixed: law(&set.laws.fixed),
                pairs: Vec::new(),
            };
            let results = compare::<2, 1>(&set, &other, 8, 1);
            let wrong: usize = results.iter().map(|r| r.mismatches).sum();
            assert!(wrong > 0, "{results:?}");
        }
    }

    #[test]
    fn rough_kernels_equal_the_generic_rough_kernels_and_a_wrong_law_is_caught() {
        let set = Scene::from_toml(ROUGH, "rough.toml").unwrap().pairs();
        assert!(matches!(set.laws.ball, ContactKind::Rough { .. }));
        assert!(matches!(set.laws.wall, ContactKind::Rough { .. }));
        assert!(matches!(set.laws.fixed, ContactKind::Rough { .. }));
        let results = check::<2, 1>(&set, 4, 1);
        assert_eq!(results.len(), set.all().len());
        assert_eq!(results.len(), 4); // ball-ball, two walls, obstacle
        assert!(results.iter().all(|r| r.mismatches == 0), "{results:?}");
        // Against the no-slip map, or another rough law, every point differs.
        for law in [
            ContactKind::NoSlip,
            ContactKind::Rough {
                e: "9/10".parse().unwrap(),
                beta: "1/3".parse().unwrap(),
            },
        ] {
            let mut other = set.clone();
            other.laws = noslip_scene::PairLaws {
                ball: law.clone(),
                wall: law.clone(),
                fixed: law,
                pairs: Vec::new(),
            };
            let results = compare::<2, 1>(&set, &other, 4, 1);
            assert!(results.iter().all(|r| r.mismatches == 4), "{results:?}");
        }
    }

    /// Two species whose three pairs have three laws (`[[contact.pair]]`): rough between the
    /// grains (the default), another rough law between grain and tracer, Walton between the
    /// tracers.
    const PAIRS: &str = r#"
dim = 2
[box]
size = [10, 10]
boundary = ["periodic", "periodic"]
[[species]]
name = "grain"
mass = 1
radius = "1/2"
gamma2 = "1/2"
count = 3
[[species]]
name = "tracer"
mass = 4
radius = 1
gamma2 = "2/5"
count = 2
[contact]
balls = { e = "0.9", beta = "1/2" }
[[contact.pair]]
species = ["tracer", "grain"]
law = { e = "0.8", beta = "-1/5" }
[[contact.pair]]
species = ["tracer", "tracer"]
law = { e = "0.7", mu = "3/10", beta0 = "3/5" }
"#;

    #[test]
    fn each_pair_kernel_folds_its_own_law_and_a_swapped_law_is_caught() {
        let set = Scene::from_toml(PAIRS, "pairs.toml").unwrap().pairs();
        assert_eq!(set.ball_ball, [(0, 0), (0, 1), (1, 1)]);
        let results = check::<2, 1>(&set, 8, 1);
        assert_eq!(results.len(), 3);
        assert!(results.iter().all(|r| r.mismatches == 0), "{results:?}");
        // The grain-tracer pair checked against the default law instead of its own: its
        // kernel differs at every point, the other pairs' kernels at none.
        let mut other = set.clone();
        other.laws.pairs.retain(|(p, _)| *p != (0, 1));
        let results = compare::<2, 1>(&set, &other, 8, 1);
        let wrong: Vec<usize> = results.iter().map(|r| r.mismatches).collect();
        assert_eq!(wrong, [0, 8, 0], "{results:?}");
    }
}
