//! Contacts per second of the event loop on hard-ball gases built here, against the number of
//! balls `N` and the packing fraction `phi` (issue 15), in 2 to 6 dimensions:
//!
//! ```text
//! cargo run --release -p noslip-sim --example event_rate -- \
//!     [--dims 2,3] [--balls 100,1000,10000,100000] [--phi 0.1,0.2,0.3,0.4] \
//!     [--runs 3] [--contacts C] [--warm W] [--smooth] [--seed S] [--lists SKIN]
//! ```
//!
//! Each gas: `N` balls of radius 1/2 (contact distance 1, mass 1, uniform density) in a
//! periodic cube of side `L = (N V_1 / phi)^(1/n)`, `V_1` the volume of one ball. They start on
//! a random subset of the `m^n` sites of a cubic lattice (`m = ceil(N^(1/n))`, spacing `L / m`,
//! which must exceed 1: the densest packing reached this way is `V_1 / 1^n` per site, 0.785
//! in 2D and 0.524 in 3D), with velocity and spin components uniform in `[-1, 1]` (mean
//! velocity removed). The gas is melted by `W` contacts (default `max(2 N, 10^5)`), then
//! timed over `runs` stretches of `C` contacts each (default `max(N, 2 10^5)`); printed: the
//! median (and min, max) of contacts per second of this thread's CPU time
//! (`/proc/thread-self/schedstat` on Linux, steadier than the wall clock on a shared machine;
//! the wall clock elsewhere), its inverse in µs per contact, the cell crossings per contact, the build time and the
//! stale ball-ball events per contact (a partner's contact came first: a full rescan each).
//! `--smooth` makes the ball-ball contacts smooth (specular, as in hard-sphere codes); the
//! default is no-slip, through the generic generated kernels. `--lists SKIN` runs the list
//! engine (`noslip_sim::ListSimulation`, shells of radius `SKIN` contact distances) instead of
//! the cell engine; its crossings column counts the shells drawn again.

use collision_core::{Ball, BodyState, Generated, Kernel};
use noslip_sim::{
    Body, ContactKind, GenericKernels, ListSimulation, Setup, Simulation, Step, Table,
};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::time::Instant;

#[path = "support/args.rs"]
mod args;
use args::Cli;

/// Large arrays on 2 MiB pages, as the `noslip` command has them (`noslip_sim::huge_pages`).
#[global_allocator]
static ALLOC: noslip_sim::huge_pages::HugePages = noslip_sim::huge_pages::HugePages;

/// Seconds of CPU time this thread has run (Linux), or of wall clock since `start`.
fn seconds(start: &Instant) -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .map_or_else(|| start.elapsed().as_secs_f64(), |ns| ns * 1e-9)
}

/// The volume of a ball of radius 1/2 in R^n.
fn ball_volume(n: usize) -> f64 {
    // V_n(r) = pi^(n/2) r^n / Gamma(n/2 + 1).
    let r: f64 = 0.5;
    let gamma_half = |k: usize| -> f64 {
        // Gamma(k/2) for k >= 1.
        if k % 2 == 0 {
            (1..k / 2).map(|i| i as f64).product()
        } else {
            let mut g = std::f64::consts::PI.sqrt();
            let mut x = 0.5;
            while x < k as f64 / 2.0 - 0.25 {
                g *= x;
                x += 1.0;
            }
            g
        }
    };
    std::f64::consts::PI.powf(n as f64 / 2.0) * r.powi(n as i32) / gamma_half(n + 2)
}

