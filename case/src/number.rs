//! Numbers in the input, and how each scalar type reads and prints them.
//!
//! A number is a JSON number or a string holding a decimal (`1e-3`, `0.1`, `-2.5E+3`,
//! `.5`, `+4`) or a rational `p/q` (`3/5`, `-7/2`; `p` and `q` unsigned integers, the sign
//! in front). A JSON number is read from its literal text (serde_json's
//! `arbitrary_precision`), so `0.1` is 1/10 however it is written.
//!
//! A number has at most [`MAX_DIGITS`] digits (a decimal's mantissa, or a rational's numerator
//! and denominator together), in both modes, so that no input asks for a huge integer.
//!
//! - [`Exact`]: the number the text spells, exactly. The exponent of a decimal is limited
//!   to `|e| <=` [`MAX_EXACT_EXPONENT`] so that a short input cannot ask for a huge integer.
//! - `f64`: the nearest `f64` (round half to even): decimals by Rust's correctly rounded
//!   parser, rationals as the exact rational rounded once (num-rational's `to_f64`).
//!   Results beyond the `f64` range are errors; results below it round to (signed) zero.

use crate::error::{quote, CaseError};
use crate::node::Node;
use collision_core::{Exact, Scalar};
use num_traits::{ToPrimitive, Zero};
use serde_json::Value;
use std::str::FromStr;

/// The most digits of one number (the scene grammar's limit, the same for both).
pub use noslip_scene::MAX_DIGITS;

/// The largest `|e|` accepted in the exponent of a decimal in exact mode: beyond the range
/// of `f64` (`1e-324 .. 1.8e308`) with room, while keeping every case fast (a 3D case with
/// exponents near 10000 took seconds).
pub const MAX_EXACT_EXPONENT: u64 = 1000;

/// How many characters of a bad number a message quotes.
const QUOTE_CHARS: usize = 40;

/// A scalar the `collide` command can read from and print to JSON.
pub trait InputScalar: Scalar<Unbounded: collision_core::ScalarRoot> {
    /// The number `text` spells (see the module documentation); the error is a message.
    fn parse_number(text: &str) -> Result<Self, String>;
    /// The value as JSON output; `None` if it is not finite.
    fn to_json(&self) -> Option<Value>;
    /// Append the JSON text of [`InputScalar::to_json`] (serde_json's compact form) to
    /// `json`; `false` (nothing appended) if the value is not finite.
    fn write_json(&self, json: &mut String) -> bool {
        match self.to_json() {
            Some(v) => {
                json.push_str(&v.to_string());
                true
            }
            None => false,
        }
    }
    /// [`InputScalar::write_json`] of `0 - self` (`0 - x`, not `-x`: a zero stays `+0` in
    /// floats).
    fn write_negated_json(&self, json: &mut String) -> bool {
        (Self::zero() - self.clone()).write_json(json)
    }
    /// Whether `x`, read from `text`, is a nonzero number that lies below the normal range
    /// of the type: it was rounded to a subnormal or to zero, with an absolute error of up to
    /// half the smallest subnormal (`2^-1075` in `f64`) instead of `eps/2` of itself. Never
    /// in exact arithmetic.
    fn below_normal(text: &str, x: &Self) -> bool;
}

/// The absolute rounding error of an `f64` below the normal range, half the spacing of the
/// subnormals, as messages write it: `2^-1075` is itself below the smallest subnormal, so no
/// `f64` holds it (an `f64` constant for it is 0).
pub const SUBNORMAL_ERROR: &str = "2^-1075 (about 2.5e-324)";

impl InputScalar for Exact {
    /// A short number in one pass (`crate::short`), anything else by the scan.
    fn parse_number(text: &str) -> Result<Self, String> {
        if let Some(x) = crate::short::exact(text) {
            return Ok(x);
        }
        exact(&scan(text)?, text)
    }

    /// A reduced rational as a string: `"-3/5"`, `"2"`.
    fn to_json(&self) -> Option<Value> {
        Some(Value::String(self.to_string()))
    }

    /// `"p/q"` or `"p"` (a JSON string, no escapes needed), its digits written in place.
    fn write_json(&self, json: &mut String) -> bool {
        write_quoted(self, false, json)
    }

    /// `0 - x = -x` (`0` stays `0`), written without computing `-x`.
    fn write_negated_json(&self, json: &mut String) -> bool {
        write_quoted(self, true, json)
    }

    fn below_normal(_: &str, _: &Self) -> bool {
        false
    }
}

/// `"x"` (or `"-x"` if `negated`) into `json`: always finite.
fn write_quoted(x: &Exact, negated: bool, json: &mut String) -> bool {
    json.push('"');
    // Writing into a `String` cannot fail.
    let _ = x.write_decimal(negated, json);
    json.push('"');
    true
}

impl InputScalar for f64 {
    fn parse_number(text: &str) -> Result<Self, String> {
        let x = match scan(text)? {
            Scanned::Decimal { .. } => text.parse::<f64>().map_err(|_| malformed(text))?,
            ratio @ Scanned::Ratio { .. } => {
                ToPrimitive::to_f64(&exact(&ratio, text)?).unwrap_or(f64::INFINITY)
            }
        };
        if x.is_finite() {
            Ok(x)
        } else {
            Err(format!(
                "{} is out of the range of f64 (|x| < 1.8e308)",
                quote(text, QUOTE_CHARS)
            ))
        }
    }

