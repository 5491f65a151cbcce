//! `noslip simulate` and `noslip gen` from the outside: exit codes, one-line errors, outputs.

use crate::support;
use std::path::Path;
use std::process::Command;
use support::{noslip, run_ok};

#[test]
fn a_bad_scene_exits_2_with_one_line() {
    let dir = scratch("bad");
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, "dim = 2\n[box]\nsize = [1, 1]\nboundary = [\"wall\", \"wall\"]\n[[species]]\nmass = 1\nradius = \"1/4\"\nlambda = 1\ncount = 1\n").unwrap();
    for sub in [
        ["simulate", bad.to_str().unwrap(), "--quiet"].as_slice(),
        ["gen", "--scene", bad.to_str().unwrap()].as_slice(),
    ] {
        let out = noslip().args(sub).output().unwrap();
        assert_eq!(out.status.code(), Some(2));
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(
            err.contains("bad.toml: species[0].lambda: must be in [0, R^2/n] = [0, 1/32], got 1"),
            "{err}"
        );
    }
}

#[test]
fn sinai_runs_and_writes_its_pictures() {
    let dir = scratch("sinai");
    let log = dir.join("events.jsonl");
    let stdout = run_ok(
        noslip()
            .args([
                "simulate",
                "scenes/sinai.toml",
                "--events",
                "300",
                "--quiet",
                "--out",
            ])
            .arg(&dir)
            .arg("--log")
            .arg(&log),
    );
    assert!(
        stdout.starts_with(
            "300 contacts (0 ball-ball, 0 ball-wall, 300 ball-obstacle, 0 ball-boundary)"
        ),
        "{stdout}"
    );
    assert_eq!(std::fs::read_to_string(&log).unwrap().lines().count(), 300);
    for f in ["summary.json", "energy.svg", "trajectories.svg"] {
        let text = std::fs::read_to_string(dir.join(f)).unwrap();
        assert!(text.len() > 100, "{f}");
    }
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["events"], 300);
}

#[test]
fn gen_prints_the_module_and_checks_it() {
    let out = noslip()
        .args(["gen", "--scene", "scenes/sinai.toml"])
        .output()
        .unwrap();
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.starts_with("// @generated"));
    assert!(text.contains("pub fn ball_obstacle_0<T: Scalar>"));
    assert!(
        !text.contains("pub fn ball_ball_"),
        "one disk: no ball-ball kernel"
    );
    assert!(
        !text.contains("pub fn ball_wall_"),
        "a periodic box: no wall kernel"
    );
    let out = noslip()
        .args(["gen", "--scene", "scenes/sinai.toml", "--check", "4"])
        .output()
        .unwrap();
    assert!(out.status.success());
    assert!(String::from_utf8(out.stdout)
        .unwrap()
        .contains("ok   ball_obstacle_0: 4 of 4"));
}

#[test]
fn a_scene_without_possible_contacts_stops_with_its_reason() {
    // issue 16: one disk moving parallel to the walls of a periodic axis, an event limit and
    // no time limit, ran forever printing nothing.
    let dir = scratch("never");
    let scene = dir.join("parallel.toml");
    std::fs::write(
        &scene,
        "dim = 2\n[box]\nsize = [10, 4]\nboundary = [\"periodic\", \"wall\"]\n\
         [[species]]\nmass = 1\nradius = \"1/2\"\n\
         [[ball]]\nspecies = 0\nposition = [1, 2]\nvelocity = [1, 0]\n\
         [simulation]\nevents = 1000\n",
    )
    .unwrap();
    let mut child = noslip()
        .args(["simulate", scene.to_str().unwrap(), "--quiet", "--out"])
        .arg(dir.join("out"))
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // It must stop by itself: kill it after 60 s rather than hang the test suite.
    let start = std::time::Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed().as_secs() > 60 {
            child.kill().unwrap();
            panic!("simulate did not stop within 60 s");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let out = child.wait_with_output().unwrap();
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.starts_with("0 contacts"), "{stdout}");
    assert!(
        stdout.contains("stopped: no contact can happen: no ball moves along a walled axis"),
        "{stdout}"
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("out/summary.json")).unwrap())
            .unwrap();
    assert!(summary["stopped"]
        .as_str()
        .unwrap()
        .starts_with("no contact can happen"));
}

