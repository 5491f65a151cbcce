//! `noslip collide` with a contact law (`"contact"`, docs/derivation.md §15), end to end: the
//! built binary on JSON cases. Expected outputs are derived by hand in the comments.

use serde_json::{json, Value};
use std::io::Write;
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
    let _ = child.stdin.take().unwrap().write_all(stdin.as_bytes());
    let out = child.wait_with_output().expect("wait for noslip");
    (
        out.status.code().expect("noslip exited"),
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    )
}

fn collide(args: &[&str], input: &Value) -> Value {
    let (code, out, err) = noslip(args, &input.to_string());
    assert_eq!(code, 0, "stderr: {err}");
    serde_json::from_str(&out).expect("the output is JSON")
}

/// The README's example (body 1: m = 2, R = 1, lambda = 1/5; body 2 immovable at rest;
/// nu = (0, 3/5, 4/5); body 1 approaching with u_1 = (1, 0, 1/2)), with `contact` if given.
fn example(contact: Option<Value>) -> Value {
    let mut case = json!({
        "dim": 3,
        "normal": ["0", "3/5", "4/5"],
        "bodies": [
            {"mass": "2", "radius": "1", "lambda": "1/5",
             "angular_velocity": [["0","1","-2"],["-1","0","3"],["2","-3","0"]],
             "velocity": ["1","0","1/2"]},
            {"mass": "inf", "radius": "3/2", "gamma2": "2/5",
             "angular_velocity": [["0","0","0"],["0","0","0"],["0","0","0"]],
             "velocity": ["0","0","0"]}
        ]
    });
    if let Some(c) = contact {
        case["contact"] = c;
    }
    case
}

#[test]
fn no_slip_explicit_and_one_one_give_the_default_output() {
    let exact = &["collide", "--exact"][..];
    let default = collide(exact, &example(None));
    assert_eq!(collide(exact, &example(Some(json!("no-slip")))), default);
    let one_one = json!({"e": "1", "beta": "1"});
    assert_eq!(collide(exact, &example(Some(one_one.clone()))), default);
    // In floats too, bit for bit (the rough kernel at (1, 1) is the no-slip kernel's
    // operations times exact ones).
    let float = &["collide"][..];
    assert_eq!(
        collide(float, &example(Some(one_one))),
        collide(float, &example(None))
    );
}

/// Derivation §15 on the example: w_1 = 1/2, w_2 = 0, k_1 = w_1 / g_1 = 5/4, so the inverse
/// effective masses are a = 1/2 and b = 7/4. dn = -2/5, t = (0, -54/25, 81/50)
/// (tests/cli_collide.rs derives both). With e = 9/10, beta = 1/2: h_n = 19/20, h_t = 3/4,
///
/// - P = h_n dn / a nu + h_t t / b = -(19/25) nu + (3/7) t
///   = (0, -57/125 - 162/175, -76/125 + 243/350) = (0, -1209/875, 151/1750);
/// - u_1+ = u_1 + 2 w_1 P = u_1 + P = (1, -1209/875, 513/875);
/// - U_1+ = U_1 + (2 k_1 / R_1) nu ^ P_t, P_t = (3/7) t: (nu ^ P_t)_12 = P_1 nu_2 - nu_1 P_2
///   = -648/875 - 729/1750 = -81/70, times 5/2 is -81/28, so U_1+ (1, 2) = 3 - 81/28 = 3/28.
///
/// Checks: dn+ = -u_1+ . nu = -(-3627 + 2052)/4375 = 9/25 = -e dn.
#[test]
fn the_rough_law_on_the_example_by_hand() {
    let law = json!({"e": "9/10", "beta": "1/2"});
    let out = collide(&["collide", "--exact"], &example(Some(law)));
    assert_eq!(
        out["bodies"][0],
        json!({"angular_velocity": [["0","1","-2"],["-1","0","3/28"],["2","-3/28","0"]],
               "velocity": ["1","-1209/875","513/875"]})
    );
    // Body 2 is immovable: returned unchanged.
    assert_eq!(
        out["bodies"][1],
        json!({"angular_velocity": [["0","0","0"],["0","0","0"],["0","0","0"]],
               "velocity": ["0","0","0"]})
    );
}

