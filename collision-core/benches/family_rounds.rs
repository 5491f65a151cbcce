//! The rough-ball family's batch paths beside the no-slip ones, in alternated rounds (every
//! round runs each variant once in turn, so a change of the shared machine's load hits them
//! alike); each figure the median (min-max) over the rounds, ns per contact, CPU time of the
//! calling thread, AVX-512 (or the widest level this CPU runs), one thread.
//!
//! ```sh
//! cargo bench -p collision-core --bench family_rounds -- [--rounds 7] [--dims 2 4 6] [--in-cache]
//! ```
//!
//! `f64`, per-contact ball parameters, on 64 MB of row-major input and output (twice the
//! 32 MB L3), or 512 contacts with `--in-cache` (each sample repeating the call for about
//! 5 ms). Variants (docs/batch.md, "The rough-ball family"):
//!
//! - `free`: `Exec::free` (no-slip) on the blocked batch;
//! - `rough`, `walton`: `Exec::rough_free` under one law for the call, `(0.9, 0.4)` and
//!   `(0.9, 0.2, 0.4)`;
//! - `rough_each`, `walton_each`: `Exec::free_each` with a law per contact (drawn in the
//!   laws' ranges; the kernels are branch-free, so the values do not change the time);
//! - `rows`: `Exec::free_rows` (no-slip) on the row-major arrays;
//! - `rows_rough`, `rows_walton`: `Exec::rough_free_rows` with every law column a single
//!   value (the shared-law kernel);
//! - `rows_rough_each`, `rows_walton_each`: the same with a column per row (the `_each`
//!   kernel, each row's law gathered into the law lanes), the checks of the laws included.

#[path = "support/cases.rs"]
mod cases;
#[path = "support/rounds.rs"]
mod rounds;

use cases::batch;
use collision_core::batch::{
    BatchKernel, Contact, EachLawBatchKernel, Exec, FreeBatch, FreeEachBatch, PairBatch,
    RestitutionLanes, RestitutionRows, RoughBatchKernel, WaltonLanes, WaltonRows, LANES,
};
use collision_core::{Generated, Restitution, Walton};
use rounds::{summary, thread_seconds, RowArrays};
use std::hint::black_box;

const SEED: u64 = 0x6e6f_736c_6970; // "noslip"

/// Row-major input plus output bytes of the out-of-cache call.
const OUT_OF_CACHE_BYTES: usize = 64 << 20;

/// Contacts of the in-cache batch.
const IN_CACHE: usize = 512;

struct Args {
    rounds: usize,
    dims: Vec<usize>,
    in_cache: bool,
}

fn args() -> Args {
    let mut a = Args {
        rounds: 7,
        dims: vec![2, 3, 4, 5, 6],
        in_cache: false,
    };
    let mut it = std::env::args().skip(1).peekable();
    while let Some(x) = it.next() {
        match x.as_str() {
            "--rounds" => a.rounds = it.next().and_then(|v| v.parse().ok()).expect("--rounds K"),
            "--dims" => {
                a.dims.clear();
                while let Some(d) = it.peek().and_then(|v| v.parse().ok()) {
                    a.dims.push(d);
                    it.next();
                }
            }
            "--in-cache" => a.in_cache = true,
            _ => {} // cargo bench passes `--bench`
        }
    }
    a
}

/// `len` laws spread over the family's ranges, a fixed pattern (`k` a golden-ratio walk).
fn laws(len: usize) -> (Vec<Restitution<f64>>, Vec<Walton<f64>>) {
    let u = |k: usize, j: f64| ((k as f64 + j) * 0.618_033_988_749_895).fract();
    let rough = (0..len)
        .map(|k| Restitution::new(u(k, 0.0), 2.0 * u(k, 0.5) - 1.0).expect("in range"))
        .collect();
    let walton = (0..len)
        .map(|k| Walton::new(u(k, 0.0), 2.0 * u(k, 0.3), 2.0 * u(k, 0.5) - 1.0).expect("in range"))
        .collect();
    (rough, walton)
}

