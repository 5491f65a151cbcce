//! `noslip collide`, end to end: the built binary on JSON cases.
//!
//! The expected outputs are derived by hand from the closed form of docs/derivation.md (derivations in
//! the comments), not copied from the program.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::Signed;
use serde_json::{json, Value};
use std::io::Write;
use std::path::Path;
use std::process::{Command, Stdio};

/// `(exit code, stdout, stderr)` of `noslip <args>` with `stdin` as input.
fn noslip(args: &[&str], stdin: &str) -> (i32, String, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_noslip"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run noslip");
    // The command may exit before reading all of stdin (a usage error): ignore EPIPE.
    let _ = child.stdin.take().unwrap().write_all(stdin.as_bytes());
    let out = child.wait_with_output().expect("wait for noslip");
    (
        out.status
            .code()
            .expect("noslip exited, not killed by a signal"),
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    )
}

/// Collide `input` successfully; the output parsed.
fn collide(args: &[&str], input: &str) -> Value {
    let (code, out, err) = noslip(args, input);
    assert_eq!(code, 0, "stderr: {err}");
    assert!(err.is_empty(), "stderr: {err}");
    assert!(
        out.ends_with('\n') && out.trim_end().lines().count() == 1,
        "{out}"
    );
    serde_json::from_str(&out).expect("the output is JSON")
}

/// Collide `input` and expect the one-line error naming `case`, `field` and `what`.
fn reject(args: &[&str], input: &str, case: usize, field: &str, what: &str) {
    let (code, out, err) = noslip(args, input);
    assert_eq!(code, 2, "input {input}\nstdout {out}\nstderr {err}");
    assert!(out.is_empty(), "stdout: {out}");
    assert!(
        err.ends_with('\n') && err.lines().count() == 1,
        "not one line: {err:?}"
    );
    let line = err.trim_end();
    let head = if field.is_empty() {
        format!("error: case {case}: ")
    } else {
        format!("error: case {case}: {field}: ")
    };
    assert!(
        line.starts_with(&head),
        "{line:?} does not start with {head:?}"
    );
    assert!(line.contains(what), "{line:?} does not say {what:?}");
}

/// The example of the specification, with body 1 moving towards body 2:
/// `velocity` `(1, 0, 1/2)`. (The specification writes `(1, 0, -1/2)`, for which
/// `(u_2 - u_1) . nu = +2/5`: separating, see `the_specifications_example_is_separating`.)
fn example(u1z: &str) -> Value {
    json!({
        "dim": 3,
        "normal": ["0", "3/5", "4/5"],
        "bodies": [
            {"mass": "2", "radius": "1", "lambda": "1/5",
             "angular_velocity": [["0","1","-2"],["-1","0","3"],["2","-3","0"]],
             "velocity": ["1","0",u1z]},
            {"mass": "inf", "radius": "3/2", "gamma2": "2/5",
             "angular_velocity": [["0","0","0"],["0","0","0"],["0","0","0"]],
             "velocity": ["0","0","0"]}
        ]
    })
}

/// The post-collision state of `example("1/2")`, by hand from the closed form (docs/derivation.md §8).
///
/// Body 1: m = 2, R = 1, lambda = 1/5, so gamma^2 = 2 lambda / R^2 = 2/5, w_1 = 1/2,
/// k_1 = w_1 / gamma^2 = 5/4. Body 2 is immovable: w_2 = k_2 = 0, U_2 = 0, u_2 = 0.
/// nu = (0, 3/5, 4/5).
///
/// - c = R_1 U_1 nu + R_2 U_2 nu = U_1 nu = (3/5 - 8/5, 12/5, -9/5) = (-1, 12/5, -9/5)
/// - du = u_2 - u_1 = (-1, 0, -1/2); dn = du . nu = -2/5 (approaching)
/// - t = du - dn nu - c = (-1, 0, -1/2) + (0, 6/25, 8/25) - (-1, 12/5, -9/5)
///   = (0, -54/25, 81/50)   (t . nu = -162/125 + 162/125 = 0)
/// - P = dn/(w_1 + w_2) nu + t/(w_1 + w_2 + k_1 + k_2) = (-4/5) nu + (4/7) t
///   = (0, -12/25 - 216/175, -16/25 + 162/175) = (0, -12/7, 2/7)
/// - u_1+ = u_1 + 2 w_1 P = u_1 + P = (1, -12/7, 1/2 + 2/7) = (1, -12/7, 11/14)
/// - nu ^ P = P nu^T - nu P^T: only (1,2) = P_1 nu_2 - nu_1 P_2 = -48/35 - 6/35 = -54/35
///   and (2,1) = 54/35 are non-zero; U_1+ = U_1 + (2 k_1 / R_1) nu ^ P = U_1 + (5/2) nu ^ P:
///   (1,2): 3 - 27/7 = -6/7, (2,1): -3 + 27/7 = 6/7.
///
/// Checks: the normal velocity flips (u_1+ . nu = -36/35 + 22/35 = -2/5 = -u_1 . nu); the
/// energy of body 1 `m [lambda Tr(U U^T) + |u|^2]` (Tr(U U^T) = 2 sum_{i<j} U_ij^2) is
/// 2 (28/5 + 5/4) = 2 * 137/20 before and 2 (562/245 + 893/196) = 2 * 6713/980 = 2 * 137/20
/// after; the slip t+ computed from the post state is (0, 54/25, -81/50) = -t.
fn example_after() -> Value {
    json!({"bodies": [
        {"angular_velocity": [["0","1","-2"],["-1","0","-6/7"],["2","6/7","0"]],
         "velocity": ["1","-12/7","11/14"]},
        {"angular_velocity": [["0","0","0"],["0","0","0"],["0","0","0"]],
         "velocity": ["0","0","0"]}
    ]})
}

