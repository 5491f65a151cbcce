//! The case (`case.rs`): its fields' paths, and the scalars below `f64`'s normal range that
//! a case refuses or takes (`tiny.rs`, as `Case::from_json` and `from_floats` apply it).

use super::*;
use crate::error::CaseError;
use collision_core::Exact;
use serde_json::{json, Value};

/// The fields spelled once are the paths `join` spells.
#[test]
fn body_fields_are_the_joined_paths() {
    for (i, path) in BODY_PATHS.iter().enumerate() {
        assert_eq!(*path, format!("bodies[{i}]"));
        for key in BODY_KEYS {
            assert_eq!(body_field(i, key), join(path, key));
        }
    }
}

/// A 2D case: body 1 (`mass`, `radius`, spin `c`, velocity `u`) against a unit ball at
/// rest.
fn case(mass: &str, radius: &str, c: &str, u: [&str; 2]) -> Value {
    json!({"dim": 2, "normal": ["1", "0"], "bodies": [
        {"mass": mass, "radius": radius, "angular_velocity": c, "velocity": u},
        {"mass": "1", "radius": "1", "angular_velocity": "0", "velocity": ["0", "0"]}]})
}

fn refused(v: &Value) -> CaseError {
    Case::<f64>::from_json(v).expect_err("refused in f64")
}

/// Issue 26, item 2: a radius of `4e-324` was read as `4.94e-324` (23% off) and body 1's
/// spin came back 19% off, exit 0. Every body scalar below the normal range is refused,
/// naming it; exact mode takes it as written.
#[test]
fn body_scalars_below_the_normal_range_are_refused_naming_them() {
    for (text, field) in [
        (case("1", "4e-324", "0", ["1", "0"]), "bodies[0].radius"),
        (case("1", "2.3e-319", "0", ["1", "0"]), "bodies[0].radius"),
        (case("1", "1e-400", "0", ["1", "0"]), "bodies[0].radius"),
        (case("3e-310", "1", "0", ["1", "0"]), "bodies[0].mass"),
    ] {
        let e = refused(&text);
        assert_eq!(e.field, field, "{e}");
        assert!(e.message.contains("below the normal range of f64"), "{e}");
        assert!(Case::<Exact>::from_json(&text).is_ok(), "{text}");
    }
    let mut lambda = case("1", "1", "0", ["1", "0"]);
    lambda["bodies"][0]["lambda"] = json!("1e-310");
    assert_eq!(refused(&lambda).field, "bodies[0].lambda");
    let mut gamma2 = case("1", "1", "0", ["1", "0"]);
    gamma2["bodies"][0]["gamma2"] = json!(5e-324);
    assert_eq!(refused(&gamma2).field, "bodies[0].gamma2");
    // The smallest normal, and a zero, are taken (a zero radius is refused later, by the
    // ball's own check, as not positive).
    assert!(Case::<f64>::from_json(&case("1", "2.2250738585072014e-308", "0", ["1", "0"])).is_ok());
    assert!(Case::<f64>::from_json(&case("1", "1", "0", ["0.0e-999", "0"])).is_ok());
}

/// A component below the range is taken when its error, at most 2^-1075, is within
/// eps/2 of the contact's speed scale, and refused naming it when not.
#[test]
fn components_below_the_range_are_measured_against_the_speed_scale() {
    // Against a speed of 1: taken.
    assert!(Case::<f64>::from_json(&case("1", "1", "0", ["1", "1e-310"])).is_ok());
    assert!(Case::<f64>::from_json(&case("1", "1", "1e-320", ["1", "0"])).is_ok());
    // At the edge: a speed scale of exactly 2^-1022 takes it.
    let edge = format!("{:e}", f64::MIN_POSITIVE);
    assert!(Case::<f64>::from_json(&case("1", "1", "0", [&edge, "1e-310"])).is_ok());
    // The whole speed scale below the range: refused, naming the first such component.
    let e = refused(&case("1", "1", "0", ["1e-310", "3e-311"]));
    assert_eq!(e.field, "bodies[0].velocity[0]", "{e}");
    assert!(e.message.contains("itself below the normal range"), "{e}");
    // The error is 2^-1075, which no f64 holds: the message writes it (it printed 0e0).
    assert!(
        e.message
            .contains("error of up to 2^-1075 (about 2.5e-324)"),
        "{e}"
    );
    // A spin entry on a huge ball: R 2^-1075 = 2.5e-16 against a speed of 1.
    let e = refused(&case("1", "1e308", "7e-320", ["1", "0"]));
    assert_eq!(e.field, "bodies[0].angular_velocity", "{e}");
    assert!(
        e.message
            .contains("moves the contact point by up to 1e308 x 2^-1075"),
        "{e}"
    );
    assert!(!e.message.contains("0e0"), "{e}");
    // ... but not on the same ball moving at 1e-6 of the range's top.
    assert!(Case::<f64>::from_json(&case("1", "1e308", "7e-320", ["1e302", "0"])).is_ok());
    // Matrix and omega forms name their entry.
    let mut m = case("1", "1e308", "0", ["1", "0"]);
    m["bodies"][0]["angular_velocity"] = json!([["0", "-7e-320"], ["7e-320", "0"]]);
    assert_eq!(refused(&m).field, "bodies[0].angular_velocity[0][1]");
    // Exact mode reads all of them as written.
    assert!(Case::<Exact>::from_json(&case("1", "1", "0", ["1e-310", "3e-311"])).is_ok());
}

/// The Python package writes its floats as JSON numbers in their shortest round-trip
/// form: read as those floats, a subnormal lost nothing and is taken; its strings are
/// still decimals, refused as above.
#[test]
fn json_numbers_read_as_floats_are_taken_below_the_range_and_strings_are_not() {
    let mut floats = case("1", "1", "0", ["0", "0"]);
    floats["bodies"][0]["radius"] = json!(5e-324);
    floats["bodies"][0]["velocity"] = json!([1e-310, 3e-311]);
    floats["bodies"][0]["angular_velocity"] = json!(1e-320);
    let read = Case::<f64>::from_floats(&floats).unwrap();
    assert_eq!(read.bodies[0].radius, 5e-324);
    assert_eq!(read.bodies[0].velocity, [1e-310, 3e-311]);
    assert!(Case::<f64>::from_json(&floats).is_err());
    let e = Case::<f64>::from_floats(&case("1", "4e-324", "0", ["1", "0"])).unwrap_err();
    assert_eq!(e.field, "bodies[0].radius", "{e}");
    let e = Case::<f64>::from_floats(&case("1", "1", "0", ["1e-310", "3e-311"])).unwrap_err();
    assert_eq!(e.field, "bodies[0].velocity[0]", "{e}");
}
