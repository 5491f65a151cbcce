//! A ball-ball law per pair of species (`[[contact.pair]]`, issue 27) in whole runs:
//!
//! - a scene listing every pair with the law of `contact.balls` writes the very event log
//!   (byte for byte) of the scene without pairs, and so does the shipped mixture with its
//!   pairs all set to one law;
//! - in a two-species gas whose three pairs have three rough laws, every contact of each pair
//!   leaves the normal and the tangential contact-point velocity `-e` and `-beta` times what
//!   they were, with that pair's `(e, beta)` (first principles, `docs/derivation.md` §15),
//!   and each pair kind occurs.

use crate::common;

use collision_core::BodyState;
use noslip_scene::Scene;
use noslip_sim::setup::setup;
use noslip_sim::{Contact, GenericKernels, Setup, Simulation, Step};
use std::path::Path;

/// The shipped mixture (`scenes/mixture2d.toml`) without its `[[contact.pair]]` tables and
/// its TC model, followed by `tail`.
fn mixture(tail: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/mixture2d.toml");
    let text = std::fs::read_to_string(path).unwrap();
    let (head, rest) = text.split_once("[[contact.pair]]").expect("pairs");
    let (_, random) = rest.split_once("[random]").expect("a [random] table");
    let head = head
        .lines()
        .filter(|l| !l.starts_with("tc ="))
        .collect::<Vec<_>>()
        .join("\n");
    format!("{head}\n{tail}\n[random]{random}")
}

fn scene(text: &str) -> Scene {
    Scene::from_toml(text, "mixture.toml").unwrap_or_else(|e| panic!("{e}"))
}

/// The event log of the first `events` contacts of `setup` (generic kernels,
/// `common::log_of`), which must run them all.
fn log_of(setup: Setup<2, 1>, events: u64) -> Vec<u8> {
    let (log, contacts) = common::log_of(setup, events);
    assert_eq!(contacts, events);
    log
}

#[test]
fn listing_every_pair_with_the_default_law_changes_no_byte_of_the_log() {
    const EVENTS: u64 = 3000;
    let plain = scene(&mixture(""));
    assert!(plain.pair_contacts.is_empty());
    let reference = log_of(setup::<2, 1>(&plain).unwrap(), EVENTS);
    // The default's law written another way (exact 9/10 and 1/2), pairs by name and index.
    let listed = scene(&mixture(
        "[[contact.pair]]\nspecies = [\"grain\", \"grain\"]\nlaw = { e = \"9/10\", beta = \"1/2\" }\n\
         [[contact.pair]]\nspecies = [1, \"grain\"]\nlaw = { e = \"0.9\", beta = \"0.5\" }\n\
         [[contact.pair]]\nspecies = [\"tracer\", 1]\nlaw = { e = 0.9, beta = 0.5 }\n",
    ));
    assert_eq!(listed.pair_contacts.len(), 3);
    let start = setup::<2, 1>(&listed).unwrap();
    assert!(!start.table.pair_contact.is_empty(), "the table is built");
    let log = log_of(start, EVENTS);
    let first = log.iter().zip(&reference).position(|(a, b)| a != b);
    assert!(log == reference, "the logs differ from byte {first:?}");
    // The logs see the pair laws: one other law for the grain-tracer pair changes them.
    let other = scene(&mixture(
        "[[contact.pair]]\nspecies = [\"grain\", \"tracer\"]\nlaw = { e = 0.9, beta = 0.4 }\n",
    ));
    assert!(log_of(setup::<2, 1>(&other).unwrap(), EVENTS) != reference);
}

