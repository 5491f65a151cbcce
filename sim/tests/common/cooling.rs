//! The engine's homogeneous cooling state of rough balls (docs/granular.md): one freely
//! cooling run of a periodic gas, and six seeds of them. Shared by `granular.rs` (against the
//! two-temperature theory) and `cooling_state.rs` (against the Boltzmann equation's DSMC and
//! the box's hydrodynamic stability).

use super::{mean_se, periodic_gas, two_temperature};
use collision_core::{Generated, Kernel};
use noslip_scene::Scene;
use noslip_sim::granular::temperatures;
use noslip_sim::setup::setup;
use noslip_sim::{GenericKernels, PairKernels, Setup, Simulation, Step};
use std::f64::consts::TAU;

/// [`periodic_gas`] with the rough law `{ e, beta }` at every ball-ball contact and a
/// Maxwellian start at equal temperatures: a freely cooling gas.
pub fn cooling_gas(dim: usize, side: f64, count: usize, e: f64, beta: f64) -> String {
    periodic_gas(
        dim,
        side,
        count,
        &format!(
            "[contact]\nballs = {{ e = {e}, beta = {beta} }}\n[random]\nseed = {{seed}}\n\
             velocities = \"maxwellian\"\n"
        ),
    )
}

/// What one cooling run measured over its window.
#[derive(Clone, Copy, Debug)]
pub struct Run {
    /// The mean of `T_rot / T_tr` over the samples.
    pub ratio: f64,
    /// `<T_rot / E> / <T_tr / E>`, `E = n T_tr + S T_rot` (twice the energy per ball): the
    /// ratio of the two temperatures' means once the cooling is scaled out by a quantity that
    /// changes only through dissipation, so without the `O(1 / N_b)` bias of a mean of ratios
    /// of fluctuating temperatures.
    pub ratio_of_means: f64,
    /// Contacts per ball and unit time over `sqrt(T_tr)` in the window's first and last
    /// quarters (equal while the gas stays homogeneous).
    pub frequency: [f64; 2],
    /// The momentum field's transverse and longitudinal structure factors on the box's lowest
    /// shell of wave vectors, `k = 2 pi / L` along each axis (both 1 without correlations;
    /// NaN unless asked for): see [`modes`].
    pub shell: [f64; 2],
}

/// The momentum field's structure factors on the lowest shell of the periodic box (side `L`
/// on every axis): with `c_i = u_i - V` (equal masses) and `j(k) = sum_i c_i exp(-i k . x_i)`,
/// for `k = (2 pi / L) e_a`, `a = 1..n`,
///
/// ```text
/// S_par  = (1/n) sum_a |j_a(k_a)|^2 / (sum_i |c_i|^2 / n),
/// S_perp = (1/n) sum_a sum_{b != a} |j_b(k_a)|^2 / ((n - 1) sum_i |c_i|^2 / n).
/// ```
///
/// Velocities independent of positions (molecular chaos at the box's scale) give 1 for both
/// (`E |j_b(k)|^2 = sum_i c_ib^2`). A shear flow `U sin(k x)` of the box's size adds `N_b^2
/// U^2 / 4` to `|j_b(k)|^2`: `S_perp - 1` counts the box-scale vortical flow that a `T_tr`
/// about the centre of mass's velocity reads as heat, `(S_perp - 1) 2 (n - 1) / N_b` of it (the
/// `2 n` vectors `+-k_a`). Linear fluctuating hydrodynamics of the cooling state (van Noije,
/// Ernst, Brito & Orza, PRL 79, 411 (1997)) has `S_perp(k) = 1 / (1 - (k_c / k)^2)` below the
/// shear instability `k > k_c`, `k_c^2 = zeta / (2 nu)`.
pub fn modes<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
    sim: &Simulation<N, S, K>,
) -> [f64; 2] {
    let balls = sim.len();
    let v: [f64; N] = std::array::from_fn(|b| {
        (0..balls).map(|i| sim.state(i).velocity[b]).sum::<f64>() / balls as f64
    });
    let mut heat = 0.0;
    // re[a][b], im[a][b]: component b of j at k_a.
    let (mut re, mut im) = ([[0.0f64; N]; N], [[0.0f64; N]; N]);
    for i in 0..balls {
        let x = sim.position(i);
        let c: [f64; N] = std::array::from_fn(|b| sim.state(i).velocity[b] - v[b]);
        heat += c.iter().map(|y| y * y).sum::<f64>();
        for a in 0..N {
            let (s, co) = (TAU * x[a] / sim.box_size()[a]).sin_cos();
            for b in 0..N {
                re[a][b] += c[b] * co;
                im[a][b] -= c[b] * s;
            }
        }
    }
    let n = N as f64;
    let (mut par, mut perp) = (0.0, 0.0);
    for a in 0..N {
        for b in 0..N {
            let j2 = re[a][b] * re[a][b] + im[a][b] * im[a][b];
            if a == b {
                par += j2 / (heat / n) / n;
            } else {
                perp += j2 / ((n - 1.0) * heat / n) / n;
            }
        }
    }
    [perp, par]
}