/// A number of the output as f64 (a JSON number in float mode, a rational string exactly).
fn f64_of(v: &Value) -> f64 {
    match v {
        Value::Number(n) => n.as_str().parse().unwrap(),
        Value::String(s) => {
            let (p, q) = s.split_once('/').unwrap_or((s, "1"));
            p.parse::<f64>().unwrap() / q.parse::<f64>().unwrap()
        }
        other => panic!("not a number: {other}"),
    }
}

fn leaves(v: &Value, out: &mut Vec<f64>) {
    match v {
        Value::Array(xs) => xs.iter().for_each(|x| leaves(x, out)),
        Value::Object(m) => m.values().for_each(|x| leaves(x, out)),
        x => out.push(f64_of(x)),
    }
}

/// The numbers of an exact output, in order.
fn exact_leaves(v: &Value, out: &mut Vec<BigRational>) {
    match v {
        Value::Array(xs) => xs.iter().for_each(|x| exact_leaves(x, out)),
        Value::Object(m) => m.values().for_each(|x| exact_leaves(x, out)),
        x => out.push(rational(x)),
    }
}

#[test]
fn the_example_exactly_from_stdin_and_from_a_file() {
    let input = example("1/2").to_string();
    assert_eq!(collide(&["collide", "--exact"], &input), example_after());
    let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("cli_collide_example.json");
    std::fs::write(&path, &input).unwrap();
    let file = path.to_str().unwrap();
    assert_eq!(collide(&["collide", "--exact", file], ""), example_after());
    assert_eq!(
        collide(&["collide", "--exact", "-"], &input),
        example_after()
    );
}

#[test]
fn json_numbers_are_read_as_the_decimals_they_spell() {
    // 0.6, 0.8 as JSON numbers are exactly 3/5, 4/5 in --exact (arbitrary_precision), and
    // 0.2 exactly 1/5; 2 and 1.5 are integers/decimals as numbers.
    let input = r#"{"dim": 3, "normal": [0, 0.6, 0.8], "bodies": [
        {"mass": 2, "radius": 1, "lambda": 0.2,
         "angular_velocity": [[0, 1, -2], [-1, 0, 3], [2, -3, 0]], "velocity": [1, 0, 0.5]},
        {"mass": "inf", "radius": 1.5, "gamma2": "0.4",
         "angular_velocity": [[0, 0, 0], [0, 0, 0], [0, 0, 0]], "velocity": [0, 0, 0]}]}"#;
    assert_eq!(collide(&["collide", "--exact"], input), example_after());
}

#[test]
fn float_mode_agrees_with_the_exact_result() {
    // Rounding: the inputs 3/5, 4/5, 1/5 are rounded once (relative error <= 2^-53), the
    // rest are exact in binary; the kernel does O(100) operations on quantities of size <= 3
    // whose denominators are w_1 + w_2 = 1/2 and w_1 + w_2 + k_1 + k_2 = 7/4 (no
    // cancellation is amplified). So each output is within a few hundred ulps of 3, i.e.
    // ~1e-13; 1e-12 is a safe bound and still far below any formula error (the outputs
    // differ from the input state by >= 2/7).
    let float = collide(&["collide"], &example("1/2").to_string());
    let (mut got, mut want) = (vec![], vec![]);
    leaves(&float, &mut got);
    leaves(&example_after(), &mut want);
    assert_eq!(got.len(), want.len());
    for (g, w) in got.iter().zip(&want) {
        assert!((g - w).abs() <= 1e-12, "{g} vs {w}");
    }
    // Float output is JSON numbers (Rust's shortest round trip: 1.0, -0.0 kept as such).
    let v = &float["bodies"][0]["velocity"];
    assert!(v[0].is_number(), "{v}");
    assert_eq!(v[0].to_string(), "1.0");
}

#[test]
fn the_specifications_example_is_separating() {
    // u_1 = (1, 0, -1/2), u_2 = 0: (u_2 - u_1) . nu = (1/2)(4/5) = 2/5 > 0.
    reject(
        &["collide", "--exact"],
        &example("-1/2").to_string(),
        0,
        "bodies[*].velocity",
        "separating: (u_2 - u_1) . nu = 2/5 > 0",
    );
}

#[test]
fn the_3d_omega_form_comes_back_as_omega() {
    // U x = omega x x: U = [[0, -w3, w2], [w3, 0, -w1], [-w2, w1, 0]]. U_1 of the example
    // is omega = (-3, -2, -1); U_1+ (U_12 = -6/7) is omega = (6/7, -2, -1).
    let mut case = example("1/2");
    case["bodies"][0]["angular_velocity"] = json!(["-3", "-2", "-1"]);
    case["bodies"][1]["angular_velocity"] = json!([0, 0, 0]);
    let out = collide(&["collide", "--exact"], &case.to_string());
    assert_eq!(
        out["bodies"][0]["angular_velocity"],
        json!(["6/7", "-2", "-1"])
    );
    assert_eq!(out["bodies"][0]["velocity"], json!(["1", "-12/7", "11/14"]));
    assert_eq!(out["bodies"][1]["angular_velocity"], json!(["0", "0", "0"]));
}

