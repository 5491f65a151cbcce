//! Inelastic collapse and the TC model (docs/granular.md).
//!
//! Three equal disks on a line, the first moving onto the two others at rest, with normal
//! restitution `e = 0.05`: below `7 - 4 sqrt(3) ~ 0.072` three balls in a row collapse
//! (McNamara & Young): in exact arithmetic they collide infinitely often before a finite
//! time, the gaps and relative speeds shrinking geometrically. In floating point the burst
//! ends only when rounding stops it, after dozens of contacts within a vanishing time. Under
//! the TC model a contact within `t_c` of a ball's previous one is elastic, and the burst
//! is cut to a few contacts in any time `t_c`. The disks move along the line without spin,
//! so the contact point's tangential velocity is 0 and `beta` plays no part.

use collision_core::{Ball, BodyState};
use noslip_sim::table::{ContactKind, Table};
use noslip_sim::{Body, GenericKernels, NoContact, Setup, Simulation, Step};

const DISK: Ball<f64> = Ball {
    inv_mass: 1.0,
    radius: 0.5,
    gamma2: 0.5,
};

/// The simulation of scene `text` (named `name` in errors) in dimension `N`.
fn simulation_of<const N: usize, const S: usize>(
    text: &str,
    name: &str,
) -> Simulation<N, S, GenericKernels<f64>>
where
    collision_core::Generated: collision_core::Kernel<f64, N, S>,
{
    let scene = noslip_scene::Scene::from_toml(text, name).unwrap();
    let setup = noslip_sim::setup::setup::<N, S>(&scene).unwrap();
    let kernels = GenericKernels {
        species: setup.species.clone(),
    };
    Simulation::new(setup, kernels).unwrap()
}

/// The contact times of the run (no box: the disks fly apart at the end and it stops).
fn contact_times(tc: f64) -> Vec<f64> {
    let body = |x: f64, u: f64| Body {
        species: 0,
        position: [x, 0.0],
        state: BodyState {
            spin: [0.0],
            velocity: [u, 0.0],
        },
    };
    let setup = Setup {
        size: [4.0, 4.0],
        periodic: [false; 2],
        species: vec![DISK],
        obstacles: vec![],
        bodies: vec![body(0.0, 1.0), body(1.5, 0.0), body(2.6, 0.0)],
        orientation: false,
        table: Table {
            boxed: false,
            ball_contact: ContactKind::Rough { e: 0.05, beta: 0.5 },
            tc,
            ..Table::boxed()
        },
    };
    let kernels = GenericKernels {
        species: setup.species.clone(),
    };
    let mut sim = Simulation::new(setup, kernels).unwrap();
    let mut times = Vec::new();
    loop {
        match sim.step(f64::INFINITY) {
            Step::Contact(e) => times.push(e.time),
            Step::Never(why) => {
                assert_eq!(why, NoContact::Escaped);
                return times;
            }
            Step::Quiet { .. } | Step::Until | Step::LeftTable(_) => panic!("the disks fly apart"),
        }
        assert!(times.len() < 10_000, "no end to the contacts");
    }
}

/// The most contacts within any time window of length `w`.
fn most_within(times: &[f64], w: f64) -> usize {
    (0..times.len())
        .map(|i| times[i..].iter().take_while(|&&t| t - times[i] < w).count())
        .max()
        .unwrap_or(0)
}

#[test]
fn the_tc_model_cuts_an_inelastic_collapse_short() {
    let tc = 1e-3;
    let collapse = contact_times(0.0);
    // Without the TC model: a burst of contacts in a vanishing time (rounding ends it).
    assert!(most_within(&collapse, 1e-9) >= 20, "{collapse:?}");
    let cut = contact_times(tc);
    // With it: after the first dissipative contacts every contact of the cluster comes within
    // t_c of the previous one and is elastic; three equal disks in a row then exchange their
    // velocities in at most a few contacts and fly apart.
    assert!(most_within(&cut, tc) <= 4, "{cut:?}");
    assert!(
        cut.len() < collapse.len(),
        "{} {}",
        cut.len(),
        collapse.len()
    );
    eprintln!(
        "without TC: {} contacts, {} within 1e-9; with t_c = {tc}: {} contacts, {} within t_c",
        collapse.len(),
        most_within(&collapse, 1e-9),
        cut.len(),
        most_within(&cut, tc)
    );
}

