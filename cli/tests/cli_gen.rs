//! `noslip gen` at the edges of the float ranges: a species constant whose folded literal
//! would overflow `f32` or `f64` is refused with exit 2 naming the field (never a panic), a
//! tiny radius gives literals the straight-line check accepts, and a bad crate path is bad
//! input.

use std::process::Command;

/// `noslip gen` on a walled 2D scene of one species of two balls (so ball-ball kernels).
fn gen(mass: &str, radius: &str, extra: &[&str]) -> (i32, String, String) {
    let dir = std::env::temp_dir().join(format!("noslip-gen-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join(format!("m{mass}-r{radius}.toml").replace('/', "_"));
    std::fs::write(
        &file,
        format!(
            "dim = 2\n[box]\nsize = [1000, 1000]\nboundary = [\"wall\", \"wall\"]\n\
             [[species]]\nmass = \"{mass}\"\nradius = \"{radius}\"\ncount = 2\n"
        ),
    )
    .unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_noslip"))
        .arg("gen")
        .arg("--scene")
        .arg(&file)
        .args(extra)
        .output()
        .unwrap();
    let _ = std::fs::remove_file(&file);
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    )
}

#[test]
fn constants_beyond_the_float_ranges_are_refused_naming_the_field() {
    for (mass, radius, field, format) in [
        ("1e-39", "1/10", "species[0].mass", "f32"),
        ("1e39", "1/10", "species[0].mass", "f32"),
        ("1e400", "1/10", "species[0].mass", "f64"),
    ] {
        let (code, out, err) = gen(mass, radius, &[]);
        assert_eq!(code, 2, "mass {mass}: {err}");
        assert_eq!(out, "");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(!err.contains("panicked"), "{err}");
        assert!(err.contains(field), "mass {mass}: {err}");
        // The scene's validation may refuse an extreme value first; if it passes, the range
        // rule names the format.
        assert!(
            err.contains(&format!("beyond the {format} range")) || !err.contains("kernel"),
            "{err}"
        );
    }
}

#[test]
fn a_tiny_radius_gives_float_literals_and_exact_kernels() {
    // Radius 1e-7 folds constants near 1e14: once emitted as `100000000000000f64`, an integer
    // literal with a float suffix that the straight-line check refused (a panic).
    let (code, out, err) = gen("1", "1e-7", &[]);
    assert_eq!(code, 0, "{err}");
    assert!(out.starts_with("// @generated"), "{out:.200}");
    assert!(out.contains("T::from_literal("), "{out:.200}");
    let (code, out, err) = gen("1", "1e-7", &["--check", "2"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.lines().all(|l| l.starts_with("ok  ")), "{out}");
}

#[test]
fn a_bad_crate_path_is_bad_input() {
    let (code, _, err) = gen("1", "1/10", &["--crate-path", "not a path"]);
    assert_eq!(code, 2, "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("crate path: \"not a path\" is not a Rust path"),
        "{err}"
    );
}