/// A disk (body 2: m = 1, R = 1, gamma^2 = 1/4, U = c J with c = 3, u = (1, -2)) falling
/// on an immovable wall (body 1), nu = (0, 1).
///
/// By hand: w_2 = 1, k_2 = w_2 / gamma^2 = 4; c-vector R_2 U_2 nu = 3 J (0,1) = (-3, 0);
/// du = (1, -2), dn = -2; t = du - dn nu - c = (1, 0) + (3, 0) = (4, 0);
/// P = dn/w_2 nu + t/(w_2 + k_2) = (0, -2) + (4/5, 0) = (4/5, -2);
/// u_2+ = u_2 - 2 w_2 P = (1 - 8/5, -2 + 4) = (-3/5, 2);
/// U_2+ = U_2 + (2 k_2 / R_2) nu ^ P, (nu ^ P)_01 = P_0 nu_1 - nu_0 P_1 = 4/5, so
/// U_01 = -3 + 8 (4/5) = 17/5 and c+ = -U_01 = -17/5.
/// The same from the wall matrix of docs/derivation.md §11 with g = 1/2 on (g R c, u.tau, u.nu), tau = (1, 0):
/// x = 3/2, y = 1: x+ = -3/5 x - 4/5 y = -17/10 (c+ = -17/5), y+ = -4/5 x + 3/5 y = -3/5.
/// Energy (lambda = gamma^2 R^2 / 2 = 1/8): c^2/4 + |u|^2 = 9/4 + 5 = 29/4 before,
/// 289/100 + 9/25 + 4 = 29/4 after.
fn disk_on_wall() -> Value {
    json!({"dim": 2, "normal": [0, 1], "bodies": [
        {"mass": "inf", "radius": 1, "angular_velocity": 0, "velocity": [0, 0]},
        {"mass": 1, "radius": 1, "gamma2": "1/4", "angular_velocity": 3, "velocity": [1, -2]}
    ]})
}

#[test]
fn the_2d_scalar_form_comes_back_as_a_scalar() {
    let out = collide(&["collide", "--exact"], &disk_on_wall().to_string());
    assert_eq!(
        out,
        json!({"bodies": [
            {"angular_velocity": "0", "velocity": ["0", "0"]},
            {"angular_velocity": "-17/5", "velocity": ["-3/5", "2"]}
        ]})
    );
    // The same body given as the matrix c J comes back as a matrix.
    let mut case = disk_on_wall();
    case["bodies"][1]["angular_velocity"] = json!([[0, -3], [3, 0]]);
    let out = collide(&["collide", "--exact"], &case.to_string());
    assert_eq!(
        out["bodies"][1]["angular_velocity"],
        json!([["0", "17/5"], ["-17/5", "0"]])
    );
    assert_eq!(out["bodies"][0]["angular_velocity"], json!("0"));
    // Float mode: every number here is exact in binary except 17/5 and 3/5.
    let out = collide(&["collide"], &disk_on_wall().to_string());
    assert_eq!(out["bodies"][1]["velocity"][1].to_string(), "2.0");
    assert!((f64_of(&out["bodies"][1]["angular_velocity"]) + 3.4).abs() < 1e-14);
}

#[test]
fn an_array_of_cases_comes_back_in_order_and_an_empty_one_empty() {
    let input = json!([disk_on_wall(), example("1/2")]).to_string();
    let out = collide(&["collide", "--exact"], &input);
    let list = out.as_array().expect("an array");
    assert_eq!(list.len(), 2);
    assert_eq!(list[0]["bodies"][1]["angular_velocity"], json!("-17/5"));
    assert_eq!(list[1], example_after());
    assert_eq!(collide(&["collide"], "[]"), json!([]));
    // A single case gives a single object.
    assert!(collide(&["collide"], &disk_on_wall().to_string()).is_object());
}

#[test]
fn dims_above_6_run_the_reference_and_agree_with_the_kernels() {
    // The example embedded in R^7 (zeros in the new coordinates) is the same collision:
    // c, t, P and nu ^ P stay in the first three coordinates. gamma2 = 1/4 fits both
    // dims (<= 2/7); body 2 is movable here, so both formulas are exercised.
    let embed = |n: usize| {
        let pad = |v: &[&str]| -> Value {
            (0..n)
                .map(|k| json!(v.get(k).copied().unwrap_or("0")))
                .collect()
        };
        let u1 = [["0", "1", "-2"], ["-1", "0", "3"], ["2", "-3", "0"]];
        let u2 = [["0", "-1", "0"], ["1", "0", "1/3"], ["0", "-1/3", "0"]];
        let matrix = |u: &[[&str; 3]; 3]| -> Value {
            (0..n)
                .map(|r| if r < 3 { pad(&u[r]) } else { pad(&[]) })
                .collect()
        };
        json!({"dim": n, "normal": pad(&["0", "3/5", "4/5"]), "bodies": [
            {"mass": "2", "radius": "1", "gamma2": "1/4",
             "angular_velocity": matrix(&u1), "velocity": pad(&["1", "0", "1/2"])},
            {"mass": "3", "radius": "3/2", "gamma2": "1/4",
             "angular_velocity": matrix(&u2), "velocity": pad(&["0", "-1", "0"])}
        ]})
    };
    let small = collide(&["collide", "--exact"], &embed(3).to_string());
    let big = collide(&["collide", "--exact"], &embed(7).to_string());
    for b in 0..2 {
        let (s, g) = (&small["bodies"][b], &big["bodies"][b]);
        for r in 0..7 {
            for c in 0..7 {
                let want = if r < 3 && c < 3 {
                    s["angular_velocity"][r][c].clone()
                } else {
                    json!("0")
                };
                assert_eq!(g["angular_velocity"][r][c], want, "body {b} U[{r}][{c}]");
            }
            let want = if r < 3 {
                s["velocity"][r].clone()
            } else {
                json!("0")
            };
            assert_eq!(g["velocity"][r], want, "body {b} u[{r}]");
        }
    }
    // Float mode takes the same path.
    let float = collide(&["collide"], &embed(7).to_string());
    assert_eq!(float["bodies"][1]["velocity"][6].to_string(), "0.0");
}