    /// Rust's shortest round-trip form (`{:?}`): `2.0`, `-0.0`, `0.1`, `1e-300`, `1.5e300`
    /// (printed by serde_json as `1.5e+300`). Always a valid JSON number.
    fn to_json(&self) -> Option<Value> {
        if !self.is_finite() {
            return None;
        }
        serde_json::Number::from_str(&format!("{self:?}"))
            .ok()
            .map(Value::Number)
    }

    fn below_normal(text: &str, x: &Self) -> bool {
        if *x != 0.0 {
            return x.abs() < f64::MIN_POSITIVE;
        }
        // A zero read from a nonzero number: an underflow.
        match scan(text) {
            Ok(Scanned::Decimal { int, frac, .. }) => {
                int.bytes().chain(frac.bytes()).any(|c| c != b'0')
            }
            Ok(Scanned::Ratio { numer, .. }) => numer.bytes().any(|c| c != b'0'),
            Err(_) => false,
        }
    }
}

/// Read the number at `field` of a case: a JSON number or a string.
pub fn from_json<T: InputScalar, V: Node>(value: &V, field: &str) -> Result<T, CaseError> {
    read(value, false)
        .map(|(x, _)| x)
        .map_err(|m| CaseError::new(field, m))
}

/// [`from_json`] for a scalar of a body (mass, radius, lambda, gamma2): one that lies below
/// the normal range of `T` is refused, since it would be read with less than `T`'s
/// relative precision (a radius `4e-324` is read as `4.94e-324`, 23% off); with `floats`, a
/// JSON number is a float of `T` in its shortest round-trip form and is taken as that float
/// ([`crate::case::Case::from_floats`]).
pub fn scalar_from_json<T: InputScalar, V: Node>(
    value: &V,
    field: &str,
    floats: bool,
) -> Result<T, CaseError> {
    let (x, tiny) = read::<T, V>(value, floats).map_err(|m| CaseError::new(field, m))?;
    if tiny {
        return Err(CaseError::new(
            field,
            format!(
                "{} is below the normal range of {} (magnitudes under {:e}), where it would \
                 be read as {} with less than {}'s precision; --exact reads it as written",
                number_text(value).map_or_else(String::new, |t| quote(t, QUOTE_CHARS)),
                T::NAME,
                f64::MIN_POSITIVE,
                format_args!("{:.16e}", x.to_f64()),
                T::NAME,
            ),
        ));
    }
    Ok(x)
}

/// The number `value` holds and whether it was rounded below the normal range of `T`
/// ([`InputScalar::below_normal`]); with `floats`, a JSON number is a float of `T` in its
/// shortest round-trip form ([`crate::case::Case::from_floats`]): read as that float, it
/// lost nothing. The error is the message for the number's field.
pub(crate) fn read<T: InputScalar, V: Node>(value: &V, floats: bool) -> Result<(T, bool), String> {
    let Some(text) = number_text(value) else {
        return Err(format!(
            "expected a number (a JSON number or a string such as \"3/5\"), got {}",
            value.kind()
        ));
    };
    let x = T::parse_number(text)?;
    let tiny = T::below_normal(text, &x) && !(floats && value.is_number());
    Ok((x, tiny))
}

/// The text of a JSON number or string.
pub(crate) fn number_text<V: Node>(value: &V) -> Option<&str> {
    value.as_number().or_else(|| value.as_str())
}

/// The parts of a number's text, checked against the grammar.
#[derive(Debug, PartialEq, Eq)]
enum Scanned<'a> {
    /// `[+-] int [. frac] [e exp]`: `int` and `frac` digits (one of them non-empty), `exp` a
    /// signed integer.
    Decimal {
        negative: bool,
        int: &'a str,
        frac: &'a str,
        exp: Option<&'a str>,
    },
    /// `[+-] numer / denom`, both non-empty digit strings.
    Ratio {
        negative: bool,
        numer: &'a str,
        denom: &'a str,
    },
}

fn malformed(text: &str) -> String {
    format!(
        "malformed number {}: expected a decimal (0.1, -2.5e3) or a rational (-7/2)",
        quote(text, QUOTE_CHARS)
    )
}

fn digits(s: &str) -> bool {
    !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit())
}

/// Refuse a number with more than [`MAX_DIGITS`] digits in `parts`.
fn digit_limit(text: &str, parts: &[&str]) -> Result<(), String> {
    let count: usize = parts.iter().map(|p| p.len()).sum();
    if count > MAX_DIGITS {
        return Err(format!(
            "{} has {count} digits: at most {MAX_DIGITS} are accepted",
            quote(text, QUOTE_CHARS)
        ));
    }
    Ok(())
}

