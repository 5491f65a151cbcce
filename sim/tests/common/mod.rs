//! Shared by the sim crate's tests (`granular.rs`, `boltzmann.rs`, `observables.rs`, the
//! elastic-member and pair-law log comparisons, ...): the statistics of six seeds, runs of a
//! gas sampled by `noslip_sim::granular::Sampler`, an event log of a setup, and the
//! two-temperature theory of the homogeneous cooling state (docs/granular.md).
// Each test crate compiles this module and uses part of it.
#![allow(dead_code)]

use collision_core::{Generated, Kernel};
use noslip_scene::Scene;
use noslip_sim::granular::{Row, Sampler};
use noslip_sim::run::Limits;
use noslip_sim::setup::setup;
use noslip_sim::{GenericKernels, Setup, Simulation, Step};
use std::f64::consts::PI;

pub mod cooling;
pub mod dsmc;

/// Runs `text` (with `{seed}` replaced) to time `until`, a row every `every`.
pub fn rows(text: &str, seed: u64, every: f64, until: f64) -> (Vec<Row>, usize) {
    let scene = Scene::from_toml(&text.replace("{seed}", &seed.to_string()), "t.toml").unwrap();
    collision_core::with_dim!(
        scene.dim,
        |N, S| run::<N, S>(&scene, every, until),
        unreachable!()
    )
}

pub fn run<const N: usize, const S: usize>(
    scene: &Scene,
    every: f64,
    until: f64,
) -> (Vec<Row>, usize)
where
    Generated: Kernel<f64, N, S>,
{
    let setup = setup::<N, S>(scene).unwrap();
    let species = setup.species.clone();
    let kernels = GenericKernels {
        species: species.clone(),
    };
    let mut sim = Simulation::new(setup, kernels).unwrap();
    let mut sampler = Sampler::start(every, &sim, &species);
    while let Step::Contact(e) = sim.step(until) {
        sampler.contact(&e, &sim, &species);
    }
    (sampler.rows().to_vec(), sim.contacts() as usize)
}

/// A periodic box of side `side` in R^`dim` holding `count` balls of diameter 1 and mass 1
/// (uniform), then `tail` (`{seed}` to be replaced).
pub fn periodic_gas(dim: usize, side: f64, count: usize, tail: &str) -> String {
    let axes = vec!["\"periodic\""; dim].join(", ");
    let sizes = vec![format!("{side}"); dim].join(", ");
    format!(
        "dim = {dim}\n[box]\nsize = [{sizes}]\nboundary = [{axes}]\n[[species]]\nmass = 1\n\
         radius = \"1/2\"\ncount = {count}\n{tail}"
    )
}

/// The volume of a ball of diameter 1 in R^`dim` (2 or 3).
pub fn ball_volume(dim: usize) -> f64 {
    if dim == 2 {
        PI / 4.0
    } else {
        PI / 6.0
    }
}

/// The packing fraction of `count` balls of diameter 1 in a cube of side `side` in R^`dim`.
pub fn packing_fraction(dim: usize, side: f64, count: usize) -> f64 {
    count as f64 * ball_volume(dim) / side.powi(dim as i32)
}

/// The hard-ball fluid's contact value `chi` at packing fraction `phi`: Henderson
/// `(1 - 7 phi / 16) / (1 - phi)^2` in 2D, Carnahan-Starling `(1 - phi / 2) / (1 - phi)^3` in 3D.
pub fn contact_chi(dim: usize, phi: f64) -> f64 {
    if dim == 2 {
        (1.0 - 7.0 * phi / 16.0) / (1.0 - phi).powi(2)
    } else {
        (1.0 - phi / 2.0) / (1.0 - phi).powi(3)
    }
}

/// The Enskog collision frequency per ball at temperature `T = 1` of `count` balls of diameter
/// 1 and mass 1 in a cube of side `side` in R^`dim`:
/// `omega = 2 pi^((n-1)/2) / Gamma(n/2) rho sigma^(n-1) chi sqrt(T / m)` (`2 sqrt(pi)` in 2D,
/// `4 sqrt(pi)` in 3D; it scales as `sqrt(T)`).
pub fn enskog_frequency(dim: usize, side: f64, count: usize) -> f64 {
    let c = if dim == 2 {
        2.0 * PI.sqrt()
    } else {
        4.0 * PI.sqrt()
    };
    let rho = count as f64 / side.powi(dim as i32);
    c * rho * contact_chi(dim, packing_fraction(dim, side, count))
}

/// The dilute gases of Haff's law test (`granular.rs`), also driven (`driven.rs`): `(side,
/// count)`, 400 disks in side 100 (`phi = 0.031`) or 1000 spheres in side 30 (`phi = 0.019`),
/// where Enskog's `chi` is close to 1 and clustering is slow.
pub fn haff_gas(dim: usize) -> (f64, usize) {
    if dim == 2 {
        (100.0, 400)
    } else {
        (30.0, 1000)
    }
}

/// Student's t, two-sided 99.9 %, for `K - 1 = 5` degrees of freedom.
pub const T_5: f64 = 6.869;

/// Student's t, two-sided 99.9 % (the 0.9995 quantile), for `K - 1 = 11` degrees of freedom.
pub const T_11: f64 = 4.437;