/// The shipped cooling gas (`scenes/granular3d.toml`: 500 rough spheres, the TC model) with
/// `e = 0`, and with the smooth member's `beta = -1` and no TC model: after an `e = 0`
/// contact the pair's normal velocity is 0 in exact arithmetic and a rounding residue in
/// floats. Where that residue points inwards and the law changes no bit of the states, the
/// pair used to be predicted again at zero flight time, forever: the run stopped at `t =
/// 0.043176` with every later contact between balls 283 and 326 (with the TC model), and
/// without it the same pair repeated an ulp or two apart at `t = 0.1465`. Both must now reach
/// `t = 0.2` within 10^5 contacts (they take 83 and 203), and no contact may repeat the pair
/// of its balls' last contact at the same time (the rule: `sim/src/last_contact.rs`).
#[test]
fn a_sticking_pair_at_e_0_does_not_repeat_its_contact_at_once() {
    let shipped = include_str!("../../scenes/granular3d.toml");
    let e0 = r#"balls = { e = 0, beta = "0.5" }"#;
    let smooth = r#"balls = { e = 0, beta = "-1" }"#;
    let law = r#"balls = { e = "0.9", beta = "0.5" }"#;
    assert!(shipped.contains(law), "the shipped scene's law");
    let no_tc = |s: String| s.replace("tc = \"1e-5\"", "");
    for (name, text) in [
        ("e = 0, beta = 0.5, TC", shipped.replace(law, e0)),
        (
            "e = 0, beta = -1, no TC",
            no_tc(shipped.replace(law, smooth)),
        ),
    ] {
        let mut sim = simulation_of::<3, 3>(&text, "granular3d.toml");
        let until = 0.2;
        let mut last: Vec<Option<(usize, f64)>> = vec![None; 500];
        let mut contacts = 0;
        loop {
            let e = match sim.step(until) {
                Step::Contact(e) => e,
                Step::Until => break,
                Step::Quiet { .. } => continue,
                Step::Never(why) => panic!("{name}: {why:?} at t = {}", sim.now()),
                Step::LeftTable(left) => panic!("{name}: {left}"),
            };
            contacts += 1;
            assert!(
                contacts < 100_000,
                "{name}: no end to the contacts at t = {}",
                e.time
            );
            if let noslip_sim::Contact::Ball { i, j } = e.contact {
                let repeat = last[i] == Some((j, e.time)) && last[j] == Some((i, e.time));
                assert!(!repeat, "{name}: balls {i}, {j} again at t = {}", e.time);
                last[i] = Some((j, e.time));
                last[j] = Some((i, e.time));
            }
        }
        eprintln!("{name}: {contacts} contacts to t = {until}");
    }
}

/// The shipped Sinai table (`scenes/sinai.toml`: one disk, a periodic unit square, a disk
/// obstacle) with the obstacle's law `e = 0`, `beta = -1`: the disk left touching the
/// obstacle used to meet it again at once, forever (100 000 obstacle contacts by `t =
/// 0.219265`). It must now reach `t = 10` within 1000 contacts (it takes 2).
#[test]
fn a_ball_left_touching_an_obstacle_at_e_0_does_not_repeat_its_contact() {
    let shipped = include_str!("../../scenes/sinai.toml");
    let obstacle = "radius = \"3/10\"\n";
    assert!(shipped.contains(obstacle), "the shipped obstacle");
    let text = shipped.replace(
        obstacle,
        "radius = \"3/10\"\ncontact = { e = 0, beta = \"-1\" }\n",
    );
    let mut sim = simulation_of::<2, 1>(&text, "sinai.toml");
    let mut contacts = 0;
    loop {
        match sim.step(10.0) {
            Step::Contact(_) => contacts += 1,
            Step::Until => break,
            Step::Quiet { .. } => {}
            Step::Never(why) => panic!("{why:?} at t = {}", sim.now()),
            Step::LeftTable(left) => panic!("{left}"),
        }
        assert!(
            contacts < 1000,
            "no end to the contacts at t = {}",
            sim.now()
        );
    }
    eprintln!("{contacts} contacts to t = 10");
}

