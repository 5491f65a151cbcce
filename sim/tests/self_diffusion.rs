//! The self-diffusion coefficient of `Sampler::with_self_diffusion` against the kinetic theory
//! of dilute elastic smooth hard balls (docs/granular.md, "Self-diffusion"): Chapman-Enskog's
//! first Sonine approximation, derived there (a ball drifting through the gas, the drift's
//! relaxation rate `zeta` from the contacts' momentum transfer with a shifted Maxwellian, and
//! `D = T / (m zeta)`),
//!
//! ```text
//! [D]_1 = 3 / (8 rho sigma^2 chi) sqrt(T / (pi m))   (3D),     [D]_1 = 1 / (2 rho sigma chi) sqrt(T / (pi m))   (2D),
//! ```
//!
//! with Enskog's factor `1 / chi` (the contact value of the pair correlation: Carnahan-Starling
//! in 3D, Henderson in 2D). The theory's stated accuracy: the Sonine expansion's higher orders,
//! derived there and computed exactly by `scripts/sonine_self_diffusion.py`, raise the
//! Boltzmann equation's `D` to `[D]_inf = 1.018954 [D]_1` (3D) and `1.027094 [D]_1` (2D). The
//! sequence `[D]_P` increases with `P` (each is the maximum of the variational functional over
//! a larger space: proved in the docs), so `[D]_10` is a lower bound; the remainder above it,
//! estimated from the sequence's differences (about `1e-7` in 3D, `5e-7` in 2D), is allowed
//! `1e-5`. Enskog leaves out velocity correlations (ring collisions) of relative order `phi`;
//! in 2D the velocity autocorrelation's long-time tail `(1 / (2 rho)) / (4 pi (D + nu) t)`
//! adds up to `(phi / pi) ln(t / tau_v)` to `D` measured up to time `t` (`nu = D` in the
//! dilute 2D gas; derived in the docs). So, with `s` the standard error of six runs' `D / [D]_1` and `t = 6.87` (Student's
//! two-sided 99.9 % with 5 degrees of freedom):
//!
//! ```text
//! [D]_10 / [D]_1 - t s - phi  <  D / [D]_1  <  [D]_10 / [D]_1 + 1e-5 + phi + tail + t s,
//! ```
//!
//! and `s < 0.5 %` (power: with the measured `s` of 0.2-0.3 %, a `D` 4 % off `[D]_inf` either
//! way fails). Each run also checks its blocks' standard
//! error against the runs' scatter: the six runs' variance over the mean of the blocks'
//! squared standard errors must lie between the 0.1 % and 99.95 % points of `chi^2_5 / 5`
//! (0.042 and 4.42), the blocks' error being nearly exact (60 and 96 blocks in all).

use crate::common;
use common::{ball_volume, contact_chi, mean_se, periodic_gas, T_5};
use noslip_sim::granular::Sampler;
use std::f64::consts::PI;

/// One run of `count` smooth elastic balls at packing `phi` in R^`dim` (Maxwellian start at
/// `T = 1`, seed `seed`): rows every `tau_v / 2`, self-diffusion blocks of `20 tau_v` from
/// `2 tau_v` (`tau_v = m [D]_1 / T`, the velocity's correlation time; each block's fit from
/// `4 tau_v` on, where its slope is low by about 0.1 %: `noslip_sim::self_diffusion`), `blocks`
/// of them.
/// Returns `(D / [D]_1, s_D / [D]_1, blocks)` with `[D]_1` at the run's mean `T_tr`.
fn run(dim: usize, count: usize, phi: f64, seed: u64, blocks: usize) -> (f64, f64, usize) {
    let side = (count as f64 * ball_volume(dim) / phi).powf(1.0 / dim as f64);
    let tail =
        "[contact]\nballs = \"smooth\"\n[random]\nseed = {seed}\nvelocities = \"maxwellian\"\n";
    let text = periodic_gas(dim, side, count, tail).replace("{seed}", &seed.to_string());
    let rho = count as f64 / side.powi(dim as i32);
    let first = first_sonine(dim, rho, contact_chi(dim, phi));
    let tau_v = first(1.0);
    let (block, from) = (20.0 * tau_v, 2.0 * tau_v);
    let scene = noslip_scene::Scene::from_toml(&text, "t.toml").unwrap();
    let sampler: Sampler = collision_core::with_dim!(
        scene.dim,
        |N, S| {
            let setup = noslip_sim::setup::setup::<N, S>(&scene).unwrap();
            let species = setup.species.clone();
            let kernels = noslip_sim::GenericKernels {
                species: species.clone(),
            };
            let mut sim = noslip_sim::Simulation::new(setup, kernels).unwrap();
            let mut s = Sampler::start(tau_v / 2.0, &sim, &species)
                .with_self_diffusion(block, from)
                .unwrap();
            // Half a block past the last block's nominal end.
            let end = from + (blocks as f64 + 0.5) * block;
            while let noslip_sim::Step::Contact(e) = sim.step(end) {
                s.contact(&e, &sim, &species);
            }
            s
        },
        unreachable!()
    );
    let rows = sampler.rows();
    let t = rows.iter().map(|r| r.t_tr).sum::<f64>() / rows.len() as f64;
    let d = sampler.self_diffusion().unwrap();
    let (mean, se) = d.estimate();
    (mean / first(t), se / first(t), d.blocks().len())
}

