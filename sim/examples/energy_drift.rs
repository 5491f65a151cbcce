//! The energy drift of the shipped one-disk tables, contact by contact, in exact rationals.
//!
//! ```sh
//! cargo run --release -p noslip-sim --example energy_drift -- walls 100000
//! cargo run --release -p noslip-sim --example energy_drift -- sinai 100000
//! cargo run --release -p noslip-sim --example energy_drift -- random 4 0.3 4 100000
//! ```
//!
//! `random N R SEEDS CONTACTS`: one ball in R^N (`gamma2 = 2/(N+2)`, radius `R`) bouncing off
//! walls `+-e_k` with the axis drawn at random (as in `src/kernels/energy_drift.rs`), one
//! line per seed: the mean energy change per contact, its rms, and the drift in units of the
//! random walk `rms sqrt(CONTACTS)`: with exactly unit normals, the constants' bias and the
//! arithmetic's.
//!
//! Runs `scenes/disk_between_walls.toml` or `scenes/sinai.toml` (their `f64` setups, written
//! out here) with the generic kernels, and for every contact splits the exact energy change
//! `E(post) - E(pre)` of the `f64` states (`E = m/2 (|u|^2 + g R^2 U_01^2)`, `g`, `R` the
//! `f64` parameters) into:
//!
//! - **normal**: `E(M(pre)) - E(pre)` with `M` the exact map at the `f64` normal, which is not
//!   exactly unit (walls: exactly unit, 0); first order:
//!   `2 m (|nu|^2 - 1) (dn^2 / (1 + g) + g |t|^2 / (1 + g)^2)`;
//! - **constants**: the exact map with the kernel's rounded constants (`p = g/(1+g)` and
//!   `rho = 2/(R(1+g))`, each rounded) minus `M`, against its first-order prediction
//!   `m/2 4 g/(1+g)^2 (g e_p + e_rho) |t|^2` (`e_p`, `e_rho` their relative roundings);
//! - **arithmetic**: the rest, the roundings of the contact's own operations.
//!
//! Every figure is per contact, in eps of the initial energy.

use collision_core::{Ball, BodyState, Exact, Generated, Kernel};
use noslip_sim::{Body, Contact, FixedBall, GenericKernels, Setup, Simulation, Step};
use rand::{Rng as _, SeedableRng};
use rand_chacha::ChaCha8Rng;

type State = BodyState<f64, 2, 1>;
type ExactState = BodyState<Exact, 2, 1>;

fn exact(x: f64) -> Exact {
    Exact::from_float(x).expect("finite")
}

fn exact_state(s: &State) -> ExactState {
    BodyState {
        spin: s.spin.map(exact),
        velocity: s.velocity.map(exact),
    }
}

fn int(k: i64) -> Exact {
    Exact::from_integer(k)
}

/// The disk and the setup of a shipped one-disk scene.
fn scene(name: &str) -> (Ball<f64>, Setup<2, 1>) {
    let disk = |radius: f64| Ball {
        inv_mass: 1.0,
        radius,
        gamma2: 0.5, // uniform disk: 2 / (n + 2)
    };
    match name {
        "walls" => {
            let ball = disk(0.5);
            let setup = Setup {
                size: [10.0, 4.0],
                periodic: [true, false],
                species: vec![ball.clone()],
                obstacles: vec![],
                bodies: vec![Body {
                    species: 0,
                    position: [1.0, 2.0],
                    state: State::from_scalar_spin(2.0, [0.3, 1.0]),
                }],
                orientation: false,
                table: noslip_sim::Table::boxed(),
            };
            (ball, setup)
        }
        "sinai" => {
            let ball = disk(1.0 / 20.0);
            let setup = Setup {
                size: [1.0, 1.0],
                periodic: [true, true],
                species: vec![ball.clone()],
                obstacles: vec![FixedBall {
                    position: [0.5, 0.5],
                    radius: 0.3,
                }],
                bodies: vec![Body {
                    species: 0,
                    position: [0.1, 0.1],
                    state: State::from_scalar_spin(0.0, [0.6, 0.8]),
                }],
                orientation: false,
                table: noslip_sim::Table::boxed(),
            };
            (ball, setup)
        }
        _ => panic!("scene: walls or sinai"),
    }
}