/// Smooth: (e, beta) = (1, -1). Spins are kept; u_1+ = u_1 + 2 w_1 dn / (w_1 + w_2) nu =
/// u_1 + 2 dn nu = (1, 0, 1/2) - (4/5)(0, 3/5, 4/5) = (1, -12/25, -7/50).
#[test]
fn smooth_keeps_the_spins_and_reflects_the_normal_velocity() {
    let exact = &["collide", "--exact"][..];
    let out = collide(exact, &example(Some(json!("smooth"))));
    assert_eq!(
        out["bodies"][0],
        json!({"angular_velocity": [["0","1","-2"],["-1","0","3"],["2","-3","0"]],
               "velocity": ["1","-12/25","-7/50"]})
    );
    let object = json!({"e": "1", "beta": "-1"});
    assert_eq!(collide(exact, &example(Some(object))), out);
}

/// Bad laws: exit 2 and one line naming the field.
#[test]
fn bad_laws_are_refused_naming_the_field() {
    #[rustfmt::skip]
    let cases: Vec<(&[&str], Value, &str, &str)> = vec![
        (&["collide", "--exact"], json!({"e": "3/2", "beta": "0"}), "contact.e", "must be in [0, 1], got 3/2"),
        (&["collide"], json!({"e": -0.1, "beta": 0}), "contact.e", "must be in [0, 1], got -0.1"),
        (&["collide", "--exact"], json!({"e": "1/2", "beta": "-2"}), "contact.beta", "must be in [-1, 1], got -2"),
        (&["collide"], json!({"e": 0.5, "beta": 1.0000001}), "contact.beta", "must be in [-1, 1]"),
        (&["collide"], json!({"e": "NaN", "beta": 0}), "contact.e", "not a finite number"),
        (&["collide", "--exact"], json!({"e": "1/2"}), "contact.beta", "missing"),
        (&["collide", "--exact"], json!({"e": "1/2", "beta": "0", "mu": "1"}), "contact.mu", "unknown key"),
        (&["collide", "--exact"], json!({"e": "1/2", "mu": "-1", "beta0": "0"}), "contact.mu", "must be finite and >= 0, got -1"),
        (&["collide"], json!({"e": 0.5, "mu": 0.1, "beta0": 1.5}), "contact.beta0", "must be in [-1, 1], got 1.5"),
        (&["collide"], json!({"e": 0.5, "mu": "NaN", "beta0": 0}), "contact.mu", "not a finite number"),
        (&["collide", "--exact"], json!({"e": "1/2", "mu": "1"}), "contact.beta0", "missing"),
        (&["collide", "--exact"], json!("rough"), "contact", "expected \"no-slip\", \"smooth\" or an object"),
        (&["collide", "--exact"], json!(1), "contact", "got a number"),
    ];
    for (args, law, field, what) in cases {
        let input = example(Some(law.clone())).to_string();
        let (code, out, err) = noslip(args, &input);
        assert_eq!(code, 2, "{law}: stdout {out} stderr {err}");
        assert!(out.is_empty(), "{law}: stdout {out}");
        assert_eq!(err.lines().count(), 1, "{law}: {err}");
        let head = format!("error: case 0: {field}: ");
        assert!(
            err.starts_with(&head),
            "{law}: {err:?} does not start with {head:?}"
        );
        assert!(err.contains(what), "{law}: {err:?} does not say {what:?}");
    }
}

/// The Walton law (docs/derivation.md §15.1) on the example: with `mu = 0` the tangential
/// impulse is zero whenever the contact slips (`beta = -1`), so the output is the rough law's
/// at `(e, -1)`; with `mu` large it sticks, and the output is the rough law's at `beta0`.
#[test]
fn the_walton_law_is_the_rough_law_at_its_beta() {
    let exact = &["collide", "--exact"][..];
    for (mu, beta) in [("0", "-1"), ("1000", "1/3")] {
        let walton = json!({"e": "1/2", "mu": mu, "beta0": "1/3"});
        let rough = json!({"e": "1/2", "beta": beta});
        assert_eq!(
            collide(exact, &example(Some(walton))),
            collide(exact, &example(Some(rough))),
            "mu = {mu}"
        );
    }
}

#[test]
fn a_law_above_dim_6_is_refused() {
    let n = 7;
    let zero_row = vec!["0"; n];
    let body = |mass: &str, v: &str| {
        json!({"mass": mass, "radius": "1",
               "angular_velocity": vec![zero_row.clone(); n],
               "velocity": (0..n).map(|k| if k == 0 { v } else { "0" }).collect::<Vec<_>>()})
    };
    let mut normal = vec!["0"; n];
    normal[0] = "1";
    let case = json!({"dim": n, "normal": normal, "bodies": [body("1", "1"), body("1", "0")],
                      "contact": {"e": "1/2", "beta": "0"}});
    let (code, _, err) = noslip(&["collide", "--exact"], &case.to_string());
    assert_eq!(code, 2, "{err}");
    assert!(err.starts_with("error: case 0: contact: "), "{err}");
}
