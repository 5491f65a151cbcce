//! Where the `fixed` kernel's residual energy bias comes from (issue 28 item 4;
//! `docs/accuracy.md`, "Energy bias"): the shipped kernel against two references on the same
//! one-ball tables, with the statistic of `energy_bias.rs`.
//!
//! ```sh
//! cargo run --release -p noslip-sim --example energy_bias_sources -- 1000000
//! cargo run --release -p noslip-sim --example energy_bias_sources -- 1000000 --radius 1/8 scenes/strip.toml
//! cargo run --release -p noslip-sim --example energy_bias_sources -- 1000000 --only coefficients
//! ```
//!
//! Arguments: contacts per run (default 10^6), then optionally `--radius p/q` (every species'
//! radius replaced, to compare a dyadic radius with the scene's), `--only NAME` (one kernel:
//! `generated`, `coefficients` or `rounded`; the exact one is slow, about 20 s per 10^6
//! contacts), then scene files (default: every `scenes/*.toml` with one ball). Per scene and
//! kernel: the mean change of `E = |u|^2 + g R^2 sum U_ij^2` per contact in eps of `E_0`, its
//! standard error from 100 batch means and `z` = mean / standard error.
//!
//! The kernels, all the `fixed` map of the ball against the table at rest:
//!
//! - `generated`: the shipped kernel (`kernels::dN::fixed`).
//! - `coefficients`: the map with exact coefficients. `p = g / (1 + g)` to about `u^2`
//!   (`1 + g` by TwoSum, the quotient's remainder by one fused multiply-add), carried as
//!   head + tail in both the velocity's `p` and the spin's `2 (1 - p)` (the shipped kernel
//!   carries `2 (1 - p^)` of the rounded `p^`), and `R U` exact (TwoProduct) in the slip.
//!   Every other operation is the shipped kernel's. This is the change issue 28 suggested,
//!   measured before building it into the generator.
//! - `rounded`: the correctly rounded map: the kernel's rational map evaluated exactly
//!   (`Exact`) on the float inputs, each output rounded once to `f64`.

use collision_core::{with_dim, Ball, BodyState, Exact, Generated, Kernel};
use noslip_scene::Scene;
use noslip_sim::setup::setup;
use noslip_sim::{GenericKernels, PairKernels, Simulation, Step};

/// Batches of the standard error.
const BATCHES: usize = 100;

fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// `|u|^2 + w sum U_ij^2` in double-double, `w = g R^2` (as in `energy_bias.rs`: the one
/// rounding of `w` is a fixed factor of the spin part, whose changes telescope).
fn energy<const N: usize, const S: usize>(w: f64, s: &BodyState<f64, N, S>) -> (f64, f64) {
    let terms = s.velocity.iter().map(|&x| (1.0, x));
    terms
        .chain(s.spin.iter().map(|&x| (w, x)))
        .fold((0.0, 0.0), |(hi, lo), (c, x)| {
            let (sq, sq_lo) = two_prod(x, x);
            let (a, a_lo) = two_prod(c, sq);
            let (s, e) = two_sum(hi, a);
            (s, lo + e + a_lo + c * sq_lo)
        })
}

/// The `fixed` map with exact coefficients (module docs): `u+ = u - 2 (dn nu + p t)`,
/// `U+ = U + nu ^ (2 (1 - p) t / R)`, `t = u - dn nu - (R U) nu` with `R U` as `hi + lo`.
fn exact_coefficients<const N: usize, const S: usize>(
    nu: &[f64; N],
    ball: &Ball<f64>,
    s: &BodyState<f64, N, S>,
) -> BodyState<f64, N, S> {
    let (r, g) = (ball.radius, ball.gamma2);
    let u = s.spin_matrix();
    let dn: f64 = (0..N).map(|k| s.velocity[k] * nu[k]).sum();
    let t: [f64; N] = std::array::from_fn(|k| {
        let mut hi = s.velocity[k] - dn * nu[k];
        let mut lo = 0.0;
        for j in 0..N {
            let (wh, wl) = two_prod(r, u[k][j]);
            let (a, b) = two_prod(wh, nu[j]);
            let (sum, e) = two_sum(hi, -a);
            hi = sum;
            lo += e - b - wl * nu[j];
        }
        hi + lo
    });
    // p = q1 + q2: d + dl = 1 + g exactly, q1 = fl(g / d), g - q1 d exact by one fma.
    let (d, dl) = two_sum(1.0, g);
    let q1 = g / d;
    let q2 = ((-q1).mul_add(d, g) - q1 * dl) / d;
    let p_head = (1.0 - 2f64.powi(-20)) * q1;
    let p_tail = (q1 - p_head) + q2;
    let velocity = std::array::from_fn(|k| {
        s.velocity[k] - 2.0 * (dn * nu[k] + (p_head * t[k] + p_tail * t[k]))
    });
    // 2 (1 - p) = 2 (o_hi + o_lo), as head + tail (`noslip_codegen::unbiased`).
    let o_hi = 1.0 - q1;
    let o_lo = ((1.0 - o_hi) - q1) - q2;
    let head = (2.0 - 2f64.powi(-19)) * o_hi;
    let tail = (2.0 * o_hi - head) + 2.0 * o_lo;
    let y: [f64; N] = std::array::from_fn(|k| (head * t[k] + tail * t[k]) / r);
    let mut spin = s.spin;
    let pairs = (0..N).flat_map(|i| (i + 1..N).map(move |j| (i, j)));
    for (x, (i, j)) in spin.iter_mut().zip(pairs) {
        *x += y[i] * nu[j] - nu[i] * y[j];
    }
    BodyState { spin, velocity }
}