/// `[D]_1` of the module docs as a function of `T` (`m = sigma = 1`).
fn first_sonine(dim: usize, rho: f64, chi: f64) -> impl Fn(f64) -> f64 {
    let c = if dim == 3 {
        3.0 / (8.0 * rho * chi)
    } else {
        1.0 / (2.0 * rho * chi)
    };
    move |t: f64| c * (t / PI).sqrt()
}

/// `[D]_10 / [D]_1`, Chapman-Enskog's tenth Sonine approximation over the first, in R^`dim`
/// (`scripts/sonine_self_diffusion.py --orders 10`, exact rationals rounded down to 7
/// decimals: a lower bound of the Boltzmann equation's `D / [D]_1`).
fn tenth_sonine(dim: usize) -> f64 {
    if dim == 3 {
        SONINE_10_3D
    } else {
        SONINE_10_2D
    }
}

/// `[D]_10 / [D]_1` for spheres (module docs).
const SONINE_10_3D: f64 = 1.018_953_7;
/// `[D]_10 / [D]_1` for disks (module docs).
const SONINE_10_2D: f64 = 1.027_093_5;
/// What the orders beyond the tenth are allowed to add (module docs: the sequence's own
/// differences put it near `1e-7` in 3D and `5e-7` in 2D).
const SONINE_REMAINDER: f64 = 1e-5;

/// The runs of one check: their seeds, Student's two-sided 99.9 % point for their `k = runs -
/// 1` degrees of freedom, and the bounds on the runs' variance over the blocks' (points of
/// `chi^2_k / k`: 0.1 % and 99.95 % for the six runs, 0.05 % and 99.95 % for the 24).
struct Runs {
    seeds: std::ops::Range<u64>,
    t: f64,
    chi2: (f64, f64),
}

/// The default tests' six runs: `t = 6.87`, `chi^2_5 / 5` in `[0.042, 4.42]`.
const SIX: Runs = Runs {
    seeds: 0..6,
    t: T_5,
    chi2: (0.042, 4.42),
};

/// Runs of `count` balls at `phi`, `blocks` blocks each, against `[D]_10` (module docs).
fn against_chapman_enskog(dim: usize, count: usize, phi: f64, blocks: usize, check: Runs) {
    let runs: Vec<(f64, f64, usize)> = check
        .seeds
        .clone()
        .map(|seed| run(dim, count, phi, seed, blocks))
        .collect();
    for r in &runs {
        assert_eq!(r.2, blocks, "{runs:?}");
    }
    let k = runs.len() as f64;
    let t = check.t;
    let d: Vec<f64> = runs.iter().map(|r| r.0).collect();
    let (mean, se) = mean_se(&d);
    let var_runs = se * se * k;
    let var_blocks = runs.iter().map(|r| r.1 * r.1).sum::<f64>() / k;
    let sonine = tenth_sonine(dim);
    // The 2D tail over a block's fit, `t` in [4, 20] tau_v: ln 15, above the fit's mean of
    // `ln t` (about ln 12).
    let tail = if dim == 2 { phi / PI * 15f64.ln() } else { 0.0 };
    eprintln!(
        "{dim}D smooth, {count} balls, phi = {phi}: D / [D]_1 = {mean:.4} +- {se:.4} ({k} runs \
         of {blocks} blocks; the blocks' own error {:.4} a run, the runs' scatter {:.4}); \
         allowed [{:.4}, {:.4}]; ([D] - [D]_10) / s = {:.2}",
        var_blocks.sqrt(),
        var_runs.sqrt(),
        sonine - t * se - phi,
        sonine + SONINE_REMAINDER + phi + tail + t * se,
        (mean - sonine) / se
    );
    assert!(se < 0.005, "too noisy to test: {runs:?}");
    assert!(mean > sonine - t * se - phi, "{runs:?}");
    assert!(
        mean < sonine + SONINE_REMAINDER + phi + tail + t * se,
        "{runs:?}"
    );
    let f = var_runs / var_blocks;
    assert!(
        f > check.chi2.0 && f < check.chi2.1,
        "the blocks' error is off: {f} {runs:?}"
    );
}

/// 3D: 2000 smooth spheres at `phi = 0.01` (a box of 4.0 mean free paths), 10 blocks a run.
#[test]
fn self_diffusion_of_dilute_smooth_spheres_is_chapman_enskogs() {
    against_chapman_enskog(3, 2000, 0.01, 10, SIX);
}

/// 2D: 2000 smooth disks at `phi = 0.01` (a box of 14.3 mean free paths), 16 blocks a run
/// (a 2D ball's displacement has two components, not three: more blocks for the same
/// error).
#[test]
fn self_diffusion_of_dilute_smooth_disks_is_chapman_enskogs() {
    against_chapman_enskog(2, 2000, 0.01, 16, SIX);
}

/// The 3D test with 24 more runs (seeds 6..30), to resolve how far the spheres' `D` lies
/// above `[D]_inf` (docs/granular.md, "Self-diffusion against Chapman-Enskog"): `t_23 =
/// 3.768`, `chi^2_23 / 23` in `[0.301, 2.261]`. About 3 minutes in the debug profile:
/// `cargo test -p noslip-sim --test sim self_diffusion:: -- --ignored --nocapture`.
#[test]
#[ignore]
fn self_diffusion_of_dilute_smooth_spheres_over_24_runs() {
    let runs = Runs {
        seeds: 6..30,
        t: 3.768,
        chi2: (0.301, 2.261),
    };
    against_chapman_enskog(3, 2000, 0.01, 10, runs);
}