/// The contact-point relative velocity `g = (u_2 - R_2 U_2 nu) - (u_1 + R_1 U_1 nu)` of two
/// disks in contact (`nu` from 1 to 2), split into its normal part `g . nu` and tangential
/// part `g - (g . nu) nu` (in 2D, `U x = c J x` with `J x = (x_1, -x_0)` for the compact
/// entry `c = U_01`), and the scale of the velocities it is made of.
fn contact_velocity(
    nu: &[f64; 2],
    radii: [f64; 2],
    s: &[BodyState<f64, 2, 1>; 2],
) -> (f64, [f64; 2], f64) {
    let spin = |c: f64, x: &[f64; 2]| [c * x[1], -c * x[0]];
    let (w1, w2) = (spin(s[0].spin[0], nu), spin(s[1].spin[0], nu));
    let g: [f64; 2] = std::array::from_fn(|k| {
        (s[1].velocity[k] - radii[1] * w2[k]) - (s[0].velocity[k] + radii[0] * w1[k])
    });
    let gn = g[0] * nu[0] + g[1] * nu[1];
    let gt = [g[0] - gn * nu[0], g[1] - gn * nu[1]];
    let scale = s.iter().zip(radii).fold(0.0, |acc, (b, r)| {
        acc + b.velocity[0].abs() + b.velocity[1].abs() + r * b.spin[0].abs()
    });
    (gn, gt, scale)
}

/// Each pair's contacts follow that pair's `(e, beta)`. Tolerance: the rough kernels' largest
/// measured `f64` error is 28.6 eps of the states' norm (docs/accuracy.md, "The rough-ball
/// family"), and forming `g` from the states adds a few roundings of the same size, so
/// `|g_n+ + e g_n| <= 64 eps s` and `|t+ + beta t| <= 64 eps s`, `s` the sum of the
/// magnitudes of the velocities and the spins times radii before and after (`e` and `beta`
/// are the nearest doubles of the scene's decimals, 2^-53 relative: inside the bound).
#[test]
fn every_contact_of_each_pair_follows_that_pairs_law() {
    // grain-grain (0.9, 0.5) by default; grain-tracer (0.6, -0.3); tracer-tracer (0.3, 0.8).
    let laws = [[0.9, 0.5], [0.6, -0.3], [0.3, 0.8]];
    let s = scene(&mixture(
        "[[contact.pair]]\nspecies = [\"grain\", \"tracer\"]\nlaw = { e = \"0.6\", beta = \"-0.3\" }\n\
         [[contact.pair]]\nspecies = [\"tracer\", \"tracer\"]\nlaw = { e = \"0.3\", beta = \"0.8\" }\n",
    ));
    let setup = setup::<2, 1>(&s).unwrap();
    let radii: Vec<f64> = setup.species.iter().map(|b| b.radius).collect();
    let kernels = GenericKernels {
        species: setup.species.clone(),
    };
    let mut sim = Simulation::new(setup, kernels).unwrap();
    let mut seen = [0usize; 3];
    let mut worst = [0.0f64; 2];
    while sim.contacts() < 4000 {
        let e = match sim.step(f64::INFINITY) {
            Step::Contact(e) => e,
            Step::Quiet { .. } | Step::Until => continue,
            Step::Never(why) => panic!("the gas stopped: {why:?}"),
            Step::LeftTable(left) => panic!("the gas stopped: {left}"),
        };
        let Contact::Ball { i, j } = e.contact else {
            panic!("a periodic gas has ball-ball contacts only: {e:?}");
        };
        let (a, b) = (sim.species_of(i), sim.species_of(j));
        let pair = a + b; // 0: grain-grain, 1: grain-tracer, 2: tracer-tracer
        let [el, beta] = laws[pair];
        let r = [radii[a], radii[b]];
        let (gn, gt, s0) = contact_velocity(&e.nu, r, &e.pre);
        let (gn1, gt1, s1) = contact_velocity(&e.nu, r, &e.post);
        let tol = 64.0 * f64::EPSILON * (s0 + s1);
        let normal = (gn1 + el * gn).abs();
        let tangential = (gt1[0] + beta * gt[0]).hypot(gt1[1] + beta * gt[1]);
        assert!(
            normal <= tol && tangential <= tol,
            "contact {} of species ({a}, {b}): g_n {gn} -> {gn1} (e = {el}), t {gt:?} -> \
             {gt1:?} (beta = {beta}), tolerance {tol:e}",
            sim.contacts()
        );
        worst = [worst[0].max(normal / tol), worst[1].max(tangential / tol)];
        seen[pair] += 1;
    }
    eprintln!("contacts per pair {seen:?}; largest deviation / tolerance {worst:?}");
    assert!(
        seen.iter().all(|&k| k > 0),
        "each pair kind occurs: {seen:?}"
    );
}

