//! The batch kernels and the row-major batch path against their memory floors and the
//! scalar kernel, timed in alternated rounds: every round runs each variant once in turn, so
//! a change of the shared machine's load hits them alike, and each variant's figure is the
//! median (min-max) over the rounds, in ns per contact (CPU time of the calling thread,
//! `CLOCK_THREAD_CPUTIME_ID`).
//!
//! ```sh
//! cargo bench -p collision-core --bench batch_rounds -- [--rounds 7] [--dims 2 4 6] [--in-cache]
//! ```
//!
//! `free` with per-contact parameters, `f64`, on [`OUT_OF_CACHE_BYTES`] of input and output
//! (8 times the 32 MB L3), or 512 contacts with `--in-cache` (each sample then repeats the
//! call for about 5 ms). Variants (docs/batch.md, "Out of cache"):
//!
//! - `floor`: one pass over the blocked batch reading every input lane and writing every
//!   output lane (one add per input word), on the widest instruction set;
//! - `floor_aos`: the same work over the per-collision (array of structs) layout;
//! - `scalar`: the generated scalar kernel, one contact at a time, over the per-collision
//!   layout, results stored into a vector;
//! - `read_blocked`, `read_aos`: the sum of every input word of either layout, in address
//!   order (8 accumulators): the same bytes read the same way, a control that the layouts'
//!   memory is alike;
//! - `rows_copy`: the copy floor of row-major arrays (as NumPy holds them): inputs summed,
//!   each body's states copied (`copy_from_slice`) into the outputs;
//! - `rows_steps`: the row-major path before issue 30: chunks of 512 rows gathered
//!   (`fill_from_rows`), run (`Exec::free`) and scattered (`write_rows`);
//! - `rows`: `Exec::free_rows` on the same arrays;
//! - `baseline`, `avx2`, `avx512`: `Exec::free` on one thread at each level this CPU runs.

#[path = "support/cases.rs"]
mod cases;
#[path = "support/rounds.rs"]
mod rounds;

use cases::{batch, Case};
use collision_core::batch::{
    BatchKernel, Contact, Exec, FreeBatch, FreeLanes, Isa, PairBatch, StateLanes, LANES,
};
use collision_core::{BodyState, Generated, Kernel};
use rounds::{summary, thread_seconds, RowArrays};
use std::hint::black_box;

const SEED: u64 = 0x6e6f_736c_6970; // "noslip"

/// Input plus output bytes of the out-of-cache batch.
const OUT_OF_CACHE_BYTES: usize = 256 << 20;

/// Contacts of the in-cache batch.
const IN_CACHE: usize = 512;

/// Bytes read and written per contact: normal, two balls, two states in; two states out.
fn bytes_per_contact(n: usize, s: usize) -> usize {
    8 * (n + 6 + 4 * (n + s))
}

/// The floor's work on one block: every input lane read, every output lane written.
#[inline(always)]
fn floor_block<const N: usize, const S: usize>(
    b: &FreeLanes<f64, N, S>,
    o: &mut [StateLanes<f64, N, S>; 2],
) {
    for l in 0..LANES {
        let mut x = 0.0;
        for nu in &b.contact.nu {
            x += nu[l];
        }
        for ball in &b.balls {
            x += ball.inv_mass[l] + ball.radius[l] + ball.gamma2[l];
        }
        for (state, out) in b.contact.states.iter().zip(o.iter_mut()) {
            for (a, y) in state.spin.iter().zip(out.spin.iter_mut()) {
                y[l] = a[l] + x;
            }
            for (a, y) in state.velocity.iter().zip(out.velocity.iter_mut()) {
                y[l] = a[l] + x;
            }
        }
    }
}

/// # Safety
/// The CPU must have AVX-512F.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx2,fma")]
unsafe fn floor_avx512<const N: usize, const S: usize>(
    blocks: &[FreeLanes<f64, N, S>],
    out: &mut [[StateLanes<f64, N, S>; 2]],
) {
    for (b, o) in blocks.iter().zip(out.iter_mut()) {
        floor_block(b, o);
    }
}

#[inline(never)]
fn floor<const N: usize, const S: usize>(
    blocks: &[FreeLanes<f64, N, S>],
    out: &mut [[StateLanes<f64, N, S>; 2]],
) {
    #[cfg(target_arch = "x86_64")]
    if Isa::Avx512.is_available() {
        // SAFETY: AVX-512F was detected just now.
        return unsafe { floor_avx512(black_box(blocks), out) };
    }
    for (b, o) in black_box(blocks).iter().zip(out.iter_mut()) {
        floor_block(b, o);
    }
}

/// The floor's work on the per-collision layout: every input read, every output written.
#[inline(never)]
fn floor_aos<const N: usize, const S: usize>(
    cases: &[Case<N, S>],
    out: &mut [[BodyState<f64, N, S>; 2]],
) {
    for (c, o) in black_box(cases).iter().zip(out.iter_mut()) {
        let mut x: f64 = c.nu.iter().sum();
        for b in &c.balls {
            x += b.inv_mass + b.radius + b.gamma2;
        }
        for (s, o) in c.states.iter().zip(o.iter_mut()) {
            for (a, y) in s.spin.iter().zip(o.spin.iter_mut()) {
                *y = a + x;
            }
            for (a, y) in s.velocity.iter().zip(o.velocity.iter_mut()) {
                *y = a + x;
            }
        }
    }
}

