//! The rough-ball family's `fixed` kernels (body 1 immovable) from row-major arrays:
//! `Exec::rough_fixed_rows` against the per-row loop a caller would otherwise write (each row
//! read into a `BodyState`, the scalar `rough::fixed` kernel, the result written back as a full
//! skew matrix), in alternated rounds (every round runs each variant once in turn, so a change
//! of the shared machine's load hits them alike); each figure the median (min-max) over the
//! rounds, ns per contact, CPU time of the calling thread, the widest level this CPU runs, one
//! thread, 512 contacts in cache (each sample repeating the call for about 5 ms).
//!
//! ```sh
//! cargo bench -p collision-core --bench fixed_rows_rounds -- [--rounds 7] [--dims 2 3 6]
//! ```
//!
//! Variants: `scalar_rough`: the per-row loop under `(0.9, 0.4)`; `rows_rough`:
//! `rough_fixed_rows` with every law column one value (the shared-law kernel);
//! `rows_rough_each`: a law per row (the `_each` kernel); `rows_walton`, `rows_walton_each`:
//! the same for `(0.9, 0.2, 0.4)` and per-row Walton laws. The laws' checks are included.

#[path = "support/cases.rs"]
mod cases;
// `RowArrays::split` (the free rows' view) is not used here.
#[allow(dead_code)]
#[path = "support/rounds.rs"]
mod rounds;

use cases::batch;
use collision_core::batch::{
    BallRows, EachLawBatchKernel, Exec, FixedRows, RestitutionLanes, RestitutionRows,
    RoughBatchKernel, StateRows, StateRowsMut, WaltonLanes, WaltonRows,
};
use collision_core::kernels::RoughKernel;
use collision_core::{BodyState, Generated, Restitution, Walton};
use rounds::{summary, thread_seconds, RowArrays};
use std::hint::black_box;

const SEED: u64 = 0x0066_6978_6564; // "fixed"

/// Contacts of the in-cache call.
const LEN: usize = 512;

fn args() -> (usize, Vec<usize>) {
    let (mut rounds, mut dims) = (7, vec![2, 3, 4, 5, 6]);
    let mut it = std::env::args().skip(1).peekable();
    while let Some(x) = it.next() {
        match x.as_str() {
            "--rounds" => rounds = it.next().and_then(|v| v.parse().ok()).expect("--rounds K"),
            "--dims" => {
                dims.clear();
                while let Some(d) = it.peek().and_then(|v| v.parse().ok()) {
                    dims.push(d);
                    it.next();
                }
            }
            _ => {} // cargo bench passes `--bench`
        }
    }
    (rounds, dims)
}

/// The per-row loop: row `i` read, `rough::fixed` under `law`, written back.
fn scalar_rows<const N: usize, const S: usize>(
    rows: &FixedRows<'_, f64>,
    law: &Restitution<f64>,
    out: &mut StateRowsMut<'_, f64>,
) where
    Generated: RoughKernel<f64, N, S>,
{
    let pairs: Vec<(usize, usize)> = collision_core::skew_pairs(N).collect();
    let state = |s: &StateRows<'_, f64>, i: usize| BodyState::<f64, N, S> {
        spin: std::array::from_fn(|k| s.spin[i * N * N + pairs[k].0 * N + pairs[k].1]),
        velocity: std::array::from_fn(|k| s.velocity[i * N + k]),
    };
    for i in 0..rows.nu.len() / N {
        let nu: [f64; N] = std::array::from_fn(|k| rows.nu[i * N + k]);
        let b = &rows.ball2;
        let ball2 = collision_core::Ball {
            inv_mass: b.inv_mass[i],
            radius: b.radius[i],
            gamma2: b.gamma2[i],
        };
        let (s1, s2) = (state(&rows.states[0], i), state(&rows.states[1], i));
        let after = Generated::rough_fixed(&nu, &rows.radius1[i], &ball2, law, &s1, &s2);
        let m = &mut out.spin[i * N * N..(i + 1) * N * N];
        for r in 0..N {
            m[r * N + r] = 0.0;
        }
        for (x, &(r, c)) in after.spin.iter().zip(&pairs) {
            m[r * N + c] = *x;
            m[c * N + r] = 0.0 - x;
        }
        out.velocity[i * N..(i + 1) * N].copy_from_slice(&after.velocity);
    }
}