/// The observables' `lost_ball_ball` with several pair laws is the energy lost at every
/// ball-ball contact, whatever the pair's law: the sum of the per-contact losses
/// (`noslip_sim::granular::lost`) of the three pairs, added in the same order (so equal to
/// the bit in every row), each pair's share positive (every law dissipates), and the energy balance
/// `E_0 - E = lost` within the bound of `sim/tests/granular.rs` (64 eps of the start energy
/// per contact for the loss's roundings, plus the energy sums' own).
///
/// Each pair's columns (`lost_ball_ball_{a}-{b}`, `contacts_{a}-{b}`, named by the species)
/// are, in every row and to the bit, that pair's per-contact losses added in contact order
/// and its contacts counted. The pairs' columns add up to `lost_ball_ball` to rounding only
/// (two orders of summation of the same `C` losses `x_k`): each running sum of `C` terms is
/// within `(C - 1) u sum |x_k|` of the exact sum (`u = eps / 2`), the three pairs' sum adds
/// two roundings, so the two differ by at most `(C + 2) eps sum |x_k|`.
#[test]
fn lost_ball_ball_is_the_loss_of_every_pair_law() {
    use noslip_sim::granular::{lost, Sampler};
    let s = scene(&mixture(
        "[[contact.pair]]\nspecies = [\"grain\", \"tracer\"]\nlaw = { e = \"0.6\", beta = \"-0.3\" }\n\
         [[contact.pair]]\nspecies = [\"tracer\", \"tracer\"]\nlaw = { e = \"0.7\", mu = \"0.3\", beta0 = \"0.6\" }\n",
    ));
    let setup = setup::<2, 1>(&s).unwrap();
    let species = setup.species.clone();
    let kernels = GenericKernels {
        species: species.clone(),
    };
    let mut sim = Simulation::new(setup, kernels).unwrap();
    let names = ["grain".to_string(), "tracer".to_string()];
    let mut sampler = Sampler::start(1.0, &sim, &species).with_species_names(&names);
    let (mut total, mut per_pair, mut contacts_of) = (0.0, [0.0f64; 3], [0u64; 3]);
    let mut magnitudes = 0.0;
    // The losses summed here when each row was written: the total, and per pair.
    let mut at_rows = vec![0.0];
    let mut pairs_at_rows = vec![(vec![0.0; 3], vec![0; 3])];
    while let Step::Contact(e) = sim.step(5.0) {
        let Contact::Ball { i, j } = e.contact else {
            unreachable!("a periodic gas")
        };
        let loss = lost(&e, &sim, &species);
        total += loss;
        magnitudes += loss.abs();
        // 0: grain-grain, 1: grain-tracer, 2: tracer-tracer (the pairs' order).
        let pair = sim.species_of(i) + sim.species_of(j);
        per_pair[pair] += loss;
        contacts_of[pair] += 1;
        sampler.contact(&e, &sim, &species);
        if sampler.rows().len() > at_rows.len() {
            at_rows.push(total);
            pairs_at_rows.push((per_pair.to_vec(), contacts_of.to_vec()));
        }
    }
    let rows = sampler.rows();
    assert!(rows.len() >= 5, "a row per unit time");
    let row_losses: Vec<f64> = rows.iter().map(|r| r.lost[0]).collect();
    assert_eq!(row_losses, at_rows);
    // Each pair's columns, to the bit (`f64` equality: the same additions in the same order).
    let row_pairs: Vec<(Vec<f64>, Vec<u64>)> = rows
        .iter()
        .map(|r| (r.pair_lost.clone(), r.pair_contacts.clone()))
        .collect();
    assert_eq!(row_pairs, pairs_at_rows);
    let columns: Vec<String> = sampler.columns().into_iter().map(|c| c.0).collect();
    let tail: Vec<&str> = columns[columns.len() - 6..]
        .iter()
        .map(String::as_str)
        .collect();
    assert_eq!(
        tail,
        [
            "lost_ball_ball_grain-grain",
            "lost_ball_ball_grain-tracer",
            "lost_ball_ball_tracer-tracer",
            "contacts_grain-grain",
            "contacts_grain-tracer",
            "contacts_tracer-tracer"
        ]
    );
    let last_values = rows.last().unwrap().values();
    assert_eq!(last_values.len(), columns.len());
    let (lost_at_last, contacts_at_last) = pairs_at_rows.last().unwrap();
    assert_eq!(
        last_values[columns.len() - 6..columns.len() - 3],
        lost_at_last[..]
    );
    let counts: Vec<f64> = contacts_at_last.iter().map(|&k| k as f64).collect();
    assert_eq!(last_values[columns.len() - 3..], counts[..]);
    // The pairs add up to the total within two summation orders' rounding.
    let c = sim.contacts() as f64;
    let sum_of_pairs: f64 = per_pair.iter().sum();
    let rounding = (c + 2.0) * f64::EPSILON * magnitudes;
    assert!(
        (sum_of_pairs - total).abs() <= rounding,
        "{sum_of_pairs} {total} {rounding}"
    );
    assert_eq!(contacts_of.iter().sum::<u64>(), sim.contacts());
    let (first, last) = (&rows[0], rows.last().unwrap());
    let total = last.lost[0];
    assert!(per_pair.iter().all(|&l| l > 0.0), "{per_pair:?}");
    let contacts = sim.contacts() as f64;
    let bound = (64.0 * contacts + 40.0 * 170.0) * f64::EPSILON * first.energy;
    let drop = first.energy - last.energy;
    assert!((drop - total).abs() <= bound, "{drop} {total} {bound}");
    eprintln!(
        "{contacts} contacts; lost per pair {per_pair:?}, lost_ball_ball at the last row {total}"
    );
}