#[test]
fn the_output_fed_back_is_separating() {
    // The post state moves apart ((u_2+ - u_1+) . nu = -(u_2- - u_1-) . nu = 2/5): the
    // collision map is an involution, but the command only collides approaching bodies.
    let mut case = example("1/2");
    let out = collide(&["collide", "--exact"], &case.to_string());
    for b in 0..2 {
        case["bodies"][b]["angular_velocity"] = out["bodies"][b]["angular_velocity"].clone();
        case["bodies"][b]["velocity"] = out["bodies"][b]["velocity"].clone();
    }
    reject(
        &["collide", "--exact"],
        &case.to_string(),
        0,
        "bodies[*].velocity",
        "separating: (u_2 - u_1) . nu = 2/5 > 0",
    );
    // The same in floats.
    let mut case = disk_on_wall();
    let out = collide(&["collide"], &case.to_string());
    for b in 0..2 {
        case["bodies"][b]["angular_velocity"] = out["bodies"][b]["angular_velocity"].clone();
        case["bodies"][b]["velocity"] = out["bodies"][b]["velocity"].clone();
    }
    reject(
        &["collide"],
        &case.to_string(),
        0,
        "bodies[*].velocity",
        "separating",
    );
}

/// The example with one field replaced (`path` of object keys and array indices).
fn with(path: &[&str], value: Value) -> String {
    let mut case = example("1/2");
    let mut at = &mut case;
    for key in &path[..path.len() - 1] {
        at = match key.parse::<usize>() {
            Ok(i) => &mut at[i],
            Err(_) => &mut at[*key],
        };
    }
    let last = path[path.len() - 1];
    match last.parse::<usize>() {
        Ok(i) => at[i] = value,
        Err(_) => at[last] = value,
    }
    case.to_string()
}

fn without(path: &[&str]) -> String {
    let mut case = example("1/2");
    let mut at = &mut case;
    for key in &path[..path.len() - 1] {
        at = match key.parse::<usize>() {
            Ok(i) => &mut at[i],
            Err(_) => &mut at[*key],
        };
    }
    at.as_object_mut().unwrap().remove(path[path.len() - 1]);
    case.to_string()
}

#[test]
fn every_kind_of_bad_input_has_its_message() {
    let exact = &["collide", "--exact"][..];
    let float = &["collide"][..];
    let b0 = |k: &str| format!("bodies[0].{k}");
    let b1 = |k: &str| format!("bodies[1].{k}");
    #[rustfmt::skip]
    let cases: Vec<(&[&str], String, String, &str)> = vec![
        // malformed numbers
        (exact, with(&["bodies", "0", "radius"], json!("1..5")), b0("radius"), "malformed number \"1..5\""),
        (float, with(&["normal", "1"], json!("3/5x")), "normal[1]".into(), "malformed number"),
        (exact, with(&["bodies", "0", "velocity", "2"], json!("1/0")), b0("velocity[2]"), "zero denominator"),
        (exact, with(&["bodies", "0", "velocity", "0"], json!([1])), b0("velocity[0]"), "expected a number"),
        (exact, with(&["bodies", "0", "mass"], json!("1e999999")), b0("mass"), "exponent"),
        (float, with(&["bodies", "0", "mass"], json!("1e999999")), b0("mass"), "out of the range of f64"),
        // NaN and infinities
        (float, with(&["bodies", "0", "velocity", "1"], json!("NaN")), b0("velocity[1]"), "not a finite number"),
        (float, with(&["bodies", "0", "radius"], json!("inf")), b0("radius"), "not a finite number"),
        (exact, with(&["bodies", "1", "mass"], json!("Infinity")), b1("mass"), "write \"inf\""),
        (exact, with(&["bodies", "1", "mass"], json!("-inf")), b1("mass"), "must be positive"),
        // masses, radii, inertia
        (exact, with(&["bodies", "0", "mass"], json!("-2")), b0("mass"), "must be positive (or \"inf\"), got -2"),
        (float, with(&["bodies", "0", "mass"], json!(0)), b0("mass"), "must be positive"),
        (exact, with(&["bodies", "0", "radius"], json!("0")), b0("radius"), "must be positive, got 0"),
        (exact, with(&["bodies", "0", "lambda"], json!("1/2")), b0("lambda"), "must be in [0, R^2/n] = [0, 1/3], got 1/2"),
        (exact, with(&["bodies", "0", "lambda"], json!("-1/5")), b0("lambda"), "must be in [0, R^2/n]"),
        (float, with(&["bodies", "0", "lambda"], json!(0.5)), b0("lambda"), "must be in [0, R^2/n] = [0, 0.3333333333333333], got 0.5"),
        (exact, with(&["bodies", "1", "gamma2"], json!("1")), b1("gamma2"), "must be in [0, 2/n] = [0, 2/3], got 1"),
        (exact, with(&["bodies", "0", "gamma2"], json!("1/5")), b0("gamma2"), "conflicts with lambda"),
        (exact, with(&["bodies", "1", "distribution"], json!("shell")), b1("distribution"), "conflicts with gamma2"),
        (exact, with(&["bodies", "1", "gamma2"], json!({"x": 1})), b1("gamma2"), "expected a number"),
        // shapes and keys
        (exact, with(&["dim"], json!(1)), "dim".into(), "must be at least 2, got 1"),
        (exact, with(&["dim"], json!(0)), "dim".into(), "must be at least 2"),
        (exact, with(&["dim"], json!(1000000)), "dim".into(), "at most 16"),
        (exact, with(&["dim"], json!("3")), "dim".into(), "expected an integer"),
        (exact, with(&["dim"], json!(3.5)), "dim".into(), "expected an integer"),
        (exact, with(&["dim"], json!(4)), "normal".into(), "expected 4 numbers (dim = 4), got 3"),
        (exact, with(&["normal"], json!("0, 3/5, 4/5")), "normal".into(), "expected an array of 3 numbers, got a string"),
        (exact, with(&["bodies", "0", "velocity"], json!(["1", "0"])), b0("velocity"), "expected 3 numbers"),
        (exact, with(&["bodies", "0", "angular_velocity", "1"], json!(["-1", "0"])), b0("angular_velocity[1]"), "expected 3 numbers"),
        (exact, with(&["bodies", "0", "angular_velocity"], json!([["0", "1", "-2"]])), b0("angular_velocity"), "3 x 3 skew matrix"),
        (exact, with(&["bodies", "0", "angular_velocity"], json!("1")), b0("angular_velocity"), "got a string"),
        (exact, with(&["bodies", "0", "angular_velocity"], json!(["1", "2"])), b0("angular_velocity"), "got an array of 2 numbers"),
        (exact, with(&["bodies", "0", "angular_velocity"], json!([])), b0("angular_velocity"), "got an empty array"),
        (exact, with(&["bodies", "0", "distribution"], json!(1)), b0("distribution"), "conflicts with lambda"),
        (exact, with(&["bodies", "1", "gamma2"], json!(null)), b1("gamma2"), "expected a number"),
        (exact, with(&["bodies", "0", "lamda"], json!("1/5")), b0("lamda"), "unknown key"),
        (exact, with(&["Dim"], json!(3)), "Dim".into(), "unknown key"),
        (exact, without(&["bodies", "1", "radius"]), b1("radius"), "missing"),
        (exact, without(&["normal"]), "normal".into(), "missing"),
        (exact, with(&["bodies"], json!([{}])), "bodies".into(), "expected 2 bodies, got 1"),
        (exact, with(&["bodies", "1"], json!([])), "bodies[1]".into(), "expected a body"),
        // skew, unit normal, pairs, separating
        (exact, with(&["bodies", "0", "angular_velocity", "1", "0"], json!("1")), b0("angular_velocity"), "not skew: entries (0,1) and (1,0) are not opposite"),
        (float, with(&["bodies", "0", "angular_velocity", "2", "2"], json!(0.1)), b0("angular_velocity"), "not skew: diagonal entry (2,2)"),
        (exact, with(&["normal", "1"], json!("0.6000001")), "normal".into(), "must be a unit vector (exactly), got |nu|^2 = "),
        (float, with(&["normal"], json!([0, 1, 1])), "normal".into(), "must be a unit vector (| |nu|^2 - 1 | <= 14 eps |nu|^2 = 6.217248937900877e-15, the rounding allowance in 3D), got |nu|^2 = 2.0"),
        (exact, with(&["bodies", "0", "mass"], json!("inf")), "bodies".into(), "both bodies are immovable"),
        (exact, with(&["bodies", "1", "velocity", "2"], json!("1")), "bodies[*].velocity".into(), "separating: (u_2 - u_1) . nu = 2/5 > 0"),
        (float, with(&["bodies", "1", "velocity", "2"], json!("1")), "bodies[*].velocity".into(), "separating: (u_2 - u_1) . nu = 0.4"),
    ];
    for (args, input, field, what) in &cases {
        reject(args, input, 0, field, what);
    }
    // Both point masses: two movable bodies with lambda = 0.
    let mut case = example("1/2");
    case["bodies"][0]["lambda"] = json!(0);
    case["bodies"][1] = json!({"mass": 1, "radius": 1, "lambda": 0,
        "angular_velocity": [[0, 0, 0], [0, 0, 0], [0, 0, 0]], "velocity": [0, 0, 0]});
    reject(
        exact,
        &case.to_string(),
        0,
        "bodies",
        "both bodies are point masses",
    );
    // The error names the case of an array, 0-based.
    let input = format!(
        "[{}, {}]",
        example("1/2"),
        with(&["bodies", "1", "radius"], json!(-1))
    );
    reject(
        exact,
        &input,
        1,
        "bodies[1].radius",
        "must be positive, got -1",
    );
}

