//! Numbers in scene files: a TOML integer, a TOML float (its exact binary value), or a
//! string holding a decimal (`"0.1"`, `"-2.5e-3"`, read exactly as written) or a rational
//! (`"3/5"`). All are kept as exact rationals, so the generator folds them without rounding.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, ToPrimitive, Zero};
use serde::de::{self, Deserializer, Visitor};
use std::fmt;

/// An exact rational read from a scene file.
#[derive(Clone, Debug, PartialEq)]
pub struct Number(pub BigRational);

/// Largest decimal exponent accepted in a string (`1e400` would build a 400-digit integer).
pub(crate) const MAX_EXPONENT: i64 = 400;

/// Most digits accepted in one number (the digits of a decimal's mantissa, or of a rational's
/// numerator and denominator together), so that no input asks for huge integers, as the
/// exponent limit does for exponents. The JSON cases of `noslip collide` take the same limit.
/// Chosen from the exact path's cost (release build, random rationals of this many digits in
/// every field): a 6D `noslip collide --exact` case takes 0.7 s at 100 digits, 4.1 s at 300
/// and 46 s at 1000 (one number of 10^6 digits did not finish). Every `f64` fits, as its
/// shortest decimal (at most 17 digits).
pub const MAX_DIGITS: usize = 100;

/// `text` for a message: quoted, and cut after 40 characters.
fn shown(text: &str) -> String {
    match text.char_indices().nth(40) {
        Some((k, _)) => format!("{:?}...", &text[..k]),
        None => format!("{text:?}"),
    }
}

/// Refuse `text` if `parts` hold more than [`MAX_DIGITS`] digits.
fn digit_limit(text: &str, parts: &[&str]) -> Result<(), String> {
    let count: usize = parts
        .iter()
        .map(|p| p.bytes().filter(u8::is_ascii_digit).count())
        .sum();
    if count > MAX_DIGITS {
        return Err(format!(
            "the number {} has {count} digits: at most {MAX_DIGITS} are accepted",
            shown(text)
        ));
    }
    Ok(())
}

/// Parse `"p/q"` or a decimal with optional exponent, exactly.
pub fn parse_exact(text: &str) -> Result<BigRational, String> {
    let s = text.trim();
    if let Some((p, q)) = s.split_once('/') {
        digit_limit(text, &[p, q])?;
        let p: BigInt = p
            .trim()
            .parse()
            .map_err(|_| format!("bad numerator in {}", shown(text)))?;
        let q: BigInt = q
            .trim()
            .parse()
            .map_err(|_| format!("bad denominator in {}", shown(text)))?;
        if q.is_zero() {
            return Err(format!("zero denominator in {}", shown(text)));
        }
        return Ok(BigRational::new(p, q));
    }
    let (mantissa, exponent) = match s.find(['e', 'E']) {
        Some(i) => (&s[..i], Some(&s[i + 1..])),
        None => (s, None),
    };
    let (int_part, frac_part) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    digit_limit(text, &[int_part, frac_part])?;
    let exponent = match exponent {
        Some(e) => e
            .parse::<i64>()
            .map_err(|_| format!("bad exponent in {}", shown(text)))?,
        None => 0,
    };
    if exponent.abs() > MAX_EXPONENT {
        return Err(format!(
            "exponent of {} is beyond +-{MAX_EXPONENT}",
            shown(text)
        ));
    }
    let digits = format!("{int_part}{frac_part}");
    let valid = |d: &str| d.chars().all(|c| c.is_ascii_digit());
    let unsigned = digits.trim_start_matches(['+', '-']);
    if unsigned.is_empty() || !valid(unsigned) || !valid(frac_part) {
        return Err(format!(
            "not a number: {} (write 3/5, 0.25 or 1e-3)",
            shown(text)
        ));
    }
    let value: BigInt = digits
        .parse()
        .map_err(|_| format!("not a number: {}", shown(text)))?;
    let scale = exponent - frac_part.len() as i64;
    let ten = BigInt::from(10);
    let power = num_traits::pow(ten, scale.unsigned_abs() as usize);
    Ok(if scale >= 0 {
        BigRational::from_integer(value * power)
    } else {
        BigRational::new(value, power)
    })
}

