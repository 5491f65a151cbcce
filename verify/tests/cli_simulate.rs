//! `noslip simulate` and `noslip gen` from the outside: exit codes, one-line errors, outputs.

use std::process::Command;

fn noslip() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_noslip"));
    c.current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."));
    c
}

#[test]
fn a_bad_scene_exits_2_with_one_line() {
    let dir = std::env::temp_dir().join(format!("noslip-sim-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
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
    let dir = std::env::temp_dir().join(format!("noslip-sinai-{}", std::process::id()));
    let log = dir.join("events.jsonl");
    std::fs::create_dir_all(&dir).unwrap();
    let out = noslip()
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
        .arg(&log)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(
        stdout.starts_with("300 contacts (0 ball-ball, 0 ball-wall, 300 ball-obstacle)"),
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
    let dir = std::env::temp_dir().join(format!("noslip-never-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
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
