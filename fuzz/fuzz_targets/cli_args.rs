//! Fuzz target `cli_args`: the command line of `noslip`.
//!
//! The input bytes, split at each `\n`, are the arguments after `noslip` (any bytes, not
//! only UTF-8). They go through the command's own clap parser (`noslip::Cli`) and then
//! through each subcommand's validation, as far as it goes without heavy work:
//! - a parse error or `--help`/`--version`: clap's message is rendered (not printed) and its
//!   exit code must be 2 (usage) or 0 (help, version);
//! - `collide FILE`: the file is read and collided (both modes, as given); stdin (no FILE or
//!   `-`) is not read (the content of inputs is `json_case`'s job);
//! - `simulate`: `--time`/`--events` (`check_limits`), the scene file read and validated, the
//!   `--out` directory prepared (`Staging::new`, dropped unpublished); no run (`scene_toml`
//!   runs scenes);
//! - `gen`: the scene read and validated, and without `--check` the module generated with the
//!   given `--crate-path` (not printed); `--check K` is not run (exact points, seconds);
//!   `gen --lang c|opencl` runs whole (`command::gen::run`: the generic kernels of `--dims`,
//!   the scene's if given, written into `--out`), when its paths are inside the sandbox;
//! - `lyapunov`: its options (`Options`: events, blocks, k, method, contact) and the scene
//!   read and validated, `--out` prepared; `orbits`: the scene read and validated, `--out`
//!   prepared (its starts are parsed in the run; nothing is run: seconds to minutes);
//! - `verify`, `report`: their options (`--points`, `--samples`, `--dims`, `--seed`) and
//!   `--out` prepared as above; the golden copy is not read and nothing is run (minutes).
//!
//! Sandbox: the process works in a fresh temporary directory holding two fixtures
//! (`case.json`, `scene.toml`); a path argument is used only if it is relative and has no
//! `..` (other paths are skipped: the target must not read `/dev/zero` or write outside its
//! directory), and everything but the fixtures is removed after each input.
//!
//! Contract checked: no panic, abort, hang or unbounded memory; every refusal is the exit
//! code the CLI gives (2 for bad input and usage; 1 only for an output that cannot be made).

#![no_main]

use clap::Parser;
use libfuzzer_sys::fuzz_target;
use std::ffi::OsString;
use std::os::unix::ffi::OsStringExt;
use std::path::{Component, Path};
use std::sync::Once;

use noslip::command;
use noslip::exit::{publish_failure, Exit, Failure};
use noslip::json::{collide_json, Mode};
use noslip::publish::Staging;
use noslip::{Cli, Command};
use noslip_scene::Scene;

const FIXTURES: [(&str, &str); 2] = [
    ("case.json", include_str!("../../examples/case.json")),
    (
        "scene.toml",
        include_str!("../../scenes/disk_between_walls.toml"),
    ),
];

static SANDBOX: Once = Once::new();