/// A scene value in a message: its exact fraction when that is short (`3/5`, `-2`), else a
/// decimal approximation with the fraction after it, as a TOML float reads (`lambda = -0.1`
/// is the binary fraction `-3602879701896397/36028797018963968`: "about -1.0000e-1
/// (exactly -3602879701896397/36028797018963968)").
pub(crate) fn show_q(x: &BigRational) -> String {
    let exact = x.to_string();
    if exact.len() <= 20 {
        return exact;
    }
    match x.to_f64().filter(|v| v.is_normal()) {
        Some(v) => format!("about {v:.4e} (exactly {exact})"),
        None => exact,
    }
}

/// Reads a [`Number`] from any of its spellings (also the spin's visitor,
/// `spin_shape.rs`).
pub(crate) struct NumberVisitor;

impl Visitor<'_> for NumberVisitor {
    type Value = Number;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a number, or a string holding a decimal or a rational such as \"3/5\"")
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Number, E> {
        Ok(Number(BigRational::from_integer(v.into())))
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Number, E> {
        Ok(Number(BigRational::from_integer(v.into())))
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Number, E> {
        BigRational::from_float(v)
            .map(Number)
            .ok_or_else(|| E::custom(format!("must be finite, got {v}")))
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<Number, E> {
        parse_exact(v).map(Number).map_err(E::custom)
    }
}

impl<'de> serde::Deserialize<'de> for Number {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(NumberVisitor)
    }
}

impl Default for Number {
    fn default() -> Self {
        Number(BigRational::one())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(p: i64, d: i64) -> BigRational {
        BigRational::new(p.into(), d.into())
    }

    #[test]
    fn long_fractions_are_shown_with_a_decimal_beside_them() {
        assert_eq!(super::show_q(&q(3, 5)), "3/5");
        assert_eq!(super::show_q(&q(-2, 1)), "-2");
        let tenth = BigRational::from_float(-0.1).unwrap();
        assert_eq!(
            super::show_q(&tenth),
            "about -1.0000e-1 (exactly -3602879701896397/36028797018963968)"
        );
    }

    #[test]
    fn decimals_and_rationals_are_exact() {
        assert_eq!(parse_exact("0.1").unwrap(), q(1, 10));
        assert_eq!(parse_exact("-2.5e-3").unwrap(), q(-1, 400));
        assert_eq!(parse_exact("3/6").unwrap(), q(1, 2));
        assert_eq!(parse_exact("12E2").unwrap(), q(1200, 1));
        for bad in ["", "1/0", "x", "1.2.3", "1e999", "--1", "."] {
            assert!(parse_exact(bad).is_err(), "{bad:?} accepted");
        }
    }

    #[test]
    fn digit_counts_are_limited() {
        let at_limit = "7".repeat(MAX_DIGITS);
        assert!(parse_exact(&at_limit).is_ok());
        let half = "3".repeat(MAX_DIGITS / 2);
        assert!(parse_exact(&format!("{half}/{half}")).is_ok());
        for long in [
            "7".repeat(MAX_DIGITS + 1),
            format!("0.{}1", "0".repeat(MAX_DIGITS)),
            format!("{half}/{half}1"),
            format!("1/{}", "0".repeat(1_000_000)),
        ] {
            let e = parse_exact(&long).unwrap_err();
            assert!(e.contains(&format!("at most {MAX_DIGITS}")), "{e}");
            assert!(e.len() < 120, "{e}");
        }
        // Every f64's shortest decimal fits.
        assert!(parse_exact(&format!("{:e}", f64::from_bits((1 << 52) - 1))).is_ok());
    }
}