/// A fresh scratch directory for one test ([`support::scratch`]; `simulate-` keeps it apart
/// from the other modules' paths in this test process).
fn scratch(name: &str) -> support::Scratch {
    support::scratch(&format!("simulate-{name}"))
}

/// Run `cmd`, killing it (and failing) if it does not finish within `seconds`.
fn output_within(cmd: &mut Command, seconds: u64) -> std::process::Output {
    use std::process::Stdio;
    let mut child = cmd
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = std::time::Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed().as_secs() >= seconds {
            child.kill().unwrap();
            child.wait().unwrap();
            panic!("{cmd:?} did not finish within {seconds} s");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

/// `noslip simulate` on the scene `text` (written to `dir/name.toml`) with `extra` flags:
/// exit code, stdout, stderr.
fn simulate_text(
    dir: &std::path::Path,
    name: &str,
    text: &str,
    extra: &[&str],
) -> (i32, String, String) {
    let file = dir.join(format!("{name}.toml"));
    std::fs::write(&file, text).unwrap();
    let mut cmd = noslip();
    cmd.arg("simulate")
        .arg(&file)
        .args(["--quiet", "--out"])
        .arg(dir.join(format!("out-{name}")))
        .args(extra);
    let out = output_within(&mut cmd, 60);
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    )
}

/// A 2D scene: box sides, species lines, extra tables.
fn scene2(size: &str, species: &str, extra: &str) -> String {
    format!(
        "dim = 2\n[box]\nsize = [{size}, {size}]\nboundary = [\"wall\", \"periodic\"]\n\
         [[species]]\n{species}\n{extra}"
    )
}

#[test]
fn scenes_outside_the_f64_range_are_refused_naming_the_field() {
    let dir = scratch("range");
    let cases = [
        // Issue 16's cases: 1/m overflows; R^2 underflows (energy NaN); the box scale squared
        // overflows (phantom contacts); the spin energy overflows; |u|^2 underflows.
        ("mass", scene2("10", "mass = \"1e-400\"\nradius = \"1/2\"\ncount = 3", ""), "species[0].mass: "),
        ("heavy", scene2("10", "mass = \"1e400\"\nradius = \"1/2\"\ncount = 3", ""), "species[0].mass: "),
        ("radius", scene2("10", "mass = 1\nradius = \"1e-200\"\ncount = 3", ""), "species[0].radius: "),
        ("box", scene2("\"1e200\"", "mass = 1\nradius = 1\ncount = 3", ""), "box.size[0]: "),
        ("spin", scene2("10", "mass = 1\nradius = \"1/2\"\ncount = 3", "[random]\nspin = \"1e300\"\n"), "random.spin: "),
        ("speed", scene2("10", "mass = 1\nradius = \"1/2\"\ncount = 3", "[random]\nspeed = \"1e-300\"\n"), "random.speed: "),
        // lambda = gamma^2 R^2 / 2 underflows.
        ("gamma2", scene2("10", "mass = 1\nradius = \"1/2\"\ngamma2 = \"1e-320\"\ncount = 3", ""), "species[0].gamma2: "),
        ("lambda", scene2("10", "mass = 1\nradius = \"1/2\"\nlambda = \"1e-330\"\ncount = 3", ""), "species[0].lambda: "),
        // Species 1 (m = 1e300, R = 1e-100) meets itself: R D = 1e-100 * 1.5e-300 underflows.
        (
            "pair",
            scene2(
                "\"1e-95\"",
                "mass = 1\nradius = \"1e-100\"\ncount = 2\n[[species]]\nmass = \"1e300\"\nradius = \"1e-100\"\ncount = 2",
                "",
            ),
            "species[1]: with species[1], the contact map's D",
        ),
        (
            "obstacle",
            scene2("10", "mass = 1\nradius = \"1/2\"\ncount = 3", "[[obstacle]]\nposition = [5, 5]\nradius = \"1e200\"\n"),
            "obstacle[0].radius: the box scale",
        ),
        // R / L = 1e-9 < 2^-26: contact distances would keep fewer than half the digits.
        ("resolution", scene2("\"1e9\"", "mass = 1\nradius = 1\ncount = 3", ""), "species[0].radius: R = 1e0 is less than 2^-26"),
        (
            "velocity",
            scene2("10", "mass = 1\nradius = \"1/2\"", "[[ball]]\nspecies = 0\nposition = [1, 1]\nvelocity = [\"1e200\", 0]\n"),
            "ball[0].velocity: ",
        ),
        (
            "angular",
            scene2("10", "mass = 1\nradius = \"1/2\"", "[[ball]]\nspecies = 0\nposition = [1, 1]\nvelocity = [1, 0]\nangular_velocity = \"1e300\"\n"),
            "ball[0].angular_velocity: ",
        ),
        // The speed is fine alone, but (B V)^2 of the contact-time discriminant overflows.
        ("discriminant", scene2("10", "mass = 1\nradius = \"1/2\"\ncount = 3", "[random]\nspeed = \"1e152\"\n"), "random.speed: the box scale"),
        // (R_min v)^2 = (1e-80 * 1e-120)^2 underflows at the contact scale.
        (
            "contact",
            scene2("\"1e-75\"", "mass = 1\nradius = \"1e-80\"\ncount = 3", "[random]\nspeed = \"1e-120\"\n"),
            "random.speed: with the typical speed",
        ),
        ("time", scene2("10", "mass = 1\nradius = \"1/2\"\ncount = 3", "[simulation]\ntime = \"1e-400\"\n"), "simulation.time: "),
        ("still", scene2("10", "mass = 1\nradius = \"1/2\"\ncount = 3", "[random]\nspeed = 0\n"), "random.speed: nothing moves"),
    ];
    for (name, text, want) in cases {
        let (code, _, err) = simulate_text(&dir, name, &text, &["--events", "100"]);
        assert_eq!(code, 2, "{name}: exit {code}, stderr {err}");
        assert_eq!(err.lines().count(), 1, "{name}: {err}");
        let want = format!(
            "error: {}: {want}",
            dir.join(format!("{name}.toml")).display()
        );
        assert!(err.starts_with(&want), "{name}:\n got  {err}\n want {want}");
    }
    std::fs::remove_dir_all(dir).unwrap();
}

/// Every number of an events-log line, with positions scaled by `length`, velocities by
/// `speed`, spins by `spin` and times by `time` (powers of two, so exactly).
fn scaled(
    line: &serde_json::Value,
    length: f64,
    speed: f64,
    spin: f64,
    time: f64,
) -> serde_json::Value {
    let mut v = line.clone();
    let num = |x: &serde_json::Value, s: f64| serde_json::json!(x.as_f64().unwrap() * s);
    v["time"] = num(&line["time"], time);
    for (k, p) in line["positions"].as_array().unwrap().iter().enumerate() {
        for (a, x) in p.as_array().unwrap().iter().enumerate() {
            v["positions"][k][a] = num(x, length);
        }
    }
    for side in ["pre", "post"] {
        for (k, s) in line[side].as_array().unwrap().iter().enumerate() {
            for (a, x) in s["velocity"].as_array().unwrap().iter().enumerate() {
                v[side][k]["velocity"][a] = num(x, speed);
            }
            for (a, x) in s["spin"].as_array().unwrap().iter().enumerate() {
                v[side][k]["spin"][a] = num(x, spin);
            }
        }
    }
    v
}

#[test]
fn an_accepted_scene_far_from_unit_scale_runs_the_same_events() {
    // Lengths x 2^250, times x 2^350 (speeds x 2^-100, spins x 2^-350), masses x 2^-400: every
    // product the range rule bounds stays normal, and scaling by powers of two changes no digit,
    // so the events must be the unscaled ones scaled, bit for bit.
    let dir = scratch("scale");
    let (length, time, mass) = (2f64.powi(250), 2f64.powi(350), 2f64.powi(-400));
    let scene = |l: f64, t: f64, m: f64| {
        format!(
            "dim = 2\n[box]\nsize = [{:e}, {:e}]\nboundary = [\"wall\", \"periodic\"]\n\
             [[species]]\nmass = {:e}\nradius = {:e}\ngamma2 = \"1/2\"\ncount = 40\n\
             [[species]]\nmass = {:e}\nradius = {:e}\ngamma2 = \"2/5\"\ncount = 10\n\
             [random]\nseed = 5\nspeed = {:e}\nspin = {:e}\n",
            20.0 * l,
            20.0 * l,
            m,
            0.5 * l,
            4.0 * m,
            l,
            l / t,
            1.0 / t
        )
    };
    let mut logs = Vec::new();
    for (name, l, t, m) in [("unit", 1.0, 1.0, 1.0), ("far", length, time, mass)] {
        let log = dir.join(format!("{name}.jsonl"));
        let (code, out, err) = simulate_text(
            &dir,
            name,
            &scene(l, t, m),
            &["--events", "400", "--log", log.to_str().unwrap()],
        );
        assert_eq!(code, 0, "{name}: {err}");
        assert!(out.starts_with("400 contacts ("), "{out}");
        let lines: Vec<serde_json::Value> = std::fs::read_to_string(&log)
            .unwrap()
            .lines()
            .map(|l| serde_json::from_str(l).unwrap())
            .collect();
        assert_eq!(lines.len(), 400);
        logs.push(lines);
    }
    let kinds: std::collections::BTreeSet<_> =
        logs[0].iter().map(|l| l["kind"].to_string()).collect();
    assert!(
        kinds.len() >= 2,
        "both ball-ball and ball-wall contacts: {kinds:?}"
    );
    for (a, b) in logs[0].iter().zip(&logs[1]) {
        assert_eq!(scaled(a, length, length / time, 1.0 / time, time), *b);
    }
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn counts_beyond_the_limit_or_the_box_are_refused_at_once() {
    let dir = scratch("counts");
    let cases = [
        // 10^9 balls in a box they would fill to 1e-3: placement used to run for ever.
        (
            "billion",
            scene2(
                "\"1e6\"",
                "mass = 1\nradius = \"1/2\"\ncount = 1_000_000_000",
                "",
            ),
            "species[0].count: 1000000000 balls",
        ),
        // 4 x 2^62 balls: the total used to wrap to 0 ("the scene has no balls").
        (
            "wrap",
            scene2(
                "10",
                &["mass = 1\nradius = \"1/2\"\ncount = 4611686018427387904"; 4]
                    .join("\n[[species]]\n"),
                "",
            ),
            "species[0].count: 4611686018427387904 balls",
        ),
        // 200 disks of area pi/4 in a box of area 100: more than the box holds.
        (
            "full",
            scene2("10", "mass = 1\nradius = \"1/2\"\ncount = 200", ""),
            "species[0].count: the balls would fill 1.571 times",
        ),
        // 0.70 of the box: possible (hexagonal packing reaches 0.91) but beyond random placement.
        (
            "jammed",
            scene2("10", "mass = 1\nradius = \"1/2\"\ncount = 89", ""),
            "species[0].count: placed ",
        ),
        // The lattice holds 13 x 14 / 2 = 91 disks (between the walls 9 / 0.707 = 12.7 gives
        // 12 + 1 points; periodic, 10 / 0.707 = 14.1 gives 14), not 92.
        (
            "lattice",
            scene2(
                "10",
                "mass = 1\nradius = \"1/2\"\ncount = 92",
                "[random]\nplacement = \"lattice\"\n",
            ),
            "species[0].count: the lattice start holds 91 balls",
        ),
        (
            "placement",
            scene2(
                "10",
                "mass = 1\nradius = \"1/2\"\ncount = 9",
                "[random]\nplacement = \"hexagonal\"\n",
            ),
            "random.placement: must be \"random\" or \"lattice\"",
        ),
    ];
    for (name, text, want) in cases {
        let (code, _, err) = simulate_text(&dir, name, &text, &["--events", "10"]);
        assert_eq!(code, 2, "{name}: {err}");
        assert_eq!(err.lines().count(), 1, "{name}: {err}");
        let want = format!(
            "error: {}: {want}",
            dir.join(format!("{name}.toml")).display()
        );
        assert!(err.starts_with(&want), "{name}:\n got  {err}\n want {want}");
    }
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_lattice_start_beyond_random_placement_simulates() {
    // 89 disks at 0.70 of the box: refused by random placement (the "jammed" case above),
    // placed on the lattice (91 sites) and run.
    let dir = scratch("lattice");
    let text = scene2(
        "10",
        "mass = 1\nradius = \"1/2\"\ncount = 89",
        "[random]\nplacement = \"lattice\"\nseed = 3\nspin = 1\n",
    );
    let (code, out, err) = simulate_text(&dir, "lattice", &text, &["--events", "2000"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.starts_with("2000 contacts ("), "{out}");
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn time_and_events_flags_are_checked_like_the_scene() {
    for (flag, value, want) in [
        (
            "--time",
            "NaN",
            "error: --time: must be positive and finite, got NaN",
        ),
        (
            "--time",
            "-1",
            "error: --time: must be positive and finite, got -1",
        ),
        (
            "--time",
            "0",
            "error: --time: must be positive and finite, got 0",
        ),
        (
            "--time",
            "inf",
            "error: --time: must be positive and finite, got inf",
        ),
        (
            "--time",
            "1e-320",
            "error: --time: 1e-320 is not a normal f64 (the least is 2.2250738585072014e-308)",
        ),
        ("--events", "0", "error: --events: must be at least 1"),
    ] {
        let out = noslip()
            .args(["simulate", "scenes/sinai.toml", "--quiet", flag, value])
            .output()
            .unwrap();
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(out.status.code(), Some(2), "{flag} {value}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.starts_with(want), "{flag} {value}: {err}");
    }
}

#[test]
fn sinai_trajectories_stay_small_at_many_events() {
    // 10^5 contacts used to write 9.2 MB of 81 000 polylines, most with one point.
    let dir = scratch("sinai-size");
    run_ok(
        noslip()
            .args([
                "simulate",
                "scenes/sinai.toml",
                "--events",
                "200000",
                "--quiet",
                "--out",
            ])
            .arg(&dir),
    );
    let svg = std::fs::read_to_string(dir.join("trajectories.svg")).unwrap();
    assert!(
        svg.len() <= 1_000_000,
        "trajectories.svg is {} bytes",
        svg.len()
    );
    let single = svg
        .lines()
        .filter(|l| l.starts_with("<polyline") && l.matches(',').count() == 1)
        .count();
    assert_eq!(single, 0, "one-point polylines");
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn the_log_may_go_into_the_output_directory_not_yet_made() {
    let dir = scratch("log-dir");
    let out_dir = dir.join("run");
    let log = out_dir.join("events.jsonl");
    run_ok(
        noslip()
            .args([
                "simulate",
                "scenes/sinai.toml",
                "--events",
                "50",
                "--quiet",
                "--out",
            ])
            .arg(&out_dir)
            .arg("--log")
            .arg(&log),
    );
    assert_eq!(std::fs::read_to_string(&log).unwrap().lines().count(), 50);
    let mut names: Vec<String> = std::fs::read_dir(&out_dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            ".noslip-output",
            "energy.svg",
            "events.jsonl",
            "summary.json",
            "trajectories.svg"
        ]
    );
    std::fs::remove_dir_all(dir).unwrap();
}

/// `--log` named inside `--out` by another spelling than `--out`'s (relative against
/// absolute, `..` through the directory itself) is the same member of the set under its own
/// name: a review found `--out /abs/o4 --log o4/ev.jsonl` writing `events.jsonl` and no
/// `ev.jsonl`, and `--out o7 --log ./o7/../o7/ev.jsonl` refused as "not directly in it".
#[test]
fn the_log_named_inside_out_by_another_spelling_keeps_its_name() {
    let dir = scratch("log-spelling");
    std::fs::create_dir_all(&dir).unwrap();
    let scene = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/sinai.toml");
    for (out, log) in [
        (
            dir.join("o4").display().to_string(),
            "o4/ev.jsonl".to_string(),
        ),
        (
            "o6".to_string(),
            dir.join("o6/ev.jsonl").display().to_string(),
        ),
        ("o7".to_string(), "./o7/../o7/ev.jsonl".to_string()),
    ] {
        run_ok(
            noslip()
                .current_dir(&dir)
                .arg("simulate")
                .arg(&scene)
                .args(["--events", "20", "--quiet", "--out", &out, "--log", &log]),
        );
        let set = dir.join(std::path::Path::new(&out).file_name().unwrap());
        let lines = std::fs::read_to_string(set.join("ev.jsonl")).unwrap();
        assert_eq!(lines.lines().count(), 20, "{out} {log}");
        assert!(!set.join("events.jsonl").exists(), "{out} {log}");
    }
    std::fs::remove_dir_all(dir).unwrap();
}

/// A side output that names a directory (an existing one, or `--out` itself) is refused
/// before the run, exit 2, naming the option (it was a failure to create the file, exit 1).
#[test]
fn a_log_or_map_naming_a_directory_is_refused_naming_the_option() {
    let dir = scratch("log-directory");
    let _ = std::fs::remove_dir_all(&dir);
    let existing = dir.join("existing");
    std::fs::create_dir_all(&existing).unwrap();
    let out = dir.join("set");
    for option in ["--log", "--boundary-map"] {
        for path in [&existing, &out] {
            let o = noslip()
                .args(["simulate", "scenes/sinai.toml", "--events", "20", "--quiet"])
                .arg("--out")
                .arg(&out)
                .arg(option)
                .arg(path)
                .output()
                .unwrap();
            let err = String::from_utf8_lossy(&o.stderr);
            assert_eq!(o.status.code(), Some(2), "{option} {path:?}: {err}");
            assert!(err.starts_with(&format!("error: {option}: ")), "{err}");
            assert!(err.contains("directory"), "{err}");
            assert!(!out.exists(), "a refused path costs no run");
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The summary's momentum and angular-momentum drifts are relative: the same run with every
/// mass scaled by `10^160` or `10^-170` (velocities and times unchanged) gives the same
/// figures. A review found `inf` (squares overflowing) and `0` (underflowing) there.
#[test]
fn the_momentum_drifts_do_not_depend_on_the_mass_scale() {
    let dir = scratch("drift-scale");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let scene = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../scenes/disk_between_walls.toml"
    ))
    .unwrap();
    assert!(scene.contains("\nmass = 1\n"));
    let drifts = |mass: &str| {
        let path = dir.join(format!("m{mass}.toml"));
        std::fs::write(
            &path,
            scene.replace("\nmass = 1\n", &format!("\nmass = {mass}\n")),
        )
        .unwrap();
        let out = dir.join(format!("out{mass}"));
        run_ok(
            noslip()
                .arg("simulate")
                .arg(&path)
                .args(["--events", "20", "--quiet", "--out"])
                .arg(&out),
        );
        let s: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        let f = |k: &str| {
            s[k].as_f64()
                .unwrap_or_else(|| panic!("{mass}: {k} = {}", s[k]))
        };
        (f("momentum_drift"), f("angular_momentum_drift"))
    };
    let (p, l) = drifts("1");
    assert!(p > 0.1 && l > 0.1, "walls change the momentum: {p} {l}");
    for mass in ["1e160", "1e-170"] {
        let (p2, l2) = drifts(mass);
        // The same contacts (the mass of the only ball scales out of the map); the drifts
        // differ only by the rounding of the sums, a few eps.
        for (a, b) in [(p, p2), (l, l2)] {
            assert!((a - b).abs() <= 1e-13 * a, "mass {mass}: {a} against {b}");
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The entries of `dir` whose names contain `part`.
fn entries_with(dir: &Path, part: &str) -> Vec<std::path::PathBuf> {
    let mut v: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.file_name().unwrap().to_string_lossy().contains(part))
        .collect();
    v.sort();
    v
}

/// A run whose log cannot be written: exit 1 with one line, the summary printed and written,
/// and nothing left where the log was to go (no new entry of its directory carries its name).
fn log_fails_cleanly(log: &Path, out_dir: &Path) {
    let (dir, name) = (
        log.parent().unwrap(),
        log.file_name().unwrap().to_string_lossy(),
    );
    let before = entries_with(dir, &name);
    let out = noslip()
        .args([
            "simulate",
            "scenes/sinai.toml",
            "--events",
            "5000",
            "--quiet",
            "--out",
        ])
        .arg(out_dir)
        .arg("--log")
        .arg(log)
        .output()
        .unwrap();
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.starts_with("error: cannot write the events log"),
        "{err}"
    );
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(stdout.starts_with("5000 contacts ("), "{stdout}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out_dir.join("summary.json")).unwrap())
            .unwrap();
    assert_eq!(summary["events"], 5000);
    assert_eq!(
        entries_with(dir, &name),
        before,
        "no partial log or temporary file in {}",
        dir.display()
    );
}

#[test]
fn a_log_on_a_full_device_leaves_nothing_and_the_summary_is_written() {
    let out_dir = scratch("log-full");
    // /dev/full: every write fails with ENOSPC; it must stay the device it is.
    log_fails_cleanly(Path::new("/dev/full"), &out_dir);
    use std::os::unix::fs::FileTypeExt;
    assert!(std::fs::metadata("/dev/full")
        .unwrap()
        .file_type()
        .is_char_device());
    std::fs::remove_dir_all(&out_dir).unwrap();
}

/// A tmpfs of 1 MB mounted on a fresh directory, unmounted when dropped.
struct TinyDisk(std::path::PathBuf);

impl Drop for TinyDisk {
    fn drop(&mut self) {
        let _ = Command::new("umount").arg(&self.0).status();
        let _ = std::fs::remove_dir(&self.0);
    }
}

#[test]
fn a_log_on_a_full_disk_leaves_nothing_and_the_summary_is_written() {
    let out_dir = scratch("log-disk");
    let mount = std::env::temp_dir().join(format!("noslip-tiny-{}", std::process::id()));
    std::fs::create_dir_all(&mount).unwrap();
    let mounted = Command::new("mount")
        .args(["-t", "tmpfs", "-o", "size=1m", "tmpfs"])
        .arg(&mount)
        .output();
    let disk = TinyDisk(mount.clone());
    match mounted {
        Ok(o) if o.status.success() => {}
        Ok(o) => {
            println!(
                "skipped: cannot mount a tmpfs here ({}); the /dev/full test covers the write failure",
                String::from_utf8_lossy(&o.stderr).trim()
            );
            return;
        }
        Err(e) => {
            println!(
                "skipped: no mount command ({e}); the /dev/full test covers the write failure"
            );
            return;
        }
    }
    // 5000 Sinai contacts make about 3 MB of log: the disk fills part way through a line.
    // The log is a member of the set (its file beside --out a link to it), so the set is on
    // the small disk too; it fits once the failed log's temporary is removed.
    let set = disk.0.join("out");
    let log = disk.0.join("events.jsonl");
    let out = noslip()
        .args([
            "simulate",
            "scenes/sinai.toml",
            "--events",
            "5000",
            "--quiet",
        ])
        .arg("--out")
        .arg(&set)
        .arg("--log")
        .arg(&log)
        .output()
        .unwrap();
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.starts_with("error: cannot write the events log"),
        "{err}"
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(set.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["events"], 5000);
    assert!(
        !log.exists(),
        "the log is absent: its link shows the set's none"
    );
    let mut left: Vec<String> = std::fs::read_dir(&disk.0)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    left.sort();
    assert_eq!(
        left,
        ["events.jsonl", "out"],
        "no temporary on the full disk"
    );
    drop(disk);
    std::fs::remove_dir_all(&out_dir).unwrap();
}

#[test]
fn the_output_directory_is_replaced_as_one_set_and_never_a_foreign_one() {
    let dir = scratch("sim-set");
    let out = dir.join("out");
    let run = |scene: &str, out: &Path| {
        noslip()
            .args(["simulate", scene, "--events", "20", "--quiet", "--out"])
            .arg(out)
            .output()
            .unwrap()
    };
    // A 2D run writes the trajectories; a 3D run into the same directory replaces the whole
    // set, so no picture of the first run is left beside the second run's summary.
    assert!(run("scenes/sinai.toml", &out).status.success());
    assert!(out.join("trajectories.svg").exists());
    let second = run("scenes/gas3d.toml", &out);
    assert!(
        second.status.success(),
        "{}",
        String::from_utf8_lossy(&second.stderr)
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["dim"], 3);
    assert!(!out.join("trajectories.svg").exists());
    // A directory noslip did not make is refused before the run, and left as it was.
    let foreign = dir.join("notes");
    std::fs::create_dir_all(&foreign).unwrap();
    std::fs::write(foreign.join("keep.txt"), "keep me").unwrap();
    let refused = run("scenes/sinai.toml", &foreign);
    assert_eq!(refused.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert!(
        stderr.starts_with("error: --out: ") && stderr.contains("refusing to replace"),
        "{stderr}"
    );
    assert!(refused.stdout.is_empty(), "no run before the refusal");
    assert_eq!(std::fs::read_dir(&foreign).unwrap().count(), 1);
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_long_flight_without_contact_is_noticed_and_the_run_goes_on() {
    // Sinai's table with the disk moving almost along the corridor above the obstacle: its
    // next contact comes after about 1350 box lengths. The run reports the quiet stretch on
    // stderr and goes on to the contact (it used to stop at 1000 box lengths).
    let dir = scratch("corridor");
    let scene = dir.join("corridor.toml");
    std::fs::write(
        &scene,
        "dim = 2\n[box]\nsize = [1, 1]\nboundary = [\"periodic\", \"periodic\"]\n\
         [[species]]\nmass = 1\nradius = \"1/20\"\n\
         [[ball]]\nspecies = 0\nposition = [\"0.49\", \"0.8501\"]\n\
         velocity = [\"-0.99165\", \"2.2077e-4\"]\n\
         [[obstacle]]\nposition = [\"1/2\", \"1/2\"]\nradius = \"3/10\"\n",
    )
    .unwrap();
    let out = output_within(
        noslip()
            .args([
                "simulate",
                scene.to_str().unwrap(),
                "--events",
                "1",
                "--quiet",
                "--out",
            ])
            .arg(dir.join("out")),
        60,
    );
    let (stdout, stderr) = (
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr),
    );
    assert_eq!(out.status.code(), Some(0), "{stdout}{stderr}");
    assert!(stdout.starts_with("1 contacts"), "{stdout}");
    assert!(!stdout.contains("stopped:"), "{stdout}");
    assert!(
        stderr.starts_with("notice: no contact while every moving ball travelled"),
        "{stderr}"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn outputs_that_would_overwrite_the_scene_or_each_other_are_refused() {
    let dir = scratch("clash");
    let scene = dir.join("sinai.toml");
    std::fs::copy(
        concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/sinai.toml"),
        &scene,
    )
    .unwrap();
    let before = std::fs::read(&scene).unwrap();
    let both = dir.join("same.txt");
    std::fs::write(&both, "kept").unwrap();
    let dotted = dir.join(".").join("sinai.toml");
    let cases: Vec<(Vec<&std::ffi::OsStr>, &str)> = vec![
        (vec!["--log".as_ref(), scene.as_os_str()], "--log: "),
        (
            vec!["--boundary-map".as_ref(), dotted.as_os_str()],
            "--boundary-map: ",
        ),
        (
            vec![
                "--log".as_ref(),
                both.as_os_str(),
                "--boundary-map".as_ref(),
                both.as_os_str(),
            ],
            "is also --log; the two need two files",
        ),
    ];
    for (args, want) in cases {
        let out = noslip()
            .arg("simulate")
            .arg(&scene)
            .args(["--quiet", "--events", "5", "--out"])
            .arg(dir.join("out"))
            .args(&args)
            .output()
            .unwrap();
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains(want), "{args:?}: {err}");
        assert!(!dir.join("out").exists(), "{args:?}: nothing is run");
    }
    assert_eq!(std::fs::read(&scene).unwrap(), before, "the scene is kept");
    assert_eq!(std::fs::read_to_string(&both).unwrap(), "kept");
    std::fs::remove_dir_all(&dir).unwrap();
}