/// One freely cooling run (a periodic gas, ball-ball contacts only): the Maxwellian start of
/// `scene` with the centre of mass brought to rest and every spin multiplied by `spin` (so
/// `T_rot / T_tr` starts near `spin^2`), run for `skip + window` contacts per ball, sampled
/// every half contact per ball in the window ([`Run`]; the lowest shell's structure factors
/// only if `shell`). Hard-ball dynamics is invariant under a common scaling of all velocities
/// and spins (it only rescales time), so whenever `T_tr` has fallen by `1e-8` the run is
/// restarted from the current positions with every velocity and spin scaled back up: the same
/// trajectory, kept in a comfortable floating-point range.
pub fn cooling<const N: usize, const S: usize>(
    scene: &Scene,
    spin: f64,
    skip: f64,
    window: f64,
    shell: bool,
) -> Run
where
    Generated: Kernel<f64, N, S>,
{
    let mut setup = setup::<N, S>(scene).unwrap();
    let balls = setup.bodies.len();
    let species = setup.species.clone();
    let restart = |setup: &mut Setup<N, S>, scale: f64| {
        // The centre of mass's velocity (equal masses).
        let v: [f64; N] = std::array::from_fn(|k| {
            setup
                .bodies
                .iter()
                .map(|b| b.state.velocity[k])
                .sum::<f64>()
                / balls as f64
        });
        for b in &mut setup.bodies {
            b.state.velocity = std::array::from_fn(|k| (b.state.velocity[k] - v[k]) * scale);
            b.state.spin = b.state.spin.map(|x| x * scale);
        }
    };
    for b in &mut setup.bodies {
        b.state.spin = b.state.spin.map(|x| x * spin);
    }
    restart(&mut setup, 1.0);
    let fresh = setup.clone();
    let kernels = || GenericKernels {
        species: species.clone(),
    };
    let mut sim = Simulation::new(setup, kernels()).unwrap();
    let t_start = temperatures(&sim, &species)[0];
    let every = (balls / 4) as u64;
    // Contacts and time (in the start's units) before the current run; `scale` the factor
    // its velocities were scaled by, all told.
    let (mut done, mut origin, mut scale) = (0u64, 0.0f64, 1.0f64);
    let (mut ratios, mut clock) = (Vec::new(), Vec::new());
    let (mut scaled, mut shells) = ([0.0f64; 2], Vec::new());
    loop {
        let Step::Contact(_) = sim.step(f64::INFINITY) else {
            panic!("the gas stopped colliding")
        };
        if sim.contacts() % every != 0 {
            continue;
        }
        let tau = 2.0 * (done + sim.contacts()) as f64 / balls as f64;
        let [tr, rot] = temperatures(&sim, &species);
        if tau >= skip {
            ratios.push(rot / tr);
            let energy = N as f64 * tr + S as f64 * rot;
            scaled[0] += tr / energy;
            scaled[1] += rot / energy;
            clock.push((tau, origin + sim.now() * scale, tr / (scale * scale)));
            if shell {
                shells.push(modes(&sim));
            }
        }
        if tau >= skip + window {
            break;
        }
        if tr < 1e-8 * t_start {
            let mut next = fresh.clone();
            for (i, b) in next.bodies.iter_mut().enumerate() {
                b.position = std::array::from_fn(|k| {
                    let x = sim.position(i)[k].rem_euclid(sim.box_size()[k]);
                    if x < sim.box_size()[k] {
                        x
                    } else {
                        0.0
                    }
                });
                b.state = sim.state(i).clone();
            }
            let up = (t_start / tr).sqrt();
            restart(&mut next, up);
            done += sim.contacts();
            origin += sim.now() * scale;
            scale *= up;
            sim = Simulation::new(next, kernels()).unwrap();
        }
    }
    let mean = |r: &[f64]| r.iter().sum::<f64>() / r.len() as f64;
    // Contacts per ball and unit time over sqrt(T_tr), sample to sample (`T_tr` at the
    // interval's geometric mean), averaged over the first and the last quarter.
    let k: Vec<f64> = clock
        .windows(2)
        .map(|w| (w[1].0 - w[0].0) / (w[1].1 - w[0].1) / (w[0].2 * w[1].2).powf(0.25))
        .collect();
    let q = k.len() / 4;
    let shell = if shell {
        let m = shells.len() as f64;
        [0, 1].map(|c| shells.iter().map(|s| s[c]).sum::<f64>() / m)
    } else {
        [f64::NAN; 2]
    };
    Run {
        ratio: mean(&ratios),
        ratio_of_means: scaled[1] / scaled[0],
        frequency: [mean(&k[..q]), mean(&k[k.len() - q..])],
        shell,
    }
}