/// Any slice of plain `f64` structs as its words.
fn words<B>(x: &[B]) -> &[f64] {
    // SAFETY: only called on types made of f64 fields (no padding).
    unsafe { std::slice::from_raw_parts(x.as_ptr().cast(), std::mem::size_of_val(x) / 8) }
}

/// The sum of `w` with eight accumulators (vectorised: reading costs more than adding).
#[inline(never)]
fn flat_sum(w: &[f64]) -> f64 {
    let mut acc = [0.0; 8];
    let chunks = black_box(w).chunks_exact(8);
    let rest: f64 = chunks.remainder().iter().sum();
    for c in chunks {
        for (a, x) in acc.iter_mut().zip(c) {
            *a += x;
        }
    }
    acc.iter().sum::<f64>() + rest
}

/// The rows before `Exec::free_rows`: chunks of 512 rows gathered, run and scattered.
#[inline(never)]
fn rows_steps<const N: usize, const S: usize>(a: &mut RowArrays)
where
    Generated: BatchKernel<f64, N, S>,
{
    let (rows, mut out) = a.split();
    let len = rows.len::<N>();
    let (mut batch, mut pairs) = (FreeBatch::<f64, N, S>::new(), PairBatch::new());
    let exec = Exec::auto().serial();
    for start in (0..len).step_by(512) {
        let end = (start + 512).min(len);
        batch.fill_from_rows(&rows, start..end);
        exec.free(&batch, &mut pairs);
        let [o1, o2] = &mut out;
        pairs.write_rows([o1.slice::<N>(start..end), o2.slice::<N>(start..end)]);
    }
}

#[inline(never)]
fn rows_fused<const N: usize, const S: usize>(a: &mut RowArrays)
where
    Generated: BatchKernel<f64, N, S>,
{
    let (rows, out) = a.split();
    Exec::auto().serial().free_rows::<f64, N, S>(&rows, out);
}

/// The copy floor on the rows: inputs summed, each body's states copied to the outputs.
#[inline(never)]
fn rows_copy(a: &mut RowArrays) -> f64 {
    let mut x = flat_sum(&a.nu);
    for p in a.params.iter().flatten() {
        x += flat_sum(p);
    }
    for b in 0..2 {
        a.out[b][0].copy_from_slice(&a.spin[b]);
        a.out[b][1].copy_from_slice(&a.velocity[b]);
    }
    x
}

#[inline(never)]
fn scalar<const N: usize, const S: usize>(
    cases: &[Case<N, S>],
    out: &mut [[BodyState<f64, N, S>; 2]],
) where
    Generated: Kernel<f64, N, S>,
{
    for (c, o) in black_box(cases).iter().zip(out.iter_mut()) {
        let [b1, b2] = &c.balls;
        let [s1, s2] = &c.states;
        *o = Generated::free(&c.nu, b1, b2, s1, s2);
    }
}

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

fn run_dim<const N: usize, const S: usize>(a: &Args)
where
    Generated: Kernel<f64, N, S> + BatchKernel<f64, N, S>,
{
    let len = if a.in_cache {
        IN_CACHE
    } else {
        (OUT_OF_CACHE_BYTES / bytes_per_contact(N, S)).next_multiple_of(LANES)
    };
    let cases = batch::<N, S>(SEED ^ (N as u64) << 8, len);
    let batch: FreeBatch<f64, N, S> = cases
        .iter()
        .map(|c| {
            let contact = Contact {
                nu: c.nu,
                states: c.states.clone(),
            };
            (contact, c.balls.clone())
        })
        .collect();
    let mut out: PairBatch<f64, N, S> = PairBatch::new();
    Exec::auto().serial().free(&batch, &mut out);
    let mut scalar_out = vec![[BodyState::zero(), BodyState::zero()]; len];
    let mut row_arrays = RowArrays::new(&cases);
    let isas: Vec<Isa> = Isa::available().collect();
    let mut names: Vec<String> = [
        "floor",
        "floor_aos",
        "scalar",
        "read_blocked",
        "read_aos",
        "rows_copy",
        "rows_steps",
        "rows",
    ]
    .map(String::from)
    .to_vec();
    names.extend(isas.iter().map(|i| i.name().to_string()));
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
        time(&mut || floor(batch.blocks(), out.blocks_mut()));
        time(&mut || floor_aos(&cases, &mut scalar_out));
        time(&mut || scalar(&cases, &mut scalar_out));
        time(&mut || {
            black_box(flat_sum(words(batch.blocks())));
        });
        time(&mut || {
            black_box(flat_sum(words(&cases)));
        });
        time(&mut || {
            black_box(rows_copy(&mut row_arrays));
        });
        time(&mut || rows_steps::<N, S>(&mut row_arrays));
        time(&mut || rows_fused::<N, S>(&mut row_arrays));
        for &isa in &isas {
            let exec = Exec::auto().with_isa(isa).expect("available").serial();
            time(&mut || exec.free(black_box(&batch), &mut out));
        }
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
        "{} rounds, {}, ns per contact, median (min-max), CPU time of one thread",
        a.rounds,
        if a.in_cache {
            "in cache (512 contacts)"
        } else {
            "out of cache (256 MB)"
        }
    );
    for &n in &a.dims {
        collision_core::with_dim!(n, |N, S| run_dim::<N, S>(&a), ());
    }
}
