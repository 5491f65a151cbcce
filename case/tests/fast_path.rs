//! The fast path of `collide_json` (one pass from the text, output written straight into a
//! string) against the reference built from serde_json, on random cases in 2..6 dimensions
//! (fixed and free, every contact law, every angular-velocity form, numbers spelled as JSON
//! floats, decimals and ratios) and on broken variants of them:
//!
//! - `collide_json` and `collide_json_serde` (serde_json's `Value`, the former path) give
//!   the same answer, or the same error message, for every input;
//! - the written answer is, byte for byte, serde_json's compact text of the answer's value
//!   built from [`InputScalar::to_json`], and every number in it reads back as exactly the
//!   value the collision computed;
//! - reading a case from the fast tree and from the `Value` gives the same case.

use collision_core::rng::Rng;
use collision_core::{skew_pairs, stereographic_normal, Exact, Scalar, State2, State3};
use noslip_case::case::{Case, Spin};
use noslip_case::collide::collide_json_serde;
use noslip_case::node::Members;
use noslip_case::number::InputScalar;
use noslip_case::output::render;
use noslip_case::solve::{solve, BodyOutput};
use noslip_case::text;
use noslip_case::{collide_json, Mode};
use serde_json::{json, Value};

/// A number spelled one of the ways the format allows: a JSON number (shortest, or with an
/// `E`), a decimal string, or a ratio string of its exact value.
fn spell(x: f64, rng: &mut Rng) -> String {
    spell_as(x, rng.integer(0..=4))
}

/// [`spell`] in form `form` (0..=4): `x` and `-x` in one form are exact negatives.
fn spell_as(x: f64, form: u64) -> String {
    match form {
        0 => format!("{x:?}"),
        1 => format!("{x:E}"),
        2 => format!("\"{x:e}\""),
        3 => format!("\"{}\"", Exact::from_float(x).expect("finite")),
        _ => format!("\"{:.6}\"", x),
    }
}

fn list(items: &[String], rng: &mut Rng) -> String {
    let sep = [",", ", ", ",\n  ", " ,\t"][rng.integer(0..=3) as usize];
    format!("[{}]", items.join(sep))
}

/// A random case in `dim` dimensions as JSON text, approaching along its normal.
fn case_text(dim: usize, rng: &mut Rng) -> String {
    let y: Vec<Exact> = (0..dim - 1)
        .map(|_| Exact::from_ratio(rng.integer(0..=2000) as i64 - 1000, 997))
        .collect();
    let nu = stereographic_normal(&y);
    let nu_f: Vec<f64> = nu.iter().map(Exact::to_f64).collect();
    // A ratio: exact mode needs |nu| = 1 exactly.
    let normal: Vec<String> = nu.iter().map(|c| format!("\"{c}\"")).collect();
    let mut u: Vec<Vec<f64>> = (0..2)
        .map(|_| (0..dim).map(|_| rng.uniform(-1.0, 1.0)).collect())
        .collect();
    let dn: f64 = (0..dim).map(|k| (u[1][k] - u[0][k]) * nu_f[k]).sum();
    if dn > 0.0 {
        u.iter_mut().flatten().for_each(|c| *c = -*c);
    }
    let fixed = rng.integer(0..=3) == 0;
    let bodies: Vec<String> = (0..2)
        .map(|b| {
            let mass = if b == 1 && fixed {
                "\"inf\"".to_string()
            } else {
                spell(rng.uniform(-2.0, 2.0).exp2(), rng)
            };
            let r = rng.uniform(-1.0, 1.0).exp2();
            let radius = spell(r, rng);
            let inertia = match rng.integer(0..=4) {
                0 => String::new(),
                1 => format!(
                    ", \"gamma2\": {}",
                    spell(rng.uniform(0.01, 2.0 / dim as f64), rng)
                ),
                2 => ", \"distribution\": \"shell\"".into(),
                3 => ", \"distribution\": \"uniform\"".into(),
                _ => format!(", \"lambda\": {}", spell(r * r / (dim + 1) as f64, rng)),
            };
            let spin = match (dim, rng.integer(0..=2)) {
                (2, 0) => spell(rng.uniform(-1.0, 1.0), rng),
                (3, 0) => {
                    let w: Vec<String> =
                        (0..3).map(|_| spell(rng.uniform(-1.0, 1.0), rng)).collect();
                    list(&w, rng)
                }
                _ => {
                    // Exactly skew: an entry and its mirror spelled in the same form.
                    let mut m = vec![vec![spell(0.0, rng); dim]; dim];
                    for (i, j) in skew_pairs(dim) {
                        let (x, form) = (rng.uniform(-1.0, 1.0), rng.integer(0..=4));
                        (m[i][j], m[j][i]) = (spell_as(x, form), spell_as(-x, form));
                    }
                    let rows: Vec<String> = m.iter().map(|r| list(r, rng)).collect();
                    list(&rows, rng)
                }
            };
            let v: Vec<String> = u[b].iter().map(|&x| spell(x, rng)).collect();
            format!(
                "{{\"mass\": {mass}, \"radius\": {radius}{inertia}, \"angular_velocity\": {spin}, \
                 \"velocity\": {}}}",
                list(&v, rng)
            )
        })
        .collect();
    let contact = match rng.integer(0..=5) {
        0 => ", \"contact\": \"smooth\"".to_string(),
        1 => ", \"contact\": \"no-slip\"".to_string(),
        2 if dim <= 6 => ", \"contact\": {\"e\": \"9/10\", \"beta\": 0.25}".to_string(),
        3 if dim <= 6 => {
            ", \"contact\": {\"e\": 0.8, \"mu\": \"1/4\", \"beta0\": \"1/2\"}".to_string()
        }
        _ => String::new(),
    };
    format!(
        "{{\"dim\": {dim}, \"normal\": {}, \"bodies\": [{}, {}]{contact}}}",
        list(&normal, rng),
        bodies[0],
        bodies[1]
    )
}

