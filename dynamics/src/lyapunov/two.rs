//! The largest exponent from two nearby trajectories (Benettin et al. 1976), with no tangent
//! map: a second engine run starts at distance `d0` from the reference; after every `every`
//! contacts of the reference (time `t`), once the second run has met the same contacts (as a
//! set: near-simultaneous contacts of a gas may swap order), its state is flown freely to `t`
//! and compared: `d = |z_2(t) - z_1(t)|` (Euclidean in `[x, u, U]`, minimum image on periodic
//! axes), `log(d / d0)` is added to the growth, and the second run restarts at
//! `z_1 + (d0 / d)(z_2 - z_1)`. Comparing just after the same contacts is the nonlinear
//! counterpart of the tangent map's convention (both states after the contact, at the same
//! time).

use super::stats::Blocks;
use super::touch::unordered;
use super::{
    never, next_contact, push_state, Dim, Interrupted, LyapunovError, Options, Plan, Running,
    Spectrum,
};
use crate::law::{Law, LawKernels};
use collision_core::rng::Rng;
use collision_core::{BodyState, Generated};
use noslip_sim::{Body, Contact, Setup, Simulation};

/// The distance `d0` the second trajectory is kept at (lengths and speeds of order 1: far
/// above rounding, `1e-16 / 1e-9`, and far below the scale of the table).
pub const D0: f64 = 1e-9;

/// Default contacts between renormalisations: 1 for one ball (a dispersing contact stretches
/// by a factor of order 10), else half the balls (each ball meets about one other).
fn default_every(balls: usize) -> u64 {
    (balls as u64 / 2).max(1)
}

/// Contacts the second run may be behind or ahead before it is declared diverged.
const SLACK: usize = 16;

/// The largest exponent by two trajectories (see the module docs).
pub fn two_trajectory<const N: usize, const S: usize>(
    setup: Setup<N, S>,
    options: &Options,
) -> Result<Spectrum, LyapunovError>
where
    Generated: Dim<N, S>,
{
    two_trajectory_interruptible(setup, options, &never)
}

/// [`two_trajectory`], asking `interrupted` before every contact of either run
/// ([`LyapunovError::Interrupted`] when it says stop).
pub fn two_trajectory_interruptible<const N: usize, const S: usize>(
    setup: Setup<N, S>,
    options: &Options,
    interrupted: Interrupted<'_>,
) -> Result<Spectrum, LyapunovError>
where
    Generated: Dim<N, S>,
{
    let plan = Plan::new(options)?;
    let balls = setup.bodies.len();
    let dimension = balls * crate::tangent::block_len(N, S);
    if let Some(k) = options.k.filter(|&k| k != 1) {
        return Err(LyapunovError::K { k, dimension: 1 });
    }
    let every = plan.every(options.every, default_every(balls))?;
    // The engine runs smooth contacts itself; its kernels are the no-slip ones.
    let kernels = LawKernels {
        law: Law::NoSlip,
        species: setup.species.clone(),
    };
    let setup = super::overridden(setup, options.law);
    let template = setup.clone();
    let mut reference = Simulation::new(setup, kernels.clone()).map_err(LyapunovError::Setup)?;
    let mut rng = Rng::new(options.seed);
    let start = snapshot(&reference);
    let direction: Vec<f64> = (0..start.len()).map(|_| rng.uniform(-1.0, 1.0)).collect();
    let norm = direction.iter().map(|x| x * x).sum::<f64>().sqrt();
    let shifted: Vec<f64> = start
        .iter()
        .zip(&direction)
        .map(|(z, d)| z + D0 * d / norm)
        .collect();
    let mut second = rebuild(&template, &shifted, &kernels)?;
    let mut offset = 0.0; // the second run's clock starts at the reference's time `offset`
    let mut blocks = Blocks::new(plan.blocks, 1);
    let mut running = Vec::new();
    let stride = (plan.events / every / 1000).max(1);
    let (mut last_time, mut last_contact, mut renormalised) = (0.0f64, 0u64, 0u64);
    let (mut growth, mut measured_time) = (0.0f64, 0.0f64);
    let mut c = 0u64;
    while c < plan.events {
        let (mut a, mut b): (Vec<Contact>, Vec<Contact>) = (Vec::new(), Vec::new());
        let mut t = 0.0;
        for _ in 0..every.min(plan.events - c) {
            let e = next_contact(&mut reference, &kernels.species, interrupted)?;
            a.push(unordered(&e.contact));
            t = e.time;
            c += 1;
        }
        let mut second_time = offset;
        loop {
            while b.len() < a.len() {
                let e = next_contact(&mut second, &kernels.species, interrupted)?;
                b.push(unordered(&e.contact));
                second_time = offset + e.time;
            }
            if same_set(&a, &b) {
                break;
            }
            if a.len() > every as usize + SLACK || c >= plan.events {
                return Err(LyapunovError::Diverged { at: c });
            }
            let e = next_contact(&mut reference, &kernels.species, interrupted)?;
            a.push(unordered(&e.contact));
            t = e.time;
            c += 1;
        }
        let z1 = snapshot(&reference);
        let z2 = flown(&second, t - second_time);
        let diff: Vec<f64> = z1
            .iter()
            .zip(&z2)
            .enumerate()
            .map(|(idx, (p, q))| image(&template, idx, q - p))
            .collect();
        let d = diff.iter().map(|x| x * x).sum::<f64>().sqrt();
        let log = (d / D0).ln();
        if !log.is_finite() {
            return Err(LyapunovError::Singular { at: c });
        }
        let restart: Vec<f64> = z1.iter().zip(&diff).map(|(p, x)| p + x * D0 / d).collect();
        second = rebuild(&template, &restart, &kernels)?;
        offset = t;
        if let Some(blk) = plan.block(c) {
            let dt = t - last_time;
            blocks.add(blk, &[log], dt, c - last_contact);
            growth += log;
            measured_time += dt;
            renormalised += 1;
            if renormalised % stride == 0 || c == plan.events {
                running.push(Running {
                    contacts: c,
                    time: t,
                    exponents: vec![growth / measured_time],
                });
            }
        }
        last_time = t;
        last_contact = c;
    }
    let (per_time, per_contact) = blocks.estimates();
    Ok(Spectrum {
        method: "two-trajectory",
        law: options.law,
        dimension,
        contacts: plan.events,
        warmup: plan.warmup,
        every,
        time: measured_time,
        sum: blocks.sum(),
        per_time,
        per_contact,
        running,
    })
}