/// Two point masses (`gamma2 = 0`) under laws without tangential impulse (`beta = -1`, and
/// the Walton laws validation names so: `mu = 0`, `beta0 = -1`), the one rough law scenes
/// allow between point masses: the rough kernel's tangential coefficient is `0 / 0` there
/// (`D = 0`), and every state after the contact was NaN. Now the normal relative velocity
/// becomes `-e` times itself (to a few ulps of the speeds: `1e-15`), the momentum and the
/// spins are kept, and the run goes on to `t = 10` with finite states.
#[test]
fn point_masses_under_a_smooth_inelastic_law_collide_without_nan() {
    for law in [
        r#"{ e = "0.8", beta = -1 }"#,
        r#"{ e = "0.8", mu = 0, beta0 = 1 }"#,
        r#"{ e = "0.8", mu = 1, beta0 = -1 }"#,
    ] {
        let text = format!(
            r#"
dim = 2
[box]
size = [4, 4]
boundary = ["periodic", "periodic"]
[contact]
balls = {law}
[[species]]
mass = 1
radius = "1/5"
gamma2 = 0
[[ball]]
species = 0
position = [1, 1]
velocity = [1, 0]
[[ball]]
species = 0
position = [2, "1.1"]
"#
        );
        let setup: Setup<2, 1> = setup(&Scene::from_toml(&text, "points.toml").unwrap()).unwrap();
        let kernels = GenericKernels {
            species: setup.species.clone(),
        };
        let mut sim = Simulation::new(setup, kernels).unwrap();
        let Step::Contact(e) = sim.step(f64::INFINITY) else {
            panic!("{law}: the points must meet");
        };
        let dn = |s: &[BodyState<f64, 2, 1>; 2]| {
            (0..2)
                .map(|k| (s[1].velocity[k] - s[0].velocity[k]) * e.nu[k])
                .sum::<f64>()
        };
        assert!(dn(&e.pre) < 0.0, "{law}: approaching");
        assert!(
            (dn(&e.post) + 0.8 * dn(&e.pre)).abs() < 1e-15,
            "{law}: {e:?}"
        );
        for k in 0..2 {
            let p = |s: &[BodyState<f64, 2, 1>; 2]| s[0].velocity[k] + s[1].velocity[k];
            assert!((p(&e.post) - p(&e.pre)).abs() < 1e-15, "{law}: momentum");
        }
        assert_eq!(
            (e.post[0].spin, e.post[1].spin),
            (e.pre[0].spin, e.pre[1].spin)
        );
        loop {
            match sim.step(10.0) {
                Step::Contact(e) => assert!(
                    e.post
                        .iter()
                        .all(|s| s.velocity.iter().all(|x| x.is_finite())),
                    "{law}: {e:?}"
                ),
                Step::Until => break,
                other => panic!("{law}: {other:?}"),
            }
        }
    }
}
