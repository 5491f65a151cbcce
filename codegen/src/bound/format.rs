//! The floating-point formats a kernel runs in, as the rounding model needs them.

use super::round::{mul_up, pow2_floor};
use num_rational::BigRational;
use num_traits::{FromPrimitive, Signed, ToPrimitive};

/// A binary floating-point format with round-to-nearest: its precision `p` (significand
/// bits, the hidden one included), its smallest normal exponent `e_min` and its largest
/// finite value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Format {
    /// `"f64"` or `"f32"`.
    pub name: &'static str,
    /// `p`: 53 or 24.
    pub precision: i32,
    /// `e_min`: -1022 or -126.
    pub min_exponent: i32,
}

impl Format {
    /// IEEE binary64.
    pub const F64: Format = Format {
        name: "f64",
        precision: 53,
        min_exponent: -1022,
    };
    /// IEEE binary32.
    pub const F32: Format = Format {
        name: "f32",
        precision: 24,
        min_exponent: -126,
    };

    /// The unit roundoff `u = 2^-p`.
    pub fn unit_roundoff(self) -> f64 {
        2f64.powi(-self.precision)
    }

    /// Machine epsilon `2u`, the unit the report states errors in.
    pub fn epsilon(self) -> f64 {
        2.0 * self.unit_roundoff()
    }

    /// The largest finite value.
    pub fn max(self) -> f64 {
        match self.precision {
            24 => f64::from(f32::MAX),
            _ => f64::MAX,
        }
    }

    /// An upper bound of `|RN(x) - x|` for every real `x` with `|x| <= x_max < max()`:
    /// `u 2^floor(log2 x_max)`, or `u 2^e_min` below the normal range (half the spacing of
    /// the floats around `x`; the subnormal spacing is `2u 2^e_min`), and never more than
    /// `x_max` itself (0 is a float, so the nearest float is no farther than 0: an exact zero
    /// rounds exactly). `+inf` when `x_max` reaches [`Format::max`], where rounding may
    /// overflow.
    pub fn rounding(self, x_max: f64) -> f64 {
        if x_max.is_nan() || x_max >= self.max() {
            return f64::INFINITY;
        }
        let tiny = 2f64.powi(self.min_exponent);
        mul_up(self.unit_roundoff(), pow2_floor(x_max).max(tiny)).min(x_max)
    }

    /// The format's value nearest to `c` as an `f64`, and whether it equals `c` exactly.
    pub fn round_constant(self, c: &BigRational) -> (f64, bool) {
        let f = c.to_f64().unwrap_or(f64::NAN);
        let representable = match self.precision {
            24 => f64::from(f as f32) == f,
            _ => true,
        };
        let exact = f.is_finite()
            && representable
            && BigRational::from_f64(f).is_some_and(|back| &back == c);
        (f, exact)
    }

    /// Whether multiplying a float by `c` is exact whenever it does not overflow: `c = +-2^k`
    /// with `k >= 0`.
    pub fn scales_exactly(c: &BigRational) -> bool {
        let a = c.abs();
        a.is_integer() && {
            let n = a.numer();
            n.bits() > 0 && (n - 1u32) & n == num_bigint::BigInt::from(0)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(p: i64, d: i64) -> BigRational {
        BigRational::new(p.into(), d.into())
    }

    #[test]
    fn constants_are_exact_only_when_representable() {
        assert_eq!(Format::F64.round_constant(&q(2, 1)), (2.0, true));
        assert!(!Format::F64.round_constant(&q(1, 3)).1);
        assert!(Format::F64.round_constant(&q(1, 1 << 30)).1);
        // 1 + 2^-30 is an f64 but not an f32.
        let c = q((1 << 30) + 1, 1 << 30);
        assert!(Format::F64.round_constant(&c).1);
        assert!(!Format::F32.round_constant(&c).1);
    }

    #[test]
    fn powers_of_two_scale_exactly() {
        assert!(Format::scales_exactly(&q(2, 1)));
        assert!(Format::scales_exactly(&q(-4, 1)));
        assert!(Format::scales_exactly(&q(1, 1)));
        assert!(!Format::scales_exactly(&q(3, 1)));
        assert!(!Format::scales_exactly(&q(1, 2)));
        assert!(!Format::scales_exactly(&q(0, 1)));
    }

    #[test]
    fn rounding_is_half_the_spacing() {
        let u = Format::F64.unit_roundoff();
        // Between 1 and 2 the spacing is 2u: half of it is u (plus the one outward step).
        assert!(Format::F64.rounding(1.5) >= u && Format::F64.rounding(1.5) <= u * (1.0 + 1e-15));
        assert!(Format::F64.rounding(f64::MAX).is_infinite());
        assert!(Format::F32.rounding(1e39).is_infinite());
        assert_eq!(Format::F64.rounding(0.0), 0.0);
        assert_eq!(Format::F32.rounding(1e-50), 1e-50);
    }
}
