//! Tests of the unbounded-exponent floats (`wide.rs`).

use super::*;
use crate::Exact;
use num_traits::ToPrimitive;

type W = Wide<f64>;

fn w(x: f64) -> W {
    W::from(x)
}

/// `m 2^e` exactly.
fn exact(x: W) -> Exact {
    let m = Exact::from_float(x.m).unwrap();
    let p = num_traits::pow(Exact::from_integer(2), x.e.unsigned_abs() as usize);
    if x.e >= 0 {
        m * p
    } else {
        m / p
    }
}

/// A deterministic spread of f64 values: both signs, normal and subnormal magnitudes,
/// mantissas near 1 and 2 (carries and halfway cases).
fn samples() -> Vec<f64> {
    let mut s = 0x9E37_79B9_7F4A_7C15_u64;
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        s
    };
    let mut out = vec![
        1.0,
        -1.0,
        1.5,
        3.0,
        f64::MAX,
        f64::MIN_POSITIVE,
        5e-324,
        -0.5,
    ];
    for _ in 0..300 {
        let x = f64::from_bits(next());
        if x.is_finite() && x != 0.0 {
            out.push(x);
        }
        out.push(f64::from_bits(0x3FF0_0000_0000_0000 | (next() & 0xF)));
        out.push(-f64::from_bits(0x3FFF_FFFF_FFFF_FFF0 | (next() & 0xF)));
    }
    out
}

#[test]
fn in_range_operations_are_f64_bit_for_bit() {
    // Sums are exact or correctly rounded in f64 (subnormal sums are exact), so they agree
    // everywhere, overflow included; products and quotients agree wherever f64's result
    // is normal or infinite (below, f64 rounds once into the subnormal grid and Wide
    // twice).
    let xs = samples();
    let normal = |f: f64| f.is_infinite() || f.abs() >= 2.0 * f64::MIN_POSITIVE;
    for (i, &a) in xs.iter().enumerate() {
        for (j, &b) in xs.iter().enumerate().skip(i % 7).step_by(23) {
            let c = xs[(i + j) % xs.len()];
            let bits = |x: W| x.round().to_bits();
            assert_eq!(bits(w(a) + w(b)), (a + b).to_bits(), "{a:e} + {b:e}");
            assert_eq!(bits(w(a) - w(b)), (a - b).to_bits(), "{a:e} - {b:e}");
            for (op, f, wide) in [("*", a * b, w(a) * w(b)), ("/", a / b, w(a) / w(b))] {
                if normal(f) {
                    assert_eq!(bits(wide), f.to_bits(), "{a:e} {op} {b:e}");
                }
            }
            let fused = a.mul_add(b, c);
            if normal(fused) {
                assert_eq!(bits(W::mul_add(&w(a), &w(b), &w(c))), fused.to_bits());
            }
            assert_eq!(
                w(a).partial_cmp(&w(b)),
                a.partial_cmp(&b),
                "{a:e} <=> {b:e}"
            );
            assert_eq!(bits(w(a) % w(b)), (a % b).to_bits(), "{a:e} % {b:e}");
        }
    }
}

#[test]
fn results_outside_f64_are_correctly_rounded() {
    // One operation on operands far outside the f64 range, against exact rationals:
    // got = want (1 + d), |d| <= eps/2.
    let xs = samples();
    let half_eps = Exact::from_float(f64::EPSILON / 2.0).unwrap();
    for (i, &a) in xs.iter().enumerate().step_by(37) {
        for &b in xs.iter().skip(i % 5).step_by(97) {
            let big = w(a) * w(f64::MAX) * w(8.0);
            let small = w(b) * w(5e-324) / w(16.0);
            let near = big * w(1.0 + f64::EPSILON);
            for (got, want) in [
                (big * small, exact(big) * exact(small)),
                (big / small, exact(big) / exact(small)),
                (big + w(b), exact(big) + exact(w(b))),
                (near - big, exact(near) - exact(big)),
                (small + small * w(b), exact(small) + exact(small * w(b))),
                (
                    W::mul_add(&big, &small, &w(b)),
                    exact(big) * exact(small) + exact(w(b)),
                ),
                (big % small, {
                    let q = (exact(big) / exact(small)).trunc();
                    exact(big) - q * exact(small)
                }),
            ] {
                let err = (exact(got) - want.clone()).abs();
                assert!(
                    err <= want.abs() * half_eps.clone(),
                    "{got} against {:e}",
                    ToPrimitive::to_f64(&want).unwrap_or(0.0)
                );
            }
        }
    }
}