/// Student's t, two-sided 99.9 %, for `K - 1 = 23` degrees of freedom.
pub const T_23: f64 = 3.768;

/// Student's t, two-sided 99.9 %, for `K - 1 = 95` degrees of freedom.
pub const T_95: f64 = 3.396;

/// The standard normal's one-sided 99 % quantile: an estimate lies more than `Z_99` standard
/// errors below its expectation at most 1 % of the time.
pub const Z_99: f64 = 2.326;

/// The largest standard error at which a test with band `t se` catches a departure `delta`
/// from the theory at least 99 % of the time: `delta >= (t + Z_99) se`, so the mean, which
/// lies within `Z_99 se` of `theory + delta` 99 % of the time, is then outside the band.
pub fn se_to_catch(delta: f64, t: f64) -> f64 {
    delta / (t + Z_99)
}

/// Mean and standard error of the mean.
pub fn mean_se(x: &[f64]) -> (f64, f64) {
    let k = x.len() as f64;
    let mean = x.iter().sum::<f64>() / k;
    let var = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (k - 1.0);
    (mean, (var / k).sqrt())
}

/// The two-temperature theory of a dilute gas of equal rough balls in R^n (Huthmann &
/// Zippelius 1997; Luding, Huthmann, McNamara & Zippelius 1998; derived for any `n` in
/// docs/granular.md): with `k = gamma^2 = I / (m R^2)`, `eta = k (1 + beta) / (2 (1 + k))` and
/// `tau` the contacts per ball (`dtau = omega dt`), a Maxwellian gas at `T_tr`, `T_rot` has
///
/// ```text
/// n dT_tr/dtau  = -a T_tr + b T_rot,   a = 1 - e^2 + 2 (n-1) eta (1 - eta),  b = 2 (n-1) eta^2 / k,
/// n dT_rot/dtau =  c T_tr - d T_rot,   c = 4 eta^2 / k,                       d = 4 (eta / k) (1 - eta / k),
/// ```
///
/// so `r = T_rot / T_tr` follows `n dr/dtau = c + (a - d) r - b r^2 = -b (r - r_+)(r - r_-)`:
/// the homogeneous cooling state's ratio is the positive root `r_+` of `b r^2 + (d - a) r - c
/// = 0`, and `(r - r_+) / (r - r_-)` decays exactly as `exp(-kappa tau)`, `kappa = b (r_+ -
/// r_-) / n`.
#[derive(Clone, Copy, Debug)]
pub struct TwoTemperature {
    pub n: f64,
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub d: f64,
}

pub fn two_temperature(n: usize, e: f64, beta: f64, k: f64) -> TwoTemperature {
    let eta = k * (1.0 + beta) / (2.0 * (1.0 + k));
    let n1 = (n - 1) as f64;
    TwoTemperature {
        n: n as f64,
        a: 1.0 - e * e + 2.0 * n1 * eta * (1.0 - eta),
        b: 2.0 * n1 * eta * eta / k,
        c: 4.0 * eta * eta / k,
        d: 4.0 * eta / k * (1.0 - eta / k),
    }
}

impl TwoTemperature {
    /// The roots `(r_+, r_-)` of `b r^2 + (d - a) r - c` (`b > 0`: `beta > -1`).
    pub fn roots(&self) -> (f64, f64) {
        let w = ((self.a - self.d).powi(2) + 4.0 * self.b * self.c).sqrt();
        let m = self.a - self.d;
        ((m + w) / (2.0 * self.b), (m - w) / (2.0 * self.b))
    }

    /// The homogeneous cooling state's `T_rot / T_tr`.
    pub fn ratio(&self) -> f64 {
        self.roots().0
    }

    /// `kappa`: the ratio's relaxation rate per contact per ball.
    pub fn rate(&self) -> f64 {
        let (p, m) = self.roots();
        self.b * (p - m) / self.n
    }

    /// The contacts per ball after which `r`, started at `r0`, is within `eps r_+` of `r_+`:
    /// `|r - r_+| = |delta| (r_+ - r_-) / (1 - delta)` with `delta = (r - r_+) / (r - r_-)`.
    pub fn settled(&self, r0: f64, eps: f64) -> f64 {
        let (p, m) = self.roots();
        let delta0 = ((r0 - p) / (r0 - m)).abs();
        let target = eps * p / (p - m + eps * p);
        (delta0 / target).ln().max(0.0) / self.rate()
    }
}

/// The event log of `events` contacts of `setup` on the generic kernels, and the number of
/// contacts.
pub fn log_of<const N: usize, const S: usize>(setup: Setup<N, S>, events: u64) -> (Vec<u8>, u64)
where
    Generated: Kernel<f64, N, S>,
{
    let species = setup.species.clone();
    let kernels = GenericKernels {
        species: species.clone(),
    };
    let mut sim = Simulation::new(setup, kernels).unwrap();
    let limits = Limits {
        events: Some(events),
        time: None,
        samples: 10,
        traced: 0,
        contact_points: 0,
    };
    let mut log = Vec::new();
    let (summary, _) =
        noslip_sim::run::run(&mut sim, &species, &limits, Some(&mut log), &mut |_| {}).unwrap();
    (log, summary.events)
}