fn run_dim<const N: usize, const S: usize>(a: &Args)
where
    Generated: BatchKernel<f64, N, S>
        + RoughBatchKernel<Restitution<f64>, f64, N, S>
        + RoughBatchKernel<Walton<f64>, f64, N, S>
        + EachLawBatchKernel<RestitutionLanes<f64>, f64, N, S>
        + EachLawBatchKernel<WaltonLanes<f64>, f64, N, S>,
{
    let row = 8 * (N + 6 + 4 * (N * N + N));
    let len = if a.in_cache {
        IN_CACHE
    } else {
        (OUT_OF_CACHE_BYTES / row).next_multiple_of(LANES)
    };
    let cases = batch::<N, S>(SEED ^ (N as u64) << 8, len);
    let items: Vec<_> = cases
        .iter()
        .map(|c| {
            let contact = Contact {
                nu: c.nu,
                states: c.states.clone(),
            };
            (contact, c.balls.clone())
        })
        .collect();
    let (rough_laws, walton_laws) = laws(len);
    let blocks: FreeBatch<f64, N, S> = items.iter().cloned().collect();
    let rough_each: FreeEachBatch<f64, N, S, RestitutionLanes<f64>> = items
        .iter()
        .cloned()
        .zip(rough_laws.iter().cloned())
        .collect();
    let walton_each: FreeEachBatch<f64, N, S, WaltonLanes<f64>> = items
        .iter()
        .cloned()
        .zip(walton_laws.iter().cloned())
        .collect();
    let (e, beta): (Vec<f64>, Vec<f64>) = rough_laws.iter().map(|l| (l.e, l.beta)).unzip();
    let (we, (mu, beta0)): (Vec<f64>, (Vec<f64>, Vec<f64>)) =
        walton_laws.iter().map(|l| (l.e, (l.mu, l.beta0))).unzip();
    let mut out = PairBatch::new();
    let mut rows = RowArrays::new(&cases);
    let exec = Exec::auto().serial();
    let rough = Restitution::new(0.9, 0.4).expect("in range");
    let walton = Walton::new(0.9, 0.2, 0.4).expect("in range");
    let names = [
        "free",
        "rough",
        "rough_each",
        "walton",
        "walton_each",
        "rows",
        "rows_rough",
        "rows_rough_each",
        "rows_walton",
        "rows_walton_each",
    ];
    let reps = if a.in_cache {
        (5e-3 / (len as f64 * 5e-9)).ceil() as usize
    } else {
        1
    };
    let mut t: Vec<Vec<f64>> = vec![Vec::new(); names.len()];
    for _ in 0..a.rounds {
        let mut k = 0;
        let mut time = |f: &mut dyn FnMut()| {
            let t0 = thread_seconds();
            for _ in 0..reps {
                f();
            }
            t[k].push((thread_seconds() - t0) * 1e9 / (reps * len) as f64);
            k += 1;
        };
        time(&mut || exec.free(black_box(&blocks), &mut out));
        time(&mut || exec.rough_free(black_box(&rough), black_box(&blocks), &mut out));
        time(&mut || exec.free_each(black_box(&rough_each), &mut out));
        time(&mut || exec.rough_free(black_box(&walton), black_box(&blocks), &mut out));
        time(&mut || exec.free_each(black_box(&walton_each), &mut out));
        time(&mut || {
            let (r, o) = rows.split();
            exec.free_rows::<f64, N, S>(&r, o);
        });
        let shared_rough = RestitutionRows {
            e: &[0.9],
            beta: &[0.4],
        };
        time(&mut || {
            let (r, o) = rows.split();
            let laws = black_box(&shared_rough);
            exec.rough_free_rows::<_, f64, N, S>(laws, &r, o)
                .expect("valid");
        });
        let each_rough = RestitutionRows { e: &e, beta: &beta };
        time(&mut || {
            let (r, o) = rows.split();
            let laws = black_box(&each_rough);
            exec.rough_free_rows::<_, f64, N, S>(laws, &r, o)
                .expect("valid");
        });
        let shared_walton = WaltonRows {
            e: &[0.9],
            mu: &[0.2],
            beta0: &[0.4],
        };
        time(&mut || {
            let (r, o) = rows.split();
            let laws = black_box(&shared_walton);
            exec.rough_free_rows::<_, f64, N, S>(laws, &r, o)
                .expect("valid");
        });
        let each_walton = WaltonRows {
            e: &we,
            mu: &mu,
            beta0: &beta0,
        };
        time(&mut || {
            let (r, o) = rows.split();
            let laws = black_box(&each_walton);
            exec.rough_free_rows::<_, f64, N, S>(laws, &r, o)
                .expect("valid");
        });
    }
    let cells: Vec<String> = t.iter_mut().map(|v| summary(v)).collect();
    if N == a.dims[0] {
        println!("| n | {} |", names.join(" | "));
        println!("|---:|{}", "---:|".repeat(names.len()));
    }
    println!("| {N} | {} |", cells.join(" | "));
}

fn main() {
    let a = args();
    println!(
        "{} rounds, {}, {}, ns per contact, median (min-max), CPU time of one thread",
        a.rounds,
        Exec::auto().isa(),
        if a.in_cache {
            "in cache (512 contacts)"
        } else {
            "64 MB of rows"
        }
    );
    for &n in &a.dims {
        collision_core::with_dim!(n, |N, S| run_dim::<N, S>(&a), ());
    }
}