/// The kernel's rational map on the float inputs, each output rounded once.
fn correctly_rounded<const N: usize, const S: usize>(
    nu: &[f64; N],
    ball: &Ball<f64>,
    s: &BodyState<f64, N, S>,
) -> BodyState<f64, N, S>
where
    Generated: Kernel<Exact, N, S>,
{
    let x = |v: f64| Exact::from_float(v).expect("finite");
    let nu: [Exact; N] = std::array::from_fn(|k| x(nu[k]));
    let ball = Ball {
        inv_mass: x(ball.inv_mass),
        radius: x(ball.radius),
        gamma2: x(ball.gamma2),
    };
    let state = BodyState::<Exact, N, S> {
        spin: std::array::from_fn(|k| x(s.spin[k])),
        velocity: std::array::from_fn(|k| x(s.velocity[k])),
    };
    let after =
        <Generated as Kernel<Exact, N, S>>::fixed(&nu, &x(1.0), &ball, &BodyState::zero(), &state);
    BodyState {
        spin: std::array::from_fn(|k| after.spin[k].to_f64()),
        velocity: std::array::from_fn(|k| after.velocity[k].to_f64()),
    }
}

/// The pair kernels with one of the two reference `fixed` maps for every boundary.
struct Reference {
    species: Vec<Ball<f64>>,
    exact: bool,
}

impl<const N: usize, const S: usize> PairKernels<f64, N, S> for Reference
where
    Generated: Kernel<f64, N, S> + Kernel<Exact, N, S>,
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
        self.ball_obstacle(species, &nu, state)
    }

    fn ball_obstacle(
        &self,
        species: usize,
        nu: &[f64; N],
        state: &BodyState<f64, N, S>,
    ) -> BodyState<f64, N, S> {
        let ball = &self.species[species];
        if self.exact {
            correctly_rounded(nu, ball, state)
        } else {
            exact_coefficients(nu, ball, state)
        }
    }
}

/// Mean energy change per contact (eps of `E_0`) and its batch-means standard error
/// (`energy_bias.rs`'s `measure`).
fn measure<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
    scene: &Scene,
    kernels: K,
    contacts: usize,
) -> (f64, f64) {
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
    if changes.len() < BATCHES {
        return (f64::NAN, f64::NAN);
    }
    let per_batch = changes.len() / BATCHES;
    let means: Vec<f64> = changes
        .chunks_exact(per_batch)
        .take(BATCHES)
        .map(|c| c.iter().sum::<f64>() / per_batch as f64)
        .collect();
    let mean = means.iter().sum::<f64>() / BATCHES as f64;
    let var = means.iter().map(|m| (m - mean).powi(2)).sum::<f64>() / (BATCHES - 1) as f64;
    (mean, (var / BATCHES as f64).sqrt())
}

fn report<const N: usize, const S: usize>(
    name: &str,
    scene: &Scene,
    contacts: usize,
    only: Option<&str>,
) where
    Generated: Kernel<f64, N, S> + Kernel<Exact, N, S>,
{
    let species = setup::<N, S>(scene).expect("valid scene").species;
    let mut cells = String::new();
    for kernel in ["generated", "coefficients", "rounded"] {
        if only.is_some_and(|o| o != kernel) {
            continue;
        }
        let (mean, se) = match kernel {
            "generated" => {
                let species = species.clone();
                measure::<N, S, _>(scene, GenericKernels { species }, contacts)
            }
            _ => {
                let exact = kernel == "rounded";
                let species = species.clone();
                measure::<N, S, _>(scene, Reference { species, exact }, contacts)
            }
        };
        cells += &format!(" {kernel}: {mean:+.5} | {se:.5} | {:+.1} |", mean / se);
    }
    let radius = species[0].radius;
    println!("| {name} | {N} | {radius} |{cells}");
}

fn main() {
    let mut args = std::env::args().skip(1).peekable();
    let contacts: usize = args
        .next()
        .map_or(1_000_000, |s| s.parse().expect("contacts"));
    assert!(contacts >= BATCHES, "at least {BATCHES} contacts");
    let (mut radius, mut only, mut files) = (None, None, Vec::new());
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--radius" => {
                let text = args.next().expect("--radius p/q");
                radius = Some(noslip_scene::parse_exact(&text).expect("a rational radius"));
            }
            "--only" => only = Some(args.next().expect("--only NAME")),
            _ => files.push(arg),
        }
    }
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
    println!("| scene | n | R | kernel: mean | se | z | ... |");
    for file in files {
        let text = std::fs::read_to_string(&file).expect("readable scene");
        let mut scene = Scene::from_toml(&text, &file).expect("valid scene");
        if let Some(r) = &radius {
            for species in &mut scene.species {
                species.radius = r.clone();
            }
        }
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
            |N, S| report::<N, S>(&name, &scene, contacts, only.as_deref()),
            ()
        );
    }
}
