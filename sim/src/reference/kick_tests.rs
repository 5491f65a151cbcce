//! The cell engine's event log equals the all-pairs reference's, byte for byte, under the
//! white-noise thermostat ([`crate::thermostat`]): both step to each kick's time, take the same
//! kick, and go on.

use super::Reference;
use crate::run::event_json;
use crate::setup::setup;
use crate::thermostat::Noise;
use crate::{Event, GenericKernels, Setup, Simulation, Step};
use collision_core::{Generated, Kernel};
use noslip_scene::Scene;

/// Compares the first `contacts` contacts of both engines, kicking both at every `k dt`;
/// returns the kicks and the cell engine's re-basings.
fn compare<const N: usize, const S: usize>(
    name: &str,
    setup: Setup<N, S>,
    contacts: u64,
) -> (u64, u64)
where
    Generated: Kernel<f64, N, S>,
{
    let kernels = GenericKernels {
        species: setup.species.clone(),
    };
    let thermostat = setup.table.thermostat.expect("a thermostat in the scene");
    let inv_mass: Vec<f64> = setup
        .bodies
        .iter()
        .map(|b| setup.species[b.species].inv_mass)
        .collect();
    let mut fast = Simulation::new(setup.clone(), kernels.clone()).unwrap();
    let mut reference = Reference::new(setup, kernels);
    let mut noise = Noise::new(thermostat);
    let mut index = 0;
    while index < contacts {
        let t = noise.next_time();
        loop {
            let fast_event = loop {
                match fast.step(t) {
                    Step::Contact(e) => break Some(e),
                    Step::Until | Step::Never(_) | Step::LeftTable(_) => break None,
                    Step::Quiet { .. } => {}
                }
            };
            let reference_event = reference.next_contact_until(t);
            let line =
                |e: &Option<Event<N, S>>| e.as_ref().map(|e| event_json(index + 1, e).to_string());
            assert_eq!(
                line(&fast_event),
                line(&reference_event),
                "{name}: contact {}",
                index + 1
            );
            if fast_event.is_none() {
                break;
            }
            index += 1;
        }
        assert_eq!(fast.now(), t, "{name}: the clock at the kick");
        let dv = noise.kick::<N>(&inv_mass);
        fast.kick(&dv);
        reference.kick(&dv);
    }
    eprintln!(
        "{name}: {index} contacts, {} kicks, {} re-basings",
        noise.done(),
        fast.rebases()
    );
    (noise.done(), fast.rebases())
}

/// A driven 2D gas in a walled box with a rough obstacle and a rough slanted wall (a kick can
/// turn a ball that just left the wall back towards it), the TC model, and a driven 3D periodic
/// gas; kicks every few contacts per ball.
#[test]
fn driven_gases_log_the_same_bytes_in_both_engines() {
    let gas2d = r#"
dim = 2
[box]
size = [16, 16]
boundary = ["wall", "wall"]
contact = { e = "0.9", beta = 0 }
[[species]]
mass = 3
radius = 1
count = 12
[[species]]
mass = 1
radius = "1/2"
count = 80
[[obstacle]]
position = [8, 8]
radius = 2
contact = { e = "0.9", beta = "0.4" }
[[wall]]
point = [0, 12]
normal = [1, -1]
contact = { e = "0.95", beta = "-0.5" }
[contact]
balls = { e = "0.8", beta = "0.3" }
tc = "0.05"
[random]
seed = 11
velocities = "maxwellian"
[thermostat]
kind = "white-noise"
strength = 1
interval = "0.37"
seed = 4
"#;
    let gas3d = r#"
dim = 3
[box]
size = [9, 9, 9]
boundary = ["periodic", "periodic", "periodic"]
[[species]]
mass = 1
radius = "1/2"
count = 150
[contact]
balls = { e = "0.7", beta = "0.5" }
[random]
seed = 3
velocities = "maxwellian"
[thermostat]
kind = "white-noise"
strength = 2
interval = "0.1"
seed = 9
"#;
    // Dilute: kicks rarer than the clock's re-basings, which a kick must first take.
    let dilute = r#"
dim = 2
[box]
size = [60, 60]
boundary = ["periodic", "periodic"]
[[species]]
mass = 3
radius = 1
count = 10
[[species]]
mass = 1
radius = "1/2"
count = 60
[contact]
balls = { e = "0.9", beta = "0.9" }
[random]
seed = 5
velocities = "maxwellian"
[thermostat]
kind = "white-noise"
strength = "0.1"
interval = 300
seed = 2
"#;
    for (name, text, contacts, rebasing) in [
        ("driven 2D", gas2d, 6_000, false),
        ("driven 3D", gas3d, 3_000, false),
        ("driven dilute 2D", dilute, 2_000, true),
    ] {
        let scene = Scene::from_toml(text, name).unwrap();
        let (kicks, rebases) = collision_core::with_dim!(
            scene.dim,
            |N, S| compare(name, setup::<N, S>(&scene).unwrap(), contacts),
            unreachable!("dim {}", scene.dim)
        );
        assert!(
            kicks >= if rebasing { 3 } else { 20 },
            "{name}: {kicks} kicks"
        );
        // Each kick is a re-basing; the dilute gas re-bases between kicks too.
        assert!(
            rebases >= kicks,
            "{name}: {rebases} re-basings, {kicks} kicks"
        );
        if rebasing {
            assert!(
                rebases > 2 * kicks,
                "{name}: {rebases} re-basings, {kicks} kicks"
            );
        }
    }
}

/// The shipped driven gases ([`super::tests`] checks that every shipped scene is compared).
pub(super) const DRIVEN: [&str; 1] = ["driven3d"];

#[test]
fn the_shipped_driven_gas_logs_the_same_bytes_in_both_engines() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    for name in DRIVEN {
        let text = std::fs::read_to_string(dir.join(format!("{name}.toml"))).unwrap();
        let scene = Scene::from_toml(&text, name).unwrap();
        let (kicks, _) = collision_core::with_dim!(
            scene.dim,
            |N, S| compare(name, setup::<N, S>(&scene).unwrap(), 10_000),
            unreachable!("dim {}", scene.dim)
        );
        assert!(kicks >= 5, "{name}: {kicks} kicks");
    }
}
