//! A driven granular gas (docs/granular.md, "A driven steady state"): the white-noise
//! thermostat's kicks (`[thermostat]`, `noslip_sim::thermostat`) through the run loop of
//! `noslip simulate` (`run_observed`), against its own energy accounting and against kinetic
//! theory. Statistical tolerances as in `granular.rs`: six seeds, the theory within `t s` of
//! their mean (`t = 6.87`, Student's 99.9 % with 5 degrees of freedom, `s` the standard error),
//! and `s` small enough for the test to have power.

use collision_core::{Generated, Kernel};
use noslip_scene::Scene;
use noslip_sim::granular::{lost, Row, Sampler};
use noslip_sim::run::{run_observed, Limits, Summary};
use noslip_sim::setup::setup;
use noslip_sim::{GenericKernels, Simulation};

use crate::common;
use common::{
    enskog_frequency, haff_gas, mean_se, packing_fraction, periodic_gas, two_temperature, T_5,
};

/// What a driven run reports: its summary, its rows, and the energy its contacts took.
struct Driven {
    summary: Summary,
    rows: Vec<Row>,
    lost: f64,
}

/// Runs `text` (`{seed}` replaced) to time `until` through `run_observed`, a row every `every`.
fn driven(text: &str, seed: u64, every: f64, until: f64) -> Driven {
    let scene = Scene::from_toml(&text.replace("{seed}", &seed.to_string()), "t.toml").unwrap();
    collision_core::with_dim!(
        scene.dim,
        |N, S| driven_in::<N, S>(&scene, every, until),
        unreachable!()
    )
}

fn driven_in<const N: usize, const S: usize>(scene: &Scene, every: f64, until: f64) -> Driven
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
    let mut taken = 0.0;
    let limits = Limits {
        events: None,
        time: Some(until),
        samples: 1,
        traced: 0,
        contact_points: 0,
    };
    let (summary, _) = run_observed(
        &mut sim,
        &species,
        &limits,
        None,
        &mut |_| {},
        &mut |_, e, sim| {
            taken += lost(e, sim, &species);
            sampler.contact(e, sim, &species);
            Ok(())
        },
    )
    .unwrap();
    Driven {
        summary,
        rows: sampler.rows().to_vec(),
        lost: taken,
    }
}

/// The energy balance of a driven rough gas with walls, an obstacle, a slanted wall and the TC
/// model: `E_end - E_start = injected - lost`, to rounding. Each contact's loss and each
/// kick's gain are differences of ball energies; with `E_max` the largest energy of the run
/// (taken as twice the largest of its rows and ends), a contact errs by at most `64 eps E_max`
/// (as in `granular.rs`: four energies of relative error below `16 eps`), a kick by at most
/// `(16 + 2 N_b) eps E_max` (each ball's term `m sum_k (u'_k - u_k)(u'_k + u_k) / 2` within
/// `8 eps` of `m (|u|^2 + |u'|^2) / 2`, and the sum over `N_b` balls), and the two totals over
/// the balls by `40 N_b eps E_max`.
#[test]
fn the_kicks_and_the_contacts_account_for_the_energy() {
    let gas = r#"
dim = 2
[box]
size = [24, 24]
boundary = ["wall", "wall"]
contact = { e = "0.9", beta = 0 }
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
velocities = "maxwellian"
[thermostat]
kind = "white-noise"
strength = "0.3"
interval = "0.05"
seed = {seed}
"#;
    let run = driven(gas, 1, 1.0, 200.0);
    let s = &run.summary;
    assert_eq!(s.kicks, 4000);
    let e_max = 2.0
        * run
            .rows
            .iter()
            .map(|r| r.energy)
            .fold(s.energy_start.max(s.energy_end), f64::max);
    let balls = 120.0;
    let bound = (64.0 * s.events as f64 + (16.0 + 2.0 * balls) * s.kicks as f64 + 40.0 * balls)
        * f64::EPSILON
        * e_max;
    let balance = s.energy_end - s.energy_start - (s.energy_injected - run.lost);
    eprintln!(
        "energy balance: E {} -> {}, injected {}, lost {}, off by {balance:e} (bound {bound:e})",
        s.energy_start, s.energy_end, s.energy_injected, run.lost
    );
    assert!(balance.abs() <= bound, "{balance} > {bound}");
    // The gas is driven: it received and lost several times its energy.
    assert!(s.energy_injected > 3.0 * s.energy_start && run.lost > 3.0 * s.energy_start);
}

