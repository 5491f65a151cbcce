//! How `noslip` writes: stdout that fails or goes away, output sets published whole under
//! faults and kills, progress off a terminal, the golden copy from anywhere, and the exit
//! codes each `--help` promises.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn noslip() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_noslip"));
    c.current_dir(repo());
    c.env_remove("NOSLIP_FAULT");
    c
}

/// A fresh empty directory for one test ([`support::scratch`]).
fn scratch(test: &str) -> crate::support::Scratch {
    crate::support::scratch(&format!("outputs-{test}"))
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// Stderr lines that report an error.
fn errors(out: &Output) -> Vec<String> {
    text(&out.stderr)
        .lines()
        .filter(|l| l.starts_with("error:"))
        .map(String::from)
        .collect()
}

fn assert_no_panic(what: &str, out: &Output) {
    let err = text(&out.stderr);
    assert_ne!(out.status.code(), Some(101), "{what}: {err}");
    assert!(out.status.code().is_some(), "{what}: killed by a signal");
    assert!(!err.contains("panicked"), "{what}: {err}");
}

/// One invocation per subcommand that prints, with the files it writes into `dir`.
fn printing_runs(dir: &Path) -> Vec<(Vec<String>, Vec<PathBuf>)> {
    let d = |name: &str| dir.join(name).to_str().unwrap().to_string();
    let s = |v: &[&str]| v.iter().map(|x| x.to_string()).collect::<Vec<_>>();
    vec![
        (
            [
                s(&["verify", "--dims", "2", "--points", "1", "--out"]),
                vec![d("v")],
            ]
            .concat(),
            vec![dir.join("v/verify.md"), dir.join("v/verify.json")],
        ),
        (
            [
                s(&["report", "--dims", "2", "--samples", "2", "--out"]),
                vec![d("r")],
            ]
            .concat(),
            vec![
                dir.join("r/report.json"),
                dir.join("r/error-vs-time-n2.svg"),
            ],
        ),
        (
            [
                s(&[
                    "simulate",
                    "scenes/sinai.toml",
                    "--events",
                    "50",
                    "--quiet",
                    "--out",
                ]),
                vec![d("s")],
            ]
            .concat(),
            vec![dir.join("s/summary.json"), dir.join("s/trajectories.svg")],
        ),
        (s(&["gen", "--scene", "scenes/gas4d.toml"]), vec![]),
        (s(&["gen", "--scene", "scenes/gas2d.toml", "--ops"]), vec![]),
        (
            s(&["gen", "--scene", "scenes/sinai.toml", "--check", "1"]),
            vec![],
        ),
    ]
}

/// A pipe whose reading end is already closed: the first write meets a broken pipe.
#[cfg(target_os = "linux")]
fn reader_gone() -> Stdio {
    use std::os::fd::{FromRawFd, OwnedFd};
    let mut fds = [0; 2];
    // SAFETY: `pipe` fills the two descriptors; each is owned once below.
    assert_eq!(unsafe { libc::pipe(fds.as_mut_ptr()) }, 0);
    let (read, write) = unsafe { (OwnedFd::from_raw_fd(fds[0]), OwnedFd::from_raw_fd(fds[1])) };
    drop(read);
    Stdio::from(write)
}

#[cfg(target_os = "linux")]
#[test]
fn a_failing_stdout_is_one_line_and_loses_no_file() {
    let dir = scratch("dev-full");
    for (args, files) in printing_runs(&dir) {
        let what = args.join(" ");
        let out = noslip()
            .args(&args)
            .stdout(fs::File::create("/dev/full").unwrap())
            .output()
            .unwrap();
        assert_no_panic(&what, &out);
        assert_eq!(out.status.code(), Some(1), "{what}");
        assert_eq!(
            errors(&out),
            ["error: cannot write to stdout: No space left on device (os error 28)"],
            "{what}"
        );
        for f in files {
            assert!(
                fs::metadata(&f).is_ok_and(|m| m.len() > 0),
                "{what}: {} lost",
                f.display()
            );
        }
    }
    fs::remove_dir_all(dir).unwrap();
}

#[cfg(target_os = "linux")]
#[test]
fn a_reader_that_went_away_ends_output_quietly() {
    let dir = scratch("broken-pipe");
    for (args, files) in printing_runs(&dir) {
        let what = args.join(" ");
        let out = noslip().args(&args).stdout(reader_gone()).output().unwrap();
        assert_no_panic(&what, &out);
        assert_eq!(out.status.code(), Some(0), "{what}: {}", text(&out.stderr));
        assert_eq!(errors(&out), Vec::<String>::new(), "{what}");
        for f in files {
            assert!(f.exists(), "{what}: {} lost", f.display());
        }
    }
    fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_closed_stdout_fails_after_writing_the_files() {
    // `>&-`: the Rust runtime reopens a closed standard descriptor on /dev/null, which would
    // discard the output silently; noslip tells it from `> /dev/null` (issue 26): the files
    // are written, then the first print is one error line and exit 1.
    let dir = scratch("closed");
    for (args, files) in printing_runs(&dir) {
        let what = args.join(" ");
        let out = Command::new("sh")
            .current_dir(repo())
            .env_remove("NOSLIP_FAULT")
            .arg("-c")
            .arg("exec \"$0\" \"$@\" >&-")
            .arg(env!("CARGO_BIN_EXE_noslip"))
            .args(&args)
            .output()
            .unwrap();
        assert_no_panic(&what, &out);
        assert_eq!(out.status.code(), Some(1), "{what}: {}", text(&out.stderr));
        assert_eq!(
            errors(&out),
            ["error: cannot write to stdout: it is closed"],
            "{what}"
        );
        for f in files {
            assert!(f.exists(), "{what}: {} lost", f.display());
        }
    }
    fs::remove_dir_all(dir).unwrap();
}

#[test]
fn runs_off_a_terminal_print_progress_lines() {
    let dir = scratch("progress");
    let out = noslip()
        .args(["report", "--dims", "2", "--samples", "2", "--out"])
        .arg(dir.join("r"))
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", text(&out.stderr));
    let lines: Vec<String> = text(&out.stderr)
        .lines()
        .filter(|l| l.starts_with("report: n = 2 "))
        .map(String::from)
        .collect();
    assert_eq!(lines.len(), 9, "one line per regime: {lines:?}");
    assert!(lines[8].contains("(9 of 9 regimes)"), "{lines:?}");
    let out = noslip()
        .args(["verify", "--dims", "2,3", "--points", "1", "--out"])
        .arg(dir.join("v"))
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", text(&out.stderr));
    let err = text(&out.stderr);
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 2, "one line per dimension: {err}");
    assert!(lines[0].starts_with("verify: n = 2 done"), "{err}");
    assert!(lines[1].starts_with("verify: n = 3 done"), "{err}");
    fs::remove_dir_all(dir).unwrap();
}

/// The `points` a verify output set was made with, read from each of its two files: they
/// must agree (one run's set).
fn verify_set(dir: &Path) -> usize {
    let json: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(dir.join("verify.json")).unwrap()).unwrap();
    let from_json = json["points"].as_u64().unwrap() as usize;
    let md = fs::read_to_string(dir.join("verify.md")).unwrap();
    let from_md: usize = md
        .split(" points per identity")
        .next()
        .and_then(|s| s.rsplit(' ').next())
        .and_then(|s| s.parse().ok())
        .unwrap();
    assert_eq!(
        from_json, from_md,
        "verify.json and verify.md of different runs"
    );
    let mut names: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    assert_eq!(names, [".noslip-output", "verify.json", "verify.md"]);
    from_json
}

