//! Correctly rounded binary floats of exact rationals, for the literals of specialised
//! kernels (species constants folded at generation time), and their tokens.
//!
//! The rule for constants beyond a format's range: a rational whose correctly rounded `f64`
//! or `f32` is infinite (it overflows: `|x| >= MAX + ulp/2`) has no literal, and the
//! specialised kernels that need it are refused by the generator ([`overflows`]; the kernels
//! are generic over `f32`, `f64` and exact rationals, so each constant must exist in both
//! float formats). A constant that underflows rounds to a subnormal or to zero, as IEEE
//! arithmetic rounds it: the same value the generic kernel would receive as a parameter.

use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive};
use proc_macro2::{Literal, TokenStream};
use quote::quote;

/// The `f32` nearest to `x` (ties to even), from a candidate within an ulp or two.
fn nearest_f32(x: &BigRational, near: f32) -> f32 {
    let step = |v: f32, up: bool| {
        if v == 0.0 {
            if up {
                f32::from_bits(1)
            } else {
                -f32::from_bits(1)
            }
        } else if (v > 0.0) == up {
            f32::from_bits(v.to_bits() + 1)
        } else {
            f32::from_bits(v.to_bits() - 1)
        }
    };
    let err = |v: f32| (BigRational::from_float(v).expect("finite") - x).abs();
    let mut best = near;
    for c in [step(near, false), step(near, true)] {
        if !c.is_finite() {
            continue;
        }
        let (e, b) = (err(c), err(best));
        if e < b || (e == b && c.to_bits() & 1 == 0) {
            best = c;
        }
    }
    best
}

/// `(f64, f32)` nearest to `x`, each correctly rounded (ties to even). num-rational's
/// `to_f64` rounds correctly; the `f32` is found by exact comparison of the neighbours of
/// `f64 as f32` (which may double-round). Values beyond the range give infinities: IEEE
/// rounds `|x| >= MAX + ulp/2` to infinity, decided here on the exact `x`.
pub fn nearest_floats(x: &BigRational) -> (f64, f32) {
    let x64 = x.to_f64().unwrap_or(f64::NAN);
    let near = x64 as f32;
    let x32 = if near.is_finite() {
        nearest_f32(x, near)
    } else if x64.is_finite() {
        // `x64` may have rounded up onto the f32 overflow threshold from below it.
        let threshold = BigRational::from_float(f32::MAX).expect("finite")
            + BigRational::from_float(f32::MAX - f32::from_bits(f32::MAX.to_bits() - 1))
                .expect("finite")
                / BigRational::from_integer(2.into());
        match (x.abs() < threshold, x.is_negative()) {
            (true, false) => f32::MAX,
            (true, true) => -f32::MAX,
            (false, _) => near,
        }
    } else {
        near
    };
    (x64, x32)
}

/// The float format whose range `x` exceeds (`"f32"` or `"f64"`): its correctly rounded
/// value there is infinite. `None` if `x` has a finite literal in both.
pub fn overflows(x: &BigRational) -> Option<&'static str> {
    let (x64, x32) = nearest_floats(x);
    if !x64.is_finite() {
        Some("f64")
    } else if !x32.is_finite() {
        Some("f32")
    } else {
        None
    }
}

