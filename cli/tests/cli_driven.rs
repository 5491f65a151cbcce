//! `noslip simulate` on the shipped driven gas (`scenes/driven3d.toml`, a `[thermostat]`):
//! the kicks counted in summary.json and their energy in the balance, the observables
//! written (msd across the kicks, the injected energy's column in each interval's balance), and a bad thermostat, lyapunov and orbits
//! refused (exit 2, the field named).

use crate::support;
use support::{noslip, run_ok, temp};

const DRIVEN: &str = "scenes/driven3d.toml";

#[test]
fn the_driven_gas_is_kicked_and_accounts_for_its_energy() {
    let dir = temp("driven");
    run_ok(
        noslip()
            .args([
                "simulate",
                DRIVEN,
                "--time",
                "5",
                "--observables",
                "1",
                "--quiet",
                "--out",
            ])
            .arg(&dir),
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    // Kicks every 0.43 up to t = 5.
    assert_eq!(summary["kicks"], 11, "{summary}");
    let injected = summary["energy_injected"].as_f64().unwrap();
    let (start, end) = (
        summary["energy_start"].as_f64().unwrap(),
        summary["energy_end"].as_f64().unwrap(),
    );
    // The expected injection: 11 kicks of n (N - 1) m xi^2 dt / 2 = 3 * 499 * 0.36 * 0.43 / 2
    // = 115.86 each, 1274.5 in all, with the kicks' random cross term `sum m u . dv` (standard
    // deviation sqrt(2 E_tr xi^2 dt) = 15.2 per kick at E_tr = 750, 50.4 over 11): within 6 of
    // those.
    assert!((injected - 1274.5).abs() < 6.0 * 50.4, "{injected}");
    let csv = std::fs::read_to_string(dir.join("observables.csv")).unwrap();
    let rows: Vec<Vec<f64>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 5, "{csv}");
    // The balance: the energy the contacts took up to the last row is at most what came in
    // and was there, and the driven gas stays near its steady temperature (T_tr about 1).
    let last = rows.last().unwrap();
    assert!(last[6] > 0.0 && last[6] < start + injected, "{last:?}");
    assert!(end > 0.5 * start && end < 2.0 * start, "{start} -> {end}");
    // The kicks end the displacements' flights: msd is known, from 0 at the start.
    assert!(
        rows.iter().all(|r| r[13].is_finite() && r[14].is_finite()) && rows[0][13] == 0.0,
        "{csv}"
    );
    assert!(last[13] > 0.0 && last[14] <= last[13], "{last:?}");
    // The injected column (10) balances each interval with the losses (6..10), to the
    // rounding bound of sim/tests/driven_observables.rs: C contacts and K kicks in the
    // interval, 500 balls, E_max twice the largest energy, W the largest running total.
    assert_eq!(rows[0][10], 0.0);
    assert!(
        last[10] > 0.0 && last[10] < injected + 6.0 * 50.4,
        "{last:?}"
    );
    let e_max = 2.0 * rows.iter().map(|r| r[4]).fold(0.0, f64::max);
    let w = last[6..11].iter().copied().fold(0.0, f64::max);
    for pair in rows.windows(2) {
        let (a, b) = (&pair[0], &pair[1]);
        let c = b[1] - a[1];
        let k = (b[0] / 0.43).floor() - (a[0] / 0.43).floor();
        let lost: f64 = (6..10).map(|j| b[j] - a[j]).sum();
        let off = (b[4] - a[4]) - ((b[10] - a[10]) - lost);
        let bound = (64.0 * c + 1016.0 * k + 20000.0) * f64::EPSILON * e_max
            + (c + k + 10.0) * f64::EPSILON * w;
        assert!(
            off.abs() <= bound,
            "{a:?} -> {b:?}: off by {off:e} > {bound:e}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `noslip args`: it must exit 2 with `says` in its stderr.
fn refused(args: &[&str], says: &str) {
    let out = noslip().args(args).output().unwrap();
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains(says), "{err}");
}

#[test]
fn bad_thermostats_and_driven_dynamics_exit_2_naming_them() {
    let dir = temp("driven-bad");
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/driven3d.toml"),
    )
    .unwrap();
    for (from, to, says) in [
        (
            "strength = \"0.6\"",
            "strength = \"-0.6\"",
            "bad.toml: thermostat.strength: must be positive, got -3/5",
        ),
        (
            "interval = \"0.43\"",
            "interval = 0",
            "bad.toml: thermostat.interval: must be positive, got 0",
        ),
        (
            "kind = \"white-noise\"",
            "kind = \"wall\"",
            "bad.toml: thermostat.kind: must be \"white-noise\", got \"wall\"",
        ),
    ] {
        let bad = dir.join("bad.toml");
        std::fs::write(&bad, text.replace(from, to)).unwrap();
        refused(&["simulate", bad.to_str().unwrap(), "--quiet"], says);
    }
    // A one-ball table with a thermostat: orbits and lyapunov refuse it (their maps have no
    // kicks), naming the table.
    let triangle = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/triangle.toml"),
    )
    .unwrap()
        + "\n[thermostat]\nkind = \"white-noise\"\nstrength = 1\ninterval = 1\n";
    let scene = dir.join("kicked.toml");
    std::fs::write(&scene, triangle).unwrap();
    let path = scene.to_str().unwrap();
    let out = dir.join("out");
    let out = out.to_str().unwrap();
    refused(
        &["orbits", path, "--period", "3", "--grid", "1", "--out", out],
        "kicked.toml: thermostat: a driven table's random kicks have no exact return map",
    );
    refused(
        &["lyapunov", path, "--events", "100", "--out", out],
        "kicked.toml: thermostat: a driven gas's random kicks have no tangent map",
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
