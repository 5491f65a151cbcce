//! Scene numbers against their bounds: the rounding allowance of collision-core's checked
//! `collide` (scenes are exact but run in f64), and the digit limit of the number grammar.

use noslip_scene::{Scene, MAX_DIGITS};
use num_bigint::BigInt;
use num_rational::BigRational;

type Q = BigRational;

/// A 3D scene with one species given by `inertia` (a TOML line) and radius `radius`.
fn scene(radius: &str, inertia: &str) -> Result<Scene, String> {
    let text = format!(
        "dim = 3\n[box]\nsize = [40, 40, 40]\nboundary = [\"wall\", \"wall\", \"wall\"]\n\
         [[species]]\nmass = 1\nradius = \"{radius}\"\n{inertia}\ncount = 1\n"
    );
    Scene::from_toml(&text, "t.toml").map_err(|e| e.to_string())
}

fn q(p: i64, d: i64) -> Q {
    Q::new(p.into(), d.into())
}

/// `x (1 + k 2^-52)`: `k` ulps of relative size `eps` above `x`, exactly.
fn above(x: &Q, k: i64) -> Q {
    x * (Q::from_integer(1.into()) + Q::new(k.into(), BigInt::from(1u64 << 52)))
}

/// The decimal text of a rational with `digits` significant digits after the point, rounded
/// up (so the decimal is at least `x`).
fn decimal_up(x: &Q, digits: u32) -> String {
    let scale = BigInt::from(10).pow(digits);
    let scaled = (x * Q::from_integer(scale.clone())).ceil().to_integer();
    let int = &scaled / &scale;
    let frac = &scaled % &scale;
    format!(
        "{int}.{:0>width$}",
        frac.to_string(),
        width = digits as usize
    )
}

#[test]
fn an_f64_printed_shell_is_the_shell() {
    // The case: R = 5, lambda = 25/3 computed in f64 and printed in full.
    let s = scene("5", "lambda = \"8.333333333333334\"").unwrap();
    assert_eq!(s.species[0].gamma2, q(2, 3));
    let s = scene("1", "gamma2 = 0.6666666666666667").unwrap();
    assert_eq!(s.species[0].gamma2, q(2, 3));
    // A small negative gamma2 from cancellation is the point mass 0.
    let s = scene("1", "gamma2 = \"-1e-17\"").unwrap();
    assert_eq!(s.species[0].gamma2, q(0, 1));
}

#[test]
fn the_allowance_is_eight_eps_of_the_bound_and_no_more() {
    // lambda's bound R^2/n = 25/3, gamma2's 2/3; 8 eps above each is accepted (and clamped
    // exactly), 8 eps plus one part in 10^20 is refused.
    let tiny = q(1, 1) + Q::new(1.into(), BigInt::from(10).pow(20));
    for (key, bound) in [("lambda", q(25, 3)), ("gamma2", q(2, 3))] {
        let edge = above(&bound, 8);
        let beyond = &edge * &tiny;
        let text = |x: &Q| format!("{key} = \"{}/{}\"", x.numer(), x.denom());
        let s = scene("5", &text(&edge)).unwrap_or_else(|e| panic!("{key} at the edge: {e}"));
        assert_eq!(s.species[0].gamma2, q(2, 3), "{key}");
        let e = scene("5", &text(&beyond)).unwrap_err();
        assert!(e.contains(&format!("species[0].{key}: must be in")), "{e}");
        // Below zero: the same allowance, relative to the bound.
        let below = -(&bound * Q::new(8.into(), BigInt::from(1u64 << 52)));
        let s = scene("5", &text(&below)).unwrap();
        assert_eq!(s.species[0].gamma2, q(0, 1));
        let e = scene("5", &text(&(below * &tiny))).unwrap_err();
        assert!(e.contains("must be in"), "{e}");
    }
    // The same through decimals: 17 significant digits rounded up are within rounding.
    let s = scene("5", &format!("lambda = \"{}\"", decimal_up(&q(25, 3), 16))).unwrap();
    assert_eq!(s.species[0].gamma2, q(2, 3));
    let e = scene("5", "lambda = \"8.3334\"").unwrap_err();
    assert!(
        e.contains("species[0].lambda: must be in [0, R^2/n] = [0, 25/3]"),
        "{e}"
    );
}

#[test]
fn numbers_have_at_most_max_digits() {
    let long = "1".repeat(MAX_DIGITS + 1);
    let e = scene("1", &format!("gamma2 = \"0.{long}\"")).unwrap_err();
    assert!(
        e.contains(&format!("at most {MAX_DIGITS} are accepted")),
        "{e}"
    );
    assert!(e.len() < 200, "{e}");
    let e = scene("1", &format!("gamma2 = \"1/{}\"", "7".repeat(1_000_000))).unwrap_err();
    // (A number is read while the TOML is parsed: the error names the line and column.)
    assert!(
        e.contains("t.toml: line 8") && e.contains("1000001 digits"),
        "{e}"
    );
    let fits = format!("gamma2 = \"1/{}\"", "7".repeat(MAX_DIGITS - 1));
    assert!(scene("1", &fits).is_ok());
}