/// The tokens of a float literal with `suffix` for the finite `x`: exponent form with the
/// shortest digits that read back to `x` (`1e14f64`, `-2.5e-7f32`). The plain form
/// `100000000000000f64` would be an integer literal with a float suffix, which the
/// straight-line check of the generated code does not accept as a float literal.
fn float_tokens(text: String, negative: bool) -> TokenStream {
    let lit: Literal = text.parse().expect("an exponent-form float literal");
    if negative {
        quote!(-#lit)
    } else {
        quote!(#lit)
    }
}

/// An `f64` literal in exponent form (`1e14f64`); `x` must be finite.
pub fn f64_tokens(x: f64) -> TokenStream {
    assert!(x.is_finite(), "no literal for {x}");
    float_tokens(format!("{:e}f64", x.abs()), x.is_sign_negative())
}

/// An `f32` literal in exponent form (`1e14f32`); `x` must be finite.
pub fn f32_tokens(x: f32) -> TokenStream {
    assert!(x.is_finite(), "no literal for {x}");
    float_tokens(format!("{:e}f32", x.abs()), x.is_sign_negative())
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_bigint::BigInt;

    #[test]
    fn literals_are_float_literals_that_read_back_exactly() {
        for x in [
            1e14,
            1e-14,
            1e7,
            0.1,
            1.0,
            0.0,
            5e38,
            2e39,
            1e300,
            5e-324,
            -3.5e-7,
            -1e20,
            f64::MAX,
            f64::MIN_POSITIVE,
        ] {
            let tokens = f64_tokens(x);
            let expr: syn::Expr = syn::parse2(tokens.clone()).unwrap();
            let lit = match expr {
                syn::Expr::Lit(l) => l.lit,
                syn::Expr::Unary(u) => match *u.expr {
                    syn::Expr::Lit(l) => l.lit,
                    _ => panic!("{x}: {tokens} is not a literal"),
                },
                _ => panic!("{x}: {tokens} is not a literal"),
            };
            let syn::Lit::Float(f) = lit else {
                panic!("{x}: {tokens} is not a float literal")
            };
            assert_eq!(f.suffix(), "f64");
            let back: f64 = f.base10_parse().unwrap();
            assert_eq!(back, x.abs(), "{tokens}");
        }
        let tokens = f32_tokens(1e14f32);
        assert_eq!(tokens.to_string(), "1e14f32");
        let back: f32 = syn::parse2::<syn::LitFloat>(tokens)
            .unwrap()
            .base10_parse()
            .unwrap();
        assert_eq!(back, 1e14f32);
    }

    #[test]
    fn overflow_is_named_by_format() {
        let q = |p: &str, d: &str| BigRational::new(p.parse().unwrap(), d.parse().unwrap());
        assert_eq!(
            overflows(&q("340282346638528859811704183484516925440", "1")),
            None
        ); // f32::MAX
           // Just above MAX + ulp/2 = (2 - 2^-24) 2^127 = 340282356779733661637539395458142568448.
        assert_eq!(
            overflows(&q("340282356779733661637539395458142568449", "1")),
            Some("f32")
        );
        // The threshold itself rounds to infinity (ties to even: MAX is odd); one below it
        // rounds to MAX although its nearest f64 is the threshold.
        let at = q("340282356779733661637539395458142568448", "1");
        assert_eq!(overflows(&at), Some("f32"));
        let below = q("340282356779733661637539395458142568447", "1");
        assert_eq!(nearest_floats(&below).1, f32::MAX);
        assert_eq!(nearest_floats(&-below).1, -f32::MAX);
        assert_eq!(
            overflows(&q("-2", "1000000000000000000000000000000000000000")),
            None
        );
        let big = format!("5{}", "0".repeat(399));
        assert_eq!(overflows(&q(&big, "1")), Some("f64"));
        // Underflow rounds (to zero here), it does not overflow.
        assert_eq!(overflows(&q("1", &big)), None);
    }

    #[test]
    fn floats_are_nearest() {
        let q = |p: i64, d: i64| BigRational::new(BigInt::from(p), BigInt::from(d));
        assert_eq!(nearest_floats(&q(1, 10)), (0.1, 0.1f32));
        assert_eq!(nearest_floats(&q(-1, 3)), (-1.0 / 3.0, -1.0f32 / 3.0));
        // 1 + 2^-24 + 2^-60: f64 rounds to 1 + 2^-24, a tie in f32 that `as` breaks to even
        // (1.0); the true value is above the tie, so the nearest f32 is 1 + 2^-23.
        let two = BigInt::from(2);
        let x = BigRational::from_integer(1.into())
            + BigRational::new(1.into(), num_traits::pow(two.clone(), 24))
            + BigRational::new(1.into(), num_traits::pow(two, 60));
        assert_eq!(nearest_floats(&x).1, 1.0 + f32::EPSILON);
    }
}