fn verify_into(out: &Path, points: usize) -> Command {
    let mut c = noslip();
    c.args([
        "verify",
        "--dims",
        "2",
        "--points",
        &points.to_string(),
        "--out",
    ])
    .arg(out);
    c
}

/// Entries of `parent` other than `keep`.
fn leftovers(parent: &Path, keep: &Path) -> Vec<PathBuf> {
    fs::read_dir(parent)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p != keep)
        .collect()
}

#[test]
fn a_run_aborted_at_any_step_leaves_the_old_set_or_the_new_one() {
    let parent = scratch("abort");
    let out = parent.join("set");
    assert!(verify_into(&out, 1).output().unwrap().status.success());
    assert_eq!(verify_set(&out), 1);
    for (fault, expected) in [("staged", 1), ("switched", 2)] {
        let run = verify_into(&out, 2)
            .env("NOSLIP_FAULT", fault)
            .output()
            .unwrap();
        // The hook aborts the process at that step, as a kill would.
        assert_eq!(run.status.code(), None, "{fault}: aborted by a signal");
        assert_eq!(verify_set(&out), expected, "{fault}");
        assert!(!leftovers(&parent, &out).is_empty(), "{fault}: temporaries");
        // The next run cleans up after the aborted one.
        assert!(verify_into(&out, 1).output().unwrap().status.success());
        assert_eq!(verify_set(&out), 1);
        assert_eq!(leftovers(&parent, &out), Vec::<PathBuf>::new(), "{fault}");
    }
    fs::remove_dir_all(parent).unwrap();
}