/// The answer of one case as a `Value`, as the former writer built it: each number
/// `leaf(x)` (the former writer: [`InputScalar::to_json`]), the entry below the diagonal of
/// `0 - x`.
fn reference<T: InputScalar>(
    case: &Case<T>,
    out: &[BodyOutput<T>; 2],
    leaf: &mut dyn FnMut(&T) -> Value,
) -> Value {
    let mut bodies = Vec::new();
    for (i, o) in out.iter().enumerate() {
        let spin = match &case.bodies[i].spin {
            Spin::Scalar(_) => leaf(
                &State2 {
                    spin: [o.spin[0].clone()],
                    velocity: [o.velocity[0].clone(), o.velocity[1].clone()],
                }
                .scalar_spin(),
            ),
            Spin::Omega(_) => {
                let s = State3 {
                    spin: [0, 1, 2].map(|k| o.spin[k].clone()),
                    velocity: [0, 1, 2].map(|k| o.velocity[k].clone()),
                };
                Value::Array(s.omega().iter().map(&mut *leaf).collect())
            }
            Spin::Matrix(_) => {
                let n = case.dim;
                let mut m = vec![vec![Value::Null; n]; n];
                for ((r, c), x) in skew_pairs(n).zip(&o.spin) {
                    m[r][c] = leaf(x);
                    m[c][r] = leaf(&(T::zero() - x.clone()));
                }
                for (k, row) in m.iter_mut().enumerate() {
                    row[k] = leaf(&T::zero());
                }
                Value::Array(m.into_iter().map(Value::Array).collect())
            }
        };
        let velocity = Value::Array(o.velocity.iter().map(&mut *leaf).collect());
        bodies.push(json!({"angular_velocity": spin, "velocity": velocity}));
    }
    json!({ "bodies": bodies })
}

/// The leaves of `v` in the order serde_json writes them.
fn leaves(v: &Value, into: &mut Vec<Value>) {
    match v {
        Value::Array(items) => items.iter().for_each(|x| leaves(x, into)),
        Value::Object(map) => map.values().for_each(|x| leaves(x, into)),
        leaf => into.push(leaf.clone()),
    }
}