#[test]
fn malformed_json_and_unreadable_files() {
    for (input, what) in [
        (
            "",
            "malformed JSON: EOF while parsing a value at line 1 column 0",
        ),
        (
            "{\"dim\": 3,\n  \"normal\": [0, 0.6 0.8]}",
            "malformed JSON: expected `,` or `]` at line 2 column",
        ),
        ("[1, 2", "malformed JSON"),
        (
            "{} {}",
            "malformed JSON: trailing characters at line 1 column 4",
        ),
        ("NaN", "malformed JSON"),
    ] {
        let (code, out, err) = noslip(&["collide"], input);
        assert_eq!(code, 2, "{input}");
        assert!(out.is_empty());
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.starts_with(&format!("error: {what}")), "{err}");
    }
    let (code, _, err) = noslip(&["collide", "/nonexistent/noslip-case.json"], "");
    assert_eq!(code, 2);
    assert_eq!(err.lines().count(), 1);
    assert!(
        err.starts_with("error: cannot read /nonexistent/noslip-case.json: "),
        "{err}"
    );
    let (code, _, err) = noslip(&["collide"], "\"a case\"");
    assert_eq!(code, 2);
    assert_eq!(
        err.trim_end(),
        "error: expected a case (a JSON object) or an array of cases, got a string"
    );
}

