//! What this host's memory costs the event loop: a load that waits for the previous one, a
//! load whose address is known ahead, and memory touched for the first time.
//!
//! ```sh
//! cargo run --release -p noslip-sim --example memory_floor -- [--mib 1,8,64,800] [--rounds 3]
//! ```
//!
//! For each working set of `MIB` MiB (on 2 MiB pages, as the `noslip` command allocates;
//! `noslip_sim::huge_pages`), in rounds, ns per 64-byte line:
//!
//! - `chase`: loads along one random cycle through every line of the set, each address read
//!   from the line before (nothing overlaps: the latency of a miss). An event's chain (the
//!   calendar gives the ball, the ball's record its home and cell, the cell its neighbours'
//!   places, the places their records) is such a chain where nothing was looked ahead.
//! - `independent`: loads of random lines whose addresses are known in advance (a list), so
//!   the core overlaps as many misses as it can track: the cost per line of the memory
//!   traffic alone, the floor of anything that knows its addresses early enough.
//! - `pair` and `straddle`: the same, but each address is a random 128-byte block's two
//!   lines (`pair`) or the last line of one block and the first of the next (`straddle`),
//!   both loaded; ns per *two* lines. A record of more than 64 bytes, or one of 64 bytes
//!   not on a line's start, is such a pair: this asks whether its second line costs as
//!   much as a line of its own (the core's adjacent-line prefetch may fetch it with the
//!   first).
//!
//! and, per working set, `fresh`: ms per MiB to map new memory and write it once (the
//! kernel clears each new page at its first write), what every byte a run allocates costs
//! before it holds anything.
//!
//! The figures for one host are in docs/benchmarks.md ("The start at `10^6` balls"; `pair`
//! and `straddle`: "A record's second line", session 58).

use std::hint::black_box;
use std::time::Instant;

#[path = "support/args.rs"]
mod args;
use args::Cli;

/// Large arrays on 2 MiB pages, as the `noslip` command has them (`noslip_sim::huge_pages`).
#[global_allocator]
static ALLOC: noslip_sim::huge_pages::HugePages = noslip_sim::huge_pages::HugePages;

/// `u64`s in a cache line.
const LINE: usize = 8;

/// Loads timed per figure and round.
const LOADS: usize = 4_000_000;

/// xorshift64: the next of a fixed sequence (the addresses need no better randomness).
fn next(state: &mut u64) -> u64 {
    *state ^= *state << 13;
    *state ^= *state >> 7;
    *state ^= *state << 17;
    *state
}

/// The working set's lines linked into one random cycle: line `k`'s first word is the
/// index (in words) of the next line's.
fn cycle(words: &mut [u64], state: &mut u64) {
    let lines = words.len() / LINE;
    let mut order: Vec<usize> = (0..lines).collect();
    for k in (1..lines).rev() {
        order.swap(k, next(state) as usize % (k + 1));
    }
    for k in 0..lines {
        words[order[k] * LINE] = (order[(k + 1) % lines] * LINE) as u64;
    }
}

/// ns per line of the chase along the cycle.
fn chase(words: &[u64]) -> f64 {
    let start = Instant::now();
    let mut at = 0u64;
    for _ in 0..LOADS {
        at = words[at as usize];
    }
    black_box(at);
    start.elapsed().as_secs_f64() * 1e9 / LOADS as f64
}

/// ns per line of the loads at the listed word indices.
fn independent(words: &[u64], at: &[usize]) -> f64 {
    let start = Instant::now();
    let sum = at.iter().fold(0u64, |s, &i| s.wrapping_add(words[i]));
    black_box(sum);
    start.elapsed().as_secs_f64() * 1e9 / at.len() as f64
}

/// ms per MiB to map `mib` MiB of new memory (on 2 MiB pages where the system grants
/// them, as the allocator asks) and write it once; unmapped after, so that every call gets
/// pages never touched (an allocator could hand back memory it had freed).
#[cfg(target_os = "linux")]
fn fresh(mib: usize) -> f64 {
    let bytes = mib << 20;
    let start = Instant::now();
    // SAFETY: a private anonymous mapping of `bytes`, written within its bounds through a
    // slice of it and unmapped once, after its last use.
    unsafe {
        let p = libc::mmap(
            std::ptr::null_mut(),
            bytes,
            libc::PROT_READ | libc::PROT_WRITE,
            libc::MAP_PRIVATE | libc::MAP_ANONYMOUS,
            -1,
            0,
        );
        assert!(p != libc::MAP_FAILED, "mmap of {mib} MiB failed");
        libc::madvise(p, bytes, libc::MADV_HUGEPAGE);
        let words = std::slice::from_raw_parts_mut(p.cast::<u64>(), bytes / 8);
        words.fill(1);
        black_box(&words);
        let ms = start.elapsed().as_secs_f64() * 1e3;
        libc::munmap(p, bytes);
        ms / mib as f64
    }
}

/// ms per MiB to allocate `mib` MiB and write it once (the allocator may reuse memory).
#[cfg(not(target_os = "linux"))]
fn fresh(mib: usize) -> f64 {
    let start = Instant::now();
    let words = vec![1u64; mib << 17];
    black_box(&words);
    start.elapsed().as_secs_f64() * 1e3 / mib as f64
}

const CLI: Cli = Cli {
    name: "memory_floor",
    usage: "usage: memory_floor [--mib 1,8,64,800] [--rounds 3]",
};

fn main() {
    let (mut sizes, mut rounds) = (vec![1, 8, 64, 800], 3);
    let args: Vec<String> = std::env::args().skip(1).collect();
    for pair in args.chunks(2) {
        let (flag, value) = (pair[0].as_str(), pair.get(1));
        match flag {
            "--mib" => sizes = CLI.list(flag, value),
            "--rounds" => rounds = CLI.list(flag, value)[0],
            _ => CLI.refuse(&format!("unknown argument {flag:?}")),
        }
    }
    if sizes.contains(&0) || rounds == 0 {
        CLI.refuse("--mib and --rounds must be at least 1");
    }
    println!(
        "    MiB  round   chase ns/line  independent ns/line  pair ns/2 lines  \
         straddle ns/2 lines  fresh ms/MiB"
    );
    let mut state = 0x6e6f_736c_6970u64;
    for &mib in &sizes {
        let mut words = vec![0u64; mib << 17];
        cycle(&mut words, &mut state);
        let lines = words.len() / LINE;
        let at: Vec<usize> = (0..LOADS)
            .map(|_| (next(&mut state) as usize % lines) * LINE)
            .collect();
        // Two lines an address: a block's (2k, 2k + 1), or across blocks (2k + 1, 2k + 2).
        let blocks = lines / 2;
        let two_lines = |state: &mut u64, first: usize| -> Vec<usize> {
            (0..LOADS / 2)
                .flat_map(|_| {
                    let line = (2 * (next(state) as usize % (blocks - 1)) + first) * LINE;
                    [line, line + LINE]
                })
                .collect()
        };
        let (pairs, straddles) = (two_lines(&mut state, 0), two_lines(&mut state, 1));
        for round in 1..=rounds {
            let (c, i) = (chase(&words), independent(&words, &at));
            // `independent` gives ns a load; two loads an address.
            let (p, s) = (
                2.0 * independent(&words, &pairs),
                2.0 * independent(&words, &straddles),
            );
            let f = fresh(mib);
            println!("{mib:7} {round:6} {c:15.1} {i:20.1} {p:16.1} {s:20.1} {f:13.2}");
        }
    }
}