/// Every number of `answer` (in the order written) read back as `T` by `T`'s own parser
/// (`FromStr`: `p/q` for exact rationals, Rust's float parser for `f64`).
fn numbers_of<T: InputScalar + std::str::FromStr>(answer: &Value, into: &mut Vec<T>)
where
    T::Err: std::fmt::Debug,
{
    match answer {
        Value::Array(items) => items.iter().for_each(|x| numbers_of(x, into)),
        Value::Object(map) => map.values().for_each(|x| numbers_of(x, into)),
        Value::Number(n) => into.push(n.as_str().parse().unwrap()),
        Value::String(s) => into.push(s.parse().unwrap()),
        _ => panic!("unexpected {answer}"),
    }
}

/// The case's answer from both trees, and the writer against the reference; whether the
/// case was solved.
fn check_case<T: InputScalar + std::str::FromStr>(text: &str) -> bool
where
    T::Err: std::fmt::Debug,
    for<'a> &'a T::Unbounded: collision_core::RefArith<T::Unbounded>,
{
    let value: Value = serde_json::from_str(text).unwrap();
    let tree = text::parse(text).expect("the fast path reads every generated case");
    let (Ok(case), Ok(same)) = (Case::<T>::from_json(&value), Case::<T>::from_json(&tree)) else {
        panic!("{text}: refused");
    };
    assert_eq!(case, same, "{text}");
    let Ok(out) = solve(&case) else {
        // Refused by the checks (float mode: a rounding beyond the range): the errors are
        // compared with the reference path below.
        return false;
    };
    let written = render(&case, &out).unwrap();
    let former = reference(&case, &out, &mut |x: &T| x.to_json().expect("finite"));
    assert_eq!(written, serde_json::to_string(&former).unwrap());
    // Read back, the numbers are the computed values themselves: the reference with each
    // value's index as its leaf gives them in the order written.
    let back: Value = serde_json::from_str(&written).unwrap();
    let mut got: Vec<T> = Vec::new();
    numbers_of(&back, &mut got);
    let mut values: Vec<T> = Vec::new();
    let indices = reference(&case, &out, &mut |x: &T| {
        values.push(x.clone());
        Value::from(values.len() - 1)
    });
    let mut order = Vec::new();
    leaves(&indices, &mut order);
    let want: Vec<&T> = order
        .iter()
        .map(|k| &values[k.as_u64().unwrap() as usize])
        .collect();
    assert_eq!(got.len(), want.len());
    for (g, &w) in got.iter().zip(&want) {
        assert!(
            *g == *w && g.to_f64().to_bits() == w.to_f64().to_bits(),
            "{text}"
        );
    }
    true
}

/// The same answer, or the same error message, by both paths; how many modes answered.
fn same_answer(text: &str) -> usize {
    let mut answered = 0;
    for mode in [Mode::Float, Mode::Exact] {
        let (fast, serde) = (collide_json(text, mode), collide_json_serde(text, mode));
        match (&fast, &serde) {
            (Ok(a), Ok(b)) => {
                assert_eq!(a, b, "{text}");
                answered += 1;
            }
            (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string(), "{text}"),
            _ => panic!("{text}: {mode:?} {fast:?} against {serde:?}"),
        }
    }
    answered
}

/// Broken and borderline variants of a valid text: truncated, a byte dropped or inserted,
/// a repeated or unknown key, an escape, a trailing comma, wrong types.
fn variants(text: &str, rng: &mut Rng) -> Vec<String> {
    let at = |rng: &mut Rng| {
        let mut k = rng.integer(0..=text.len() as u64 - 1) as usize;
        while !text.is_char_boundary(k) {
            k -= 1;
        }
        k
    };
    let (a, b, c) = (at(rng), at(rng), at(rng));
    let insert = [
        "]", "}", ",", ":", "\"", "0", "-", "e", ".", "[", " ", "\\", "x",
    ];
    let byte = insert[rng.integer(0..=insert.len() as u64 - 1) as usize];
    vec![
        text[..a].to_string(),
        format!("{}{}", &text[..b], &text[b + 1..]),
        format!("{}{byte}{}", &text[..c], &text[c..]),
        text.replacen("{\"dim\"", "{\"normal\": [], \"dim\"", 1),
        text.replacen("\"velocity\"", "\"velocity\": 1, \"velocity\"", 1),
        text.replacen("\"radius\"", "\"r\\u0061dius\"", 1),
        text.replacen("\"radius\"", "\"radios\"", 1),
        text.replacen("\"mass\"", "\"colour\": \"red\", \"mass\"", 1),
        text.replacen("]}", "],}", 1),
        text.replacen("\"dim\": ", "\"dim\": -", 1),
        text.replacen(": \"", ": [\"", 1),
        format!("[{text}, {text}]"),
        format!("[{text}, 7]"),
        format!("{text} 1"),
        format!("\t{text}\n"),
    ]
}