#[test]
fn odd_inputs_never_panic() {
    let deep = "[".repeat(100_000);
    let huge_dim = r#"{"dim": 1000000000000000000000, "normal": [1]}"#;
    let long = format!(
        "{{\"dim\": 2, \"normal\": [\"{}\", 0]}}",
        "9".repeat(100_000)
    );
    let odd: Vec<String> = vec![
        "".into(), " ".into(), "[]".into(), "{}".into(), "[{}]".into(), "[[]]".into(),
        "null".into(), "true".into(), "\"\\u0000\"".into(), deep, huge_dim.into(), long,
        r#"{"dim": 2, "normal": [1, 0], "bodies": ["a", "b"]}"#.into(),
        r#"{"dim": 2, "normal": [[1], 0]}"#.into(),
        r#"{"dim": 2e0, "normal": [1, 0]}"#.into(),
        r#"{"dim": -0, "normal": []}"#.into(),
        r#"{"dim": 3, "normal": [1e-400, "1e400", 1]}"#.into(),
        r#"{"dim": 2, "normal": [1, 0], "bodies": [{"mass": "1/3", "radius": "1e-200", "lambda": 0, "angular_velocity": 1e300, "velocity": [1e308, -1e308]}, {"mass": "1e-300", "radius": 1e300, "angular_velocity": "-1e300", "velocity": [-1e308, 1e308]}]}"#.into(),
        r#"{"dim": 2, "normal": [1, 0], "bodies": [{"mass": 1e-308, "radius": 1e-300, "angular_velocity": 1e300, "velocity": [1e308, -1e308]}, {"mass": 1e300, "radius": 1e300, "angular_velocity": "-1e300", "velocity": [-1e308, 1e308]}]}"#.into(),
        "{\"dim\": 2, \"normal\": [1, 0], \"bodies\": [{\"mass\\n\": 1}, {}]}".into(),
    ];
    for args in [&["collide"][..], &["collide", "--exact"][..]] {
        for input in &odd {
            let (code, out, err) = noslip(args, input);
            assert!(!err.contains("panicked"), "{input:.80}: {err}");
            assert!(code == 0 || code == 2, "{input:.80}: exit {code}, {err}");
            if code == 0 {
                assert!(serde_json::from_str::<Value>(&out).is_ok(), "{out}");
            } else {
                assert_eq!(err.lines().count(), 1, "{input:.80}: {err}");
                assert!(err.len() < 1000, "{err}");
            }
        }
    }
}

#[test]
fn help_describes_schema_numbers_modes_and_exit_codes() {
    let (code, top, _) = noslip(&["--help"], "");
    assert_eq!(code, 0);
    assert!(
        top.contains("collide") && top.contains("Exit codes"),
        "{top}"
    );
    let (code, help, _) = noslip(&["collide", "--help"], "");
    assert_eq!(code, 0);
    for needle in [
        "--exact",
        "[FILE]",
        "\"normal\"",
        "lambda",
        "gamma2",
        "distribution",
        "\"inf\"",
        "angular_velocity",
        "U = c J",
        "omega",
        "\"3/5\"",
        "1e-3",
        "round-trip",
        "reference",
        "rounding allowance",
        "8 eps (eps = 2^-52)",
        "unbounded exponent",
        "digits (a decimal's mantissa",
        "given twice",
        "Exit codes",
        "2  bad input",
    ] {
        assert!(help.contains(needle), "collide --help lacks {needle:?}");
    }
    // Usage errors are clap's, also exit code 2.
    let (code, _, _) = noslip(&["collide", "--bogus"], "");
    assert_eq!(code, 2);
}

/// The case of issue 11: a thin shell, R = 5, with lambda = 25/3 computed in f64.
fn thin_shell(inertia: Value) -> String {
    let mut case = json!({"dim": 3, "normal": [0, 0, 1], "bodies": [
        {"mass": 2, "radius": 5, "angular_velocity": [1, 0, 0], "velocity": [0, 1, 1]},
        {"mass": 1, "radius": 1, "angular_velocity": [0, 0, 0], "velocity": [0, 0, 0]}]});
    let (key, value) = inertia.as_object().unwrap().iter().next().unwrap();
    case["bodies"][0][key] = value.clone();
    case.to_string()
}

#[test]
fn a_thin_shell_written_in_floating_point_is_the_shell() {
    // 25/3 in f64 is 8.333333333333334; 2 lambda / R^2 then rounds one ulp above 2/3. Within
    // the rounding allowance it is clamped: the same answer as the shell itself.
    let shell = collide(&["collide"], &thin_shell(json!({"distribution": "shell"})));
    let lambda = collide(&["collide"], &thin_shell(json!({"lambda": 25.0 / 3.0})));
    assert_eq!(lambda, shell);
    assert_eq!(
        collide(
            &["collide"],
            &thin_shell(json!({"gamma2": 0.6666666666666667}))
        ),
        shell
    );
    // In 4D with R = 1 the bound R^2/n = 1/4 has ulps of eps/4: 8 ulps above it is the edge
    // of the allowance (8 eps of 1/4), 9 ulps beyond.
    let up = |k: u64| f64::from_bits(0.25f64.to_bits() + k);
    let four_d = |lambda: f64| {
        json!({"dim": 4, "normal": [0, 0, 0, 1], "bodies": [
            {"mass": 1, "radius": 1, "lambda": lambda,
             "angular_velocity": [[0, 1, 0, 0], [-1, 0, 0, 0], [0, 0, 0, 0], [0, 0, 0, 0]],
             "velocity": [0, 0, 0, 1]},
            {"mass": "inf", "radius": 1,
             "angular_velocity": [[0, 0, 0, 0], [0, 0, 0, 0], [0, 0, 0, 0], [0, 0, 0, 0]],
             "velocity": [0, 0, 0, 0]}]})
        .to_string()
    };
    assert_eq!(
        collide(&["collide"], &four_d(up(8))),
        collide(&["collide"], &four_d(0.25))
    );
    reject(
        &["collide"],
        &four_d(up(9)),
        0,
        "bodies[0].lambda",
        "must be in [0, R^2/n]",
    );
    // Exact arithmetic takes no allowance: the decimal is above 25/3 and refused.
    reject(
        &["collide", "--exact"],
        &thin_shell(json!({"lambda": "8.333333333333334"})),
        0,
        "bodies[0].lambda",
        "must be in [0, R^2/n] = [0, 25/3]",
    );
}

#[test]
fn keys_given_twice_are_refused_naming_the_key() {
    let case = example("1/2").to_string();
    let twice = case.replacen("\"mass\":\"2\"", "\"mass\":\"2\",\"mass\":\"3\"", 1);
    assert_ne!(twice, case);
    for args in [&["collide"][..], &["collide", "--exact"][..]] {
        reject(args, &twice, 0, "bodies[0].mass", "repeated key");
        reject(
            args,
            &format!("[{case}, {twice}]"),
            1,
            "bodies[0].mass",
            "repeated key",
        );
    }
    reject(
        &["collide"],
        &case.replacen("{", "{\"dim\":3,", 1),
        0,
        "dim",
        "repeated key",
    );
}

