//! Exact rational numbers, [`Exact`]: the type the kernels run in for the proof-style checks
//! (including those of the scene-specialised kernels), the exact truth of the accuracy
//! report, `collide --exact` and the exact tangent dynamics.
//!
//! [`Rational`] wraps a big-rational representation ([`Backend`]) and gives the workspace the
//! small API it needs (construction from integers, ratios, floats and decimal digits; the
//! reduced numerator and denominator; `p/q` display and parsing; `to_f64`; comparisons), so
//! that no other crate names the bignum crate. [`Exact`] is `Rational` over dashu's reduced
//! rationals (`RBig`), chosen by measurement (docs/benchmarks.md, "Exact arithmetic").
//! [`ExactRelaxed`] keeps common factors between operations and is reduced only when it is
//! shown or converted back ([`Rational::reduced`]): the kernels' exact fast path
//! ([`Relaxing`], [`collide_exact`]).

mod backend;
pub mod decimal;
mod kernel;
mod ops;
mod root;
#[cfg(test)]
mod tests;

pub use backend::Backend;
pub use kernel::{collide_exact, Relaxing};
pub use root::ROOT_BITS;

use std::cmp::Ordering;
use std::fmt;
use std::str::FromStr;

/// An exact rational number held in the representation `B`. Equality, order and display
/// are by value, whatever common factors `B` keeps.
#[derive(Clone)]
pub struct Rational<B: Backend>(B);

/// Exact rational numbers, always reduced: the kernels instantiated with this type compute
/// the collision map with no rounding at all.
pub type Exact = Rational<dashu_ratio::RBig>;

/// Exact rationals whose operations skip the GCD (only common powers of 2 are removed): the
/// same values as [`Exact`], faster through a kernel's few dozen operations, reduced by
/// [`Rational::reduced`] at the end. Not for long chains of operations, where the unreduced
/// numbers grow.
pub type ExactRelaxed = Rational<dashu_ratio::Relaxed>;

/// The former exact type, num-rational's `BigRational`, behind the same API: only for the
/// side-by-side measurement and the old-vs-new equality test (feature `num-rational`).
#[cfg(feature = "num-rational")]
pub type ExactNumRational = Rational<num_rational::BigRational>;

/// A string that is not a rational `p`, `p/q` (decimal integers, `q != 0`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ParseRationalError(String);

impl fmt::Display for ParseRationalError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "not a rational p or p/q: {:?}", self.0)
    }
}

impl std::error::Error for ParseRationalError {}

impl<B: Backend> Rational<B> {
    /// The integer `k`.
    pub fn from_integer(k: i64) -> Self {
        Self(B::from_ratio(k, 1))
    }
    /// `num / den`; `None` if `den = 0`.
    pub fn checked_ratio(num: i64, den: i64) -> Option<Self> {
        (den != 0).then(|| Self(B::from_ratio(num, den)))
    }
    /// `num / den` from decimal digits (an optional sign, then digits); `None` if either is
    /// not an integer or `den` is zero.
    pub fn from_decimal(num: &str, den: &str) -> Option<Self> {
        B::from_decimal(num, den).map(Self)
    }
    /// The value of an exact rational of another type that displays as `p` or `p/q`
    /// (decimal integers, `q != 0`), such as the scene format's numbers; panics otherwise.
    pub fn from_fraction(x: &impl fmt::Display) -> Self {
        let text = x.to_string();
        text.parse()
            .unwrap_or_else(|e: ParseRationalError| panic!("{e}"))
    }
    /// The exact value of a finite `f64`; `None` for NaN and infinities.
    pub fn from_float(x: f64) -> Option<Self> {
        B::from_f64(x).map(Self)
    }
    /// `2^k`.
    pub fn pow2(k: i32) -> Self {
        Self::from_integer(2).pow(k)
    }
    /// `self^k`, `k` any integer (`0^k` for `k < 0` panics like a division by zero).
    pub fn pow(&self, k: i32) -> Self {
        let (mut x, mut base, mut e) = (Self::from_integer(1), self.clone(), k.unsigned_abs());
        while e > 0 {
            if e & 1 == 1 {
                x = &x * &base;
            }
            base = &base * &base;
            e >>= 1;
        }
        if k < 0 {
            x.recip()
        } else {
            x
        }
    }
    /// `1 / self`; panics if `self = 0`.
    pub fn recip(&self) -> Self {
        Self(B::div(&B::from_ratio(1, 1), &self.0))
    }
    /// Numerator and denominator of the reduced fraction (`q > 0`), as decimal integers.
    pub fn parts(&self) -> (String, String) {
        B::parts(&self.0)
    }
    /// The reduced numerator, in decimal.
    pub fn numer_string(&self) -> String {
        self.parts().0
    }
    /// The reduced denominator (positive), in decimal.
    pub fn denom_string(&self) -> String {
        self.parts().1
    }
    /// Whether the value is an integer.
    pub fn is_integer(&self) -> bool {
        self.parts().1 == "1"
    }
    /// The integer part, rounded toward zero.
    pub fn trunc(&self) -> Self {
        Self(B::trunc(&self.0))
    }
    /// The nearest `f64`, ties to even; `±inf` beyond its range, 0 or a subnormal below it.
    pub fn to_f64(&self) -> f64 {
        B::to_f64(&self.0)
    }
    /// The same value in the representation `C` (through the reduced fraction).
    pub fn convert<C: Backend>(&self) -> Rational<C> {
        let (p, q) = self.parts();
        Rational(C::from_decimal(&p, &q).expect("a reduced fraction's digits"))
    }
    /// The same value as a reduced [`Exact`].
    pub fn reduced(&self) -> Exact {
        self.convert()
    }
}

