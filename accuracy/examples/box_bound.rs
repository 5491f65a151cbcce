//! Static bounds over an input box (`noslip_codegen::bound`), beside the largest error
//! measured in it.
//!
//! The box is the typical regime's, with `gamma2` kept away from 0 (a box reaching
//! `gamma2_1 = gamma2_2 = 0` contains `D = 0` and has no finite bound): per body
//! `inv_mass in [1/4, 4]`, `radius in [1/2, 2]`, `gamma2 in [(2/n)/8, 2/n]`, every entry of
//! `U_i` and `u_i` in `[-1, 1]`, every component of `nu` in `[-1, 1]`. The bound is the
//! largest over the returned body's components of the absolute error bound, in eps (the
//! state scale is 1); the measured figure is the largest absolute component error over
//! typical cases that lie in the box (`--cases`, default 20000), against exact rationals.
//! `fixed` is measured through `collide_unchecked` with body 1 immovable. Each ball
//! parameter's range is split into `--split` pieces (default 4: `4^6` sub-boxes for `free`,
//! `4^2` for `fixed`), and the bound is the largest over the sub-boxes.
//!
//! ```sh
//! cargo run --release -p noslip-accuracy --example box_bound -- [--cases K] [--split P] [--gappa DIR]
//! ```
//!
//! `--gappa DIR` also writes the n = 2 kernels over the same box as Gappa scripts
//! (`free_f64.g`, ...), one goal per output component.

use collision_core::rng::Rng;
use collision_core::{collide_unchecked, collide_unchecked_fma, Exact, Generated, Kernel};
use noslip_accuracy::case::{flatten, Case};
use noslip_accuracy::measure::exact_result;
use noslip_accuracy::static_box::StaticBox;
use noslip_accuracy::Regime;
use noslip_codegen::bound::{gappa, Format, InputRange, KernelBound};
use noslip_codegen::program::Program;
use noslip_codegen::{model, Arith, Variant};
use std::time::Instant;

/// The typical box for dimension `n` (see the module docs; `noslip_accuracy::static_box`).
fn typical_box(n: usize, name: &str) -> InputRange {
    StaticBox::typical(n).range(name).0
}

/// The balls' parameters (`inv_mass`, `radius`, `gamma2`): the inputs the bound splits.
fn is_parameter(name: &str) -> bool {
    ["inv_mass", "radius", "gamma2"]
        .iter()
        .any(|p| name.starts_with(p))
}

fn in_box<const N: usize, const S: usize>(case: &Case<f64, N, S>) -> bool {
    let g = 2.0 / N as f64;
    case.balls.iter().all(|b| b.gamma2 >= g / 8.0)
}

/// The largest absolute component error (in eps) of the movable bodies, per kernel form.
fn measured<const N: usize, const S: usize>(cases: usize, variant: Variant) -> [f64; 3]
where
    Generated: Kernel<f64, N, S> + Kernel<f32, N, S> + Kernel<collision_core::ExactRelaxed, N, S>,
{
    let mut rng = Rng::new(0xB0C5 ^ N as u64);
    let mut worst = [0.0f64; 3];
    let mut done = 0;
    while done < cases {
        let mut case = Regime::Typical.sample::<N, S>(&mut rng);
        if !in_box(&case) {
            continue;
        }
        if variant == Variant::Fixed {
            case.balls[0].inv_mass = 0.0;
        }
        done += 1;
        let body = if variant == Variant::Fixed {
            1..2
        } else {
            0..2
        };
        let range = body.start * (S + N)..body.end * (S + N);
        let err = |computed: Vec<f64>, exact: Vec<Exact>, eps: f64| {
            range
                .clone()
                .map(|k| {
                    let d = Exact::from_float(computed[k]).expect("finite") - &exact[k];
                    d.to_f64().abs() / eps
                })
                .fold(0.0, f64::max)
        };
        let exact = flatten(&exact_result(&case.to_exact()));
        let (nu, balls, states) = (&case.nu, case.ball_refs(), case.state_refs());
        worst[0] = worst[0].max(err(
            flatten(&collide_unchecked(nu, balls, states)),
            exact.clone(),
            f64::EPSILON,
        ));
        worst[1] = worst[1].max(err(
            flatten(&collide_unchecked_fma(nu, balls, states)),
            exact,
            f64::EPSILON,
        ));
        if let Ok(c) = case.to_f32() {
            let r = collide_unchecked(&c.nu, c.ball_refs(), c.state_refs());
            let wide = c.map(|&x| f64::from(x));
            let exact = flatten(&exact_result(&wide.to_exact()));
            let computed = flatten(&r).iter().map(|&x| f64::from(x)).collect();
            worst[2] = worst[2].max(err(computed, exact, f64::from(f32::EPSILON)));
        }
    }
    worst
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let opt = |name: &str| {
        args.iter()
            .position(|a| a == name)
            .and_then(|i| args.get(i + 1))
    };
    let cases: usize = opt("--cases").and_then(|s| s.parse().ok()).unwrap_or(20000);
    let split: usize = opt("--split").and_then(|s| s.parse().ok()).unwrap_or(4);
    let forms = [
        (Arith::Plain, Format::F64, "f64"),
        (Arith::Fma, Format::F64, "f64 FMA"),
        (Arith::Plain, Format::F32, "f32"),
    ];
    println!("| n | kernel | form | static bound (eps) | bound time | measured max (eps) | bound / measured |");
    println!("|---|---|---|---:|---:|---:|---:|");
    for n in 2..=6 {
        for variant in Variant::ALL {
            let worst =
                collision_core::with_dim!(n, |N, S| measured::<N, S>(cases, variant), panic!());
            for (i, (arith, format, name)) in forms.iter().enumerate() {
                let start = Instant::now();
                let kb = KernelBound::of(n, variant, *arith, *format);
                let ranges: Vec<InputRange> =
                    kb.inputs().iter().map(|x| typical_box(n, x)).collect();
                let pieces: Vec<usize> = kb
                    .inputs()
                    .iter()
                    .map(|x| if is_parameter(x) { split } else { 1 })
                    .collect();
                let bounds = kb.analyse_split(&ranges, &pieces);
                let took = start.elapsed();
                let b = bounds
                    .bodies
                    .iter()
                    .flat_map(|b| b.components())
                    .map(|e| e.error)
                    .fold(0.0, f64::max)
                    / format.epsilon();
                println!(
                    "| {n} | {} | {name} | {b:.1} | {:.2} ms | {:.2} | {:.1}x |",
                    variant.name(),
                    took.as_secs_f64() * 1e3,
                    worst[i],
                    b / worst[i]
                );
            }
        }
    }
    if let Some(dir) = opt("--gappa") {
        std::fs::create_dir_all(dir).expect("gappa directory");
        for variant in Variant::ALL {
            for (arith, format, name) in forms {
                let p = Program::lower(&model::build(2, variant), arith);
                let ranges: Vec<InputRange> = p.inputs.iter().map(|x| typical_box(2, x)).collect();
                let outputs: usize = p
                    .outputs
                    .iter()
                    .map(|o| o.spin.len() + o.velocity.len())
                    .sum();
                let fmt = if format == Format::F32 {
                    "ieee_32"
                } else {
                    "ieee_64"
                };
                let text = gappa::script(&p, fmt, &ranges, &(0..outputs).collect::<Vec<_>>());
                let file = format!("{dir}/{}_{}.g", variant.name(), name.replace(' ', "_"));
                std::fs::write(&file, text).expect("write the script");
                eprintln!("wrote {file}");
            }
        }
    }
}
