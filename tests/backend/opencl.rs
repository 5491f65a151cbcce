//! The OpenCL side of the faithfulness tests (`opencl_backend.rs`, `scene_backends.rs`): the
//! skip rule, clang's OpenCL front end, and the host `tests/c/cl_host.c` that builds a source
//! with the OpenCL implementation (PoCL on the CPU in CI) and runs its batch kernels.

use super::{c_source, cc};
use std::path::{Path, PathBuf};
use std::process::Command;

/// Why OpenCL cannot be tested here (no clang, no headers or libOpenCL, no suitable device).
pub struct Unavailable(pub String);

/// Skip (say why on stderr) or, when `NOSLIP_REQUIRE_OPENCL` is set, fail.
pub fn skip(test: &str, why: &Unavailable) {
    if std::env::var_os("NOSLIP_REQUIRE_OPENCL").is_some() {
        panic!(
            "OpenCL required (NOSLIP_REQUIRE_OPENCL is set) but unavailable: {}",
            why.0
        );
    }
    eprintln!(
        "{test} SKIPPED: {} (set NOSLIP_REQUIRE_OPENCL=1 to fail instead)",
        why.0
    );
}

/// clang's OpenCL front end on `source`: OpenCL C 1.2 without warnings (panics otherwise).
pub fn clang_check(source: &Path) -> Result<(), Unavailable> {
    let out = Command::new("clang")
        .args([
            "-x",
            "cl",
            "-cl-std=CL1.2",
            "-Xclang",
            "-finclude-default-header",
        ])
        .args(["-fsyntax-only", "-Werror"])
        .arg(source)
        .output()
        .map_err(|e| Unavailable(format!("no clang to compile OpenCL C ({e})")))?;
    assert!(
        out.status.success(),
        "clang -x cl refused the emitted OpenCL C {}:\n{}",
        source.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    Ok(())
}

/// Build the host into `dir`.
pub fn build_host(dir: &Path) -> Result<PathBuf, Unavailable> {
    let host = dir.join("cl_host");
    let built = Command::new(cc())
        .args(["-std=c99", "-O2", "-Wall", "-Wextra", "-Werror"])
        .arg(c_source("cl_host.c"))
        .arg("-o")
        .arg(&host)
        .arg("-lOpenCL")
        .output()
        .unwrap();
    if !built.status.success() {
        return Err(Unavailable(format!(
            "the OpenCL host does not build (headers or libOpenCL missing):\n{}",
            String::from_utf8_lossy(&built.stderr)
        )));
    }
    Ok(host)
}

/// [`clang_check`] of `source`, then [`build_host`] into `dir`; `None`, after [`skip`], when
/// either is unavailable.
pub fn host_for(test: &str, source: &Path, dir: &Path) -> Option<PathBuf> {
    match clang_check(source).and_then(|()| build_host(dir)) {
        Ok(host) => Some(host),
        Err(why) => {
            skip(test, &why);
            None
        }
    }
}

/// Run the host on `source` and the case files of `dir` (the generic kernels, or those of
/// `list`: the usage in `cl_host.c`); print its platform line. Panics when it fails.
pub fn run_host(
    host: &Path,
    source: &Path,
    dir: &Path,
    list: Option<&Path>,
) -> Result<(), Unavailable> {
    let out = Command::new(host)
        .arg(source)
        .arg(dir)
        .args(list)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    match out.status.code() {
        Some(0) => {
            eprintln!("{}", stderr.trim());
            Ok(())
        }
        Some(3) => Err(Unavailable(stderr.trim().to_string())),
        _ => panic!("the OpenCL host failed ({}):\n{stderr}", out.status),
    }
}