impl Exact {
    /// The same value in the relaxed representation, for a kernel's fast path.
    pub fn relax(&self) -> ExactRelaxed {
        Rational(self.0.clone().relax())
    }
}

impl Exact {
    /// The exact square root, if the value is the square of a rational (`p/q` reduced with
    /// `p`, `q` perfect squares); `None` otherwise.
    pub fn exact_sqrt(&self) -> Option<Exact> {
        use dashu_int::ops::SquareRoot;
        let (p, q) = (self.0.numerator(), self.0.denominator());
        let p = dashu_int::UBig::try_from(p.clone()).ok()?;
        let (sp, sq) = (p.sqrt(), q.sqrt());
        (&sp * &sp == p && &sq * &sq == *q)
            .then(|| Rational(dashu_ratio::RBig::from_parts(sp.into(), sq)))
    }
}

impl Exact {
    /// Write `p` or `p/q` as [`fmt::Display`] does, of `-self` when `negated` (without
    /// computing `-self`): reduced, `q > 0`, `0` for zero either way.
    pub fn write_decimal<W: fmt::Write>(&self, negated: bool, w: &mut W) -> fmt::Result {
        backend::write_rbig(&self.0, negated, w)
    }
}

impl ExactRelaxed {
    /// The reduced value, without going through decimal digits.
    pub fn canonical(&self) -> Exact {
        Rational(self.0.clone().canonicalize())
    }
}

impl<B: Backend> fmt::Display for Rational<B> {
    /// `p` for integers, else `p/q`, reduced, `q > 0`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if f.width().is_none() && f.precision().is_none() {
            return B::write(&self.0, f);
        }
        let (p, q) = self.parts();
        if q == "1" {
            f.pad(&p)
        } else {
            f.pad(&format!("{p}/{q}"))
        }
    }
}

impl<B: Backend> fmt::Debug for Rational<B> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(self, f)
    }
}

impl<B: Backend> FromStr for Rational<B> {
    type Err = ParseRationalError;
    /// `p` or `p/q`, decimal integers with an optional sign, `q != 0`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let (p, q) = s.split_once('/').unwrap_or((s, "1"));
        let digits = |d: &str| {
            let body = d.strip_prefix(['-', '+']).unwrap_or(d);
            !body.is_empty() && body.bytes().all(|b| b.is_ascii_digit())
        };
        if !digits(p) || !digits(q) {
            return Err(ParseRationalError(s.to_string()));
        }
        Self::from_decimal(p, q).ok_or_else(|| ParseRationalError(s.to_string()))
    }
}

impl<B: Backend> PartialEq for Rational<B> {
    fn eq(&self, other: &Self) -> bool {
        B::cmp(&self.0, &other.0) == Ordering::Equal
    }
}

impl<B: Backend> Eq for Rational<B> {}

impl<B: Backend> PartialOrd for Rational<B> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl<B: Backend> Ord for Rational<B> {
    fn cmp(&self, other: &Self) -> Ordering {
        B::cmp(&self.0, &other.0)
    }
}

impl std::hash::Hash for Exact {
    /// By value: `Exact` is always reduced.
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        self.0.hash(state)
    }
}

impl<B: Backend> Default for Rational<B> {
    fn default() -> Self {
        Self::from_integer(0)
    }
}

impl<B: Backend> From<i64> for Rational<B> {
    fn from(k: i64) -> Self {
        Self::from_integer(k)
    }
}

impl<B: Backend> From<i32> for Rational<B> {
    fn from(k: i32) -> Self {
        Self::from_integer(k.into())
    }
}
