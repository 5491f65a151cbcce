//! Seconds to place `N` balls against `N`: `cargo run --release -p noslip-sim --example
//! placement -- [MAX_N [DIM [PLACEMENT [FRACTION]]]]` times `setup()` (the range checks and
//! the placement of `noslip_sim::setup`) for disks (2D) and spheres (3D) of radius 1/2 in a
//! periodic cube sized for packing fractions 0.1 to 0.4, random and lattice placement, `N`
//! from `10^4` up to `MAX_N` (default `10^6`) by factors of 10, and prints one line per run:
//! dimension, placement, fraction, `N`, seconds of wall clock, microseconds per ball. `DIM`,
//! `PLACEMENT` and `FRACTION` keep only the runs with that dimension, placement and fraction
//! (`-- 1000000 3 random 0.3` times that one case); `-` keeps all. Each line also gives the
//! seconds of this thread's CPU time (`/proc/thread-self/schedstat`, user and system; steadier
//! than the wall clock on a shared machine) and a hash of every placed ball (FNV-1a 64 over the
//! bits of its species, centre, velocity and spin, in order), which two builds must share if
//! they place the same bits. Random placement
//! is skipped beyond random sequential saturation (`noslip_sim::setup::saturation`: 0.54 in
//! 2D, 0.39 in 3D), where it would spend its whole attempt budget (`AVERAGE_ATTEMPTS` per
//! ball) before refusing; an error prints its start instead of a time.

use noslip_scene::Scene;
use noslip_sim::setup::{saturation, setup};
use std::time::Instant;

/// Large arrays on 2 MiB pages, as the `noslip` command has them (`noslip_sim::huge_pages`).
#[global_allocator]
static ALLOC: noslip_sim::huge_pages::HugePages = noslip_sim::huge_pages::HugePages;

/// The scene text: `count` balls of radius 1/2 at `fraction` of a periodic cube in `dim`
/// dimensions (side `(count V_n / 2^n / fraction)^(1/n)`, written with 12 decimals).
fn scene(dim: usize, count: usize, fraction: f64, placement: &str) -> String {
    let ball = match dim {
        2 => std::f64::consts::PI / 4.0,
        _ => std::f64::consts::PI / 6.0,
    };
    let side = (count as f64 * ball / fraction).powf(1.0 / dim as f64);
    let axes = vec![format!("\"{side:.12}\""); dim].join(", ");
    let periodic = vec!["\"periodic\""; dim].join(", ");
    format!(
        "dim = {dim}\n[box]\nsize = [{axes}]\nboundary = [{periodic}]\n\
         [[species]]\nmass = 1\nradius = \"1/2\"\ncount = {count}\n\
         [random]\nseed = 1\nplacement = \"{placement}\"\n"
    )
}

/// Seconds of CPU time this thread has run (Linux; 0 elsewhere).
fn cpu_seconds() -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .map_or(0.0, |ns| ns * 1e-9)
}

/// FNV-1a 64 of `words`' little-endian bytes, continuing from `hash`.
fn fnv1a(mut hash: u64, words: impl IntoIterator<Item = u64>) -> u64 {
    for w in words {
        for byte in w.to_le_bytes() {
            hash = (hash ^ u64::from(byte)).wrapping_mul(0x100_0000_01b3);
        }
    }
    hash
}

/// Wall and CPU seconds of `setup()` for the scene `text`, and the hash of what it placed.
fn time<const N: usize, const S: usize>(text: &str) -> Result<(f64, f64, u64), String> {
    let scene = Scene::from_toml(text, "placement").map_err(|e| e.to_string())?;
    let (start, cpu) = (Instant::now(), cpu_seconds());
    let placed = setup::<N, S>(&scene)?;
    let seconds = start.elapsed().as_secs_f64();
    let cpu = cpu_seconds() - cpu;
    assert_eq!(placed.bodies.len(), scene.ball_count());
    let hash = placed.bodies.iter().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        let h = fnv1a(h, [b.species as u64]);
        let h = fnv1a(h, bits(&b.position));
        let h = fnv1a(h, bits(&b.state.velocity));
        fnv1a(h, bits(&b.state.spin))
    });
    Ok((seconds, cpu, hash))
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let max: usize = args
        .get(1)
        .map_or(1_000_000, |s| s.parse().expect("MAX_N: a whole number"));
    // A filter: keep a run if the argument is absent, `-`, or equal to the run's value.
    let keep = |k: usize, value: &str| args.get(k).is_none_or(|a| a == "-" || a == value);
    println!("dim placement fraction N seconds us/ball cpu_seconds hash");
    for dim in [2, 3] {
        for placement in ["random", "lattice"] {
            for fraction in [0.1, 0.2, 0.3, 0.4] {
                if !keep(2, &dim.to_string())
                    || !keep(3, placement)
                    || !keep(4, &fraction.to_string())
                {
                    continue;
                }
                if placement == "random" && fraction > saturation(dim) {
                    println!("{dim} {placement} {fraction} - beyond saturation");
                    continue;
                }
                let mut count = 10_000;
                while count <= max {
                    let text = scene(dim, count, fraction, placement);
                    let result = match dim {
                        2 => time::<2, 1>(&text),
                        _ => time::<3, 3>(&text),
                    };
                    match result {
                        Ok((s, cpu, hash)) => println!(
                            "{dim} {placement} {fraction} {count} {s:.3} {:.2} {cpu:.3} {hash:016x}",
                            s * 1e6 / count as f64
                        ),
                        Err(e) => {
                            let short: String = e.chars().take(90).collect();
                            println!("{dim} {placement} {fraction} {count} - {short}");
                        }
                    }
                    count *= 10;
                }
            }
        }
    }
}
