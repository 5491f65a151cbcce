//! Fuzz target `json_case`: the JSON front end of `noslip collide`.
//!
//! Any bytes are an input file. The CLI reads it as UTF-8 (other bytes: exit 2, "cannot
//! read"), then `collide_json` parses the case (or array of cases), validates it, solves it
//! and renders the answer. Each input runs in both modes, f64 and `--exact`.
//!
//! Contract checked: no panic, abort, hang or unbounded memory (libFuzzer's `-timeout` and
//! `-rss_limit_mb`); a refused input is an error (`RunError`, exit 2 in the CLI) whose message
//! is one line; an accepted input gives JSON of the same shape (an array of as many cases, or
//! one object) whose every number is finite (f64 mode: a JSON number that reads back as a
//! finite f64; exact mode: a string `p` or `p/q` of decimal integers, q > 0). In exact mode
//! the answer or error is also that of `collide_json_general` (the path without the direct
//! path of plain cases, `case/src/direct.rs`), byte for byte.

#![no_main]

use libfuzzer_sys::fuzz_target;
use noslip::json::collide::collide_json_general;
use noslip::json::{collide_json, Mode};
use serde_json::Value;

fuzz_target!(|data: &[u8]| {
    let Ok(input) = std::str::from_utf8(data) else {
        return; // the CLI: "cannot read FILE: stream did not contain valid UTF-8", exit 2
    };
    for mode in [Mode::Float, Mode::Exact] {
        let answer = collide_json(input, mode);
        if mode == Mode::Exact {
            let general = collide_json_general(input, mode);
            assert_eq!(
                answer.as_ref().map_err(ToString::to_string),
                general.as_ref().map_err(ToString::to_string),
                "the direct path differs from the general path"
            );
        }
        match answer {
            Ok(out) => check_answer(input, &out, mode),
            Err(e) => {
                let line = e.to_string();
                assert!(!line.is_empty(), "an empty error message");
            }
        }
    }
});

/// The answer has the input's shape and only finite numbers.
fn check_answer(input: &str, out: &str, mode: Mode) {
    let input: Value = serde_json::from_str(input).expect("accepted input is JSON");
    let out: Value = serde_json::from_str(out).expect("the answer is JSON");
    match (&input, &out) {
        (Value::Array(cases), Value::Array(answers)) => {
            assert_eq!(cases.len(), answers.len(), "one answer per case");
            answers.iter().for_each(|a| check_case(a, mode));
        }
        (Value::Object(_), Value::Object(_)) => check_case(&out, mode),
        _ => panic!("answer shape differs from the input's: {out}"),
    }
}

fn check_case(answer: &Value, mode: Mode) {
    let bodies = answer["bodies"].as_array().expect("bodies");
    assert_eq!(bodies.len(), 2, "two bodies");
    for b in bodies {
        check_numbers(&b["velocity"], mode);
        check_numbers(&b["angular_velocity"], mode);
    }
}

/// Every leaf of `v` (a number, a vector or a matrix) is a finite number of the mode's form.
fn check_numbers(v: &Value, mode: Mode) {
    match (v, mode) {
        (Value::Array(items), _) => items.iter().for_each(|x| check_numbers(x, mode)),
        (Value::Number(x), Mode::Float) => {
            let f: f64 = x.to_string().parse().expect("an f64 literal");
            assert!(f.is_finite(), "non-finite component {x}");
        }
        (Value::String(s), Mode::Exact) => {
            let (p, q) = s.split_once('/').unwrap_or((s, "1"));
            let digits = |t: &str| !t.is_empty() && t.bytes().all(|c| c.is_ascii_digit());
            assert!(
                digits(p.strip_prefix('-').unwrap_or(p))
                    && digits(q)
                    && q.trim_start_matches('0') != "",
                "not a rational: {s:?}"
            );
        }
        _ => panic!("unexpected output component {v} in {mode:?} mode"),
    }
}
