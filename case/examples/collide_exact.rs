//! Microseconds per case of `noslip collide --exact` without the process: `cargo run --release
//! -p noslip-case --example collide_exact [-- ROUNDS]` times, for three 3D cases (below), the
//! library entry the command calls (`collide_json(text, Mode::Exact)`: JSON in, validation,
//! the collision, JSON out; on these cases the direct path, `case/src/direct.rs`) against the
//! pieces of the general path: `kernel`, the kernel alone (`collide_unchecked`
//! on the parsed inputs, what the exact-arithmetic benchmarks time); `checked_collide`, the
//! kernel with collision-core's checks; `solve`, the case's balls and states built and checked,
//! then `checked_collide`; `read`, the case read as the general path reads it (`read:text` the
//! text into the borrowed tree, `noslip_case::text::parse`; `read:case` `Case::from_json` on
//! that tree); `read:serde`, the same by serde_json's `Value` with the test for repeated keys
//! (the path of inputs the fast reader declines, and of errors); `write`, the answer written
//! (`noslip_case::output::render`). Each figure is the median
//! over `ROUNDS` (default 7) of the mean over a batch of calls lasting about 0.2 s, with its
//! least and greatest; the pieces alternate within a round. Prints `case piece median min
//! max` in microseconds. `collide_exact calls CASE N` only calls `collide_json` N times on one
//! case (0 fixed, 1 free, 2 typical), for `valgrind --tool=callgrind`.

use collision_core::rng::Rng;
use collision_core::{collide, collide_unchecked, stereographic_normal, Ball, BodyState, Exact};
use noslip_case::case::{Case, Spin};
use noslip_case::keys::has_every_key;
use noslip_case::output::render;
use noslip_case::solve::solve;
use noslip_case::text;
use noslip_case::{collide_json, Mode};
use serde_json::Value;
use std::hint::black_box;
use std::time::Instant;

