//! Granular gases against first principles and kinetic theory (docs/granular.md): the energy
//! balance of rough contacts, Haff's law of a cooling gas of smooth inelastic balls in 2D and
//! 3D, and equipartition in an elastic no-slip gas. Statistical tolerances come from the
//! spread of independent runs (seeds): with `K` runs of mean `x` and standard error `s`, the
//! theory's value must lie within `t s` of `x`, `t` the two-sided 99.9 % quantile of Student's
//! t with `K - 1` degrees of freedom; and `s` must be small enough for the test to have
//! power.

use collision_core::{Generated, Kernel};
use noslip_scene::Scene;
use noslip_sim::granular::{Row, Sampler};
use noslip_sim::setup::setup;
use noslip_sim::{GenericKernels, Simulation, Step};
use std::f64::consts::PI;

/// Student's t, two-sided 99.9 %, for `K - 1 = 5` degrees of freedom.
const T_5: f64 = 6.869;

/// Runs `text` (with `{seed}` replaced) to time `until`, a row every `every`.
fn rows(text: &str, seed: u64, every: f64, until: f64) -> (Vec<Row>, usize) {
    let scene = Scene::from_toml(&text.replace("{seed}", &seed.to_string()), "t.toml").unwrap();
    collision_core::with_dim!(
        scene.dim,
        |N, S| run::<N, S>(&scene, every, until),
        unreachable!()
    )
}

fn run<const N: usize, const S: usize>(scene: &Scene, every: f64, until: f64) -> (Vec<Row>, usize)
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

/// Mean and standard error of the mean.
fn mean_se(x: &[f64]) -> (f64, f64) {
    let k = x.len() as f64;
    let mean = x.iter().sum::<f64>() / k;
    let var = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (k - 1.0);
    (mean, (var / k).sqrt())
}

/// The sum of the per-contact losses is the kinetic energy lost, to rounding: each loss is
/// a difference of ball energies `1/2 m (|u|^2 + 2 lambda |U|^2)`, each evaluated with a
/// relative error below `(n + S + 4) eps <= 16 eps` in 2D, and each at most the total `E_0`,
/// so `C` contacts (four evaluations each) and the two totals over `N_b` balls err by at
/// most `(64 C + 40 N_b) eps E_0` (the sums' own roundings included in the slack).
#[test]
fn the_losses_of_the_contacts_add_up_to_the_energy_lost() {
    let gas = r#"
dim = 2
[box]
size = [24, 24]
boundary = ["wall", "wall"]
[[species]]
mass = 2
radius = 1
count = 20
[[species]]
mass = 1
radius = "1/2"
count = 100
[[obstacle]]
position = [12, 12]
radius = 2
contact = { e = "0.8", beta = "0.5" }
[[wall]]
point = [0, 18]
normal = [1, -1]
contact = { e = "0.7", beta = "-0.2" }
[contact]
balls = { e = "0.9", beta = "0.4" }
tc = "1e-4"
[random]
seed = {seed}
speed = 1
spin = 1
"#;
    let (rows, contacts) = rows(gas, 1, 1.0, 200.0);
    let (first, last) = (&rows[0], rows.last().unwrap());
    let lost: f64 = last.lost.iter().sum();
    let drop = first.energy - last.energy;
    let bound = (64.0 * contacts as f64 + 40.0 * 120.0) * f64::EPSILON * first.energy;
    assert!((lost - drop).abs() <= bound, "{lost} {drop} {bound}");
    // Every kind of contact dissipated (the box walls are no-slip: nothing lost there).
    assert!(
        last.lost[0] > 0.0 && last.lost[2] > 0.0 && last.lost[3] > 0.0,
        "{:?}",
        last.lost
    );
    assert!(last.lost[1].abs() <= bound, "{:?}", last.lost);
    assert!(
        drop > 0.5 * first.energy,
        "the gas cooled: {drop} of {}",
        first.energy
    );
}