#[test]
fn numbers_have_at_most_100_digits() {
    // One number of 10^5 digits took 24 s in --exact and longer in f64 (issue 16).
    let long_decimal = format!("1.{}", "0".repeat(100_000));
    let long_ratio = format!("1/{}", "7".repeat(100_000));
    for args in [&["collide"][..], &["collide", "--exact"][..]] {
        for text in [&long_decimal, &long_ratio] {
            let input = with(&["bodies", "0", "mass"], json!(text));
            reject(
                args,
                &input,
                0,
                "bodies[0].mass",
                "digits: at most 100 are accepted",
            );
        }
    }
    let fits = format!("1/{}", "7".repeat(99));
    collide(
        &["collide", "--exact"],
        &with(&["bodies", "0", "mass"], json!(fits)),
    );
}

/// Two disks: body 1 at rest, body 2 hitting it along e_0 with a tangential slip.
fn disks(r1: &str, r2: &str, m: &str, u2: [&str; 2], spin2: &str) -> String {
    json!({"dim": 2, "normal": [1, 0], "bodies": [
        {"mass": m, "radius": r1, "angular_velocity": 0, "velocity": [0, 0]},
        {"mass": m, "radius": r2, "angular_velocity": spin2, "velocity": u2}]})
    .to_string()
}

#[test]
fn extreme_magnitudes_are_computed_or_refused_naming_the_input_at_fault() {
    // Issue 16: R_2 = 8e307 with O(1) everything else. The f64 kernel's R_2 D overflowed
    // and body 2's spin came back unchanged; now it agrees with --exact to rounding.
    let case = disks("1", "8e307", "1/2", ["-2", "1/2"], "1/8");
    let float = collide(&["collide"], &case);
    let exact = collide(&["collide", "--exact"], &case);
    let (mut got, mut want) = (vec![], vec![]);
    leaves(&float, &mut got);
    exact_leaves(&exact, &mut want);
    assert_eq!(got.len(), want.len());
    let eps8 = BigRational::new(1.into(), BigInt::from(1u64 << 49));
    for (g, w) in got.iter().zip(&want) {
        // Each component to 8 eps of itself (no cancellation in this case), exactly.
        let g = BigRational::from_float(*g).unwrap();
        assert!((&g - w).abs() <= &eps8 * w.abs(), "{g} vs {w}");
    }
    assert_ne!(float["bodies"][1]["angular_velocity"], json!(0.125));
    // An answer beyond f64: body 1's spin ~ slip / R_1 = 1e10 / 1e-300. The error names the
    // radius at fault, not the output where the overflow landed.
    reject(
        &["collide"],
        &disks("1e-300", "1", "1", ["-1", "1e10"], "0"),
        0,
        "bodies[0].radius",
        "its angular velocity after contact would overflow f64",
    );
    // --exact computes it.
    collide(
        &["collide", "--exact"],
        &disks("1e-300", "1", "1", ["-1", "1e10"], "0"),
    );
}

/// `noslip collide FILE` run by `sh` with `redirect` applied to its stdout.
#[cfg(target_os = "linux")]
fn with_stdout(redirect: &str) -> (i32, String) {
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join("cli_collide_stdout.json");
    std::fs::write(&path, example("1/2").to_string()).unwrap();
    let out = Command::new("sh")
        .arg("-c")
        .arg(format!("exec \"$0\" collide \"$1\" {redirect}"))
        .arg(env!("CARGO_BIN_EXE_noslip"))
        .arg(&path)
        .output()
        .expect("run sh");
    (
        out.status.code().expect("an exit code"),
        String::from_utf8(out.stderr).unwrap(),
    )
}

#[cfg(target_os = "linux")]
#[test]
fn an_answer_that_cannot_be_written_is_exit_1_with_a_message() {
    // Issue 16: with stdout closed the answer went nowhere and the exit code was 0.
    let (code, err) = with_stdout(">&-");
    assert_eq!(code, 1, "{err}");
    assert_eq!(
        err.trim_end(),
        "error: cannot write the output: stdout is closed"
    );
    let (code, err) = with_stdout("> /dev/full");
    assert_eq!(code, 1, "{err}");
    assert!(
        err.starts_with("error: cannot write the output: No space left on device"),
        "{err}"
    );
    // Discarding the answer on purpose is not an error.
    assert_eq!(with_stdout("> /dev/null"), (0, String::new()));
}

#[test]
fn a_broken_pipe_is_exit_1_not_a_panic() {
    let mut child = Command::new(env!("CARGO_BIN_EXE_noslip"))
        .arg("collide")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run noslip");
    // The reader goes away before the command writes (it is still waiting for its input).
    drop(child.stdout.take());
    let mut stdin = child.stdin.take().unwrap();
    stdin
        .write_all(example("1/2").to_string().as_bytes())
        .unwrap();
    drop(stdin);
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.starts_with("error: cannot write the output: Broken pipe"),
        "{err}"
    );
}

/// An exact rational from the case's text (`"3/5"`, `"2"`).
fn rational(v: &Value) -> BigRational {
    let s = v.as_str().expect("the example writes numbers as strings");
    let (p, q) = s.split_once('/').unwrap_or((s, "1"));
    BigRational::new(p.parse::<BigInt>().unwrap(), q.parse::<BigInt>().unwrap())
}

