//! The number reader (`number.rs`): what exact and float numbers read as, and its short
//! path (`short.rs`) against its general one.

use super::*;
use crate::fraction::Fraction;
use crate::short::{exact, fraction};
use collision_core::rng::Rng;

fn q(n: i64, d: i64) -> Exact {
    Exact::from_ratio(n, d)
}

#[test]
fn exact_numbers_are_what_they_spell() {
    let cases = [
        ("0.1", q(1, 10)),
        ("-2.5E+3", q(-2500, 1)),
        ("1e-3", q(1, 1000)),
        ("3/5", q(3, 5)),
        ("-7/2", q(-7, 2)),
        ("6/4", q(3, 2)),
        ("+4", q(4, 1)),
        (".5", q(1, 2)),
        ("5.", q(5, 1)),
        ("-0", q(0, 1)),
        ("0e999999999999999999999", q(0, 1)),
        ("12.50e-1", q(5, 4)),
    ];
    for (text, want) in cases {
        assert_eq!(Exact::parse_number(text), Ok(want), "{text}");
    }
    let big = Exact::parse_number("1e1000").unwrap();
    assert_eq!(big.numer_string().len(), 1001);
    let small = Exact::parse_number("-1e-1000").unwrap();
    assert_eq!(small.denom_string().len(), 1001);
}

#[test]
fn malformed_numbers_are_rejected_with_a_message() {
    for text in [
        "", "-", ".", "e5", "1e", "1e+", "1.2.3", "1..2", "abc", "1/", "/2", "1/-2", "1.5/2",
        "1/2/3", " 1", "1 ", "0x10", "1_000", "--1", "١",
    ] {
        let e = Exact::parse_number(text).unwrap_err();
        assert!(e.starts_with("malformed number"), "{text:?}: {e}");
        assert!(f64::parse_number(text).is_err(), "{text:?}");
    }
    for text in ["inf", "-inf", "NaN", "Infinity", "+INF"] {
        let e = f64::parse_number(text).unwrap_err();
        assert!(e.contains("not a finite number"), "{text}: {e}");
    }
    assert!(Exact::parse_number("3/0")
        .unwrap_err()
        .contains("zero denominator"));
    assert!(f64::parse_number("0/0")
        .unwrap_err()
        .contains("zero denominator"));
    for text in [
        "1e999999",
        "1e1001",
        "-1e-1001",
        "1e-99999999999999999999999",
    ] {
        let e = Exact::parse_number(text).unwrap_err();
        assert!(e.contains("exponent"), "{text}: {e}");
    }
    for text in ["1e999999", "1e99999999999999999999999", "-2e308"] {
        let e = f64::parse_number(text).unwrap_err();
        assert!(e.contains("out of the range of f64"), "{text}: {e}");
    }
    let long = "9".repeat(400) + "/1";
    assert!(f64::parse_number(&long).unwrap_err().contains("..."));
}

#[test]
fn floats_are_correctly_rounded() {
    assert_eq!(f64::parse_number("0.1"), Ok(0.1));
    assert_eq!(f64::parse_number("1/3"), Ok(1.0 / 3.0));
    assert_eq!(f64::parse_number("-7/2"), Ok(-3.5));
    assert_eq!(f64::parse_number("1e-400"), Ok(0.0));
    assert!(f64::parse_number("-1e-400").unwrap().is_sign_negative());
    // Rationals beyond 2^53 go through the exact rational: compare with the correctly
    // rounded decimal parser on the same values, including halfway cases, subnormals
    // and the edge of the range.
    let decimals = [
        "9007199254740993",
        "9007199254740995",
        "18014398509481985",
        "0.30000000000000001665",
        "123456789012345678901234567890e-7",
        "2.4703282292062327e-324",
        "2.4703282292062328e-324",
        "4.9406564584124654e-324",
        "2.2250738585072011e-308",
        "2.2250738585072014e-308",
        "1.7976931348623157e308",
        "1.7976931348623158e308",
        "3.14159265358979323846264338327950288419716939937510",
    ];
    for d in decimals {
        let r = Exact::parse_number(d).unwrap();
        let ratio = format!("{}/{}", r.numer_string(), r.denom_string());
        let want: f64 = d.parse().unwrap();
        // The rational's rounding (what a rational input goes through)...
        assert_eq!(ToPrimitive::to_f64(&r), Some(want), "{d} as {ratio}");
        // ... reachable from the input when the ratio has at most MAX_DIGITS digits.
        if ratio.len() - 1 <= MAX_DIGITS {
            assert_eq!(f64::parse_number(&ratio), Ok(want), "{d} as {ratio}");
        } else {
            assert!(f64::parse_number(&ratio).unwrap_err().contains("digits"));
        }
        assert_eq!(f64::parse_number(d), Ok(want), "{d}");
    }
}

