//! The list engine's event log equals the cell engine's and the all-pairs reference's, byte
//! for byte: gases in n = 2..6, dense and dilute, periodic, walled and mixed boxes, one and
//! two species, smooth, no-slip and rough contacts, the TC model.

use super::{ListSimulation, ListsRefusal};
use crate::reference::Reference;
use crate::run::event_json;
use crate::setup::setup;
use crate::{GenericKernels, Setup, Simulation, Step};
use collision_core::{Generated, Kernel};
use noslip_scene::Scene;

/// The next contact of the list engine (`None` once every ball is at rest): it steps to a
/// contact or to the end, never to a notice.
fn next_of_lists<const N: usize, const S: usize>(
    sim: &mut ListSimulation<N, S, GenericKernels<f64>>,
) -> Option<crate::Event<N, S>>
where
    Generated: Kernel<f64, N, S>,
{
    match sim.step(f64::INFINITY) {
        Step::Contact(e) => Some(e),
        Step::Never(_) => None,
        other => panic!("the list engine stepped to {other:?}"),
    }
}

/// The next contact of the cell engine.
fn next_of_cells<const N: usize, const S: usize>(
    sim: &mut Simulation<N, S, GenericKernels<f64>>,
) -> Option<crate::Event<N, S>>
where
    Generated: Kernel<f64, N, S>,
{
    loop {
        match sim.step(f64::INFINITY) {
            Step::Contact(e) => return Some(e),
            Step::Quiet { .. } | Step::Until => {}
            _ => return None,
        }
    }
}

/// The first `contacts` lines of the list engine's log against the cell engine's and, if
/// `reference`, the all-pairs reference's; returns the list engine's shell redraws and
/// re-basings (a comparison without them would not test them).
fn compare<const N: usize, const S: usize>(
    name: &str,
    setup: Setup<N, S>,
    skin: f64,
    contacts: u64,
    reference: bool,
) -> (u64, u64)
where
    Generated: Kernel<f64, N, S>,
{
    let kernels = GenericKernels {
        species: setup.species.clone(),
    };
    let mut lists = ListSimulation::with_skin(setup.clone(), kernels.clone(), skin).unwrap();
    let mut cells = Simulation::new(setup.clone(), kernels.clone()).unwrap();
    let mut all = reference.then(|| Reference::new(setup, kernels));
    for index in 1..=contacts {
        let line = |e: Option<crate::Event<N, S>>| e.map(|e| event_json(index, &e).to_string());
        let got = line(next_of_lists(&mut lists));
        assert_eq!(
            got,
            line(next_of_cells(&mut cells)),
            "{name}: contact {index}"
        );
        if let Some(all) = &mut all {
            assert_eq!(got, line(all.next_contact()), "{name}: contact {index}");
        }
        if got.is_none() {
            break;
        }
    }
    // The clock and every ball's state, by index, after the same contacts.
    assert_eq!(
        lists.now().to_bits(),
        cells.now().to_bits(),
        "{name}: the clock"
    );
    for i in 0..lists.len() {
        assert_eq!(lists.state(i), cells.state(i), "{name}: ball {i}'s state");
    }
    eprintln!(
        "{name}: {} contacts, {} redraws, {} re-basings, mean list {:.1}",
        lists.contacts(),
        lists.redraws(),
        lists.rebases(),
        lists.mean_list()
    );
    (lists.redraws(), lists.rebases())
}

/// [`compare`] on a scene's text.
fn compare_scene(name: &str, text: &str, skin: f64, contacts: u64, reference: bool) -> (u64, u64) {
    let scene = Scene::from_toml(text, name).unwrap();
    collision_core::with_dim!(
        scene.dim,
        |N, S| compare(
            name,
            setup::<N, S>(&scene).unwrap(),
            skin,
            contacts,
            reference
        ),
        unreachable!("dim {}", scene.dim)
    )
}

/// A gas of `count` balls of radius 1/2 in a box of side `side` in `dim` dimensions, with the
/// given boundaries and contact law (TOML lines under `[contact]`), placed at random.
fn gas(dim: usize, side: &str, count: usize, boundary: &str, contact: &str) -> String {
    let sides = vec![side; dim].join(", ");
    let boundaries = vec![format!("\"{boundary}\""); dim].join(", ");
    format!(
        r#"
dim = {dim}
[box]
size = [{sides}]
boundary = [{boundaries}]
[[species]]
mass = 1
radius = "1/2"
count = {count}
[contact]
{contact}
[random]
seed = 7
speed = 1
spin = 1
"#
    )
}