/// An inelastic collapse against a concave wall (`noslip_sim::left_table`): the shipped
/// circle table with the container's law `e = 1/2`, `beta = -1` (the spin untouched, the
/// tangential velocity kept) and no TC model. A chord of a circle meets the wall at its two
/// ends at the same angle, so the normal speed at each contact is `e` times that at the one
/// before, exactly. In floats the contact point's distance from the centre is `rho` within
/// `delta`, a few ulps of `rho`; that moves the chord's end by an angle `delta / (rho theta)`
/// for a chord at angle `theta` to the wall, a relative change `delta / (rho theta^2)` of
/// the normal speed `v_n = |u| theta` (here `|u| = 1`). So each ratio is checked to within
/// `4 eps / v_n^2` (`eps = 2^-52`; measured: at most `0.002 eps / v_n^2`) while `v_n >
/// 1e-5`, a tolerance below `1e-5`: 16 ratios. The speeds halve from about 1, so at least 20
/// contacts come before `v_n` passes `1e-6`, and at most 53 before it passes `eps`, by which
/// rounding has taken the normal velocity to 0 or outwards (in this run after 33 contacts,
/// the last pre-contact speed 4.6e-10, the next 3.5e-18). The run must
/// then stop with [`Step::LeftTable`] naming the ball and the container (it used to end
/// with the false note that the table is unbounded). With `tc = 1e-3` the contacts within
/// `t_c` of the previous one are elastic, the collapse ends, and the run goes on (20 000 contacts).
#[test]
fn a_ball_collapsing_against_a_container_stops_the_run_naming_it() {
    let shipped = include_str!("../../scenes/circle.toml");
    let wall = "radius = 1\n";
    assert!(shipped.contains(wall), "the shipped container");
    let text = shipped.replacen(
        wall,
        "radius = 1\ncontact = { e = \"0.5\", beta = \"-1\" }\n",
        1,
    );
    // The normal speeds before each contact, and how the run ended (`None`: `most` contacts).
    let run = |text: &str, most: usize| {
        let mut sim = simulation_of::<2, 1>(text, "circle.toml");
        let mut speeds = Vec::new();
        let end = loop {
            if speeds.len() == most {
                break None;
            }
            match sim.step(f64::INFINITY) {
                Step::Contact(e) => {
                    let u = e.pre[0].velocity;
                    speeds.push((u[0] * e.nu[0] + u[1] * e.nu[1]).abs());
                }
                Step::Quiet { .. } => {}
                other => break Some(other),
            }
        };
        (speeds, end)
    };
    let (speeds, end) = run(&text, 100_000);
    let Some(Step::LeftTable(left)) = end else {
        panic!("the run must stop with the ball gone: {end:?}");
    };
    assert_eq!((left.ball, left.boundary), (0, 0));
    assert!(
        left.outward_speed >= 0.0 && left.outward_speed < 1e-15,
        "{left:?}"
    );
    assert!(
        (21..=54).contains(&speeds.len()),
        "{} contacts",
        speeds.len()
    );
    let mut checked = 0;
    for w in speeds.windows(2).filter(|w| w[1] > 1e-5) {
        let tolerance = 4.0 * f64::EPSILON / (w[1] * w[1]);
        assert!((w[1] / w[0] - 0.5).abs() < tolerance, "{w:?}");
        checked += 1;
    }
    assert!(checked >= 15, "{checked} ratios checked");
    let (speeds, end) = run(&format!("{text}\n[contact]\ntc = \"1e-3\"\n"), 20_000);
    assert_eq!(end, None, "with the TC model the run goes on");
    assert_eq!(speeds.len(), 20_000);
}

