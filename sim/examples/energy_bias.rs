//! The mean energy change per contact of the shipped one-ball tables, with its standard
//! error: the generated `fixed` kernel against the two-rounded-constant form it replaced,
//! side by side on the same scene (`docs/accuracy.md`, "Energy bias").
//!
//! ```sh
//! cargo run --release -p noslip-sim --example energy_bias -- 10000000
//! cargo run --release -p noslip-sim --example energy_bias -- 100000 scenes/sinai.toml
//! ```
//!
//! Arguments: contacts per run (default 10^6; the batches use the largest multiple of `B`
//! measured), then scene files (default: every
//! `scenes/*.toml` with one ball). For each scene and each kernel: the mean of the per-contact
//! changes of `E = |u|^2 + g R^2 sum U_ij^2` (twice the kinetic energy per unit mass; each
//! change computed in double-double from the `f64` states, in eps of `E_0`), the standard error
//! of that mean from `B = 100` batch means (consecutive batches of `K / B` contacts, which
//! absorb the correlation of neighbouring contacts), and `z` = mean / standard error. With no
//! bias `z` follows Student's t with 99 degrees of freedom; a drift of one sign at every
//! contact grows `z` like `sqrt(K)`.
//!
//! "conserving" is the generated kernel corrected onto the energy of its inputs
//! (`noslip_sim::Conserving`, `collision_core::conserve`).
//!
//! The old form (`two_rounded_constants`) is the generated kernel's map with
//! `p = g / (1 + g)` and `rho = 2 / (R (1 + g))` each rounded once, written out here.

use collision_core::conserve::weighted_squares;
use collision_core::{with_dim, Ball, BodyState, Generated, Kernel};
use noslip_scene::Scene;
use noslip_sim::setup::setup;
use noslip_sim::{Conserving, GenericKernels, PairKernels, Simulation, Step};

/// Batches of the standard error.
const BATCHES: usize = 100;

/// `|u|^2 + w sum U_ij^2` in double-double, `w = g R^2` (its one rounding is a fixed factor
/// of the spin part, whose changes telescope: no drift per contact).
fn energy<const N: usize, const S: usize>(w: f64, s: &BodyState<f64, N, S>) -> (f64, f64) {
    let terms = s.velocity.iter().map(|&x| (1.0, x));
    weighted_squares(terms.chain(s.spin.iter().map(|&x| (w, x))))
}

/// The kernels of the old form: `free` as generated, `fixed` with two rounded constants.
struct TwoRoundedConstants {
    species: Vec<Ball<f64>>,
}

/// `u+ = u - 2 (dn nu + p t)`, `U+ = U + rho (nu ^ t)`, `t = u - dn nu - R U nu` (the other
/// body at rest), `p = g / (1 + g)` and `rho = 2 / (R (1 + g))` each rounded.
fn two_rounded_constants<const N: usize, const S: usize>(
    nu: &[f64; N],
    ball: &Ball<f64>,
    s: &BodyState<f64, N, S>,
) -> BodyState<f64, N, S> {
    let u = s.spin_matrix();
    let dn: f64 = (0..N).map(|k| s.velocity[k] * nu[k]).sum();
    let t: [f64; N] = std::array::from_fn(|k| {
        let c: f64 = (0..N).map(|j| u[k][j] * nu[j]).sum();
        s.velocity[k] - dn * nu[k] - ball.radius * c
    });
    let d = 1.0 + ball.gamma2;
    let (p, rho) = (ball.gamma2 / d, 2.0 / (ball.radius * d));
    let mut spin = s.spin;
    let pairs = (0..N).flat_map(|i| (i + 1..N).map(move |j| (i, j)));
    for (x, (i, j)) in spin.iter_mut().zip(pairs) {
        *x += rho * (t[i] * nu[j] - nu[i] * t[j]);
    }
    BodyState {
        spin,
        velocity: std::array::from_fn(|k| s.velocity[k] - 2.0 * (dn * nu[k] + p * t[k])),
    }
}

impl<const N: usize, const S: usize> PairKernels<f64, N, S> for TwoRoundedConstants
where
    Generated: Kernel<f64, N, S>,
{
    fn ball_ball(
        &self,
        a: usize,
        b: usize,
        nu: &[f64; N],
        state1: &BodyState<f64, N, S>,
        state2: &BodyState<f64, N, S>,
    ) -> [BodyState<f64, N, S>; 2] {
        Generated::free(nu, &self.species[a], &self.species[b], state1, state2)
    }

    fn ball_wall(
        &self,
        species: usize,
        axis: usize,
        upper: bool,
        state: &BodyState<f64, N, S>,
    ) -> BodyState<f64, N, S> {
        let sign = if upper { -1.0 } else { 1.0 };
        let nu = std::array::from_fn(|k| if k == axis { sign } else { 0.0 });
        two_rounded_constants(&nu, &self.species[species], state)
    }

    fn ball_obstacle(
        &self,
        species: usize,
        nu: &[f64; N],
        state: &BodyState<f64, N, S>,
    ) -> BodyState<f64, N, S> {
        two_rounded_constants(nu, &self.species[species], state)
    }
}