fn run_dim<const N: usize, const S: usize>(rounds: usize, first: bool)
where
    Generated: RoughKernel<f64, N, S>
        + RoughBatchKernel<Restitution<f64>, f64, N, S>
        + RoughBatchKernel<Walton<f64>, f64, N, S>
        + EachLawBatchKernel<RestitutionLanes<f64>, f64, N, S>
        + EachLawBatchKernel<WaltonLanes<f64>, f64, N, S>,
{
    let cases = batch::<N, S>(SEED ^ (N as u64) << 8, LEN);
    let mut a = RowArrays::new(&cases);
    let u = |k: usize, j: f64| ((k as f64 + j) * 0.618_033_988_749_895).fract();
    let e: Vec<f64> = (0..LEN).map(|k| u(k, 0.0)).collect();
    let beta: Vec<f64> = (0..LEN).map(|k| 2.0 * u(k, 0.5) - 1.0).collect();
    let mu: Vec<f64> = (0..LEN).map(|k| 2.0 * u(k, 0.3)).collect();
    let law = Restitution::new(0.9, 0.4).expect("in range");
    let exec = Exec::auto().serial();
    let names = [
        "scalar_rough",
        "rows_rough",
        "rows_rough_each",
        "rows_walton",
        "rows_walton_each",
    ];
    let reps = (5e-3 / (LEN as f64 * 5e-9)).ceil() as usize;
    let mut t: Vec<Vec<f64>> = vec![Vec::new(); names.len()];
    let [out, _] = &mut a.out;
    let [spin_out, velocity_out] = out;
    for _ in 0..rounds {
        let rows = FixedRows {
            nu: &a.nu,
            states: [0, 1].map(|b| StateRows {
                spin: &a.spin[b],
                velocity: &a.velocity[b],
            }),
            radius1: &a.params[0][1],
            ball2: BallRows {
                inv_mass: &a.params[1][0],
                radius: &a.params[1][1],
                gamma2: &a.params[1][2],
            },
        };
        let mut k = 0;
        let mut time = |f: &mut dyn FnMut(StateRowsMut<'_, f64>)| {
            let t0 = thread_seconds();
            for _ in 0..reps {
                f(StateRowsMut {
                    spin: spin_out,
                    velocity: velocity_out,
                });
            }
            t[k].push((thread_seconds() - t0) * 1e9 / (reps * LEN) as f64);
            k += 1;
        };
        time(&mut |mut o| scalar_rows::<N, S>(black_box(&rows), black_box(&law), &mut o));
        let shared = RestitutionRows {
            e: &[0.9],
            beta: &[0.4],
        };
        time(&mut |o| {
            exec.rough_fixed_rows::<_, f64, N, S>(black_box(&shared), &rows, o)
                .expect("valid")
        });
        let each = RestitutionRows { e: &e, beta: &beta };
        time(&mut |o| {
            exec.rough_fixed_rows::<_, f64, N, S>(black_box(&each), &rows, o)
                .expect("valid")
        });
        let shared = WaltonRows {
            e: &[0.9],
            mu: &[0.2],
            beta0: &[0.4],
        };
        time(&mut |o| {
            exec.rough_fixed_rows::<_, f64, N, S>(black_box(&shared), &rows, o)
                .expect("valid")
        });
        let each = WaltonRows {
            e: &e,
            mu: &mu,
            beta0: &beta,
        };
        time(&mut |o| {
            exec.rough_fixed_rows::<_, f64, N, S>(black_box(&each), &rows, o)
                .expect("valid")
        });
    }
    let cells: Vec<String> = t.iter_mut().map(|v| summary(v)).collect();
    if first {
        println!("| n | {} |", names.join(" | "));
        println!("|---:|{}", "---:|".repeat(names.len()));
    }
    println!("| {N} | {} |", cells.join(" | "));
}

fn main() {
    let (rounds, dims) = args();
    println!(
        "{rounds} rounds, {}, {LEN} contacts in cache, ns per contact, median (min-max), CPU \
         time of one thread",
        Exec::auto().isa()
    );
    for (j, &n) in dims.iter().enumerate() {
        collision_core::with_dim!(n, |N, S| run_dim::<N, S>(rounds, j == 0), ());
    }
}
