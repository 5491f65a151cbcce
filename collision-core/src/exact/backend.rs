//! The big-rational representations [`Rational`](super::Rational) can hold: a small sealed
//! interface, so that the choice is made (and measured, `accuracy/examples/exact_backends.rs`) in one
//! place and no other crate names a bignum crate.

use super::decimal::write_words;
use dashu_int::IBig;
use dashu_ratio::{RBig, Relaxed};
use std::cmp::Ordering;
use std::fmt;

mod sealed {
    pub trait Sealed {}
    impl Sealed for dashu_ratio::RBig {}
    impl Sealed for dashu_ratio::Relaxed {}
    #[cfg(feature = "num-rational")]
    impl Sealed for num_rational::BigRational {}
}

/// What [`Rational`](super::Rational) needs of a representation. Every method is exact;
/// the comparisons and [`Backend::parts`] are by value (a representation may keep common
/// factors of numerator and denominator).
pub trait Backend: sealed::Sealed + Clone + Send + Sync + 'static {
    /// `num / den`, `den != 0`.
    fn from_ratio(num: i64, den: i64) -> Self;
    /// `num / den` from decimal digits with an optional sign; `None` if either is not an
    /// integer or `den` is zero.
    fn from_decimal(num: &str, den: &str) -> Option<Self>;
    /// The exact value of a finite `f64`.
    fn from_f64(x: f64) -> Option<Self>;
    /// `a + b`.
    fn add(a: &Self, b: &Self) -> Self;
    /// `a - b`.
    fn sub(a: &Self, b: &Self) -> Self;
    /// `a b`.
    fn mul(a: &Self, b: &Self) -> Self;
    /// `a / b`; panics if `b = 0`, like integer division.
    fn div(a: &Self, b: &Self) -> Self;
    /// `-a`.
    fn neg(a: &Self) -> Self;
    /// The integer part, rounded toward zero.
    fn trunc(a: &Self) -> Self;
    /// The order of the values.
    fn cmp(a: &Self, b: &Self) -> Ordering;
    /// The sign: `Less`, `Equal` or `Greater` than zero.
    fn sign(a: &Self) -> Ordering;
    /// Numerator and denominator of the reduced fraction (`q > 0`), in decimal.
    fn parts(a: &Self) -> (String, String);
    /// `p`, or `p/q` when `q > 1`, of the reduced fraction, written into `f` (whose width
    /// and precision are unset).
    fn write(a: &Self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (p, q) = Self::parts(a);
        f.write_str(&p)?;
        if q != "1" {
            f.write_str("/")?;
            f.write_str(&q)?;
        }
        Ok(())
    }
    /// The nearest `f64` (ties to even); `±inf` beyond its range.
    fn to_f64(a: &Self) -> f64;
}

/// `p` or `p/q` of `a` (of `-a` if `negated`), reduced, `q > 0`: the words of `p` and `q`
/// converted to decimal by [`super::decimal::write_words`].
pub(super) fn write_rbig<W: fmt::Write>(a: &RBig, negated: bool, w: &mut W) -> fmt::Result {
    let (sign, p) = a.numerator().as_sign_words();
    if (sign == dashu_int::Sign::Negative) != negated && *a.numerator() != IBig::ZERO {
        w.write_char('-')?;
    }
    write_words(p, w)?;
    let q = a.denominator();
    if !q.is_one() {
        w.write_char('/')?;
        write_words(q.as_words(), w)?;
    }
    Ok(())
}

fn ibig(digits: &str) -> Option<IBig> {
    digits.strip_prefix('+').unwrap_or(digits).parse().ok()
}

/// `add`, `sub`, `mul`, `div` and `neg` of a [`Backend`] by the type's own operators on
/// references (every representation here has them).
macro_rules! by_operators {
    () => {
        #[inline]
        fn add(a: &Self, b: &Self) -> Self {
            a + b
        }
        #[inline]
        fn sub(a: &Self, b: &Self) -> Self {
            a - b
        }
        #[inline]
        fn mul(a: &Self, b: &Self) -> Self {
            a * b
        }
        #[inline]
        fn div(a: &Self, b: &Self) -> Self {
            a / b
        }
        #[inline]
        fn neg(a: &Self) -> Self {
            -a
        }
    };
}

