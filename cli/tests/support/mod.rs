//! What the command-line tests share: the `noslip` binary run from the repository root, a run
//! that must succeed, a per-process temporary path and scratch directories removed when a
//! test is done with them. Each test file uses what it needs of it.
#![allow(dead_code)]

use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// The `noslip` binary of this build, run from the repository root (scene paths as shipped).
pub fn noslip() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_noslip"));
    c.current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."));
    c
}

/// Run `command`, require success (the panic shows its stderr) and return its stdout.
pub fn run_ok(command: &mut Command) -> String {
    let out = command.output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

/// Paths in the temporary directory and scratch directories there, removed when a test is
/// done with them (the file the repository's backend tests use).
#[path = "../../../tests/scratch.rs"]
mod scratch;
pub use scratch::{scratch, temp, Scratch};

/// Runs `command` to its end, or kills it and fails after `limit` (a run without bound, a
/// hang, is a failure, not a test that never ends).
pub fn within(command: &mut Command, limit: Duration) -> Output {
    let mut child = command
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let begun = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if begun.elapsed() > limit {
            child.kill().unwrap();
            child.wait().unwrap();
            panic!("{command:?} still running after {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}
