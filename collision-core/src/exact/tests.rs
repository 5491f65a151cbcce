use super::*;
use crate::Scalar;
use num_traits::{One, Signed, Zero};

fn q(p: i64, d: i64) -> Exact {
    Exact::from_ratio(p, d)
}

#[test]
fn values_are_reduced_with_a_positive_denominator() {
    assert_eq!(q(6, -4).parts(), ("-3".to_string(), "2".to_string()));
    assert_eq!(q(0, -7).parts(), ("0".to_string(), "1".to_string()));
    assert_eq!(q(6, -4).to_string(), "-3/2");
    assert_eq!(q(8, 4).to_string(), "2");
    assert!(q(8, 4).is_integer() && !q(1, 2).is_integer());
}

#[test]
fn parsing_round_trips_and_rejects_what_is_not_p_over_q() {
    for s in ["0", "-3/2", "7", "123456789012345678901234567891/7"] {
        assert_eq!(s.parse::<Exact>().unwrap().to_string(), s);
    }
    assert_eq!("+4/-6".parse::<Exact>().unwrap(), q(-2, 3));
    for bad in ["", "1/0", "1.5", "a/2", "1/", "/2", "1/2/3", "--1"] {
        assert!(bad.parse::<Exact>().is_err(), "{bad:?}");
    }
}

#[test]
fn arithmetic_order_and_signs() {
    let (a, b) = (q(1, 3), q(-3, 7));
    assert_eq!(&a + &b, q(-2, 21));
    assert_eq!(&a - &b, q(16, 21));
    assert_eq!(&a * &b, q(-1, 7));
    assert_eq!(&a / &b, q(-7, 9));
    assert_eq!(-&a, q(-1, 3));
    assert!(b < a && a > Exact::zero() && b.is_negative() && a.is_positive());
    assert_eq!(b.abs(), q(3, 7));
    assert_eq!(b.signum(), -Exact::one());
    assert_eq!(q(7, 2) % q(1, 1), q(1, 2));
    assert_eq!(q(-7, 2).trunc(), q(-3, 1));
    assert_eq!(Exact::pow2(-3), q(1, 8));
    assert_eq!(q(2, 3).pow(-2), q(9, 4));
    assert_eq!([q(1, 2), q(1, 3)].iter().sum::<Exact>(), q(5, 6));
}

#[test]
fn floats_convert_exactly_and_back_correctly_rounded() {
    assert_eq!(
        Exact::from_float(0.1).unwrap().denom_string(),
        (1u64 << 55).to_string()
    );
    assert_eq!(Exact::from_float(f64::NAN), None);
    assert_eq!(q(1, 3).to_f64(), 1.0 / 3.0);
    assert_eq!(q(2, 3).to_f64(), 2.0 / 3.0);
    // 1 + 2^-53 is a tie between 1 and 1 + 2^-52: ties go to even, 1.
    assert_eq!((Exact::one() + Exact::pow2(-53)).to_f64(), 1.0);
    assert_eq!(
        (Exact::one() + Exact::pow2(-53) + Exact::pow2(-80)).to_f64(),
        1.0 + f64::EPSILON
    );
    assert_eq!(Exact::pow2(2000).to_f64(), f64::INFINITY);
}

#[test]
fn the_relaxed_form_has_the_same_values() {
    // 1/6 + 1/3 = 1/2 keeps the factor 3 unreduced, and still compares and shows as 1/2.
    let (a, b) = (q(1, 6).relax(), q(1, 3).relax());
    let sum = &a + &b;
    assert_eq!(sum, q(1, 2).relax());
    assert_eq!(sum.to_string(), "1/2");
    assert_eq!(sum.canonical(), q(1, 2));
    assert_eq!(sum.reduced(), q(1, 2));
    assert!(q(1, 3).relax() > q(-1, 2).relax());
    assert_eq!((&a - &a), ExactRelaxed::zero());
}

/// `write_decimal` (and so `Display`) gives dashu's digits of the reduced numerator and
/// denominator (`parts`), and with `negated` those of `-x`; `0` has no sign either way.
#[test]
fn decimal_writing_gives_dashus_digits_and_negation() {
    let big = [Exact::pow2(-300) * q(-5, 3), Exact::pow2(2100) * q(1, 3)];
    let small = [
        q(0, 1),
        q(-3, 2),
        q(7, 1),
        q(-1, 1),
        q(i64::MAX, 3),
        q(i64::MIN + 1, 7),
    ];
    for x in small.into_iter().chain(big) {
        for negated in [false, true] {
            let (p, q) = if negated { (-&x).parts() } else { x.parts() };
            let want = if q == "1" { p } else { format!("{p}/{q}") };
            let mut s = String::new();
            x.write_decimal(negated, &mut s).unwrap();
            assert_eq!(s, want);
        }
        assert_eq!(x.to_string(), {
            let mut s = String::new();
            x.write_decimal(false, &mut s).unwrap();
            s
        });
    }
}