/// The accuracy allowed the Enskog-Maxwellian theory of the steady temperature, besides the
/// statistics: the gas's packing fraction `phi`. Enskog's collision frequency assumes molecular
/// chaos (uncorrelated velocities of colliding balls, with the static `chi`); its corrections
/// (ring collisions, the velocity correlations a driven granular gas builds up; van Noije,
/// Ernst, Trizac & Pagonabarraga, PRE 59, 4326 (1999)) are of relative order `phi`, which is
/// what is allowed: 0.031 (2D), 0.019 (3D), fixed by the theory and the gas before any run. The
/// long runs resolve the corrections at 0.3 % (3D) to 0.9 % (2D, `e` = 0.7) (docs/granular.md).
/// The rough balls' ratio, whose theory also counts contacts by molecular chaos, is allowed the
/// same (relative) `phi`.
fn beyond_enskog(dim: usize) -> f64 {
    let (side, count) = haff_gas(dim);
    packing_fraction(dim, side, count)
}

/// The driven steady state of smooth inelastic balls (`beta = -1`) against the balance of the
/// thermostat's heating and the Enskog-Haff cooling. Heating (`noslip_sim::thermostat`): a kick
/// injects `n (N - 1) m xi^2 dt / 2` on average. Cooling (Haff): `N omega / 2` contacts per
/// unit time, each losing `(1 - e^2) T`, `omega = omega_1 sqrt(T)` ([`enskog_frequency`]). Stationary,
///
/// ```text
/// n (N - 1) m xi^2 / 2 = N omega_1 (1 - e^2) T^(3/2) / 2
///   =>  T_ss = (n m xi^2 (N - 1) / (N (1 - e^2) omega_1))^(2/3).
/// ```
///
/// `xi` is chosen so that `T_ss = 1`, the Maxwellian start's temperature. The run waits
/// `5 / gamma` (`gamma = (3/2) (1 - e^2) omega / n`, the linearised relaxation rate of `T`
/// to `T_ss`), then averages `T_tr` over rows every half mean free time. The kicks come every
/// half mean free time: each raises `T` by `f = (1 - e^2) omega dt / n` (at most 0.13 here),
/// and the sawtooth changes the mean of `T^(3/2)` by about `(3/8) f^2 / 12`, below 0.06 %.
/// Two corrections are taken from the run itself, both first-principles: the heating its kicks
/// actually gave (`P`, the summary's injected energy over time, whose expectation is the one
/// above: checked too, within the statistics alone) and the velocity distribution's departure
/// from a Maxwellian, whose kurtosis `a_2` changes the cooling rate by `1 + 3 a_2 / 16` (van
/// Noije & Ernst, Granular Matter 1, 57 (1998); `a_2` of a few hundredths here, so at most
/// 0.3 % in `T`). So each run's measured `T_tr` is compared with
/// `T_ss (P / <P>)^(2/3) (1 + 3 a_2 / 16)^(-2/3)`. What remains is the Enskog theory's own
/// accuracy ([`beyond_enskog`]).
fn steady(dim: usize, e: f64, window: f64) {
    let (side, count) = haff_gas(dim);
    let (n, big) = (dim as f64, count as f64);
    let omega1 = enskog_frequency(dim, side, count);
    let xi2 = big * (1.0 - e * e) * omega1 / (n * (big - 1.0));
    let xi = xi2.sqrt();
    let dt = 1.0 / omega1;
    let text = periodic_gas(
        dim,
        side,
        count,
        &format!(
            "[contact]\nballs = {{ e = {e}, beta = -1 }}\n[random]\nseed = {{seed}}\n\
             velocities = \"maxwellian\"\n[thermostat]\nkind = \"white-noise\"\n\
             strength = {xi}\ninterval = {dt}\nseed = {{seed}}\n"
        ),
    );
    let gamma = 1.5 * (1.0 - e * e) * omega1 / n;
    let (wait, window) = (5.0 / gamma, window / gamma);
    let (mut raw, mut temperature) = (Vec::new(), Vec::new());
    let (mut power, mut a2) = (Vec::new(), Vec::new());
    for seed in 0..6 {
        // Rows every `dt / sqrt(2)`: their phases in the kicks' sawtooth spread evenly, so
        // that their mean is the time average (rows every `dt` would all follow a kick).
        let run = driven(
            &text,
            seed,
            dt * std::f64::consts::FRAC_1_SQRT_2,
            wait + window,
        );
        let late: Vec<&Row> = run.rows.iter().filter(|r| r.time >= wait).collect();
        let k = late.len() as f64;
        let t_tr = late.iter().map(|r| r.t_tr).sum::<f64>() / k;
        let a = late.iter().map(|r| r.a2).sum::<f64>() / k;
        let expected = n * (big - 1.0) * xi2 / 2.0 * run.summary.kicks as f64 * dt;
        let heating = run.summary.energy_injected / expected;
        raw.push(t_tr);
        temperature.push(t_tr / (heating / (1.0 + 3.0 * a / 16.0)).powf(2.0 / 3.0));
        a2.push(a);
        power.push(heating);
    }
    let (r, sr) = mean_se(&raw);
    let (t, st) = mean_se(&temperature);
    let (p, sp) = mean_se(&power);
    let (a, sa) = mean_se(&a2);
    eprintln!(
        "driven {dim}D, e = {e}: T_tr / T_ss = {r:.4} +- {sr:.4}; with the run's heating and a2: \
         {t:.4} +- {st:.4}; injected / theory = {p:.4} +- {sp:.4}, a2 = {a:.4} +- {sa:.4} \
         (6 seeds)"
    );
    assert!(
        st < 0.006 && sp < 0.01,
        "too noisy to test: {temperature:?} {power:?}"
    );
    assert!(
        (t - 1.0).abs() < T_5 * st + beyond_enskog(dim),
        "{temperature:?}"
    );
    assert!((p - 1.0).abs() < T_5 * sp, "{power:?}");
    assert!(
        a.abs() < 0.05,
        "a2 = {a}: the Maxwellian theory's correction is not small"
    );
}