/// Balls of radius 1/2 and mass 1 (`gamma^2 = 2 / (n + 2)`, uniform density) at the given
/// centres and velocities, each with angular velocity `spin`, in a periodic cube of side
/// `side`.
fn hand_built<const N: usize, const S: usize>(
    side: f64,
    spin: [f64; S],
    balls: &[([f64; N], [f64; N])],
) -> Setup<N, S> {
    Setup {
        size: [side; N],
        periodic: [true; N],
        species: vec![collision_core::Ball {
            inv_mass: 1.0,
            radius: 0.5,
            gamma2: 2.0 / (N as f64 + 2.0),
        }],
        obstacles: Vec::new(),
        bodies: (balls.iter())
            .map(|&(position, velocity)| crate::Body {
                species: 0,
                position,
                state: collision_core::BodyState { spin, velocity },
            })
            .collect(),
        orientation: false,
        table: crate::Table::boxed(),
    }
}

/// `text`'s balls on a random subset of a lattice's sites (random sequential placement stops
/// short of the dense gases).
fn on_lattice(text: String) -> String {
    text + "placement = \"lattice\"\n"
}

#[test]
fn dense_and_dilute_2d_gases_log_the_same_bytes_in_every_engine() {
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
        let (redraws, rebases) = compare_scene(name, &text, 0.15, 10_000, true);
        assert!(
            redraws > 0 && rebases > 0,
            "{name}: {redraws} redraws, {rebases} re-basings"
        );
    }
}

#[test]
fn three_dimensional_gases_log_the_same_bytes_in_every_engine() {
    // Packing fractions 0.40, 0.12 and 0.26 (side 8.7, 12.8 and 10 for 500 balls), no-slip and smooth,
    // periodic, walled and mixed boxes, two skins.
    let cases = [
        (
            "3D dense no-slip",
            on_lattice(gas(3, "8.7", 500, "periodic", "")),
        ),
        (
            "3D dense smooth",
            on_lattice(gas(3, "8.7", 500, "periodic", "balls = \"smooth\"")),
        ),
        ("3D dilute walled", gas(3, "12.8", 500, "wall", "")),
        (
            "3D mixed",
            gas(3, "10", 500, "periodic", "").replace(
                r#"boundary = ["periodic", "periodic", "periodic"]"#,
                r#"boundary = ["periodic", "wall", "periodic"]"#,
            ),
        ),
    ];
    for (name, text) in &cases {
        for skin in [0.05, 0.3] {
            // Against the reference too at skin 0.3 in the walled and mixed boxes.
            let reference = skin == 0.3 && !name.contains("dense");
            let (redraws, _) = compare_scene(name, text, skin, 5_000, reference);
            assert!(redraws > 0, "{name}: no redraws");
        }
    }
    // Against the reference too, at one skin (re-basings: the 2D test).
    compare_scene(cases[0].0, &cases[0].1, 0.15, 10_000, true);
}

#[test]
fn gases_in_4d_to_6d_log_the_same_bytes_in_every_engine() {
    for (dim, side, count) in [(4, "5.3", 250), (5, "4.2", 400), (6, "3.4", 300)] {
        let text = on_lattice(gas(dim, side, count, "periodic", ""));
        // Re-basings come later here (the 2D and 3D tests take them).
        let (redraws, _) = compare_scene(&format!("{dim}D"), &text, 0.05, 5_000, false);
        assert!(redraws > 0, "{dim}D: no redraws");
    }
}

/// Rough and inelastic contacts under the TC model, and the Walton law: pairs left touching
/// at `e = 0` too (`crate::last_contact`), refused alike.
#[test]
fn rough_gases_log_the_same_bytes_in_every_engine() {
    let laws = [
        "balls = { e = \"0.95\", beta = \"0.5\" }\ntc = \"0.02\"",
        "balls = { e = \"0.9\", mu = \"0.2\", beta0 = \"0.3\" }",
        "balls = { e = 0, beta = \"0.5\" }\ntc = \"1e-5\"",
    ];
    for law in laws {
        let text = gas(3, "9", 300, "periodic", law);
        compare_scene(law, &text, 0.15, 3_000, true);
    }
}

