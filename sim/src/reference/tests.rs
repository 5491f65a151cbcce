//! The cell engine's event log equals the all-pairs reference's, byte for byte (issue 30):
//! every shipped scene (gases in n = 2..6 in periodic, walled and mixed boxes; the Sinai
//! table's obstacle; tables of every kind: polygons, containers, walls, sectors, an open
//! wedge), each also with every contact smooth, and a dense and a dilute gas of two species.

use super::Reference;
use crate::run::event_json;
use crate::setup::setup;
use crate::table::ContactKind;
use crate::{GenericKernels, Setup, Simulation, Step};
use collision_core::{Generated, Kernel};
use noslip_scene::Scene;
use std::path::Path;

/// Contacts compared per scene.
const CONTACTS: usize = 10_000;

/// The first `contacts` lines of both logs (fewer if the run ends: then both must end), and
/// the cell engine's re-basings (a comparison that never re-based would not test them).
fn compare<const N: usize, const S: usize>(name: &str, setup: Setup<N, S>, contacts: usize) -> u64
where
    Generated: Kernel<f64, N, S>,
{
    compare_ending(name, setup, contacts).0
}

/// [`compare`], and the ball that left the table through a container if the run ended so
/// (both engines found the same one).
fn compare_ending<const N: usize, const S: usize>(
    name: &str,
    setup: Setup<N, S>,
    contacts: usize,
) -> (u64, Option<crate::LeftTable>)
where
    Generated: Kernel<f64, N, S>,
{
    let kernels = GenericKernels {
        species: setup.species.clone(),
    };
    let clock = std::time::Instant::now();
    let mut fast = Simulation::new(setup.clone(), kernels.clone()).unwrap();
    let mut reference = Reference::new(setup, kernels);
    for index in 1..=contacts as u64 {
        let fast_event = loop {
            match fast.step(f64::INFINITY) {
                Step::Contact(e) => break Some(e),
                Step::Never(_) => break None,
                Step::LeftTable(left) => {
                    assert_eq!(Some(left), reference.left(), "{name}: a ball left at once");
                    break None;
                }
                Step::Quiet { .. } | Step::Until => {}
            }
        };
        let reference_event = reference.next_contact();
        let line =
            |e: &Option<crate::Event<N, S>>| e.as_ref().map(|e| event_json(index, e).to_string());
        let (a, b) = (line(&fast_event), line(&reference_event));
        assert_eq!(a, b, "{name}: contact {index}");
        if a.is_none() {
            break;
        }
    }
    eprintln!(
        "{name}: {} contacts, {} re-basings, {:.2} s",
        fast.contacts(),
        fast.rebases(),
        clock.elapsed().as_secs_f64()
    );
    (fast.rebases(), reference.left())
}

/// Every contact of the table smooth.
fn smooth<const N: usize, const S: usize>(mut setup: Setup<N, S>) -> Setup<N, S> {
    let table = &mut setup.table;
    table.ball_contact = ContactKind::Smooth;
    table.pair_contact = Default::default();
    table.box_contact = ContactKind::Smooth;
    table.obstacle_contact = vec![ContactKind::Smooth; setup.obstacles.len()];
    for b in &mut table.boundaries {
        b.contact = ContactKind::Smooth;
    }
    setup
}

fn both<const N: usize, const S: usize>(name: &str, scene: &Scene, contacts: usize) -> u64
where
    Generated: Kernel<f64, N, S>,
{
    let start = setup::<N, S>(scene).unwrap();
    compare(&format!("{name} (smooth)"), smooth(start.clone()), contacts);
    compare(name, start, contacts)
}

fn run_scene(name: &str, text: &str) -> u64 {
    run_scene_for(name, text, CONTACTS)
}

fn run_scene_for(name: &str, text: &str, contacts: usize) -> u64 {
    let scene = Scene::from_toml(text, name).unwrap();
    collision_core::with_dim!(
        scene.dim,
        |N, S| both::<N, S>(name, &scene, contacts),
        unreachable!("dim {}", scene.dim)
    )
}