fn scan(text: &str) -> Result<Scanned<'_>, String> {
    let (negative, body) = match text.as_bytes().first() {
        Some(b'-') => (true, &text[1..]),
        Some(b'+') => (false, &text[1..]),
        _ => (false, text),
    };
    if ["inf", "infinity", "nan"]
        .iter()
        .any(|w| body.eq_ignore_ascii_case(w))
    {
        return Err(format!(
            "{} is not a finite number (NaN and infinities are rejected; a mass may be \"inf\")",
            quote(text, QUOTE_CHARS)
        ));
    }
    if let Some((numer, denom)) = body.split_once('/') {
        return if digits(numer) && digits(denom) {
            digit_limit(text, &[numer, denom])?;
            Ok(Scanned::Ratio {
                negative,
                numer,
                denom,
            })
        } else {
            Err(malformed(text))
        };
    }
    let (mantissa, exp) = match body.find(['e', 'E']) {
        Some(k) => (&body[..k], Some(&body[k + 1..])),
        None => (body, None),
    };
    let (int, frac) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    let part = |s: &str| s.is_empty() || digits(s);
    let exp_ok = match exp {
        None => true,
        Some(e) => digits(e.strip_prefix(['+', '-']).unwrap_or(e)),
    };
    if part(int) && part(frac) && !(int.is_empty() && frac.is_empty()) && exp_ok {
        digit_limit(text, &[int, frac])?;
        Ok(Scanned::Decimal {
            negative,
            int,
            frac,
            exp,
        })
    } else {
        Err(malformed(text))
    }
}

fn exact(scanned: &Scanned<'_>, text: &str) -> Result<Exact, String> {
    let (negative, value) = match *scanned {
        Scanned::Ratio {
            negative,
            numer,
            denom,
        } => {
            if let (Some(p), Some(q)) = (small(numer), small(denom).filter(|&q| q != 0)) {
                let value = Exact::from_ratio(p, q);
                return Ok(if negative { -value } else { value });
            }
            // The scanner let only ASCII digits through: `None` means a zero denominator.
            let Some(value) = Exact::from_decimal(numer, denom) else {
                return Err(format!("zero denominator in {}", quote(text, QUOTE_CHARS)));
            };
            (negative, value)
        }
        Scanned::Decimal {
            negative,
            int,
            frac,
            exp,
        } => {
            if int.bytes().chain(frac.bytes()).all(|b| b == b'0') {
                return Ok(Exact::zero());
            }
            let out_of_range = || {
                format!(
                    "the exponent of {} is out of range: at most {MAX_EXACT_EXPONENT} in magnitude",
                    quote(text, QUOTE_CHARS)
                )
            };
            let e = match exp {
                None => 0,
                Some(e) => e.parse::<i64>().map_err(|_| out_of_range())?,
            };
            if e.unsigned_abs() > MAX_EXACT_EXPONENT {
                return Err(out_of_range());
            }
            let shift = e - frac.len() as i64;
            if let Some(value) = small_decimal(int, frac, shift) {
                return Ok(if negative { -value } else { value });
            }
            // 10^|shift| in digits: a 1 and |shift| zeros.
            let power = format!("1{}", "0".repeat(shift.unsigned_abs() as usize));
            let mantissa = format!("{int}{frac}");
            let value = if shift >= 0 {
                Exact::from_decimal(&format!("{mantissa}{}", &power[1..]), "1")
            } else {
                Exact::from_decimal(&mantissa, &power)
            }
            .expect("decimal digits and a nonzero power of 10");
            (negative, value)
        }
    };
    Ok(if negative { -value } else { value })
}

/// The value of a string of at most 18 ASCII digits (below `10^18`, so it fits an `i64`);
/// `None` for a longer one.
fn small(digits: &str) -> Option<i64> {
    (digits.len() <= 18).then(|| {
        digits
            .bytes()
            .fold(0i64, |v, d| v * 10 + i64::from(d - b'0'))
    })
}

/// `int.frac 10^(shift + |frac|)`, that is the integer of the digits `int frac` times
/// `10^shift`, when those digits and `10^|shift|` fit in 18 digits: the same reduced
/// rational as from the digit strings, without parsing big integers. `None` otherwise.
fn small_decimal(int: &str, frac: &str, shift: i64) -> Option<Exact> {
    if int.len() + frac.len() > 18 || shift.unsigned_abs() > 18 {
        return None;
    }
    let mantissa = small(int)? * 10i64.pow(frac.len() as u32) + small(frac)?;
    let power = 10i64.pow(shift.unsigned_abs() as u32);
    if shift >= 0 {
        mantissa.checked_mul(power).map(Exact::from_integer)
    } else {
        Some(Exact::from_ratio(mantissa, power))
    }
}

/// `x` is a non-negative integer literal (for `dim`): its value, saturating at `usize::MAX`;
/// `None` if `x` is not written as an integer.
pub fn integer_literal(text: &str) -> Option<(bool, usize)> {
    let (negative, body) = match text.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, text),
    };
    if !digits(body) {
        return None;
    }
    // Only ASCII digits: the one parse error left is overflow.
    let value = body.parse::<usize>().unwrap_or(usize::MAX);
    Some((negative && value != 0, value))
}

#[cfg(test)]
#[path = "number_tests.rs"]
mod tests;