/// The fixed map (body 1 at rest) in exact arithmetic, in the two-constant form with the
/// given velocity constant `p` and spin constant `rho`.
fn two_constant_map(
    nu: &[Exact; 2],
    r: &Exact,
    p: &Exact,
    rho: &Exact,
    s: &ExactState,
) -> ExactState {
    let (t, dn) = slip(nu, r, s);
    let velocity = std::array::from_fn(|k| &s.velocity[k] - int(2) * (&dn * &nu[k] + p * &t[k]));
    let nu_t = &t[0] * &nu[1] - &nu[0] * &t[1];
    BodyState {
        spin: [&s.spin[0] + rho * nu_t],
        velocity,
    }
}

/// The slip `t = u - dn nu - R U nu` and `dn = u . nu` (2D: `(U nu) = (U_01 nu_1, -U_01 nu_0)`).
fn slip(nu: &[Exact; 2], r: &Exact, s: &ExactState) -> ([Exact; 2], Exact) {
    let w = r * &s.spin[0];
    let c = [&nu[1] * &w, -(&nu[0] * &w)];
    let dn = &s.velocity[0] * &nu[0] + &s.velocity[1] * &nu[1];
    let t = std::array::from_fn(|k| &s.velocity[k] - &dn * &nu[k] - &c[k]);
    (t, dn)
}

