//! The JSON case's Walton contact (`"contact": {"e", "mu", "beta0"}`, docs/derivation.md
//! §15.1) end to end through `collide_json`, the function `noslip collide` runs: a ball
//! falling onto a wall, whose outcome is derived by hand below, in exact arithmetic and in
//! floats; and the bad parameters, refused naming the field.

use noslip_case::{collide_json, Mode};
use serde_json::{json, Value};

/// Body 1 an immovable wall below (`nu = (0, 1, 0)` points up to body 2); body 2 a uniform
/// ball (`m = 1`, `R = 1`, `lambda = 1/5`, so `g = 2/5` and `b/a = 1 + 1/g = 7/2`) with no
/// spin falling at `u = (3, -4, 0)`: `dn = -4`, slip `t = (3, 0, 0)`.
fn falling(contact: Value) -> Value {
    let zero = json!([["0", "0", "0"], ["0", "0", "0"], ["0", "0", "0"]]);
    json!({
        "dim": 3,
        "normal": ["0", "1", "0"],
        "bodies": [
            {"mass": "inf", "radius": "1", "gamma2": "2/5",
             "angular_velocity": zero, "velocity": ["0", "0", "0"]},
            {"mass": "1", "radius": "1", "lambda": "1/5",
             "angular_velocity": zero, "velocity": ["3", "-4", "0"]}
        ],
        "contact": contact
    })
}

fn run(case: &Value, mode: Mode) -> Result<Value, String> {
    collide_json(&case.to_string(), mode)
        .map(|out| serde_json::from_str(&out).unwrap())
        .map_err(|e| e.to_string())
}

fn velocity(out: &Value) -> Value {
    out["bodies"][1]["velocity"].clone()
}

/// `e = 1/2`, `beta0 = 1/3`. Sticking would take the tangential impulse
/// `(1 + beta0) |t| / b = (4/3) 3 / (7/2) = 8/7`; the normal one is `(1 + e) |dn| = 6`.
/// With `mu = 1/10` the cone allows `6/10 < 8/7`: the ball slides, and `u_x` drops by exactly
/// `6/10` (`u+ = (12/5, 2, 0)`). With `mu = 1` it sticks: the rough law at `beta0`, whose
/// output the case's rough form gives.
#[test]
fn walton_slides_at_the_coulomb_bound_and_sticks_as_the_rough_law() {
    let sliding = falling(json!({"e": "1/2", "mu": "1/10", "beta0": "1/3"}));
    let out = run(&sliding, Mode::Exact).unwrap();
    assert_eq!(velocity(&out), json!(["12/5", "2", "0"]));
    let floats = run(&sliding, Mode::Float).unwrap();
    let u: Vec<f64> = floats["bodies"][1]["velocity"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    // A few roundings of numbers of order 1 (the root included): 1e-15 is some ulps.
    for (x, want) in u.iter().zip([2.4, 2.0, 0.0]) {
        assert!((x - want).abs() < 1e-15, "{u:?}");
    }
    let sticking = run(
        &falling(json!({"e": "1/2", "mu": "1", "beta0": "1/3"})),
        Mode::Exact,
    );
    let rough = run(&falling(json!({"e": "1/2", "beta": "1/3"})), Mode::Exact);
    assert_eq!(sticking.unwrap(), rough.unwrap());
}

#[test]
fn bad_walton_parameters_are_refused_naming_the_field() {
    for (contact, field) in [
        (json!({"e": "3/2", "mu": "1", "beta0": "0"}), "contact.e"),
        (
            json!({"e": "1/2", "mu": "-1/10", "beta0": "0"}),
            "contact.mu",
        ),
        (
            json!({"e": "1/2", "mu": "1", "beta0": "2"}),
            "contact.beta0",
        ),
        (json!({"e": "1/2", "mu": "1"}), "contact.beta0"),
        (json!({"e": "1/2", "beta0": "0"}), "contact.mu"),
        (
            json!({"e": "1/2", "mu": "1", "beta0": "0", "beta": "0"}),
            "contact.beta",
        ),
    ] {
        for mode in [Mode::Exact, Mode::Float] {
            let err = run(&falling(contact.clone()), mode).unwrap_err();
            assert!(err.contains(field), "{contact}: {err}");
        }
    }
    // NaN is no JSON number; in floats mode a string "nan" is refused as a number.
    let err = run(
        &falling(json!({"e": "1/2", "mu": "nan", "beta0": "0"})),
        Mode::Float,
    )
    .unwrap_err();
    assert!(err.contains("contact.mu"), "{err}");
}
