//! Numbers in scene files: a TOML integer, a TOML float (its exact binary value), or a
//! string holding a decimal (`"0.1"`, `"-2.5e-3"`, read exactly as written) or a rational
//! (`"3/5"`). All are kept as exact rationals, so the generator folds them without rounding.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Zero};
use serde::de::{self, Deserializer, Visitor};
use std::fmt;

/// An exact rational read from a scene file.
#[derive(Clone, Debug, PartialEq)]
pub struct Number(pub BigRational);

/// Largest decimal exponent accepted in a string (`1e400` would build a 400-digit integer).
pub const MAX_EXPONENT: i64 = 400;

/// Parse `"p/q"` or a decimal with optional exponent, exactly.
pub fn parse_exact(text: &str) -> Result<BigRational, String> {
    let s = text.trim();
    if let Some((p, q)) = s.split_once('/') {
        let p: BigInt = p
            .trim()
            .parse()
            .map_err(|_| format!("bad numerator in {text:?}"))?;
        let q: BigInt = q
            .trim()
            .parse()
            .map_err(|_| format!("bad denominator in {text:?}"))?;
        if q.is_zero() {
            return Err(format!("zero denominator in {text:?}"));
        }
        return Ok(BigRational::new(p, q));
    }
    let (mantissa, exponent) = match s.find(['e', 'E']) {
        Some(i) => (
            &s[..i],
            s[i + 1..]
                .parse::<i64>()
                .map_err(|_| format!("bad exponent in {text:?}"))?,
        ),
        None => (s, 0),
    };
    if exponent.abs() > MAX_EXPONENT {
        return Err(format!("exponent of {text:?} is beyond +-{MAX_EXPONENT}"));
    }
    let (int_part, frac_part) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    let digits = format!("{int_part}{frac_part}");
    let valid = |d: &str| d.chars().all(|c| c.is_ascii_digit());
    let unsigned = digits.trim_start_matches(['+', '-']);
    if unsigned.is_empty() || !valid(unsigned) || !valid(frac_part) {
        return Err(format!("not a number: {text:?} (write 3/5, 0.25 or 1e-3)"));
    }
    let value: BigInt = digits
        .parse()
        .map_err(|_| format!("not a number: {text:?}"))?;
    let scale = exponent - frac_part.len() as i64;
    let ten = BigInt::from(10);
    let power = num_traits::pow(ten, scale.unsigned_abs() as usize);
    Ok(if scale >= 0 {
        BigRational::from_integer(value * power)
    } else {
        BigRational::new(value, power)
    })
}

struct NumberVisitor;

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
    fn decimals_and_rationals_are_exact() {
        assert_eq!(parse_exact("0.1").unwrap(), q(1, 10));
        assert_eq!(parse_exact("-2.5e-3").unwrap(), q(-1, 400));
        assert_eq!(parse_exact("3/6").unwrap(), q(1, 2));
        assert_eq!(parse_exact("12E2").unwrap(), q(1200, 1));
        for bad in ["", "1/0", "x", "1.2.3", "1e999", "--1", "."] {
            assert!(parse_exact(bad).is_err(), "{bad:?} accepted");
        }
    }
}