/// Mean energy change per contact (eps of `E_0`), its batch-means standard error and the
/// contacts measured (fewer than asked if the ball stops meeting the table: a periodic orbit
/// along which no contact comes again).
fn measure<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
    scene: &Scene,
    kernels: K,
    contacts: usize,
) -> (f64, f64, usize) {
    let setup = setup::<N, S>(scene).expect("valid scene");
    let ball = setup.species[setup.bodies[0].species].clone();
    let w = ball.gamma2 * ball.radius * ball.radius;
    let mut sim = Simulation::new(setup, kernels).expect("valid setup");
    let mut before = energy(w, sim.state(0));
    let scale = 1.0 / (before.0 * f64::EPSILON);
    let mut changes = Vec::with_capacity(contacts);
    while changes.len() < contacts {
        match sim.step(f64::INFINITY) {
            Step::Contact(_) => {}
            Step::Quiet { .. } => continue,
            _ => break,
        }
        let after = energy(w, sim.state(0));
        changes.push(((after.0 - before.0) + (after.1 - before.1)) * scale);
        before = after;
    }
    let k = changes.len();
    if k < BATCHES {
        return (f64::NAN, f64::NAN, k);
    }
    let per_batch = k / BATCHES;
    let means: Vec<f64> = changes
        .chunks_exact(per_batch)
        .take(BATCHES)
        .map(|c| c.iter().sum::<f64>() / per_batch as f64)
        .collect();
    let mean = means.iter().sum::<f64>() / BATCHES as f64;
    let var = means.iter().map(|m| (m - mean).powi(2)).sum::<f64>() / (BATCHES - 1) as f64;
    (mean, (var / BATCHES as f64).sqrt(), BATCHES * per_batch)
}

fn report<const N: usize, const S: usize>(name: &str, scene: &Scene, contacts: usize)
where
    Generated: Kernel<f64, N, S>,
{
    let species = setup::<N, S>(scene).expect("valid scene").species;
    let generated = GenericKernels {
        species: species.clone(),
    };
    let (new, new_se, new_k) = measure::<N, S, _>(scene, generated, contacts);
    let conserving = Conserving::generic(species.clone(), true);
    let (fix, fix_se, fix_k) = measure::<N, S, _>(scene, conserving, contacts);
    let (old, old_se, old_k) = measure::<N, S, _>(scene, TwoRoundedConstants { species }, contacts);
    println!(
        "| {name} | {N} | {old_k} | {old:+.5} | {old_se:.5} | {:+.1} | {new_k} | {new:+.5} | {new_se:.5} | {:+.1} | {fix_k} | {fix:+.5} | {fix_se:.5} | {:+.1} |",
        old / old_se,
        new / new_se,
        fix / fix_se
    );
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let contacts: usize = args
        .first()
        .map_or(1_000_000, |s| s.parse().expect("contacts"));
    assert!(contacts >= BATCHES, "at least {BATCHES} contacts");
    let mut files: Vec<String> = args.iter().skip(1).cloned().collect();
    if files.is_empty() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes");
        let mut all: Vec<_> = std::fs::read_dir(dir)
            .expect("scenes/")
            .map(|e| e.expect("entry").path().display().to_string())
            .filter(|p| p.ends_with(".toml"))
            .collect();
        all.sort();
        files = all;
    }
    println!("| scene | n | old: contacts | mean | se | z | new: contacts | mean | se | z | conserving: contacts | mean | se | z |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for file in files {
        let text = std::fs::read_to_string(&file).expect("readable scene");
        let scene = Scene::from_toml(&text, &file).expect("valid scene");
        let balls: usize = with_dim!(
            scene.dim,
            |N, S| setup::<N, S>(&scene).expect("valid scene").bodies.len(),
            0
        );
        if balls != 1 {
            continue;
        }
        let name = std::path::Path::new(&file)
            .file_stem()
            .map_or(file.clone(), |s| s.to_string_lossy().into_owned());
        with_dim!(
            scene.dim,
            |N, S| report::<N, S>(&name, &scene, contacts),
            ()
        );
    }
}
