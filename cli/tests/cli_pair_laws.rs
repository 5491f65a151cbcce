//! A ball-ball law per pair of species (`[[contact.pair]]`) from the command line: the
//! shipped mixture simulates and its kernels check, and bad pairs are refused by `simulate`
//! and `gen --scene` with exit 2 and one line naming the field.

use crate::support;
use support::{noslip, run_ok, temp};

#[test]
fn the_shipped_mixture_runs_and_its_kernels_check() {
    let out = run_ok(noslip().args(["gen", "--scene", "scenes/mixture2d.toml", "--check", "4"]));
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(
        lines,
        [
            "ok   ball_ball_0_0: 4 of 4 exact points equal the generic map",
            "ok   ball_ball_0_1: 4 of 4 exact points equal the generic map",
            "ok   ball_ball_1_1: 4 of 4 exact points equal the generic map",
        ]
    );
    // The module names each pair's law in its kernels' docs.
    let module = run_ok(noslip().args(["gen", "--scene", "scenes/mixture2d.toml"]));
    for law in [
        "rough (e = 9/10, beta = 1/2)",
        "rough (e = 4/5, beta = -1/5)",
        "Walton (e = 7/10, mu = 3/10, beta0 = 3/5)",
    ] {
        assert!(module.contains(law), "no kernel with the law {law}");
    }
    let summary = run_ok(noslip().args([
        "simulate",
        "scenes/mixture2d.toml",
        "--events",
        "500",
        "--quiet",
    ]));
    assert!(summary.contains("500"), "{summary}");
}

#[test]
fn bad_pairs_exit_2_naming_the_field() {
    let dir = temp("pair-laws");
    std::fs::create_dir_all(&dir).unwrap();
    let shipped = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/mixture2d.toml"),
    )
    .unwrap();
    let pair = "species = [\"grain\", \"tracer\"]";
    let law = "law = { e = \"0.8\", beta = \"-0.2\" }";
    assert!(shipped.contains(pair) && shipped.contains(law));
    for (name, from, to, says) in [
        (
            "unknown.toml",
            pair,
            "species = [\"grain\", \"dust\"]",
            "unknown.toml: contact.pair[0].species[1]: no species named \"dust\" (the scene has \"grain\", \"tracer\")",
        ),
        (
            "twice.toml",
            "species = [\"tracer\", \"tracer\"]",
            "species = [\"tracer\", \"grain\"]",
            "twice.toml: contact.pair[1].species: the pair (\"grain\", \"tracer\") is listed twice: also at contact.pair[0] (a pair is unordered)",
        ),
        (
            "law.toml",
            law,
            "law = { e = \"0.8\", beta = \"-1.5\" }",
            "law.toml: contact.pair[0].law.beta: must be in [-1, 1], got -3/2",
        ),
    ] {
        let path = dir.join(name);
        std::fs::write(&path, shipped.replacen(from, to, 1)).unwrap();
        let path = path.to_str().unwrap();
        for args in [
            vec!["simulate", path, "--events", "10", "--quiet"],
            vec!["gen", "--scene", path, "--check", "2"],
        ] {
            let out = noslip().args(&args).output().unwrap();
            let err = String::from_utf8(out.stderr).unwrap();
            assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
            assert!(out.stdout.is_empty(), "{args:?}");
            assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
            assert!(err.contains(says), "{args:?}: {err:?} does not say {says:?}");
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