/// The fixed case of `examples/case.json`, the same with body 2 of mass 3 (the `free`
/// kernel), and a typical free case in floats as a program would print them (every input a
/// shortest round-trip `f64` decimal of about 17 digits, as in the accuracy report's typical
/// regime: masses `2^U(-2,2)`, radii `2^U(-1,1)`, `gamma2` in `(0, 2/3]`, velocity and spin
/// entries `U(-1,1)`), its normal a rational unit vector (the stereographic image of a point
/// of two 3-digit decimals).
fn cases() -> [(&'static str, String); 3] {
    let fixed = include_str!("../../examples/case.json").to_string();
    let free = fixed.replace(r#""mass": "inf""#, r#""mass": "3""#);
    assert_ne!(fixed, free);
    let mut rng = Rng::new(7);
    let mut x = |lo: f64, hi: f64| rng.uniform(lo, hi);
    let y = [
        Exact::from_decimal("317", "1000"),
        Exact::from_decimal("-589", "1000"),
    ]
    .map(Option::unwrap);
    let nu: Vec<String> = stereographic_normal(&y)
        .iter()
        .map(|c| format!("\"{c}\""))
        .collect();
    // Velocities approaching along nu (negated together if they separate).
    let nu_f = stereographic_normal(&[0.317, -0.589]);
    let mut u: [[f64; 3]; 2] = std::array::from_fn(|_| std::array::from_fn(|_| x(-1.0, 1.0)));
    if (0..3).map(|k| (u[1][k] - u[0][k]) * nu_f[k]).sum::<f64>() > 0.0 {
        u = u.map(|v| v.map(|c| -c));
    }
    let mut body = |u: [f64; 3]| {
        let (a, b, c) = (x(-1.0, 1.0), x(-1.0, 1.0), x(-1.0, 1.0));
        format!(
            "{{\"mass\": {:?}, \"radius\": {:?}, \"gamma2\": {:?}, \"angular_velocity\": \
             [[0.0, {a:?}, {b:?}], [{:?}, 0.0, {c:?}], [{:?}, {:?}, 0.0]], \"velocity\": \
             [{:?}, {:?}, {:?}]}}",
            x(-2.0, 2.0).exp2(),
            x(-1.0, 1.0).exp2(),
            x(0.01, 2.0 / 3.0),
            -a,
            -b,
            -c,
            u[0],
            u[1],
            u[2]
        )
    };
    let (b1, b2) = (body(u[0]), body(u[1]));
    let typical = format!(
        "{{\"dim\": 3, \"normal\": [{}], \"bodies\": [{b1}, {b2}]}}",
        nu.join(", ")
    );
    [("fixed", fixed), ("free", free), ("typical", typical)]
}

/// A named piece of the path, as a call to time.
type Piece<'a> = (&'static str, Box<dyn Fn() + 'a>);

/// Mean microseconds per call of `f` over a batch of about 0.2 s.
fn per_call(mut f: impl FnMut()) -> f64 {
    let mut calls = 1;
    loop {
        let start = Instant::now();
        for _ in 0..calls {
            f();
        }
        let s = start.elapsed().as_secs_f64();
        if s > 0.2 {
            return s * 1e6 / calls as f64;
        }
        calls *= 2;
    }
}

fn median(mut v: Vec<f64>) -> (f64, f64, f64) {
    v.sort_by(f64::total_cmp);
    (v[v.len() / 2], v[0], v[v.len() - 1])
}

/// The kernel's inputs of a parsed 3D case with matrix spins.
fn inputs(case: &Case<Exact>) -> ([Exact; 3], [Ball<Exact>; 2], [BodyState<Exact, 3, 3>; 2]) {
    let nu: [Exact; 3] = case.normal.clone().try_into().unwrap();
    let balls = [0, 1].map(|i| {
        let b = &case.bodies[i];
        Ball::new(3, b.mass.clone(), b.radius.clone(), b.inertia.clone()).unwrap()
    });
    let states = [0, 1].map(|i| {
        let b = &case.bodies[i];
        let Spin::Matrix(m) = &b.spin else {
            panic!("matrix spins")
        };
        let rows: [[Exact; 3]; 3] = std::array::from_fn(|r| m[r].clone().try_into().unwrap());
        BodyState::from_matrix(i, &rows, b.velocity.clone().try_into().unwrap()).unwrap()
    });
    (nu, balls, states)
}

/// `calls CASE N`: `collide_json` alone, `N` times on case `CASE` (0 fixed, 1 free, 2
/// typical), for an instruction profile (`valgrind --tool=callgrind`).
fn calls(args: &[String]) {
    let which: usize = args[0].parse().expect("CASE: 0, 1 or 2");
    let n: usize = args[1].parse().expect("N: a whole number");
    let all = cases();
    for _ in 0..n {
        black_box(collide_json(black_box(&all[which].1), Mode::Exact).unwrap());
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("calls") {
        return calls(&args[1..]);
    }
    let rounds: usize = args
        .first()
        .map_or(7, |s| s.parse().expect("ROUNDS: a whole number"));
    println!("case piece median_us min_us max_us");
    for (name, text) in cases() {
        let tree = text::parse(&text).unwrap();
        let case = Case::<Exact>::from_json(&tree).unwrap();
        let (nu, balls, states) = inputs(&case);
        let out = solve(&case).unwrap();
        let pieces: Vec<Piece<'_>> = vec![
            (
                "collide_json",
                Box::new(|| {
                    black_box(collide_json(black_box(&text), Mode::Exact).unwrap());
                }),
            ),
            (
                "kernel",
                Box::new(|| {
                    let b = [&balls[0], &balls[1]];
                    black_box(collide_unchecked(
                        black_box(&nu),
                        b,
                        [&states[0], &states[1]],
                    ));
                }),
            ),
            (
                "checked_collide",
                Box::new(|| {
                    let b = [&balls[0], &balls[1]];
                    black_box(collide(black_box(&nu), b, [&states[0], &states[1]]).unwrap());
                }),
            ),
            (
                "read",
                Box::new(|| {
                    let tree = text::parse(black_box(&text)).unwrap();
                    black_box(Case::<Exact>::from_json(&tree).unwrap());
                }),
            ),
            (
                "read:text",
                Box::new(|| {
                    black_box(text::parse(black_box(&text)).unwrap());
                }),
            ),
            (
                "read:case",
                Box::new(|| {
                    black_box(Case::<Exact>::from_json(black_box(&tree)).unwrap());
                }),
            ),
            (
                "read:serde",
                Box::new(|| {
                    let v: Value = serde_json::from_str(black_box(&text)).unwrap();
                    assert!(has_every_key(&text, &v));
                    black_box(Case::<Exact>::from_json(&v).unwrap());
                }),
            ),
            (
                "solve",
                Box::new(|| {
                    black_box(solve(black_box(&case)).unwrap());
                }),
            ),
            (
                "write",
                Box::new(|| {
                    black_box(render(black_box(&case), &out).unwrap());
                }),
            ),
        ];
        let mut times = vec![Vec::new(); pieces.len()];
        for _ in 0..rounds {
            for (k, (_, f)) in pieces.iter().enumerate() {
                times[k].push(per_call(f));
            }
        }
        for ((piece, _), t) in pieces.iter().zip(times) {
            let (m, lo, hi) = median(t);
            println!("{name} {piece} {m:.1} {lo:.1} {hi:.1}");
        }
    }
}