#[test]
fn numbers_have_at_most_max_digits() {
    let fits = "9".repeat(MAX_DIGITS);
    assert!(Exact::parse_number(&fits).is_ok());
    let half = "7".repeat(MAX_DIGITS / 2);
    assert!(f64::parse_number(&format!("-{half}/{half}")).is_ok());
    for text in [
        "9".repeat(MAX_DIGITS + 1),
        format!("0.{}", "0".repeat(MAX_DIGITS)),
        format!("{half}/{half}7"),
        format!("1.{}e5", "0".repeat(10 * MAX_DIGITS)),
    ] {
        for e in [
            Exact::parse_number(&text).unwrap_err(),
            f64::parse_number(&text).unwrap_err(),
        ] {
            assert!(
                e.contains(&format!("at most {MAX_DIGITS} are accepted")),
                "{e}"
            );
            assert!(e.len() < 120, "{e}");
        }
    }
}

#[test]
fn floats_print_as_json_numbers_that_round_trip() {
    for x in [
        0.0,
        -0.0,
        2.0,
        -3.5,
        0.1,
        1e-300,
        -1e300,
        5e-324,
        f64::MAX,
        1e16,
        123456789.123,
    ] {
        let v = x.to_json().unwrap();
        let text = serde_json::to_string(&v).unwrap();
        let back: f64 = text.parse().unwrap();
        assert_eq!(back.to_bits(), x.to_bits(), "{x:?} printed as {text}");
        assert!(serde_json::from_str::<Value>(&text).is_ok(), "{text}");
    }
    assert_eq!(serde_json::to_string(&2.0.to_json()).unwrap(), "2.0");
    assert_eq!(f64::NAN.to_json(), None);
    assert_eq!(f64::INFINITY.to_json(), None);
    assert_eq!(q(-6, 10).to_json(), Some(Value::String("-3/5".into())));
    assert_eq!(q(2, 1).to_json(), Some(Value::String("2".into())));
}

#[test]
fn json_number_literals_are_read_as_written() {
    let v: Value = serde_json::from_str("[0.1, 1E2, -0, 1e999999]").unwrap();
    let got: Vec<Result<Exact, CaseError>> = v
        .as_array()
        .unwrap()
        .iter()
        .map(|x| from_json(x, "f"))
        .collect();
    assert_eq!(got[0], Ok(q(1, 10)));
    assert_eq!(got[1], Ok(q(100, 1)));
    assert_eq!(got[2], Ok(q(0, 1)));
    assert!(got[3].as_ref().unwrap_err().message.contains("exponent"));
    let e = from_json::<f64, _>(&Value::Bool(true), "bodies[0].mass").unwrap_err();
    assert_eq!(e.field, "bodies[0].mass");
    assert!(e.message.contains("got a boolean"));
}

#[test]
fn integer_literals() {
    assert_eq!(integer_literal("3"), Some((false, 3)));
    assert_eq!(integer_literal("-3"), Some((true, 3)));
    assert_eq!(integer_literal("-0"), Some((false, 0)));
    assert_eq!(
        integer_literal("99999999999999999999999"),
        Some((false, usize::MAX))
    );
    assert_eq!(integer_literal("3.0"), None);
    assert_eq!(integer_literal("3e0"), None);
}

