//! What the command-line tests share: the `noslip` binary run from the repository root, a run
//! that must succeed, a per-process temporary path and scratch directories removed when a
//! test is done with them. Each test file uses what it needs of it.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
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

/// A path in the temporary directory, unique to `name` and this process.
pub fn temp(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("noslip-{name}-{}", std::process::id()))
}

/// A fresh empty directory at [`temp`]`(name)`, removed with its contents when the test
/// drops it: at its end, and also when it fails or returns early.
pub fn scratch(name: &str) -> Scratch {
    let dir = temp(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    Scratch(dir)
}

/// [`scratch`]'s directory: a path, removed with its contents on drop.
pub struct Scratch(PathBuf);

impl std::ops::Deref for Scratch {
    type Target = Path;

    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for Scratch {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<std::ffi::OsStr> for Scratch {
    fn as_ref(&self) -> &std::ffi::OsStr {
        self.0.as_os_str()
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        // A test may have removed it already (checking that it can).
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

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