/// Looking ahead (`ahead.rs`, on from 4 MiB of records and lists) changes no event: a dense
/// gas with it forced on logs the cell engine's bytes.
#[test]
fn looking_ahead_changes_no_event() {
    let text = on_lattice(gas(3, "8.7", 500, "periodic", ""));
    let scene = Scene::from_toml(&text, "ahead").unwrap();
    let setup = setup::<3, 3>(&scene).unwrap();
    let kernels = GenericKernels {
        species: setup.species.clone(),
    };
    let mut lists = ListSimulation::new(setup.clone(), kernels.clone()).unwrap();
    lists.set_prefetch(true);
    let mut cells = Simulation::new(setup, kernels).unwrap();
    for index in 1..=5_000 {
        let line = |e: Option<crate::Event<3, 3>>| e.map(|e| event_json(index, &e).to_string());
        let got = line(next_of_lists(&mut lists));
        assert_eq!(got, line(next_of_cells(&mut cells)), "contact {index}");
    }
}

/// A hand-built 2D gas in a periodic box of side 10: a ball on the far face (`x = L`, so its
/// first shell's centre folds to 0 with `W = 1`), two balls at rest, two moving. Both engines
/// log the same contacts, and stop at the same finite times with the same clocks.
#[test]
fn a_ball_on_the_far_face_and_balls_at_rest_log_the_same_bytes() {
    let balls = [
        ([10.0, 5.0], [0.7, 0.1]),
        ([5.0, 5.0], [0.0, 0.0]),
        ([2.5, 7.5], [0.0, 0.0]),
        ([7.5, 2.5], [-0.4, 0.9]),
        ([2.0, 2.0], [0.3, -0.8]),
    ];
    let setup = hand_built(10.0, [0.3], &balls);
    let kernels = GenericKernels {
        species: setup.species.clone(),
    };
    let mut lists = ListSimulation::new(setup.clone(), kernels.clone()).unwrap();
    let mut cells = Simulation::new(setup, kernels).unwrap();
    let (mut contacts, mut until) = (0, 0.0);
    while contacts < 500 {
        until += 0.37;
        loop {
            let (a, b) = (lists.step(until), next_of_cells_until(&mut cells, until));
            let line = |s: &Step<2, 1>| match s {
                Step::Contact(e) => Some(event_json(contacts + 1, e).to_string()),
                _ => None,
            };
            assert_eq!(line(&a), line(&b), "contact {}", contacts + 1);
            assert_eq!(lists.now().to_bits(), cells.now().to_bits(), "the clock");
            match (a, b) {
                (Step::Contact(_), _) => contacts += 1,
                (Step::Until, Step::Until) => break,
                (a, b) => panic!("lists {a:?}, cells {b:?}"),
            }
        }
    }
}

/// A ball that flies along a corridor past a ball at rest, never meeting it, its relative
/// motion not closing on itself (a drift of `sqrt(2) / 10` across): no decision, but notices
/// at 1000 and then at least 2000 box lengths, as the cell engine gives them.
#[test]
fn a_long_flight_without_contacts_is_noticed() {
    let balls = [
        ([5.0, 5.0, 5.0], [1.0, 2f64.sqrt() / 10.0, 0.0]),
        ([15.0, 15.0, 15.0], [0.0; 3]),
    ];
    let setup = hand_built(20.0, [0.0; 3], &balls);
    let kernels = GenericKernels {
        species: setup.species.clone(),
    };
    let mut lists = ListSimulation::new(setup.clone(), kernels.clone()).unwrap();
    let mut cells = Simulation::new(setup, kernels).unwrap();
    for least in [1000.0, 2000.0] {
        for (name, step) in [
            ("lists", lists.step(f64::INFINITY)),
            ("cells", cells.step(f64::INFINITY)),
        ] {
            match step {
                Step::Quiet { box_lengths } => assert!(box_lengths >= least, "{name}"),
                other => panic!("{name}: {other:?}"),
            }
        }
    }
}

/// The cell engine's next step up to `until`, past its notices.
fn next_of_cells_until<const N: usize, const S: usize>(
    sim: &mut Simulation<N, S, GenericKernels<f64>>,
    until: f64,
) -> Step<N, S>
where
    Generated: Kernel<f64, N, S>,
{
    loop {
        match sim.step(until) {
            Step::Quiet { .. } => {}
            other => return other,
        }
    }
}