/// Where the short reader answers, it answers the general reader's value, and it answers
/// every short form: integers, ratios and decimals with both signs, leading and trailing
/// zeros, 1 to 18 digits (random digits, and runs of 0s, 2s, 5s and 9s whose 2s and 5s
/// reduce), 40 000 texts in all, against `Exact::parse_number`'s general path
/// (`parse_general` below: the scan and the big-integer construction of before).
#[test]
fn short_numbers_read_as_the_general_reader_reads_them() {
    let mut rng = Rng::new(11);
    let mut answered = 0;
    for _ in 0..40_000 {
        let sign = ["", "-", "+"][rng.integer(0..=2) as usize];
        let a = rng.integer(0..=19) as usize;
        let b = rng.integer(0..=19) as usize;
        let (x, y) = (digit_string(&mut rng, a), digit_string(&mut rng, b));
        let (text, short) = match rng.integer(0..=2) {
            0 => (format!("{sign}{x}"), (1..=18).contains(&a)),
            1 => (
                format!("{sign}{x}/{y}"),
                (1..=18).contains(&a) && (1..=18).contains(&b) && y.bytes().any(|d| d != b'0'),
            ),
            _ => (format!("{sign}{x}.{y}"), (1..=18).contains(&(a + b))),
        };
        let got = exact(&text);
        assert_eq!(got.is_some(), short, "{text}");
        assert_eq!(fraction(&text).map(Fraction::exact), got, "{text}");
        if let Some(v) = got {
            answered += 1;
            assert_eq!(Ok(v), parse_general(&text), "{text}");
        }
    }
    assert!(answered > 20_000, "{answered}");
    for (text, want) in [
        ("0.5", Exact::from_ratio(1, 2)),
        ("-12.50", Exact::from_ratio(-25, 2)),
        ("0.0000000000000001", Exact::from_ratio(1, 10i64.pow(16))),
        ("-0.00", Exact::zero()),
        ("250.000", Exact::from_integer(250)),
        ("6/4", Exact::from_ratio(3, 2)),
        ("+7", Exact::from_integer(7)),
    ] {
        assert_eq!(exact(text), Some(want), "{text}");
    }
    for text in [
        "", "-", ".", "1e5", "1/0", "1/", "/2", "1.2.3", " 1", "1/-2",
    ] {
        assert_eq!(exact(text), None, "{text}");
    }
}

/// `len` digits of one of five kinds: any, or drawn from `0 5`, `0 2 4 8`, `9 0` or
/// `1 2 5 0` (numbers rich in 2s and 5s, and runs of zeros).
fn digit_string(rng: &mut Rng, len: usize) -> String {
    let kinds: [&[u8]; 5] = [b"0123456789", b"05", b"0248", b"90", b"1250"];
    let kind = kinds[rng.integer(0..=4) as usize];
    (0..len)
        .map(|_| char::from(kind[rng.integer(0..=kind.len() as u64 - 1) as usize]))
        .collect()
}

/// The general path alone: `Exact::parse_number` on a text the short reader is kept out
/// of (an exponent of 0 appended changes no value and makes the short reader decline).
fn parse_general(text: &str) -> Result<Exact, String> {
    if text.contains('/') {
        // A ratio takes no exponent: the general reader's ratio path is `from_decimal`.
        let (s, body) = match text.strip_prefix('-') {
            Some(rest) => ("-", rest),
            None => ("", text.strip_prefix('+').unwrap_or(text)),
        };
        let (p, q) = body.split_once('/').ok_or("no slash")?;
        let ok = |d: &str| !d.is_empty() && d.bytes().all(|c| c.is_ascii_digit());
        if !ok(p) || !ok(q) {
            return Err("malformed".into());
        }
        return Exact::from_decimal(&format!("{s}{p}"), q).ok_or("zero denominator".into());
    }
    if text.is_empty() || text.ends_with(['-', '+']) {
        return Err("malformed".into());
    }
    Exact::parse_number(&format!("{text}e0"))
}
