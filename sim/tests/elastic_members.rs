//! Issue 27, "must hold": the elastic members of the rough family give the same bits as the
//! no-slip and smooth paths in a whole simulation, not only in the kernels. A shipped gas
//! (balls, box walls) and a shipped table (a polygon table and a ball obstacle) run with
//! every law written as `{ e = 1, beta = 1 }` and as `"no-slip"`, and as `{ e = 1, beta = -1 }`
//! and as `"smooth"`: the event logs are byte-identical. The scene names the exact elastic
//! members (`noslip_scene::ContactKind::checked`), so that comparison covers the reading of
//! the law; a second one sets the simulator's law to `Rough { e: 1.0, beta: 1.0 }` (and
//! `-1.0`) directly, past that naming, so that the rough maps themselves run (the path a law
//! that only rounds to `(1, +-1)` takes) and must give the no-slip and smooth maps' bits.

use crate::common;

use collision_core::{Generated, Kernel};
use noslip_scene::Scene;
use noslip_sim::setup::setup;
use noslip_sim::table::ContactKind;
use noslip_sim::Setup;
use std::path::Path;

/// The shipped scene `name` with `law` written at every place `places` lists: each entry is
/// a line of the file after which `contact = {law}` is inserted; `balls` adds
/// `[contact] balls = {law}`.
fn with_law(name: &str, after: &[&str], balls: bool, law: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../scenes")
        .join(name);
    let mut text = std::fs::read_to_string(&path).unwrap();
    for line in after {
        assert!(text.contains(line), "{name} has no line {line:?}");
        text = text.replacen(line, &format!("{line}\ncontact = {law}"), 1);
    }
    if balls {
        text.push_str(&format!("\n[contact]\nballs = {law}\n"));
    }
    Scene::from_toml(&text, name).unwrap_or_else(|e| panic!("{e}"))
}

/// Every law of the set-up replaced by `law` (ball-ball, box walls, boundaries, obstacles).
fn set_law<const N: usize, const S: usize>(setup: &mut Setup<N, S>, law: ContactKind) {
    setup.table.ball_contact = law;
    setup.table.pair_contact = Default::default();
    setup.table.box_contact = law;
    for b in &mut setup.table.boundaries {
        b.contact = law;
    }
    let obstacles = setup.obstacles.len();
    setup.table.obstacle_contact = vec![law; obstacles];
}

/// The scene comparison and the simulator-level one for the shipped scene `name`.
/// `kinds`: the contact kinds the log must hold (so that each law written is exercised).
fn same_bits<const N: usize, const S: usize>(
    name: &str,
    after: &[&str],
    balls: bool,
    kinds: &[&str],
    events: u64,
) where
    Generated: Kernel<f64, N, S>,
{
    let mut references = Vec::new();
    for (named, member, beta) in [
        ("\"no-slip\"", "{ e = 1, beta = 1 }", 1.0),
        ("\"smooth\"", "{ e = 1, beta = -1 }", -1.0),
    ] {
        let named_scene = with_law(name, after, balls, named);
        let member_scene = with_law(name, after, balls, member);
        let (reference, contacts) = common::log_of(setup::<N, S>(&named_scene).unwrap(), events);
        assert_eq!(contacts, events, "{name}: the run has {events} contacts");
        let lines = reference.iter().filter(|&&b| b == b'\n').count() as u64;
        assert!(
            lines >= events,
            "{name}: {lines} log lines for {events} contacts"
        );
        let text = String::from_utf8_lossy(&reference);
        for kind in kinds {
            let quoted = format!("\"kind\":\"{kind}\"");
            assert!(
                text.contains(&quoted),
                "{name}: no {kind} contact in the log"
            );
        }
        let (log, _) = common::log_of(setup::<N, S>(&member_scene).unwrap(), events);
        assert!(
            log == reference,
            "{name}: {member} and {named} write different logs"
        );
        // Past the scene's naming: the rough maps at (1, beta).
        let mut rough = setup::<N, S>(&named_scene).unwrap();
        set_law(&mut rough, ContactKind::Rough { e: 1.0, beta });
        let (log, _) = common::log_of(rough, events);
        let first = log.iter().zip(&reference).position(|(a, b)| a != b);
        assert!(
            log == reference,
            "{name}: the rough map at (1, {beta}) and {named} differ from byte {first:?}"
        );
        references.push(reference);
    }
    // The logs see the law: the no-slip and the smooth runs differ.
    assert!(
        references[0] != references[1],
        "{name}: the log does not depend on the law"
    );
}

/// gas2d: 750 rough disks of two species in a walled box; ball-ball and box-wall contacts.
#[test]
fn gas2d_elastic_members_write_the_no_slip_and_smooth_logs() {
    same_bits::<2, 1>(
        "gas2d.toml",
        &["boundary = [\"wall\", \"wall\"]"],
        true,
        &["ball-ball", "ball-wall"],
        3000,
    );
}

/// Sinai's square: a polygon table (its four edges and corners) and a ball obstacle.
#[test]
fn sinai_square_elastic_members_write_the_no_slip_and_smooth_logs() {
    same_bits::<2, 1>(
        "sinai_square.toml",
        &[
            "polygon = [[0, 0], [1, 0], [1, 1], [0, 1]]",
            "radius = \"3/10\"",
        ],
        false,
        &["ball-boundary", "ball-obstacle"],
        3000,
    );
}