/// No contact ahead: a single moving ball, every ball at rest, and balls that all fly at one
/// velocity end both engines alike ([`crate::NoContact`]).
#[test]
fn a_gas_without_contacts_ahead_ends_as_in_the_cell_engine() {
    let gas = |velocities: &[[f64; 3]]| {
        let balls: Vec<_> = (velocities.iter().enumerate())
            .map(|(i, &velocity)| ([1.0 + 2.0 * i as f64, 3.0, 3.0], velocity))
            .collect();
        hand_built(6.0, [0.0; 3], &balls)
    };
    let cases = [
        vec![[0.3, 0.2, 0.1]],
        vec![[0.0; 3], [0.0; 3]],
        vec![[0.0, 0.5, 0.25]; 3],
    ];
    for velocities in cases {
        let setup = gas(&velocities);
        let kernels = GenericKernels {
            species: setup.species.clone(),
        };
        let mut lists = ListSimulation::new(setup.clone(), kernels.clone()).unwrap();
        let mut cells = Simulation::new(setup, kernels).unwrap();
        let ended = |s: Step<3, 3>| match s {
            Step::Never(why) => why,
            other => panic!("{velocities:?}: {other:?}"),
        };
        let why = ended(lists.step(f64::INFINITY));
        let cell_why = ended(next_of_cells_until(&mut cells, f64::INFINITY));
        assert_eq!(why, cell_why, "{velocities:?}");
    }
}

#[test]
fn what_the_list_engine_does_not_take_is_refused_by_name() {
    let refusal = |text: &str| {
        let scene = Scene::from_toml(text, "refused").unwrap();
        let setup = setup::<2, 1>(&scene).unwrap();
        let kernels = GenericKernels {
            species: setup.species.clone(),
        };
        ListSimulation::new(setup, kernels).err()
    };
    // A side of 3.5 holds two cells of reach 1.6: refused; 5 holds three.
    let short = gas(2, "3.5", 4, "periodic", "");
    assert!(matches!(
        refusal(&short),
        Some(ListsRefusal::ShortSide { axis: 0, .. })
    ));
    assert_eq!(refusal(&gas(2, "5", 4, "periodic", "")), None);
    let obstacle = gas(2, "8", 4, "periodic", "") + "[[obstacle]]\nposition = [4, 4]\nradius = 1\n";
    assert_eq!(refusal(&obstacle), Some(ListsRefusal::Obstacles));
    let wall = gas(2, "8", 4, "wall", "") + "[[wall]]\npoint = [0, 4]\nnormal = [0, 1]\n";
    assert_eq!(refusal(&wall), Some(ListsRefusal::Table));
    // A thin periodic slab beside a long side: three cells across it, taken.
    let slab = gas(2, "5", 10, "periodic", "").replace("size = [5, 5]", "size = [200, 5]");
    assert_eq!(refusal(&slab), None);
    // Skins, orientations and a thermostat.
    let scene = Scene::from_toml(&gas(2, "8", 4, "periodic", ""), "skins").unwrap();
    let setup = setup::<2, 1>(&scene).unwrap();
    let kernels = GenericKernels {
        species: setup.species.clone(),
    };
    let with = |skin: f64, change: &dyn Fn(&mut Setup<2, 1>)| {
        let mut setup = setup.clone();
        change(&mut setup);
        ListSimulation::with_skin(setup, kernels.clone(), skin).err()
    };
    for skin in [0.0, 1e-9, f64::NAN, f64::INFINITY] {
        assert!(
            matches!(with(skin, &|_| {}), Some(ListsRefusal::Skin(_))),
            "{skin}"
        );
    }
    assert_eq!(with(1e-6, &|_| {}), None);
    let orientation = with(0.3, &|s| s.orientation = true);
    assert_eq!(orientation, Some(ListsRefusal::Orientation));
    let thermostat = with(0.3, &|s| {
        s.table.thermostat = Some(crate::thermostat::Thermostat {
            strength: 1.0,
            interval: 1.0,
            seed: 1,
        })
    });
    assert_eq!(thermostat, Some(ListsRefusal::Thermostat));
}
