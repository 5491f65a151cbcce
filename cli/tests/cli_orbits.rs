//! `noslip orbits` from the outside: the bouncing orbit between two walls found and computed
//! exactly, a grid search, the bound on its work and its progress, and bad input (exit 2, one
//! line naming the place).

use crate::support;
use std::time::Duration;
use support::{noslip, run_ok, temp, within};

/// `orbits scenes/triangle.toml --period 4 --grid 1` never returned (over 120 s): the
/// eigenvalues of its orbits' return maps (1 three times, to a few ulps) stalled nalgebra's
/// uncapped Schur iteration. Now the eigenvalue iteration is bounded and the search takes
/// well under a second (the limit here is a generous 60 s).
#[test]
fn the_triangle_period_four_search_returns() {
    let dir = temp("orbits-triangle4");
    let out = within(
        noslip()
            .args([
                "orbits",
                "scenes/triangle.toml",
                "--period",
                "4",
                "--grid",
                "1",
            ])
            .arg("--out")
            .arg(&dir),
        Duration::from_secs(60),
    );
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(out.status.success(), "{stdout}");
    assert!(
        stdout.starts_with("scenes/triangle.toml: period 4, 3 starts, 3 orbits"),
        "{stdout}"
    );
    assert!(!stdout.contains("stopped"), "{stdout}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A search that reaches `--max-contacts` stops there (exit 0), publishes what it found, and
/// says how far it got; `--quiet` leaves stderr empty. The sector's period-4 grid of 64 starts
/// follows about 10^4 contacts in all; a bound of 2000 stops it part way.
#[test]
fn a_search_stops_at_its_bound_of_contacts_and_says_so() {
    let dir = temp("orbits-bound");
    let out = within(
        noslip()
            .args([
                "orbits",
                "scenes/sector.toml",
                "--period",
                "4",
                "--grid",
                "4",
            ])
            .args(["--max-contacts", "2000", "--quiet", "--out"])
            .arg(&dir),
        Duration::from_secs(60),
    );
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(out.status.success(), "{stdout}");
    assert!(
        out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stop = stdout
        .lines()
        .find(|l| l.starts_with("stopped: the search followed "))
        .unwrap_or_else(|| panic!("{stdout}"));
    assert!(
        stop.contains("its bound is 2000")
            && stop.ends_with("raise --max-contacts or give fewer starts"),
        "{stop}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("orbits.json")).unwrap()).unwrap();
    let (tried, starts) = (
        json["tried"].as_u64().unwrap(),
        json["starts"].as_u64().unwrap(),
    );
    assert!(0 < tried && tried < starts && starts == 64, "{json}");
    assert!(json["contacts"].as_u64().unwrap() <= 2000, "{json}");
    assert!(
        stop.contains(&format!("{tried} of 64 starts were tried")),
        "{stop}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bouncing_orbit_is_found_and_its_polynomial_is_exact() {
    let dir = temp("orbits-walls");
    let stdout = run_ok(
        noslip()
            .args(["orbits", "scenes/disk_between_walls.toml", "--period", "2"])
            .args(["--from", "1,1/2,0,1,0", "--from", "1,0.5,0,1,0", "--out"])
            .arg(&dir),
    );
    // The two starts are the same orbit: merged.
    assert!(stdout.starts_with("scenes/disk_between_walls.toml: period 2, 2 starts, 1 orbit (0 starts did not converge)"), "{stdout}");
    assert!(
        stdout.contains("orbit 1: Elliptic, contacts [1, 0], found from 2 starts"),
        "{stdout}"
    );
    assert!(stdout.contains("exact, --from[0]: contacts [1, 0], periodic; characteristic polynomial of the section map: l^4 - 4/9 l^3 - 10/9 l^2 - 4/9 l + 1"), "{stdout}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("orbits.json")).unwrap()).unwrap();
    assert_eq!(json["orbits"][0]["verdict"], "elliptic");
    assert_eq!(json["exact"][0]["coefficients"][1], "-4/9");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_grid_search_on_the_sinai_table_finds_elliptic_orbits() {
    let dir = temp("orbits-sinai");
    let stdout = run_ok(
        noslip()
            .args([
                "orbits",
                "scenes/sinai.toml",
                "--period",
                "2",
                "--grid",
                "3",
                "--out",
            ])
            .arg(&dir),
    );
    assert!(
        stdout.starts_with("scenes/sinai.toml: period 2, 27 starts"),
        "{stdout}"
    );
    assert!(
        stdout.contains("orbit 1: Elliptic, contacts [0, 0]"),
        "{stdout}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_input_exits_2_naming_the_place() {
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["scenes/sinai.toml", "--period", "0"],
            "--period: must be in 1..=1000",
        ),
        (
            vec!["scenes/sinai.toml", "--period", "2", "--from", "1,2,3"],
            "--from[0]: has 3 numbers, expected 2n + S = 5",
        ),
        (
            vec![
                "scenes/sinai.toml",
                "--period",
                "2",
                "--from",
                "0.85,0.5,1,0,x",
            ],
            "--from[0][4]",
        ),
        (
            vec![
                "scenes/sinai.toml",
                "--period",
                "2",
                "--from",
                "1,1/2,0,1e400,0",
            ],
            "--from[0]: number 3 is beyond the f64 range",
        ),
        (
            vec![
                "scenes/sinai.toml",
                "--period",
                "2",
                "--from",
                "0.85,0.5,-1,0,0",
            ],
            "--from[0]: the velocity must point into the table",
        ),
        (
            vec!["scenes/sinai.toml", "--period", "2", "--grid", "0"],
            "--grid: must be at least 1",
        ),
        (
            vec!["scenes/sinai.toml", "--period", "2", "--max-contacts", "0"],
            "--max-contacts: must be at least 1, got 0",
        ),
        (
            vec!["scenes/sinai.toml", "--period", "2", "--contact", "rough"],
            "--contact: must be no-slip or smooth",
        ),
        (
            vec!["scenes/gas2d.toml", "--period", "2"],
            "scenes/gas2d.toml: a one-ball table is needed",
        ),
    ];
    for (args, message) in cases {
        let out = noslip().arg("orbits").args(&args).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains(message), "{args:?}: {err}");
    }
}

/// A ball flying along a periodic axis between walls it never reaches has no first contact:
/// the refusal says so in words (it printed the enum, `(Escapes)`).
#[test]
fn a_ball_that_meets_no_boundary_is_refused_in_words() {
    let dir = temp("orbits-fly");
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("fly.toml");
    std::fs::write(
        &scene,
        "dim = 2\n[box]\nsize = [10, 4]\nboundary = [\"periodic\", \"wall\"]\n\
         [[species]]\nmass = 1\nradius = \"1/2\"\n\
         [[ball]]\nspecies = 0\nposition = [1, 2]\nvelocity = [1, 0]\n",
    )
    .unwrap();
    let out = noslip()
        .arg("orbits")
        .arg(&scene)
        .args(["--period", "2"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("the ball never touches the table: its flight meets no boundary"),
        "{err}"
    );
    assert!(!err.contains("Escapes"), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}
