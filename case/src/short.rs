//! Short numbers read in one pass: `[+-] digits`, `[+-] digits / digits` and `[+-] digits .
//! digits` (no exponent) with at most 18 digits in each integer read (so each fits an `i64`),
//! as the exact rational they spell, with no digit string parsed twice and no big integer.
//!
//! A decimal `m / 10^k` (`m` the digits without the point, `k` the digits after it) is
//! reduced by its 2s and 5s alone: `gcd(m, 10^k) = 2^a 5^b` with `a = min(v_2(m), k)` and
//! `b = min(v_5(m), k)`, so `m / 10^k = (m / (2^a 5^b)) / (2^(k-a) 5^(k-b))` in lowest
//! terms; an integer result is then made without any gcd (`Exact::from_integer`).
//!
//! Anything else (an exponent, more digits, a zero denominator, a malformed text) is not
//! read here (`None`): the general reader ([`crate::number`]) reads it, with its errors. Where
//! this reader answers, the value is the general reader's (tested on many inputs below).

use crate::fraction::Fraction;
use collision_core::{Exact, Scalar};
use num_traits::Zero;

/// The most digits of one integer read here: `10^18 - 1 < 2^63`.
const MOST: usize = 18;

/// The digits of `b` from `i` on, as `(value, end)`; `None` past [`MOST`] digits.
fn digits(b: &[u8], mut i: usize) -> Option<(i64, usize)> {
    let start = i;
    let mut value = 0i64;
    while let Some(&d) = b.get(i).filter(|d| d.is_ascii_digit()) {
        if i - start == MOST {
            return None;
        }
        value = value * 10 + i64::from(d - b'0');
        i += 1;
    }
    Some((value, i))
}

/// A short number's integers as read, before any reduction.
enum Short {
    /// `[+-] digits`.
    Integer(i64),
    /// `[+-] digits / digits`, the denominator positive.
    Ratio(i64, i64),
    /// `[+-] digits . digits`: `m / 10^k`.
    Decimal(i64, u32),
}

/// The integers of `text` if it is a short number (see the module); `None` otherwise.
fn scan(text: &str) -> Option<Short> {
    let b = text.as_bytes();
    let (negative, start) = match b.first() {
        Some(b'-') => (true, 1),
        Some(b'+') => (false, 1),
        _ => (false, 0),
    };
    let sign = |x: i64| if negative { -x } else { x };
    let (int, i) = digits(b, start)?;
    let int_len = i - start;
    match b.get(i) {
        None if int_len > 0 => Some(Short::Integer(sign(int))),
        Some(b'/') if int_len > 0 => {
            let (q, end) = digits(b, i + 1)?;
            (end > i + 1 && end == b.len() && q != 0).then(|| Short::Ratio(sign(int), q))
        }
        Some(b'.') => {
            let (frac, end) = digits(b, i + 1)?;
            let k = end - (i + 1);
            if end != b.len() || int_len + k == 0 || int_len + k > MOST {
                return None;
            }
            // `int_len + k <= 18` digits: `m < 10^18` fits.
            Some(Short::Decimal(
                sign(int * 10i64.pow(k as u32) + frac),
                k as u32,
            ))
        }
        _ => None,
    }
}

/// The exact value of `text` if it is a short number (see the module); `None` otherwise.
pub(crate) fn exact(text: &str) -> Option<Exact> {
    Some(match scan(text)? {
        Short::Integer(p) => Exact::from_integer(p),
        Short::Ratio(p, q) => Exact::from_ratio(p, q),
        Short::Decimal(0, _) => Exact::zero(),
        Short::Decimal(m, k) => match decimal(m, k) {
            (p, 1) => Exact::from_integer(p),
            (p, q) => Exact::from_ratio(p, q),
        },
    })
}

/// The value of `text` in lowest terms on machine integers if it is a short number (see the
/// module); `None` otherwise. The same value as [`exact`] (tested below).
pub(crate) fn fraction(text: &str) -> Option<Fraction> {
    Some(match scan(text)? {
        Short::Integer(p) => Fraction::integer(p),
        Short::Ratio(p, q) => Fraction::reduced(p, q),
        Short::Decimal(0, _) => Fraction::integer(0),
        Short::Decimal(m, k) => {
            let (p, q) = decimal(m, k);
            Fraction { p, q }
        }
    })
}

/// `m / 10^k` in lowest terms `(p, q)` by removing the common 2s and 5s (`m != 0`,
/// `k <= 18`).
fn decimal(m: i64, k: u32) -> (i64, i64) {
    let a = m.trailing_zeros().min(k);
    let mut p = m >> a;
    let mut b = 0;
    while b < k && p % 5 == 0 {
        p /= 5;
        b += 1;
    }
    (p, (1i64 << (k - a)) * 5i64.pow(k - b))
}