#[test]
fn the_driven_steady_state_in_2d_and_3d() {
    steady(2, 0.9, 30.0);
    steady(3, 0.7, 30.0);
}

/// Every case over windows four times longer, and the rough balls' ratio likewise
/// (docs/granular.md's tables): `cargo test -p noslip-sim --test sim driven:: -- --ignored
/// --nocapture`.
#[test]
#[ignore = "several minutes; docs/granular.md"]
fn the_driven_steady_state_over_long_windows() {
    for (dim, e) in [(2, 0.9), (2, 0.7), (3, 0.9), (3, 0.7)] {
        steady(dim, e, 120.0);
    }
    for (dim, window) in [(3, 120.0), (2, 240.0)] {
        ratio_agrees(dim, window);
    }
}

/// Rough balls driven in translation only (`beta` = 0.9, where the Maxwellian two-temperature
/// theory holds for the cooling state, `granular.rs`). In that theory (`common::TwoTemperature`,
/// `tau` the contacts per ball) `n dT_rot/dtau = c T_tr - d T_rot`: the kicks do not reach the
/// spins, so the rotational temperature has no other source, and its stationarity fixes
///
/// ```text
/// T_rot / T_tr = c / d = eta / (1 - eta / k),    eta = k (1 + beta) / (2 (1 + k)),
/// ```
///
/// whatever the forcing's strength (hard balls have no scale of time or energy: a stronger
/// forcing only makes the same state hotter and faster) and whatever `e`. The translational
/// balance `n (N - 1) m xi^2 / N = omega_1 T_tr^(3/2) (a - b c / d)` sets `xi` for `T_tr = 1`
/// (a scale only: `T_tr` itself is not tested here). Uniform solid balls (`k = 2 / (n + 2)`):
/// 3D 0.8444, 2D 0.8636 at `beta = 0.9`. The run waits `5 / gamma` (`gamma` the slower of the
/// two relaxation rates: `d / n` per contact of the ratio, `(3/2) (a - b c / d) / n` of `T_tr`),
/// then averages the ratio of the rows' temperatures over `window / gamma`; six seeds, the
/// standard error below `0.004` of the ratio (a theory off by more than 2.7 % fails).
fn driven_ratio(dim: usize, e: f64, beta: f64, window: f64) -> (f64, f64, f64) {
    let (side, count) = haff_gas(dim);
    let (n, big) = (dim as f64, count as f64);
    let k = 2.0 / (n + 2.0);
    let theory = two_temperature(dim, e, beta, k);
    let ratio = theory.c / theory.d;
    let omega1 = enskog_frequency(dim, side, count);
    let heat = theory.a - theory.b * ratio;
    let xi = (big * omega1 * heat / (n * (big - 1.0))).sqrt();
    let dt = 1.0 / omega1;
    let text = periodic_gas(
        dim,
        side,
        count,
        &format!(
            "[contact]\nballs = {{ e = {e}, beta = {beta} }}\n[random]\nseed = {{seed}}\n\
             velocities = \"maxwellian\"\n[thermostat]\nkind = \"white-noise\"\n\
             strength = {xi}\ninterval = {dt}\nseed = {{seed}}\n"
        ),
    );
    let gamma = (theory.d / n).min(1.5 * heat / n) * omega1;
    let (wait, window) = (5.0 / gamma, window / gamma);
    let mut measured = Vec::new();
    for seed in 0..6 {
        let run = driven(
            &text,
            seed,
            dt * std::f64::consts::FRAC_1_SQRT_2,
            wait + window,
        );
        let late: Vec<&Row> = run.rows.iter().filter(|r| r.time >= wait).collect();
        measured.push(late.iter().map(|r| r.t_rot / r.t_tr).sum::<f64>() / late.len() as f64);
    }
    let (mean, se) = mean_se(&measured);
    eprintln!(
        "driven rough {dim}D, e = {e}, beta = {beta}: T_rot / T_tr = {mean:.4} +- {se:.4}, \
         theory c / d = {ratio:.4} (6 seeds)"
    );
    assert!(se < 0.004 * ratio, "too noisy to test: {measured:?}");
    (mean, se, ratio)
}