/// Haff's law for smooth inelastic balls (`beta = -1`: spins untouched, translation cools
/// alone) in R^n. A contact of equal masses loses `(1 - e^2) m g_n^2 / 4`; over contacts of
/// a Maxwellian gas (rate weighted by `g_n`) `<g_n^2> = 4 T / m`, so each loses
/// `(1 - e^2) T` on average, and with `N omega / 2` contacts per unit time and `E = n N T /
/// 2`, `dT/dt = -(1 - e^2) omega T / n`. The Enskog collision frequency
/// `omega = 2 pi^((n-1)/2) / Gamma(n/2) rho sigma^(n-1) chi sqrt(T / m)` (`rho` the number
/// density, `sigma = 2R`, `chi` the pair correlation at contact) grows as `sqrt(T)`, so
/// `T(t) = T_0 / (1 + t / t_0)^2`, `t_0 = 2 n / ((1 - e^2) omega_0)`. Each run's `t_0` is
/// fitted from `1 / sqrt(T)`, linear in `t`: `(1 + t / t_0) / sqrt(T_0)`. Two values of `e`
/// test the dependence on it (`t_0` 2.7 times shorter at 0.7 than at 0.9).
fn haff(dim: usize, e: f64) {
    // phi = 0.031 in 2D, 0.019 in 3D: dilute, where Enskog's chi is close to 1 and
    // clustering is slow.
    let (side, count) = match dim {
        2 => (100.0, 400),
        _ => (30.0, 1000),
    };
    let volume = f64::powi(side, dim as i32);
    let sigma: f64 = 1.0;
    let ball = match dim {
        2 => PI * 0.25,
        _ => PI / 6.0,
    };
    let phi = count as f64 * ball / volume;
    // Henderson (2D) and Carnahan-Starling (3D).
    let chi = match dim {
        2 => (1.0 - 7.0 * phi / 16.0) / (1.0 - phi).powi(2),
        _ => (1.0 - phi / 2.0) / (1.0 - phi).powi(3),
    };
    let rho = count as f64 / volume;
    // 2 pi^((n-1)/2) / Gamma(n/2): 2 sqrt(pi) in 2D, 4 sqrt(pi) in 3D.
    let c = match dim {
        2 => 2.0 * PI.sqrt(),
        _ => 4.0 * PI.sqrt(),
    };
    let axes = vec!["\"periodic\""; dim].join(", ");
    let sizes = vec![format!("{side}"); dim].join(", ");
    let gas = format!(
        "dim = {dim}\n[box]\nsize = [{sizes}]\nboundary = [{axes}]\n[[species]]\nmass = 1\n\
         radius = \"1/2\"\ncount = {count}\n[contact]\nballs = {{ e = {e}, beta = -1 }}\n\
         [random]\nseed = {{seed}}\nvelocities = \"maxwellian\"\n"
    );
    let mut ratio = Vec::new();
    for seed in 0..6 {
        // The first row: the start's own temperature (the draw's, not the nominal 1).
        let (first, _) = rows(&gas, seed, 1e9, 0.0);
        let t_start = first[0].t_tr;
        let omega = c * rho * sigma.powi(dim as i32 - 1) * chi * t_start.sqrt();
        let t0 = 2.0 * dim as f64 / ((1.0 - e * e) * omega);
        let (rows, _) = rows(&gas, seed, t0 / 20.0, t0);
        // Least squares of y = 1 / sqrt(T) against t: t_0 = intercept / slope.
        let pts: Vec<(f64, f64)> = rows.iter().map(|r| (r.time, 1.0 / r.t_tr.sqrt())).collect();
        let k = pts.len() as f64;
        let (mt, my) = (
            pts.iter().map(|p| p.0).sum::<f64>() / k,
            pts.iter().map(|p| p.1).sum::<f64>() / k,
        );
        let slope = pts.iter().map(|p| (p.0 - mt) * (p.1 - my)).sum::<f64>()
            / pts.iter().map(|p| (p.0 - mt).powi(2)).sum::<f64>();
        let intercept = my - slope * mt;
        ratio.push(intercept / slope / t0);
    }
    let (mean, se) = mean_se(&ratio);
    eprintln!("Haff {dim}D, e = {e}: t_0 measured / Enskog = {mean:.4} +- {se:.4} (6 seeds)");
    assert!(se < 0.02, "too noisy to test: {ratio:?}");
    assert!((mean - 1.0).abs() < T_5 * se, "{ratio:?}");
}

#[test]
fn haff_law_in_2d() {
    haff(2, 0.9);
    haff(2, 0.7);
}

#[test]
fn haff_law_in_3d() {
    haff(3, 0.9);
    haff(3, 0.7);
}

/// Equipartition in an elastic no-slip gas: energy is conserved and shared among the
/// `n (N_b - 1)` translational degrees of freedom left once the centre of mass is taken out
/// (momentum is conserved in the periodic box; angular momentum is not) and the `S N_b`
/// rotational ones, so in equilibrium (the microcanonical average of each quadratic term)
/// `T_rot = T_tr` exactly, whatever `N_b`. Started with no spin at all, the gas is left 40
/// collision times per ball to relax, then `T_rot / T_tr` is the ratio of the two
/// temperatures averaged over the next 40.
fn equipartition(dim: usize, side: f64, count: usize) {
    let axes = vec!["\"periodic\""; dim].join(", ");
    let sizes = vec![format!("{side}"); dim].join(", ");
    let gas = format!(
        "dim = {dim}\n[box]\nsize = [{sizes}]\nboundary = [{axes}]\n[[species]]\nmass = 1\n\
         radius = \"1/2\"\ncount = {count}\n[random]\nseed = {{seed}}\nspeed = 1\nspin = 0\n"
    );
    let mut ratio = Vec::new();
    for seed in 0..6 {
        // The collision frequency from a short run, then 80 collision times.
        let (probe, _) = rows(&gas, seed, 1.0, 5.0);
        let omega = probe[1..].iter().map(|r| r.frequency).sum::<f64>() / (probe.len() - 1) as f64;
        let tau = 1.0 / omega;
        let (rows, _) = rows(&gas, seed, tau, 80.0 * tau);
        let late: Vec<&Row> = rows.iter().filter(|r| r.time >= 40.0 * tau).collect();
        assert!(rows[0].t_rot == 0.0 && late.len() >= 30, "{}", late.len());
        let mean =
            |f: &dyn Fn(&Row) -> f64| late.iter().map(|r| f(r)).sum::<f64>() / late.len() as f64;
        ratio.push(mean(&|r| r.t_rot) / mean(&|r| r.t_tr));
    }
    let (mean, se) = mean_se(&ratio);
    eprintln!("equipartition {dim}D: T_rot / T_tr = {mean:.4} +- {se:.4} (6 seeds)");
    assert!(se < 0.02, "too noisy to test: {ratio:?}");
    assert!((mean - 1.0).abs() < T_5 * se, "{ratio:?}");
}

#[test]
fn equipartition_in_2d() {
    equipartition(2, 30.0, 200);
}

#[test]
fn equipartition_in_3d() {
    equipartition(3, 10.0, 200);
}

/// n = 4..6 (about 20 s): `cargo test -p noslip-sim --test granular -- --ignored`.
#[test]
#[ignore]
fn equipartition_in_4d_to_6d() {
    equipartition(4, 6.0, 200);
    equipartition(5, 4.0, 200);
    equipartition(6, 3.0, 200);
}