/// The closed form (docs/derivation.md §8), in exact rationals, for a case in the matrix form: inverse masses
/// `w_i` (0 for "inf"), `k_i = w_i R_i^2 / (2 lambda_i)`,
/// `c = R_1 U_1 nu + R_2 U_2 nu`, `dn = (u_2 - u_1) . nu`, `t = u_2 - u_1 - dn nu - c`,
/// `P = dn/(w_1 + w_2) nu + t/(w_1 + w_2 + k_1 + k_2)`, `u_1+ = u_1 + 2 w_1 P`,
/// `u_2+ = u_2 - 2 w_2 P`, `U_i+ = U_i + (2 k_i / R_i) nu ^ P` with
/// `(nu ^ P)_ij = P_i nu_j - nu_i P_j`. Per body: the matrix `U+` and `u+`.
fn closed_form(case: &Value) -> [(Vec<Vec<BigRational>>, Vec<BigRational>); 2] {
    let n = case["dim"].as_u64().unwrap() as usize;
    let q = |i: i64| BigRational::from_integer(i.into());
    let nu: Vec<BigRational> = (0..n).map(|k| rational(&case["normal"][k])).collect();
    let body = |b: usize| {
        let v = &case["bodies"][b];
        let radius = rational(&v["radius"]);
        let w = match v["mass"].as_str() {
            Some("inf") => q(0),
            _ => q(1) / rational(&v["mass"]),
        };
        let lambda = if v.get("lambda").is_some() {
            rational(&v["lambda"])
        } else {
            rational(&v["gamma2"]) * &radius * &radius / q(2)
        };
        let k = &w * &radius * &radius / (q(2) * lambda);
        let u: Vec<BigRational> = (0..n).map(|i| rational(&v["velocity"][i])).collect();
        let spin: Vec<Vec<BigRational>> = (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| rational(&v["angular_velocity"][i][j]))
                    .collect()
            })
            .collect();
        (w, k, radius, spin, u)
    };
    let [(w1, k1, r1, s1, u1), (w2, k2, r2, s2, u2)] = [body(0), body(1)];
    let times = |m: &Vec<Vec<BigRational>>, x: &[BigRational]| -> Vec<BigRational> {
        (0..n)
            .map(|i| (0..n).map(|j| &m[i][j] * &x[j]).sum())
            .collect()
    };
    let (a, b) = (times(&s1, &nu), times(&s2, &nu));
    let c: Vec<BigRational> = (0..n).map(|i| &r1 * &a[i] + &r2 * &b[i]).collect();
    let dn: BigRational = (0..n).map(|i| (&u2[i] - &u1[i]) * &nu[i]).sum();
    let t: Vec<BigRational> = (0..n)
        .map(|i| &u2[i] - &u1[i] - &dn * &nu[i] - &c[i])
        .collect();
    let p: Vec<BigRational> = (0..n)
        .map(|i| &dn / (&w1 + &w2) * &nu[i] + &t[i] / (&w1 + &w2 + &k1 + &k2))
        .collect();
    let wedge = |i: usize, j: usize| &p[i] * &nu[j] - &nu[i] * &p[j];
    let after = |spin: &Vec<Vec<BigRational>>,
                 u: &[BigRational],
                 w: &BigRational,
                 k: &BigRational,
                 r: &BigRational,
                 sign: i64| {
        let spin = (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| &spin[i][j] + q(2) * k / r * wedge(i, j))
                    .collect()
            })
            .collect();
        let u = (0..n).map(|i| &u[i] + q(2 * sign) * w * &p[i]).collect();
        (spin, u)
    };
    [
        after(&s1, &u1, &w1, &k1, &r1, 1),
        after(&s2, &u2, &w2, &k2, &r2, -1),
    ]
}

#[test]
fn the_readmes_collide_command_runs_as_written() {
    // The command of README's `noslip collide` section, from the repository root.
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let section = readme
        .split("## `noslip collide`")
        .nth(1)
        .expect("the section");
    let line = section
        .lines()
        .find(|l| l.starts_with("cargo run"))
        .expect("the command");
    let command = line.split('#').next().unwrap();
    let args: Vec<&str> = command
        .split_once(" -- ")
        .expect("cargo run ... -- ARGS")
        .1
        .split_whitespace()
        .collect();
    assert_eq!(args[0], "collide", "{line}");
    let out = Command::new(env!("CARGO_BIN_EXE_noslip"))
        .args(&args)
        .current_dir(&root)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{line}: {err}");
    let got: Value = serde_json::from_slice(&out.stdout).unwrap();
    // The file is the README's JSON, and the answer the closed form (docs/derivation.md §8) on it.
    let file = args
        .iter()
        .find(|a| a.ends_with(".json"))
        .expect("a file argument");
    let text = std::fs::read_to_string(root.join(file)).unwrap();
    assert!(
        section.contains(text.trim()),
        "{file} is not the README's case"
    );
    let case: Value = serde_json::from_str(&text).unwrap();
    for (b, (spin, u)) in closed_form(&case).iter().enumerate() {
        let body = &got["bodies"][b];
        for (i, row) in spin.iter().enumerate() {
            for (j, x) in row.iter().enumerate() {
                assert_eq!(
                    rational(&body["angular_velocity"][i][j]),
                    *x,
                    "body {b} U[{i}][{j}]"
                );
            }
        }
        for (i, x) in u.iter().enumerate() {
            assert_eq!(rational(&body["velocity"][i]), *x, "body {b} u[{i}]");
        }
    }
}

/// An input larger than the 16 MiB limit (`/dev/zero` never ends) is refused with exit 2 and
/// one line, after reading one byte past the limit, not read until memory runs out.
#[cfg(target_os = "linux")]
#[test]
fn an_endless_input_is_refused_at_the_size_limit() {
    let (code, out, err) = noslip(&["collide", "/dev/zero"], "");
    assert_eq!(code, 2, "{err}");
    assert!(out.is_empty(), "{out}");
    assert_eq!(
        err.trim(),
        "error: /dev/zero: larger than 16 MiB, the limit of an input (split the cases into \
         several files)"
    );
    let (code, _, err) = noslip(&["simulate", "/dev/zero", "--quiet"], "");
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("/dev/zero: file: larger than 16 MiB, the limit of a scene file"),
        "{err}"
    );
}