#[test]
fn rounding_to_f64_handles_overflow_subnormals_and_zero() {
    let max = w(f64::MAX);
    assert_eq!((max * w(2.0)).round(), f64::INFINITY);
    assert_eq!((-max * w(2.0)).round(), f64::NEG_INFINITY);
    assert_eq!((max * w(2.0) / w(2.0)).round(), f64::MAX);
    // 2^-1074; half of it is a tie (to even: zero); 3/4 and 3/2 of it round to 1 and 2.
    let min = w(5e-324);
    assert_eq!(min.round(), 5e-324);
    assert_eq!((min / w(2.0)).round(), 0.0);
    assert_eq!((min * w(0.75)).round(), 5e-324);
    assert_eq!((min * w(1.5)).round(), 1e-323);
    assert_eq!((min * min).round(), 0.0);
    assert!((-(min * min)).round().is_sign_negative());
    let m = f64::MIN_POSITIVE;
    assert_eq!((w(3.0) * w(m) / w(4.0)).round(), 3.0 * m / 4.0);
    // Special values pass through.
    assert!((w(1.0) / w(0.0)).round().is_infinite());
    assert!((w(0.0) / w(0.0)).round().is_nan());
    assert_eq!(w(-0.0).round().to_bits(), (-0.0f64).to_bits());
    assert_eq!(w(1.0) % (w(1.0) / w(0.0)), w(1.0));
}

#[test]
fn far_apart_sums_and_fused_products_round_correctly() {
    let huge = w(1e300) * w(1e300);
    assert_eq!(huge + w(1.0), huge);
    assert_eq!(w(1.0) + huge * w(0.0), w(1.0));
    assert_eq!((w(1.0) - w(1e-300) * w(1e-300)).round(), 1.0);
    // (1 + 2^-30)^2 - 1 fused is exact, also scaled by 2^2000.
    let a = w(1.0 + 2f64.powi(-30));
    let want = 2f64.powi(-29) + 2f64.powi(-60);
    assert_eq!(W::mul_add(&a, &a, &w(-1.0)).round(), want);
    let s = w(2f64.powi(1000)) * w(2f64.powi(1000));
    assert_eq!((W::mul_add(&(a * s), &a, &-s) / s).round(), want);
    // f32 mantissas round to f32.
    let third = Wide::<f32>::from(1.0) / Wide::from(3.0);
    assert_eq!(third.round(), 1.0f32 / 3.0);
    let big = Wide::<f32>::from(f32::MAX) * Wide::from(4.0);
    assert_eq!((big / Wide::from(8.0)).round(), f32::MAX / 2.0);
    assert_eq!(big.to_f64(), f64::from(f32::MAX) * 4.0);
}

#[test]
fn display_shows_the_magnitude() {
    assert_eq!(w(0.1).to_string(), "0.1");
    let big = w(1e300) * w(1e100);
    assert!(big.to_string().ends_with("e400"), "{big}");
    assert!(big.to_string().starts_with("1.0000"), "{big}");
    assert!((-(w(1e-300) * w(1e-300)))
        .to_string()
        .starts_with("-1.0000"));
}

/// `Wide`'s root is `F`'s in range (both correctly rounded), and out of range `sqrt` of
/// the correctly rounded square of `a` is `|a|` exactly, as in IEEE arithmetic without
/// overflow or underflow.
#[test]
fn wide_roots_are_correctly_rounded() {
    let bits = |x: Wide<f64>| x.round().to_bits();
    for a in [
        0.0,
        5e-324,
        1e-310,
        0.3,
        1.0,
        2.0,
        3.0,
        7.5,
        1e300,
        f64::MAX,
    ] {
        assert_eq!(
            bits(ScalarRoot::sqrt(&Wide::from(a))),
            a.sqrt().to_bits(),
            "{a:e}"
        );
        for b in [a, -a] {
            let w = Wide::from(b);
            assert_eq!(
                bits(ScalarRoot::sqrt(&(w * w))),
                a.to_bits(),
                "sqrt({b:e}^2)"
            );
        }
    }
    assert!(ScalarRoot::sqrt(&Wide::from(-1.0f64)).round().is_nan());
    assert_eq!(
        bits(ScalarRoot::sqrt(&Wide::from(f64::INFINITY))),
        f64::INFINITY.to_bits()
    );
}