/// Contacts at one instant without end (`noslip_sim::collapse`), through the run loop that
/// `noslip simulate` and Python's `simulate` use, with a time limit and no event limit (the
/// setting that used to never return):
///
/// - the shipped wedge (20 degrees, no box) with its walls at `e = 0`, `beta = -1`: the disk
///   is driven into the apex, its speed shrinks to subnormal numbers and every contact comes
///   at `t = 2.578460` (a review's reproduction);
/// - the shipped 3D cooling gas at `e = 0`, `beta = -1` and without its TC model: three
///   balls left touching trade contacts that change no bit at `t = 0.287340`.
///
/// Each run must stop at that instant with a [`noslip_sim::collapse::Collapse`] naming the
/// balls, after `MAX_CONTACTS_AT_ONCE` contacts of the busiest, and with the TC model the
/// same scenes must run on (the disk out of the open wedge, the gas to its time limit).
#[test]
fn contacts_at_one_instant_without_end_stop_the_run_naming_the_balls() {
    use noslip_sim::collapse::MAX_CONTACTS_AT_ONCE;
    use noslip_sim::run::{run, Limits};
    let wedge = include_str!("../../scenes/wedge.toml").replace(
        "[table.wedge]",
        "[table]\ncontact = { e = 0, beta = -1 }\n[table.wedge]",
    );
    let gas = include_str!("../../scenes/granular3d.toml").replace(
        r#"balls = { e = "0.9", beta = "0.5" }"#,
        r#"balls = { e = 0, beta = "-1" }"#,
    );
    assert!(
        wedge.contains("e = 0") && gas.contains("e = 0"),
        "the laws replaced"
    );
    let no_tc = gas.replace(r#"tc = "1e-5""#, "");
    assert_ne!(no_tc, gas, "the shipped TC model removed");
    fn end<const N: usize, const S: usize>(text: &str, time: f64) -> noslip_sim::run::Summary
    where
        collision_core::Generated: collision_core::Kernel<f64, N, S>,
    {
        let scene = noslip_scene::Scene::from_toml(text, "scene.toml").unwrap();
        let setup = noslip_sim::setup::setup::<N, S>(&scene).unwrap();
        let species = setup.species.clone();
        let kernels = GenericKernels {
            species: species.clone(),
        };
        let mut sim = Simulation::new(setup, kernels).unwrap();
        let limits = Limits {
            events: None,
            time: Some(time),
            samples: 10,
            traced: 0,
            contact_points: 0,
        };
        run(&mut sim, &species, &limits, None, &mut |_| {})
            .unwrap()
            .0
    }
    let summaries = [
        (end::<2, 1>(&wedge, 10.0), 2.578459, vec![0]),
        (end::<3, 3>(&no_tc, 1.0), 0.287340, vec![412, 153, 199]),
    ];
    for (s, time, balls) in summaries {
        let c = s.collapse.clone().expect("a collapse");
        assert!((c.time - time).abs() < 1e-6, "{c:?}");
        assert_eq!(c.balls, balls);
        assert!(s.events >= c.contacts, "{s:?}");
        assert!(c.contacts > u64::from(MAX_CONTACTS_AT_ONCE), "{c:?}");
        assert!(s
            .stopped
            .as_deref()
            .unwrap()
            .starts_with("inelastic collapse at t = "));
    }
    // With the TC model the contacts within t_c are elastic and the runs go on: the disk
    // leaves the open wedge (truly: it has no box), the gas runs to its time limit.
    let s = end::<2, 1>(&format!("{wedge}\n[contact]\ntc = \"1e-4\"\n"), 10.0);
    assert_eq!(s.collapse, None);
    assert!(s.stopped.unwrap().contains("every ball flies off"));
    let s = end::<3, 3>(&gas, 0.5);
    assert_eq!((s.collapse, s.stopped), (None, None));
}
