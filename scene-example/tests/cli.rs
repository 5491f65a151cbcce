//! The example binary from the outside: `--help`, every compiled scene runs (gas2d too, with
//! its random placement), bad arguments and look-alike scenes are refused with exit 2.

use std::process::Command;

fn example(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_noslip-scene-example"))
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    )
}

#[test]
fn help_is_help_not_a_file_name() {
    for flag in ["--help", "-h"] {
        let (code, out, err) = example(&[flag]);
        assert_eq!(code, 0, "{err}");
        assert!(
            out.starts_with("Usage: noslip-scene-example [SCENE] [EVENTS]"),
            "{out}"
        );
        assert!(out.contains("Exit codes"), "{out}");
        assert_eq!(err, "");
    }
}

#[test]
fn every_compiled_scene_runs_on_its_kernels() {
    for (scene, events) in [
        ("scenes/gas2d.toml", 3000),
        ("scenes/sinai.toml", 1000),
        ("scenes/disk_between_walls.toml", 10),
    ] {
        let (code, out, err) = example(&[scene, &events.to_string()]);
        assert_eq!(code, 0, "{scene}: {err}");
        assert!(
            out.starts_with(&format!("{events} contacts in ")),
            "{scene}: {out}"
        );
        // Relative energy drift at rounding level: each contact rounds the pair's energy a
        // few ulps (docs/scenes.md bounds it by 8 eps per contact).
        let drift: f64 = out.trim().rsplit(' ').next().unwrap().parse().unwrap();
        assert!(
            drift.abs() <= 8.0 * events as f64 * f64::EPSILON,
            "{scene}: {out}"
        );
    }
}

#[test]
fn bad_arguments_and_other_scenes_exit_2_with_one_line() {
    let dir = std::env::temp_dir().join(format!("noslip-example-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // A file named like a compiled scene, with other constants.
    let shipped = include_str!("../../scenes/gas2d.toml");
    let lookalike = dir.join("gas2d.toml");
    std::fs::write(&lookalike, shipped.replace("mass = 4", "mass = 5")).unwrap();
    let lookalike = lookalike.to_str().unwrap();
    for (args, needle) in [
        (vec!["--bogus"], "unknown option \"--bogus\""),
        (vec!["scenes/sinai.toml", "many"], "EVENTS: \"many\""),
        (vec!["a", "1", "b"], "at most SCENE and EVENTS"),
        (
            vec!["scenes/gas3d.toml"],
            "scene gas3d: this example compiles",
        ),
        (vec!["no-such-file.toml"], "no-such-file.toml"),
        (vec![lookalike, "10"], "differ from scenes/gas2d.toml"),
    ] {
        let (code, out, err) = example(&args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert_eq!(out, "");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
    }
    std::fs::remove_dir_all(dir).unwrap();
}