/// A measured homogeneous cooling state over six seeds: per seed the mean of its runs'
/// `T_rot / T_tr` (`ratio`), and per start `(start, mean, standard error)`.
#[derive(Clone, Debug)]
pub struct Measured {
    pub mean: f64,
    pub se: f64,
    /// The six seeds' values.
    pub seeds: Vec<f64>,
    /// The same from [`Run::ratio_of_means`]: mean and standard error.
    pub of_means: (f64, f64),
    /// The two-temperature theory's `r_+`.
    pub theory: f64,
    pub starts: Vec<(f64, f64, f64)>,
    /// The relative change of the collision frequency over `sqrt(T_tr)` from the window's
    /// first quarter to its last, averaged over the runs.
    pub drift: f64,
    /// [`Run::shell`] averaged over the runs (NaN unless asked for).
    pub shell: [f64; 2],
}

impl Measured {
    /// The checks every use makes: the gas stayed homogeneous (the collision frequency over
    /// `sqrt(T_tr)` changed by less than 3 % over the window: a growing shear mode lowers it
    /// and carries energy into flow, clusters raise it; a single 2D run of 400 disks varies by
    /// a few per cent by chance), and the standard error is below `0.004 r_+` (power).
    pub fn checked(self) -> Self {
        assert!(self.drift.abs() < 0.03, "not homogeneous: {}", self.drift);
        assert!(
            self.se < 0.004 * self.theory,
            "too noisy to test: {:?}",
            self.seeds
        );
        self
    }
}

/// The engine's homogeneous cooling state's `T_rot / T_tr` in a periodic box of side `side`
/// (diameters) with `count` equal uniform balls, six seeds. The Maxwellian start has its spins
/// scaled so that `T_rot / T_tr` starts near one of `starts` (0: no spin, 1: equal
/// temperatures, 3: far above most ratios tested), and each run first waits out the ratio's
/// relaxation as the two-temperature theory gives it, until `|r - r_+| < 1e-3 r_+`
/// (`TwoTemperature::settled`); it then averages over `60 / kappa` contacts per ball (60
/// relaxation times). Each seed averages `replicas` independent runs from each start.
/// Prints a line; asserts nothing (see [`Measured::checked`]).
#[allow(clippy::too_many_arguments)]
pub fn hcs_in(
    dim: usize,
    side: f64,
    count: usize,
    e: f64,
    beta: f64,
    starts: &[f64],
    replicas: u64,
    shell: bool,
) -> Measured {
    let gas = cooling_gas(dim, side, count, e, beta);
    // Uniform balls: gamma^2 = 2 / (n + 2).
    let theory = two_temperature(dim, e, beta, 2.0 / (dim as f64 + 2.0));
    let window = 60.0 / theory.rate();
    let runs = starts.len() as u64 * replicas;
    // Per seed: the mean over all its runs, and over each start's.
    let (mut ratio, mut of_means, mut by_start) =
        (Vec::new(), Vec::new(), vec![Vec::new(); starts.len()]);
    let (mut drift, mut shells) = (0.0, [0.0; 2]);
    for seed in 0..6 {
        let (mut sum, mut sum_of_means) = (0.0, 0.0);
        for (k, &start) in starts.iter().enumerate() {
            let skip = theory.settled(start, 1e-3);
            let mut part = 0.0;
            for replica in 0..replicas {
                let id = seed * runs + k as u64 * replicas + replica;
                let text = gas.replace("{seed}", &id.to_string());
                let scene = Scene::from_toml(&text, "t.toml").unwrap();
                let spin = start.sqrt();
                let run = collision_core::with_dim!(
                    scene.dim,
                    |N, S| cooling::<N, S>(&scene, spin, skip, window, shell),
                    unreachable!()
                );
                let share = 1.0 / (6 * runs) as f64;
                drift += (run.frequency[1] / run.frequency[0] - 1.0) * share;
                shells = [0, 1].map(|c| shells[c] + run.shell[c] * share);
                part += run.ratio / replicas as f64;
                sum_of_means += run.ratio_of_means / runs as f64;
            }
            by_start[k].push(part);
            sum += part / starts.len() as f64;
        }
        ratio.push(sum);
        of_means.push(sum_of_means);
    }
    let (mean, se) = mean_se(&ratio);
    let r = theory.ratio();
    let starts: Vec<(f64, f64, f64)> = starts
        .iter()
        .zip(&by_start)
        .map(|(&start, x)| {
            let (m, s) = mean_se(x);
            (start, m, s)
        })
        .collect();
    let of_means = mean_se(&of_means);
    eprintln!(
        "HCS {dim}D, {count} in side {side}, e = {e}, beta = {beta}: {mean:.4} +- {se:.4} \
         (6 seeds x {runs}), theory {r:.4}, {:+.1} %, {:+.1} s; from {starts:.4?}; \
         ratio of means {:.4} +- {:.4}; frequency drift {:+.1} %; lowest shell S_perp {:.2}, \
         S_par {:.2}",
        100.0 * (mean / r - 1.0),
        (mean - r) / se,
        of_means.0,
        of_means.1,
        100.0 * drift,
        shells[0],
        shells[1]
    );
    Measured {
        mean,
        se,
        seeds: ratio,
        of_means,
        theory: r,
        starts,
        drift,
        shell: shells,
    }
}