/// [`driven_ratio`] at `e = beta = 0.9` agrees with `c / d` within the statistics and
/// [`beyond_enskog`].
fn ratio_agrees(dim: usize, window: f64) {
    let (mean, se, theory) = driven_ratio(dim, 0.9, 0.9, window);
    let within = T_5 * se + beyond_enskog(dim) * theory;
    assert!(
        (mean - theory).abs() < within,
        "{dim}D: {mean} +- {se} vs {theory}"
    );
}

#[test]
fn rough_balls_driven_in_translation_keep_the_two_temperature_ratio() {
    // The 2D gas's single rotational degree of freedom per ball fluctuates more: a longer window.
    for (dim, window) in [(3, 30.0), (2, 60.0)] {
        ratio_agrees(dim, window);
    }
}

/// A lone ball in a periodic box, kicked, with a limit of contacts but none of time: the
/// engine finds that no contact can come, and the run stops there (kicks would go on forever);
/// with a time limit, the kicks go on to it.
#[test]
fn a_lone_kicked_ball_stops_without_a_time_limit() {
    let text = "dim = 2\n[box]\nsize = [10, 10]\nboundary = [\"periodic\", \"periodic\"]\n\
                [[species]]\nmass = 1\nradius = \"1/2\"\ncount = 1\n[thermostat]\n\
                kind = \"white-noise\"\nstrength = 1\ninterval = \"0.5\"\n";
    let scene = Scene::from_toml(text, "lone.toml").unwrap();
    let run = |time: Option<f64>| {
        let setup = setup::<2, 1>(&scene).unwrap();
        let species = setup.species.clone();
        let kernels = GenericKernels {
            species: species.clone(),
        };
        let mut sim = Simulation::new(setup, kernels).unwrap();
        let limits = Limits {
            events: Some(10),
            time,
            samples: 1,
            traced: 1,
            contact_points: 0,
        };
        run_observed(
            &mut sim,
            &species,
            &limits,
            None,
            &mut |_| {},
            &mut |_, _, _| Ok(()),
        )
        .unwrap()
        .0
    };
    let endless = run(None);
    assert_eq!(endless.events, 0);
    assert!(endless.stopped.is_some(), "{endless:?}");
    let timed = run(Some(50.0));
    assert_eq!(
        (timed.events, timed.kicks, timed.time),
        (0, 100, 50.0),
        "{timed:?}"
    );
}