#[test]
fn a_full_disk_fails_with_one_line_and_leaves_nothing_partial() {
    let parent = scratch("full");
    let out = parent.join("set");
    assert!(verify_into(&out, 1).output().unwrap().status.success());
    let before = fs::read_to_string(out.join("verify.json")).unwrap();
    for args in [
        vec!["verify", "--dims", "2", "--points", "2"],
        vec!["report", "--dims", "2", "--samples", "2"],
    ] {
        let run = noslip()
            .args(&args)
            .arg("--out")
            .arg(&out)
            .env("NOSLIP_FAULT", "full-disk")
            .output()
            .unwrap();
        assert_no_panic(&args.join(" "), &run);
        assert_eq!(run.status.code(), Some(1), "{args:?}");
        let errors = errors(&run);
        assert_eq!(errors.len(), 1, "{args:?}: {errors:?}");
        assert!(
            errors[0].contains("No space left on device"),
            "{args:?}: {errors:?}"
        );
        assert_eq!(fs::read_to_string(out.join("verify.json")).unwrap(), before);
        assert_eq!(leftovers(&parent, &out), Vec::<PathBuf>::new(), "{args:?}");
    }
    fs::remove_dir_all(parent).unwrap();
}

#[cfg(unix)]
#[test]
fn kill_9_at_random_moments_never_mixes_two_runs() {
    let parent = scratch("kill");
    let out = parent.join("set");
    assert!(verify_into(&out, 1).output().unwrap().status.success());
    // A fixed pseudo-random sequence of delays over a run's whole length (~0.3-1 s here).
    let mut state = 0x2545_f491_4f6c_dd1du64;
    for round in 0..12 {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        let delay = std::time::Duration::from_millis(state % 900);
        let mut child = verify_into(&out, 1 + round % 2)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(delay);
        let _ = child.kill(); // SIGKILL
        child.wait().unwrap();
        let points = verify_set(&out);
        assert!(points == 1 || points == 2, "round {round}");
    }
    assert!(verify_into(&out, 1).output().unwrap().status.success());
    assert_eq!(verify_set(&out), 1);
    assert_eq!(leftovers(&parent, &out), Vec::<PathBuf>::new());
    fs::remove_dir_all(parent).unwrap();
}

#[test]
fn an_output_directory_noslip_did_not_make_is_refused() {
    let parent = scratch("not-ours");
    fs::write(parent.join("notes.txt"), "keep me").unwrap();
    let run = verify_into(&parent, 1).output().unwrap();
    assert_eq!(run.status.code(), Some(2));
    let errors = errors(&run);
    assert_eq!(errors.len(), 1, "{errors:?}");
    assert!(
        errors[0].starts_with("error: --out: ") && errors[0].contains("refusing to replace"),
        "{errors:?}"
    );
    assert_eq!(
        fs::read_to_string(parent.join("notes.txt")).unwrap(),
        "keep me"
    );
    assert_eq!(fs::read_dir(&parent).unwrap().count(), 1);
    fs::remove_dir_all(parent).unwrap();
}

#[test]
fn check_golden_compares_the_dimensions_run_from_any_directory() {
    let dir = scratch("golden");
    // From outside the repository, one dimension of the five the golden copy holds.
    let run = Command::new(env!("CARGO_BIN_EXE_noslip"))
        .current_dir(&dir)
        .args(["verify", "--dims", "2", "--check-golden", "--out", "v"])
        .output()
        .unwrap();
    let stdout = text(&run.stdout);
    assert_eq!(run.status.code(), Some(0), "{stdout}{}", text(&run.stderr));
    assert!(stdout.contains(": unchanged for n = [2]"), "{stdout}");
    // A golden copy with one result changed: exit 1 and a unified diff of that line.
    let shipped = fs::read_to_string(repo().join("docs/reports/verify.json")).unwrap();
    let altered = shipped.replacen("\"passed\": true", "\"passed\": false", 1);
    fs::write(dir.join("altered.json"), altered).unwrap();
    let run = Command::new(env!("CARGO_BIN_EXE_noslip"))
        .current_dir(&dir)
        .args([
            "verify",
            "--dims",
            "2",
            "--check-golden",
            "--golden",
            "altered.json",
            "--out",
            "v",
        ])
        .output()
        .unwrap();
    let stdout = text(&run.stdout);
    assert_eq!(run.status.code(), Some(1), "{stdout}");
    let diff = &stdout[stdout.find("--- golden copy").expect("a unified diff")..];
    let changes: Vec<&str> = diff
        .lines()
        .skip(2)
        .filter(|l| l.starts_with(['-', '+']))
        .collect();
    assert_eq!(
        changes,
        ["-      \"passed\": false,", "+      \"passed\": true,"],
        "{diff}"
    );
    assert!(diff.lines().nth(2).unwrap().starts_with("@@ -"), "{diff}");
    fs::remove_dir_all(dir).unwrap();
}