impl Backend for RBig {
    /// An integer (`den = 1`, or `num = 0`) is made without a gcd, as `RBig::from(num)`:
    /// `num / 1` is reduced already. Other ratios are reduced by dashu.
    fn from_ratio(num: i64, den: i64) -> Self {
        if den == 1 || (num == 0 && den != 0) {
            return RBig::from(num);
        }
        RBig::from_parts_signed(IBig::from(num), IBig::from(den))
    }
    fn from_decimal(num: &str, den: &str) -> Option<Self> {
        let (p, q) = (ibig(num)?, ibig(den)?);
        (q != IBig::ZERO).then(|| RBig::from_parts_signed(p, q))
    }
    fn from_f64(x: f64) -> Option<Self> {
        RBig::try_from(x).ok()
    }
    // `0 + b = b`, `a + 0 = a`, `a - 0 = a`, `0 b = a 0 = 0`: the reduced value at once,
    // without dashu's cross gcds (an exact case has many zeros: the diagonal of every
    // angular velocity, an immovable body's state).
    fn add(a: &Self, b: &Self) -> Self {
        if a.is_zero() {
            b.clone()
        } else if b.is_zero() {
            a.clone()
        } else {
            a + b
        }
    }
    fn sub(a: &Self, b: &Self) -> Self {
        if b.is_zero() {
            a.clone()
        } else if a.is_zero() {
            -b
        } else {
            a - b
        }
    }
    fn mul(a: &Self, b: &Self) -> Self {
        if a.is_zero() || b.is_zero() {
            RBig::ZERO
        } else {
            a * b
        }
    }
    #[inline]
    fn div(a: &Self, b: &Self) -> Self {
        a / b
    }
    #[inline]
    fn neg(a: &Self) -> Self {
        -a
    }
    fn trunc(a: &Self) -> Self {
        RBig::from(a.trunc())
    }
    fn cmp(a: &Self, b: &Self) -> Ordering {
        Ord::cmp(a, b)
    }
    fn sign(a: &Self) -> Ordering {
        Ord::cmp(a.numerator(), &IBig::ZERO)
    }
    fn parts(a: &Self) -> (String, String) {
        (a.numerator().to_string(), a.denominator().to_string())
    }
    /// The digits go straight into `f`, with no string of their own (`write_rbig`: the
    /// words converted by `decimal::write_words`).
    fn write(a: &Self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write_rbig(a, false, f)
    }
    fn to_f64(a: &Self) -> f64 {
        a.to_f64().value()
    }
}

/// Numerator times the other denominator: the cross products that order two fractions with
/// positive denominators.
fn cross(a: &Relaxed, b: &Relaxed) -> (IBig, IBig) {
    let d = |x: &Relaxed| IBig::from(x.denominator().clone());
    (a.numerator() * d(b), b.numerator() * d(a))
}

impl Backend for Relaxed {
    fn from_ratio(num: i64, den: i64) -> Self {
        Relaxed::from_parts_signed(IBig::from(num), IBig::from(den))
    }
    fn from_decimal(num: &str, den: &str) -> Option<Self> {
        RBig::from_decimal(num, den).map(RBig::relax)
    }
    fn from_f64(x: f64) -> Option<Self> {
        RBig::try_from(x).ok().map(RBig::relax)
    }
    by_operators!();
    fn trunc(a: &Self) -> Self {
        RBig::from(a.trunc()).relax()
    }
    fn cmp(a: &Self, b: &Self) -> Ordering {
        let (x, y) = cross(a, b);
        Ord::cmp(&x, &y)
    }
    fn sign(a: &Self) -> Ordering {
        Ord::cmp(a.numerator(), &IBig::ZERO)
    }
    fn parts(a: &Self) -> (String, String) {
        Backend::parts(&a.clone().canonicalize())
    }
    fn to_f64(a: &Self) -> f64 {
        a.clone().canonicalize().to_f64().value()
    }
}

#[cfg(feature = "num-rational")]
impl Backend for num_rational::BigRational {
    fn from_ratio(num: i64, den: i64) -> Self {
        Self::new(num.into(), den.into())
    }
    fn from_decimal(num: &str, den: &str) -> Option<Self> {
        let parse = |d: &str| d.parse::<num_bigint::BigInt>().ok();
        let (p, q) = (parse(num)?, parse(den)?);
        (q != 0.into()).then(|| Self::new(p, q))
    }
    fn from_f64(x: f64) -> Option<Self> {
        Self::from_float(x)
    }
    by_operators!();
    fn trunc(a: &Self) -> Self {
        a.trunc()
    }
    fn cmp(a: &Self, b: &Self) -> Ordering {
        Ord::cmp(a, b)
    }
    fn sign(a: &Self) -> Ordering {
        Ord::cmp(a.numer(), &0.into())
    }
    fn parts(a: &Self) -> (String, String) {
        (a.numer().to_string(), a.denom().to_string())
    }
    fn to_f64(a: &Self) -> f64 {
        num_traits::ToPrimitive::to_f64(a).unwrap_or(f64::NAN)
    }
}