/// The gas of `balls` balls at packing fraction `phi`, or why it cannot be built.
fn gas<const N: usize, const S: usize>(
    balls: usize,
    phi: f64,
    smooth: bool,
    seed: u64,
) -> Result<Setup<N, S>, String> {
    let side = (balls as f64 * ball_volume(N) / phi).powf(1.0 / N as f64);
    let mut m = (balls as f64).powf(1.0 / N as f64).round() as usize;
    while m.pow(N as u32) < balls {
        m += 1;
    }
    let spacing = side / m as f64;
    if spacing <= 1.0 {
        return Err(format!(
            "packing fraction {phi} with {balls} balls in {N}D: lattice spacing {spacing:.4} <= 1"
        ));
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let sites = m.pow(N as u32);
    // A random subset of the sites: a partial Fisher-Yates shuffle.
    let mut order: Vec<usize> = (0..sites).collect();
    for i in 0..balls {
        let j = rng.random_range(i..sites);
        order.swap(i, j);
    }
    let mut bodies: Vec<Body<N, S>> = order[..balls]
        .iter()
        .map(|&site| {
            let mut rest = site;
            let position = std::array::from_fn(|_| {
                let c = rest % m;
                rest /= m;
                (c as f64 + 0.5) * spacing
            });
            Body {
                species: 0,
                position,
                state: BodyState {
                    spin: std::array::from_fn(|_| rng.random_range(-1.0..1.0)),
                    velocity: std::array::from_fn(|_| rng.random_range(-1.0..1.0)),
                },
            }
        })
        .collect();
    let mean: [f64; N] = std::array::from_fn(|k| {
        bodies.iter().map(|b| b.state.velocity[k]).sum::<f64>() / balls as f64
    });
    for b in &mut bodies {
        for (u, m) in b.state.velocity.iter_mut().zip(&mean) {
            *u -= m;
        }
    }
    let species = Ball {
        inv_mass: 1.0,
        radius: 0.5,
        gamma2: 2.0 / (N as f64 + 2.0),
    };
    let mut table = Table::boxed();
    if smooth {
        table.ball_contact = ContactKind::Smooth;
    }
    Ok(Setup {
        size: [side; N],
        periodic: [true; N],
        species: vec![species],
        obstacles: Vec::new(),
        bodies,
        orientation: false,
        table,
    })
}

/// What one gas measured.
struct Rates {
    /// Contacts per CPU second, one per run, sorted.
    rates: Vec<f64>,
    /// Cell crossings per contact over the timed runs.
    crossings: f64,
    /// Stale ball-ball events (a full rescan each) per contact over the timed runs.
    stale: f64,
    /// Seconds to build the simulation (placement and first predictions).
    build: f64,
}

/// What the measurement asks of an engine.
trait Engine<const N: usize, const S: usize> {
    fn step(&mut self) -> Step<N, S>;
    /// Cell crossings (the cell engine) or shells drawn again (the list engine).
    fn moves(&self) -> u64;
    fn stale(&self) -> u64;
}

impl<const N: usize, const S: usize> Engine<N, S> for Simulation<N, S, GenericKernels<f64>>
where
    Generated: Kernel<f64, N, S>,
{
    fn step(&mut self) -> Step<N, S> {
        Simulation::step(self, f64::INFINITY)
    }
    fn moves(&self) -> u64 {
        self.crossings()
    }
    fn stale(&self) -> u64 {
        self.stale_events()
    }
}

impl<const N: usize, const S: usize> Engine<N, S> for ListSimulation<N, S, GenericKernels<f64>>
where
    Generated: Kernel<f64, N, S>,
{
    fn step(&mut self) -> Step<N, S> {
        ListSimulation::step(self, f64::INFINITY)
    }
    fn moves(&self) -> u64 {
        self.redraws()
    }
    fn stale(&self) -> u64 {
        self.stale_events()
    }
}

/// Steps `sim` through `contacts` contacts; false if it stopped early.
fn advance<const N: usize, const S: usize>(sim: &mut impl Engine<N, S>, contacts: u64) -> bool {
    let mut done = 0;
    while done < contacts {
        match sim.step() {
            Step::Contact(_) => done += 1,
            Step::Quiet { .. } => {}
            _ => return false,
        }
    }
    true
}

fn measure<const N: usize, const S: usize>(
    balls: usize,
    phi: f64,
    opts: &Options,
) -> Result<Rates, String>
where
    Generated: Kernel<f64, N, S>,
{
    let clock = Instant::now();
    let setup = gas::<N, S>(balls, phi, opts.smooth, opts.seed)?;
    let kernels = GenericKernels {
        species: setup.species.clone(),
    };
    match opts.lists {
        Some(skin) => {
            let sim = ListSimulation::with_skin(setup, kernels, skin).map_err(|e| e.to_string())?;
            run(sim, &clock, balls, opts)
        }
        None => {
            let sim = Simulation::new(setup, kernels).map_err(|e| e.to_string())?;
            run(sim, &clock, balls, opts)
        }
    }
}

/// Warms `sim` up and times its runs (`clock` started before it was built).
fn run<const N: usize, const S: usize>(
    mut sim: impl Engine<N, S>,
    clock: &Instant,
    balls: usize,
    opts: &Options,
) -> Result<Rates, String> {
    let build = clock.elapsed().as_secs_f64();
    let warm = opts.warm.unwrap_or((2 * balls as u64).max(100_000));
    let contacts = opts.contacts.unwrap_or((balls as u64).max(200_000));
    if !advance(&mut sim, warm) {
        return Err("the gas stopped during the warm-up".into());
    }
    let (moves0, stale0) = (sim.moves(), sim.stale());
    let mut rates = Vec::new();
    for _ in 0..opts.runs {
        let t0 = seconds(clock);
        if !advance(&mut sim, contacts) {
            return Err("the gas stopped".into());
        }
        rates.push(contacts as f64 / (seconds(clock) - t0));
    }
    rates.sort_by(f64::total_cmp);
    let timed = (contacts * opts.runs as u64) as f64;
    Ok(Rates {
        rates,
        crossings: (sim.moves() - moves0) as f64 / timed,
        stale: (sim.stale() - stale0) as f64 / timed,
        build,
    })
}

struct Options {
    dims: Vec<usize>,
    balls: Vec<usize>,
    phi: Vec<f64>,
    runs: usize,
    contacts: Option<u64>,
    warm: Option<u64>,
    smooth: bool,
    seed: u64,
    /// The list engine's skin, if it runs instead of the cell engine.
    lists: Option<f64>,
}

const USAGE: &str = "usage: event_rate [--dims 2,3] [--balls 100,1000,10000,100000] \
[--phi 0.1,0.2,0.3,0.4] [--runs 3] [--contacts C] [--warm W] [--smooth] [--seed S] \
[--lists SKIN]";

const CLI: Cli = Cli {
    name: "event_rate",
    usage: USAGE,
};

fn options() -> Options {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut o = Options {
        dims: vec![2, 3],
        balls: vec![100, 1000, 10_000, 100_000],
        phi: vec![0.1, 0.2, 0.3, 0.4],
        runs: 3,
        contacts: None,
        warm: None,
        smooth: false,
        seed: 1,
        lists: None,
    };
    let mut i = 0;
    while i < args.len() {
        let flag = args[i].as_str();
        let value = args.get(i + 1);
        match flag {
            "--dims" => o.dims = CLI.list(flag, value),
            "--balls" => o.balls = CLI.list(flag, value),
            "--phi" => o.phi = CLI.list(flag, value),
            "--runs" => o.runs = CLI.list::<usize>(flag, value)[0].max(1),
            "--contacts" => o.contacts = Some(CLI.list(flag, value)[0]),
            "--warm" => o.warm = Some(CLI.list(flag, value)[0]),
            "--seed" => o.seed = CLI.list(flag, value)[0],
            "--lists" => o.lists = Some(CLI.list(flag, value)[0]),
            "--smooth" => {
                o.smooth = true;
                i += 1;
                continue;
            }
            "--help" | "-h" => {
                println!("{USAGE}");
                std::process::exit(0)
            }
            _ => CLI.refuse(&format!("unknown argument {flag:?}")),
        }
        i += 2;
    }
    o
}

fn main() {
    let opts = options();
    println!(
        "{:>3} {:>8} {:>5} {:>12} {:>9} {:>12} {:>12} {:>10} {:>8} {:>10}",
        "dim",
        "N",
        "phi",
        "contacts/s",
        "us/cont",
        "min/s",
        "max/s",
        "cross/con",
        "build s",
        "stale/con"
    );
    for &dim in &opts.dims {
        for &balls in &opts.balls {
            for &phi in &opts.phi {
                let r = match dim {
                    2 => measure::<2, 1>(balls, phi, &opts),
                    3 => measure::<3, 3>(balls, phi, &opts),
                    4 => measure::<4, 6>(balls, phi, &opts),
                    5 => measure::<5, 10>(balls, phi, &opts),
                    6 => measure::<6, 15>(balls, phi, &opts),
                    _ => Err(format!("dimension {dim}: only 2..6 here")),
                };
                match r {
                    Ok(r) => {
                        let median = r.rates[r.rates.len() / 2];
                        println!(
                            "{dim:>3} {balls:>8} {phi:>5} {median:>12.0} {:>9.3} {:>12.0} {:>12.0} {:>10.3} {:>8.2} {:>10.3}",
                            1e6 / median,
                            r.rates[0],
                            r.rates[r.rates.len() - 1],
                            r.crossings,
                            r.build,
                            r.stale
                        );
                    }
                    Err(e) => println!("{dim:>3} {balls:>8} {phi:>5} skipped: {e}"),
                }
            }
        }
    }
}
