//! Correctly rounded binary floats of exact rationals, for the literals of specialised
//! kernels (species constants folded at generation time).

use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive};

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
/// `f64 as f32` (which may double-round). Values beyond the range give infinities.
pub fn nearest_floats(x: &BigRational) -> (f64, f32) {
    let x64 = x.to_f64().unwrap_or(f64::NAN);
    let near = x64 as f32;
    let x32 = if near.is_finite() {
        nearest_f32(x, near)
    } else {
        near
    };
    (x64, x32)
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_bigint::BigInt;

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