#[test]
fn fast_path_gives_the_reference_answers_and_errors() {
    let mut rng = Rng::new(30);
    let (mut solved, mut answered, mut refused) = (0, 0, 0);
    for round in 0..60 {
        let dim = 2 + round % 5;
        let text = case_text(dim, &mut rng);
        solved += usize::from(check_case::<Exact>(&text)) + usize::from(check_case::<f64>(&text));
        assert_eq!(same_answer(&text), 2, "{text}");
        for v in variants(&text, &mut rng) {
            let n = same_answer(&v);
            answered += n;
            refused += 2 - n;
        }
    }
    // Every generated case runs in both modes; the variants are a mix of accepted
    // (whitespace, arrays of cases) and refused inputs.
    assert_eq!(solved, 120);
    assert!(
        answered >= 60 * 2 * 2 && refused >= 60 * 2 * 8,
        "{answered} {refused}"
    );
    // Inputs that are not cases, and JSON the fast path leaves to serde_json.
    for text in [
        "",
        "3",
        "[]",
        "{}",
        "null",
        "[{\"dim\": 2}]",
        "\"\\u0041\"",
        "{\"a\": 1, \"a\": 2}",
        "[[[[[[[[[[[[[[[[[[[[1]]]]]]]]]]]]]]]]]]]",
        "01",
        "1.",
        "-",
        "tru",
        "{\"dim\" 2}",
    ] {
        same_answer(text);
    }
}

/// The fast reader's tree has the `Value`'s structure, keys and number values; it declines
/// escapes, repeated keys, deep nesting and anything serde_json refuses.
#[test]
fn the_tree_is_the_value_or_nothing() {
    fn same(tree: &text::Json<'_>, value: &Value) -> bool {
        use text::Json;
        match (tree, value) {
            (Json::Null, Value::Null) => true,
            (Json::Bool(a), Value::Bool(b)) => a == b,
            (Json::String(a), Value::String(b)) => a == b,
            // serde_json spells the exponent `e+`/`e-`; the number is the same.
            (Json::Number(a), Value::Number(b)) => {
                Exact::parse_number(a) == Exact::parse_number(b.as_str())
            }
            (Json::Array(a), Value::Array(b)) => {
                a.len() == b.len() && a.iter().zip(b).all(|(x, y)| same(x, y))
            }
            (Json::Object(a), Value::Object(b)) => {
                let keys: Vec<&str> = b.keys().map(String::as_str).collect();
                b.iter().all(|(k, v)| a.get(k).is_some_and(|t| same(t, v)))
                    && a.unknown_key(&keys).is_none()
            }
            _ => false,
        }
    }
    for text in [
        "{\"a\": [1, -0, 2.5E-3, 1e5, 0.0e+0, true, false, null, \"x:y\", {}], \"b\": {\"c\": []}}",
        " [ 1 , 2 ] ",
        "\"é\"",
        "-0.5",
    ] {
        let tree = text::parse(text).expect(text);
        assert!(same(&tree, &serde_json::from_str(text).unwrap()), "{text}");
    }
    for text in [
        "{\"a\": 1, \"a\": 2}",
        "\"a\\\"b\"",
        "\"tab\there\"",
        "[1,]",
        "{\"a\":1,}",
        "[01]",
        "[1.]",
        "[.5]",
        "[1e]",
        "[+1]",
        "{a: 1}",
        "[1] [2]",
        "[nul]",
        "",
        &("[".repeat(17) + &"]".repeat(17)),
    ] {
        assert_eq!(text::parse(text), None, "{text}");
    }
    assert!(text::parse(&("[".repeat(16) + &"]".repeat(16))).is_some());
}