/// The shipped scenes, each run by one of the tests below (the gases alone: they take most
/// of the time, and the tests run in parallel).
const GASES: [&str; 5] = ["gas2d", "gas3d", "gas4d", "gas5d", "gas6d"];
const TABLES: [&str; 10] = [
    "circle",
    "cube3d",
    "disk_between_walls",
    "sector",
    "sinai",
    "sinai_square",
    "sphere3d",
    "strip",
    "triangle",
    "wedge",
];

/// The shipped granular gases (rough contacts, the TC model, a Maxwellian start; the
/// mixture with a law per pair of species), each run by a test of its own.
const GRANULAR: [&str; 2] = ["granular3d", "mixture2d"];

/// Runs shipped scenes; the number of them whose cell engine re-based.
fn shipped(names: &[&str]) -> usize {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    names
        .iter()
        .filter(|name| {
            let text = std::fs::read_to_string(dir.join(format!("{name}.toml"))).unwrap();
            run_scene(name, &text) > 0
        })
        .count()
}

#[test]
fn every_shipped_scene_is_compared() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    let mut present: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .map(|p| p.file_stem().unwrap().to_string_lossy().into_owned())
        .collect();
    present.sort();
    let mut listed: Vec<&str> = GASES
        .iter()
        .chain(&TABLES)
        .chain(&GRANULAR)
        .chain(&super::kick_tests::DRIVEN)
        .copied()
        .collect();
    listed.sort();
    assert_eq!(present, listed);
}

#[test]
fn the_shipped_tables_log_the_same_bytes_in_both_engines() {
    // Every table but the open wedge (3 contacts, then it escapes) re-bases.
    assert_eq!(shipped(&TABLES), TABLES.len() - 1);
}

#[test]
fn the_shipped_gases_in_2d_and_3d_log_the_same_bytes_in_both_engines() {
    shipped(&GASES[..2]);
}

#[test]
fn the_shipped_granular_gas_logs_the_same_bytes_in_both_engines() {
    shipped(&GRANULAR[..1]);
}

