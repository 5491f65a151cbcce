//! What the command-line tests share: the `noslip` binary run from the repository root, a run
//! that must succeed, and a per-process temporary path. Each test file uses what it needs of it.
#![allow(dead_code)]

use std::path::PathBuf;
use std::process::Command;

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