fn same_set(a: &[Contact], b: &[Contact]) -> bool {
    let key = |c: &Contact| match *c {
        Contact::Ball { i, j } => (0, i, j, 0),
        Contact::Wall { i, axis, upper } => (1, i, axis, usize::from(upper)),
        Contact::Obstacle { i, obstacle } => (2, i, obstacle, 0),
        Contact::Boundary { i, boundary } => (3, i, boundary, 0),
    };
    let mut x: Vec<_> = a.iter().map(key).collect();
    let mut y: Vec<_> = b.iter().map(key).collect();
    x.sort_unstable();
    y.sort_unstable();
    x == y
}

/// Every ball's `[x, u, U]` now.
fn snapshot<const N: usize, const S: usize, K: noslip_sim::PairKernels<f64, N, S>>(
    sim: &Simulation<N, S, K>,
) -> Vec<f64> {
    flown(sim, 0.0)
}

/// Every ball's `[x + dt u, u, U]`, `dt` after (or before) now.
fn flown<const N: usize, const S: usize, K: noslip_sim::PairKernels<f64, N, S>>(
    sim: &Simulation<N, S, K>,
    dt: f64,
) -> Vec<f64> {
    let mut out = Vec::new();
    for i in 0..sim.len() {
        let s = sim.state(i);
        let p = sim.position(i);
        let x: [f64; N] = std::array::from_fn(|k| p[k] + dt * s.velocity[k]);
        push_state(&mut out, &x, s);
    }
    out
}

/// A coordinate difference, as the minimum image on a periodic axis.
fn image<const N: usize, const S: usize>(setup: &Setup<N, S>, idx: usize, d: f64) -> f64 {
    let len = crate::tangent::block_len(N, S);
    let k = idx % len;
    if k < N && setup.periodic[k] {
        let l = setup.size[k];
        d - l * (d / l).round()
    } else {
        d
    }
}

/// A simulation of the scene's balls at the phase-space point `z` (periodic coordinates
/// wrapped into the box).
fn rebuild<const N: usize, const S: usize>(
    template: &Setup<N, S>,
    z: &[f64],
    kernels: &LawKernels,
) -> Result<Simulation<N, S, LawKernels>, LyapunovError>
where
    Generated: Dim<N, S>,
{
    let len = crate::tangent::block_len(N, S);
    let mut setup = template.clone();
    setup.orientation = false;
    for (i, body) in setup.bodies.iter_mut().enumerate() {
        let w = &z[i * len..(i + 1) * len];
        *body = Body {
            species: body.species,
            position: std::array::from_fn(|k| {
                if template.periodic[k] {
                    w[k].rem_euclid(template.size[k])
                } else {
                    w[k].clamp(0.0, template.size[k])
                }
            }),
            state: BodyState {
                velocity: std::array::from_fn(|k| w[N + k]),
                spin: std::array::from_fn(|k| w[2 * N + k]),
            },
        };
    }
    Simulation::new(setup, kernels.clone()).map_err(LyapunovError::Setup)
}
