//! ns per collision, generic against specialised kernels, per pair kind (f64). The generic
//! kernels get the species' `Ball` parameters at run time; the specialised ones have them
//! folded in (scenes/gas2d.toml: species 0 `small` and 1 `large`; scenes/sinai.toml).

use collision_core::{BodyState, State2};
use criterion::{black_box, criterion_group, criterion_main, Criterion};
use noslip_scene::Scene;
use noslip_scene_example::{gas2d, sinai};
use noslip_sim::setup::species_balls;
use noslip_sim::{GenericKernels, PairKernels};
use num_traits::ToPrimitive;

fn generic(path: &str) -> GenericKernels<f64> {
    let scene = Scene::from_file(path.as_ref()).expect("shipped scene");
    GenericKernels {
        species: species_balls(&scene.species, |x| x.to_f64().expect("finite")),
    }
}

fn bench(c: &mut Criterion) {
    let gas = generic("../scenes/gas2d.toml");
    let billiard = generic("../scenes/sinai.toml");
    let nu = [0.6, 0.8];
    let s1: State2<f64> = BodyState {
        spin: [0.3],
        velocity: [1.0, 0.5],
    };
    let s2: State2<f64> = BodyState {
        spin: [-0.7],
        velocity: [-0.2, -1.1],
    };
    let mut g = c.benchmark_group("ball-ball");
    g.bench_function("generic", |b| {
        b.iter(|| {
            PairKernels::<f64, 2, 1>::ball_ball(
                &gas,
                black_box(0),
                black_box(1),
                black_box(&nu),
                black_box(&s1),
                black_box(&s2),
            )
        })
    });
    g.bench_function("specialised", |b| {
        b.iter(|| gas2d::ball_ball_0_1(black_box(&nu), black_box(&s1), black_box(&s2)))
    });
    g.finish();
    let mut g = c.benchmark_group("ball-wall");
    g.bench_function("generic", |b| {
        b.iter(|| {
            PairKernels::<f64, 2, 1>::ball_wall(
                &gas,
                black_box(0),
                black_box(1),
                black_box(false),
                black_box(&s2),
            )
        })
    });
    g.bench_function("specialised", |b| {
        b.iter(|| gas2d::ball_wall_0_1_lower(black_box(&s2)))
    });
    g.finish();
    let mut g = c.benchmark_group("ball-obstacle");
    g.bench_function("generic", |b| {
        b.iter(|| {
            PairKernels::<f64, 2, 1>::ball_obstacle(
                &billiard,
                black_box(0),
                black_box(&nu),
                black_box(&s2),
            )
        })
    });
    g.bench_function("specialised", |b| {
        b.iter(|| sinai::ball_obstacle_0(black_box(&nu), black_box(&s2)))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
