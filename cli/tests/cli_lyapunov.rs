//! `noslip lyapunov` from the outside: a run's outputs, the default `--k` and the memory cap
//! of large scenes, and bad input (exit 2, one line naming the place).

use crate::support;
use std::time::Duration;
use support::{noslip, run_ok, temp, within};

/// The shipped gas2d (750 disks, phase-space dimension 3750) with the default `--k` ran the
/// whole spectrum: two Gram-Schmidt passes of `3750^3` multiply-adds each, 223 s for
/// `--events 200`. The default now keeps the run's Gram-Schmidt within 2e9 multiply-adds:
/// the 210 largest exponents (12 re-orthonormalisations: one per block of 18 contacts at
/// least), said on stderr; the run takes seconds.
#[test]
fn a_gas_gets_a_default_k_within_the_budget_and_says_so() {
    let dir = temp("lyapunov-gas2d");
    let out = within(
        noslip()
            .args(["lyapunov", "scenes/gas2d.toml", "--events", "200", "--out"])
            .arg(&dir),
        Duration::from_secs(120),
    );
    let (stdout, stderr) = (
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    );
    assert!(out.status.success(), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.starts_with(
            "note: --k not given: the whole spectrum (3750 exponents) would need 107.288 MiB"
        ) && stderr.contains("computing the 210 largest"),
        "{stderr}"
    );
    assert!(
        stdout.contains("210 exponents by qr") && stdout.contains("phase-space dimension 3750"),
        "{stdout}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// 12 000 disks (dimension 60 000): the whole spectrum needs 28.8 GB and the run aborted on a
/// failed allocation. Asked for, it is refused before any work (exit 2, naming `--k`, the
/// memory and the cap); by default 52 vectors are carried (the work budget: 12
/// re-orthonormalisations of 100 contacts in blocks of 9; 139 would fit 64 MiB).
#[test]
fn a_spectrum_beyond_the_memory_cap_is_refused_up_front() {
    let dir = temp("lyapunov-big");
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("big.toml");
    std::fs::write(
        &scene,
        "dim = 2\n[box]\nsize = [400, 400]\nboundary = [\"periodic\", \"periodic\"]\n\
         [[species]]\nmass = 1\nradius = \"1/2\"\ncount = 12000\n\
         [random]\nseed = 1\nspeed = 1\nspin = 1\n",
    )
    .unwrap();
    let out = within(
        noslip().args(["lyapunov", scene.to_str().unwrap(), "--k", "60000"]),
        Duration::from_secs(60),
    );
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert_eq!(
        stderr.trim_end(),
        "error: --k: 60000 tangent vectors of dimension 60000 need 26.822 GiB (28800000000 \
         bytes, 8 k d), beyond the cap of 1.000 GiB: at most 2236 fit"
    );
    let out = within(
        noslip()
            .args([
                "lyapunov",
                scene.to_str().unwrap(),
                "--events",
                "100",
                "--out",
            ])
            .arg(dir.join("out")),
        Duration::from_secs(120),
    );
    let (stdout, stderr) = (
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    );
    assert!(out.status.success(), "{stderr}");
    assert!(stderr.contains("computing the 52 largest"), "{stderr}");
    assert!(stdout.contains("52 exponents by qr"), "{stdout}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn sinai_spectrum_is_printed_and_published() {
    let dir = temp("lyapunov-sinai");
    let stdout = run_ok(
        noslip()
            .args(["lyapunov", "scenes/sinai.toml", "--events", "5000", "--out"])
            .arg(&dir),
    );
    assert!(
        stdout.starts_with("scenes/sinai.toml: 5 exponents by qr (the scene's kinds of contacts)"),
        "{stdout}"
    );
    assert!(stdout.contains("3 below 1% of the largest"), "{stdout}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("spectrum.json")).unwrap()).unwrap();
    assert_eq!(json["dimension"], 5);
    assert_eq!(json["per_time"].as_array().unwrap().len(), 5);
    let l1 = json["per_time"][0]["value"].as_f64().unwrap();
    assert!(l1 > 0.5 && l1 < 2.0, "{l1}");
    let csv = std::fs::read_to_string(dir.join("running.csv")).unwrap();
    assert!(csv.starts_with("contacts,time,lambda_1,lambda_2,lambda_3,lambda_4,lambda_5\n"));
    let last: Vec<f64> = csv
        .lines()
        .last()
        .unwrap()
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect();
    assert_eq!(last[0], 5000.0);
    // The same sums in another order (per block, or running): equal to rounding.
    assert!(
        (last[2] - l1).abs() < 1e-12 * l1,
        "the running estimate ends at the estimate"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn two_trajectory_and_smooth_run() {
    let dir = temp("lyapunov-two");
    let stdout = run_ok(
        noslip()
            .args([
                "lyapunov",
                "scenes/sinai.toml",
                "--events",
                "500",
                "--method",
                "two-trajectory",
            ])
            .args(["--contact", "smooth", "--out"])
            .arg(&dir),
    );
    assert!(
        stdout.contains("1 exponent by two-trajectory (all smooth contacts)"),
        "{stdout}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_input_exits_2_naming_the_place() {
    let dir = temp("lyapunov-bad");
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, "dim = 2\n[box]\nsize = [1, 1]\nboundary = [\"wall\", \"wall\"]\n[[species]]\nmass = 0\nradius = \"1/4\"\ncount = 1\n").unwrap();
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["scenes/sinai.toml", "--k", "6"],
            "--k: must be in 1..=5",
        ),
        (
            vec!["scenes/sinai.toml", "--k", "0"],
            "--k: must be in 1..=5",
        ),
        (
            vec!["scenes/sinai.toml", "--method", "svd"],
            "--method: must be qr or two-trajectory",
        ),
        (
            vec!["scenes/sinai.toml", "--contact", "rough"],
            "--contact: must be no-slip or smooth",
        ),
        (
            vec!["scenes/sinai.toml", "--events", "10"],
            "--events: 10 contacts cannot make",
        ),
        (
            vec!["scenes/sinai.toml", "--blocks", "0"],
            "--blocks: must be in 1..=10000",
        ),
        (
            vec!["scenes/sinai.toml", "--blocks", "10001"],
            "--blocks: must be in 1..=10000",
        ),
        // blocks + 1 wrapped to 0 here once (a division by zero).
        (
            vec!["scenes/sinai.toml", "--blocks", "18446744073709551615"],
            "--blocks: must be in 1..=10000",
        ),
        // The Sinai table's lambda_1 is 1.3 a contact: in 300 contacts the vectors grow by
        // about e^400, and their squares overflow.
        (
            vec![
                "scenes/sinai.toml",
                "--events",
                "2000",
                "--blocks",
                "2",
                "--every",
                "300",
            ],
            "--every: the tangent vectors stopped being finite between contacts 0 and 300",
        ),
        // Ten blocks of 181 contacts: an interval of 300 would leave blocks empty (their
        // estimates 0/0, the errors NaN).
        (
            vec!["scenes/sinai.toml", "--events", "2000", "--every", "300"],
            "--every: 300 contacts between re-orthonormalisations would leave blocks without \
             one (no growth, no error estimate): at most 181",
        ),
        (
            vec!["scenes/sinai.toml", "--every", "0"],
            "--every: must be at least 1",
        ),
        (
            vec![
                "scenes/sinai.toml",
                "--method",
                "two-trajectory",
                "--k",
                "2",
            ],
            "--k: two-trajectory",
        ),
        (vec!["scenes/missing.toml"], "scenes/missing.toml"),
        (vec![bad.to_str().unwrap()], "species[0].mass"),
    ];
    for (args, message) in cases {
        let out = noslip().arg("lyapunov").args(&args).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains(message), "{args:?}: {err}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