/// One ball between walls, `contacts` contacts per seed (see the module docs).
fn random_walls<const N: usize, const S: usize>(radius: f64, seeds: u64, contacts: usize)
where
    Generated: Kernel<f64, N, S>,
{
    let ball = Ball {
        inv_mass: 1.0,
        radius,
        gamma2: 2.0 / (N as f64 + 2.0),
    };
    let weight = exact(ball.gamma2) * exact(radius) * exact(radius);
    let energy = |s: &BodyState<f64, N, S>| {
        let sum2 = |v: &[f64]| v.iter().map(|&x| exact(x) * exact(x)).sum::<Exact>();
        sum2(&s.velocity) + &weight * sum2(&s.spin)
    };
    for seed in 0..seeds {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut s = BodyState::<f64, N, S> {
            spin: std::array::from_fn(|_| rng.random_range(-1.0..1.0)),
            velocity: std::array::from_fn(|_| rng.random_range(-1.0..1.0)),
        };
        let e0 = energy(&s).to_f64();
        let mut before = energy(&s);
        let (mut sum, mut sum2) = (0.0, 0.0);
        for _ in 0..contacts {
            let axis = rng.random_range(0..N);
            let side = if s.velocity[axis] < 0.0 { 1.0 } else { -1.0 };
            let nu: [f64; N] = std::array::from_fn(|k| if k == axis { side } else { 0.0 });
            s = Generated::fixed(&nu, &1.0, &ball, &BodyState::zero(), &s);
            let after = energy(&s);
            let change = (&after - &before).to_f64() / e0 / f64::EPSILON;
            before = after;
            sum += change;
            sum2 += change * change;
        }
        let rms = (sum2 / contacts as f64).sqrt();
        println!(
            "n = {N}, R = {radius}, seed {seed}: mean {:.4} eps per contact, rms {rms:.3} eps, drift = {:.1} random walks",
            sum / contacts as f64,
            sum / (rms * (contacts as f64).sqrt())
        );
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let name = args.get(1).map_or("walls", String::as_str);
    if name == "random" {
        let arg = |k: usize| args.get(k).expect("random N R SEEDS CONTACTS");
        let radius: f64 = arg(3).parse().expect("R");
        let seeds: u64 = arg(4).parse().expect("SEEDS");
        let contacts: usize = arg(5).parse().expect("CONTACTS");
        match arg(2).as_str() {
            "2" => random_walls::<2, 1>(radius, seeds, contacts),
            "3" => random_walls::<3, 3>(radius, seeds, contacts),
            "4" => random_walls::<4, 6>(radius, seeds, contacts),
            "5" => random_walls::<5, 10>(radius, seeds, contacts),
            "6" => random_walls::<6, 15>(radius, seeds, contacts),
            n => panic!("N must be 2..6, got {n}"),
        }
        return;
    }
    let contacts: u64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(100_000);
    let (ball, setup) = scene(name);
    let kernels = GenericKernels {
        species: setup.species.clone(),
    };
    let mut sim = Simulation::new(setup, kernels).expect("valid setup");

    let (g, r) = (exact(ball.gamma2), exact(ball.radius));
    let half = Exact::pow2(-1);
    let energy = |s: &ExactState| {
        let u2 = &s.velocity[0] * &s.velocity[0] + &s.velocity[1] * &s.velocity[1];
        &half * (u2 + &g * &r * &r * &s.spin[0] * &s.spin[0])
    };
    let ball_x = Ball {
        inv_mass: int(1),
        radius: r.clone(),
        gamma2: g.clone(),
    };
    // The constants as the f64 kernel computes them: d = 1 + g, p = g / d, rho = 2 / (R d).
    let d = 1.0 + ball.gamma2;
    let (rho, p) = (exact(2.0 / (ball.radius * d)), exact(ball.gamma2 / d));
    let p_true = &g / (int(1) + &g);
    let rho_true = int(2) / (&r * (int(1) + &g));
    let bias = (&g * (&p - &p_true) / &p_true + (&rho - &rho_true) / &rho_true).to_f64();

    let e0 = energy(&exact_state(sim.state(0)));
    let zero = ExactState::zero();
    let sum = || Exact::from_integer(0);
    let (mut normal, mut constants, mut arithmetic) = (sum(), sum(), sum());
    let (mut predicted_normal, mut predicted_constants) = (0.0, 0.0);
    let mut unit_error = 0.0;
    let mut n = 0u64;
    while n < contacts {
        let event = match sim.step(f64::INFINITY) {
            Step::Contact(event) => event,
            Step::Quiet { .. } => continue,
            _ => break,
        };
        if matches!(event.contact, Contact::Ball { .. }) {
            continue;
        }
        n += 1;
        let pre = exact_state(&event.pre[0]);
        let nu = event.nu.map(exact);
        let exact_map =
            <Generated as Kernel<Exact, 2, 1>>::fixed(&nu, &int(1), &ball_x, &zero, &pre);
        let rounded = two_constant_map(&nu, &r, &p, &rho, &pre);
        let e_pre = energy(&pre);
        normal += energy(&exact_map) - &e_pre;
        constants += energy(&rounded) - energy(&exact_map);
        arithmetic += energy(&exact_state(&event.post[0])) - energy(&rounded);
        let (t, dn) = slip(&nu, &r, &pre);
        let t2 = (&t[0] * &t[0] + &t[1] * &t[1]).to_f64();
        let dn = dn.to_f64();
        let e = (&nu[0] * &nu[0] + &nu[1] * &nu[1] - int(1)).to_f64();
        unit_error += e;
        let gf = ball.gamma2;
        predicted_normal += 2.0 * e * (dn * dn / (1.0 + gf) + gf * t2 / ((1.0 + gf) * (1.0 + gf)));
        predicted_constants += 0.5 * 4.0 * gf / ((1.0 + gf) * (1.0 + gf)) * bias * t2;
    }
    let e0f = e0.to_f64();
    let per = |x: f64| x / e0f / n as f64 / f64::EPSILON;
    let per_x = |x: &Exact| per(x.to_f64());
    let e1 = energy(&exact_state(sim.state(0)));
    let drift = ((&e1 - &e0) / &e0).to_f64();
    println!(
        "{name}: {n} contacts, relative drift {drift:.3e} ({:.4} eps per contact)",
        per(e1.to_f64() - e0f)
    );
    println!(
        "  normal      {:.4}  (first order: {:.4}; mean |nu|^2 - 1 = {:.4} eps)",
        per_x(&normal),
        per(predicted_normal),
        unit_error / n as f64 / f64::EPSILON
    );
    println!(
        "  constants   {:.4}  (first order: {:.4})",
        per_x(&constants),
        per(predicted_constants)
    );
    println!("  arithmetic  {:.4}", per_x(&arithmetic));
}