/// Work in a fresh temporary directory with the fixtures; no fault injection.
fn sandbox() {
    SANDBOX.call_once(|| {
        std::env::remove_var("NOSLIP_FAULT");
        let dir = std::env::temp_dir().join(format!("noslip-fuzz-cli-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("temporary directory");
        for (name, text) in FIXTURES {
            std::fs::write(dir.join(name), text).expect("fixture");
        }
        std::env::set_current_dir(&dir).expect("enter the temporary directory");
    });
}

/// Remove everything the input made (all but the fixtures).
fn clean() {
    for entry in std::fs::read_dir(".").expect("the sandbox").flatten() {
        let name = entry.file_name();
        if FIXTURES.iter().any(|(f, _)| name == *f) {
            continue;
        }
        let path = entry.path();
        let _ = if path.is_dir() && !path.is_symlink() {
            std::fs::remove_dir_all(&path)
        } else {
            std::fs::remove_file(&path)
        };
    }
}

/// A path the sandbox may use: relative, without `..`.
fn inside(p: &Path) -> bool {
    p.components()
        .all(|c| matches!(c, Component::Normal(_) | Component::CurDir))
}

/// A validation step's failure must be bad input (exit 2), or, for an output directory
/// that cannot be made, an output failure (exit 1).
fn refused(f: Failure, output: bool) {
    let ok = f.exit == Exit::BadInput || (output && f.exit == Exit::OutputFailed);
    assert!(ok, "exit {:?} for: {}", f.exit, f.message);
    assert!(!f.message.is_empty());
}

/// `--out` prepared as the subcommand prepares it, then dropped (the drop guard removes the
/// staging directory).
fn stage(out: &Path) {
    if inside(out) {
        if let Err(e) = Staging::new(out) {
            refused(publish_failure(&e), true);
        }
    }
}

/// The scene file, read and validated as `simulate` and `gen` do.
fn scene(path: &Path) -> Option<Scene> {
    if !inside(path) {
        return None;
    }
    Scene::from_file(path)
        .map_err(|e| refused(Failure::bad_input(e.to_string()), false))
        .ok()
}

fn validate(command: Command) {
    match command {
        Command::Collide(a) => {
            let Some(file) = a.file.filter(|f| f.as_os_str() != "-" && inside(f)) else {
                return;
            };
            let mode = if a.exact { Mode::Exact } else { Mode::Float };
            if let Ok(text) = std::fs::read_to_string(&file) {
                let _ = collide_json(&text, mode); // Err: exit 2
            }
        }
        Command::Simulate(a) => {
            if let Err(f) = command::simulate::check_limits(&a) {
                return refused(f, false);
            }
            if scene(&a.file).is_some() {
                stage(a.out.as_deref().unwrap_or(Path::new("out/simulate/scene")));
            }
        }
        Command::Gen(a) if matches!(a.lang, command::gen::Language::Backend(_)) => {
            // `--lang c|opencl` writes its files (milliseconds: the generic kernels' text is
            // generated at build time), into the sandbox only.
            let paths = a.out.iter().chain(&a.scene);
            if paths.into_iter().all(|p| inside(p)) {
                if let Err(f) = command::gen::run(&a) {
                    refused(f, true);
                }
            }
        }
        Command::Gen(a) => {
            if let Some(s) = a.scene.as_deref().and_then(scene) {
                if a.check.is_none() {
                    if let Err(e) = noslip_codegen::specialise::generate(
                        &s.pairs(),
                        &a.crate_path,
                        "noslip_sim",
                    ) {
                        refused(Failure::bad_input(e.to_string()), false);
                    }
                }
            }
        }
        Command::Lyapunov(a) => match command::lyapunov::options(&a) {
            Ok(_) => {
                if scene(&a.file).is_some() {
                    stage(a.out.as_deref().unwrap_or(Path::new("out/lyapunov/scene")));
                }
            }
            Err(f) => refused(f, false),
        },
        Command::Orbits(a) => {
            if scene(&a.file).is_some() {
                stage(a.out.as_deref().unwrap_or(Path::new("out/orbits/scene")));
            }
        }
        Command::Verify(a) => match command::verify::options(&a) {
            Ok(_) => stage(&a.out),
            Err(f) => refused(f, false),
        },
        Command::Report(a) => match command::report::options(&a) {
            Ok(_) => stage(&a.out),
            Err(f) => refused(f, false),
        },
    }
}

fuzz_target!(|data: &[u8]| {
    sandbox();
    let args = std::iter::once(OsString::from("noslip")).chain(
        data.split(|&b| b == b'\n')
            .map(|a| OsString::from_vec(a.to_vec())),
    );
    match Cli::try_parse_from(args) {
        Ok(cli) => validate(cli.command),
        Err(e) => {
            let _ = e.render();
            let code = e.exit_code();
            assert!(
                code == 2 || code == 0,
                "clap exit code {code} for {}",
                e.kind()
            );
        }
    }
    clean();
});