/// The shipped cooling gas at `e = 0` (under its TC model, and with `beta = -1` and no TC
/// model), and a 2D gas at `e = 0` around an obstacle with `(e, beta) = (0, -1)`: pairs and
/// obstacle contacts left touching with a rounding residue of normal velocity, whose repeat
/// both engines refuse by the same rules (`crate::last_contact`; the 12th contact of the
/// first is such a pair, which used to repeat forever). 2000 contacts each (fewer if the gas
/// freezes: both logs must then end together).
#[test]
fn gases_at_e_0_log_the_same_bytes_in_both_engines() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    let text = std::fs::read_to_string(dir.join("granular3d.toml")).unwrap();
    let law = r#"balls = { e = "0.9", beta = "0.5" }"#;
    assert!(text.contains(law), "the shipped scene's law");
    let sticking = text.replace(law, r#"balls = { e = 0, beta = "0.5" }"#);
    let smooth = text
        .replace(law, r#"balls = { e = 0, beta = "-1" }"#)
        .replace(r#"tc = "1e-5""#, "");
    for (name, text) in [("e = 0, TC", sticking), ("e = 0, beta = -1", smooth)] {
        let scene = Scene::from_toml(&text, name).unwrap();
        compare(name, setup::<3, 3>(&scene).unwrap(), 2000);
    }
    // Disks left touching an obstacle too (periodic images of it included).
    let obstacle = r#"
dim = 2
[box]
size = [6, 6]
boundary = ["periodic", "periodic"]
[[species]]
mass = 1
radius = "1/4"
count = 30
[[obstacle]]
position = [3, 3]
radius = 1
contact = { e = 0, beta = "-1" }
[contact]
balls = { e = 0, beta = "0.5" }
[random]
seed = 5
speed = 1
spin = 1
"#;
    let scene = Scene::from_toml(obstacle, "e = 0 obstacle").unwrap();
    compare("e = 0, obstacle", setup::<2, 1>(&scene).unwrap(), 2000);
}

/// Disks in a circular container whose wall has `e = 1/2` and no TC model: a disk that
/// collapses against the wall leaves along it (`crate::left_table`), and both engines end
/// the run there, after the same contacts, with the same [`crate::LeftTable`].
#[test]
fn a_ball_leaving_a_container_ends_both_engines_alike() {
    let text = r#"
dim = 2
[[container]]
centre = [0, 0]
radius = 3
contact = { e = "0.5", beta = "-1" }
[[species]]
mass = 1
radius = "1/4"
[[ball]]
species = 0
position = [0, 0]
velocity = ["0.6", "0.8"]
angular_velocity = 1
[[ball]]
species = 0
position = [1, "-1"]
velocity = ["-0.3", "0.1"]
[[ball]]
species = 0
position = ["-1.5", "0.5"]
velocity = ["0.2", "-0.9"]
angular_velocity = -2
"#;
    let scene = Scene::from_toml(text, "container at e = 1/2").unwrap();
    let (_, left) = compare_ending("container", setup::<2, 1>(&scene).unwrap(), 100_000);
    let left = left.expect("a disk collapses against the wall and leaves");
    assert_eq!(left.boundary, 0);
    assert!(left.outward_speed >= 0.0);
}

/// The mixture cools and clusters, and its contacts past the first few thousand come slowly
/// in the debug profile (10^4 took 11.6 s): 4000 of them (2 re-basings, 1.3 s) keep the test
/// at a few seconds.
#[test]
fn the_shipped_mixture_with_pair_laws_logs_the_same_bytes_in_both_engines() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    let text = std::fs::read_to_string(dir.join("mixture2d.toml")).unwrap();
    assert!(run_scene_for(GRANULAR[1], &text, 4000) > 0, "it re-bases");
}

#[test]
fn the_shipped_gases_in_4d_to_6d_log_the_same_bytes_in_both_engines() {
    // Their contacts come fast enough that 10^4 of them take a few re-basings.
    assert_eq!(shipped(&GASES[2..]), 3);
}

/// A two-species 2D gas at packing fraction 0.40 (dense: many contacts per crossing)
/// and the same balls in a box 30 times wider (dilute: many crossings and wraps per contact).
#[test]
fn dense_and_dilute_gases_log_the_same_bytes_in_both_engines() {
    for (name, side) in [("dense", "14"), ("dilute", "360")] {
        let text = format!(
            r#"
dim = 2
[box]
size = [{side}, {side}]
boundary = ["periodic", "periodic"]
[[species]]
mass = 3
radius = 1
count = 10
[[species]]
mass = 1
radius = "1/2"
count = 60
[random]
seed = 5
speed = 1
spin = 1
"#
        );
        run_scene(name, &text);
    }
}

/// Rough gases (inelastic, every kind of contact with a rough law) under the TC model: a 2D
/// gas in a walled box with a rough obstacle and a rough slanted wall, and a 3D periodic gas;
/// `t_c` long enough that a good part of the contacts are made elastic by it. Mildly
/// inelastic (`e` near 1) and about 20 contacts per ball: a cooled gas keeps only its centre
/// of mass's motion (momentum is conserved), its balls drifting together with contacts ever
/// rarer, which makes both engines re-base the clock many times per contact and the
/// all-pairs reference slow.
#[test]
fn rough_gases_log_the_same_bytes_in_both_engines() {
    let gas2d = r#"
dim = 2
[box]
size = [16, 16]
boundary = ["wall", "wall"]
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
balls = { e = "0.95", beta = "0.3" }
tc = "0.05"
[random]
seed = 11
speed = 1
spin = 1
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
balls = { e = "0.95", beta = "0.5" }
tc = "0.02"
[random]
seed = 3
speed = 1
spin = 1
"#;
    // The Walton law on the 2D gas's balls and obstacle: sticking and sliding contacts.
    let walton2d = gas2d
        .replace(
            r#"e = "0.9", beta = "0.4""#,
            r#"e = "0.9", mu = "0.1", beta0 = "0.4""#,
        )
        .replace(
            r#"e = "0.95", beta = "0.3""#,
            r#"e = "0.95", mu = "0.2", beta0 = "0.3""#,
        );
    for (name, text, contacts) in [
        ("rough 2D", gas2d, CONTACTS),
        ("rough 3D", gas3d, 3_000),
        ("Walton 2D", &walton2d, 3_000),
    ] {
        let scene = Scene::from_toml(text, name).unwrap();
        collision_core::with_dim!(
            scene.dim,
            |N, S| {
                compare(name, setup::<N, S>(&scene).unwrap(), contacts);
            },
            unreachable!("dim {}", scene.dim)
        );
    }
}