/// The exit-code lines of a subcommand's `--help`.
fn exit_lines(sub: &str) -> Vec<String> {
    let out = noslip().args([sub, "--help"]).output().unwrap();
    assert!(out.status.success());
    let help = text(&out.stdout);
    let section = &help[help.find("Exit codes:").expect("an exit-code section")..];
    section
        .lines()
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .map(|l| l.trim().to_string())
        .collect()
}

#[cfg(target_os = "linux")]
#[test]
fn each_help_lists_the_exit_codes_its_subcommand_returns() {
    let dir = scratch("codes");
    let full = || Stdio::from(fs::File::create("/dev/full").unwrap());
    let d = |n: &str| dir.join(n).to_str().unwrap().to_string();
    let shipped = fs::read_to_string(repo().join("docs/reports/verify.json")).unwrap();
    fs::write(
        dir.join("altered.json"),
        shipped.replacen("\"passed\": true", "\"passed\": false", 1),
    )
    .unwrap();
    let bad_scene = dir.join("bad.toml");
    fs::write(
        &bad_scene, "dim = 9
",
    )
    .unwrap();
    let bad = bad_scene.to_str().unwrap().to_string();
    let golden = d("altered.json");
    // (subcommand, invocation, stdout to /dev/full, the outcome's help line) for each outcome
    // that a cheap invocation produces; the help lists exactly the expected outcomes.
    let (v, r, sim) = (d("v"), d("r"), d("s"));
    let runs: Vec<(&str, Vec<&str>, bool, &str)> = vec![
        (
            "verify",
            vec!["--dims", "2", "--points", "1", "--out", &v],
            false,
            "0  success",
        ),
        (
            "verify",
            vec![
                "--dims",
                "2",
                "--check-golden",
                "--golden",
                &golden,
                "--out",
                &v,
            ],
            false,
            "1  a check failed",
        ),
        (
            "verify",
            vec!["--dims", "2", "--points", "1", "--out", &v],
            true,
            "1  an output",
        ),
        ("verify", vec!["--dims", "9"], false, "2  bad input"),
        (
            "report",
            vec!["--dims", "2", "--samples", "1", "--out", &r],
            true,
            "1  an output",
        ),
        ("report", vec!["--samples", "0"], false, "2  bad input"),
        (
            "simulate",
            vec![
                "scenes/sinai.toml",
                "--events",
                "5",
                "--quiet",
                "--out",
                &sim,
            ],
            false,
            "0  success",
        ),
        (
            "simulate",
            vec![
                "scenes/sinai.toml",
                "--events",
                "5",
                "--quiet",
                "--out",
                &sim,
            ],
            true,
            "1  an output",
        ),
        ("simulate", vec![&bad], false, "2  bad input"),
        (
            "gen",
            vec!["--scene", "scenes/sinai.toml", "--ops"],
            false,
            "0  success",
        ),
        (
            "gen",
            vec!["--scene", "scenes/sinai.toml"],
            true,
            "1  an output",
        ),
        ("gen", vec!["--scene", &bad], false, "2  bad input"),
        ("collide", vec!["no-such-case.json"], false, "2  bad input"),
    ];
    for (sub, args, to_full, line) in &runs {
        let mut c = noslip();
        c.arg(sub).args(args);
        if *to_full {
            c.stdout(full());
        }
        let out = c.output().unwrap();
        let code: u8 = line[..1].parse().unwrap();
        assert_eq!(
            out.status.code(),
            Some(code.into()),
            "{sub} {args:?}: {}",
            text(&out.stderr)
        );
        let listed = exit_lines(sub);
        assert!(
            listed.iter().any(|l| l.starts_with(line)),
            "{sub} returned {code} ({line}) but its help lists {listed:?}"
        );
    }
    let all = [
        "0  success",
        "1  a check failed",
        "1  an output",
        "2  bad input",
    ];
    for (sub, expected) in [
        ("verify", &all[..]),
        ("report", &all[..]),
        ("gen", &all[..]),
        (
            "simulate",
            &["0  success", "1  an output", "2  bad input"][..],
        ),
        (
            "collide",
            &["0  success", "1  an output", "2  bad input"][..],
        ),
    ] {
        let listed = exit_lines(sub);
        assert_eq!(listed.len(), expected.len(), "{sub}: {listed:?}");
        for (l, e) in listed.iter().zip(expected) {
            assert!(l.starts_with(e), "{sub}: {listed:?}");
        }
        // The scene commands read TOML: no JSON in their exit codes.
        if sub == "simulate" || sub == "gen" {
            assert!(
                !listed.iter().any(|l| l.contains("JSON")),
                "{sub}: {listed:?}"
            );
        }
    }
    fs::remove_dir_all(dir).unwrap();
}
