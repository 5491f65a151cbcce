//! The float formats a companion runs in: the kernel's unit roundoff `u`, the magnitude
//! floor `s`, the inflation `F(d)` that makes a computed bound rigorous, and the rounding of
//! constants ([`super`], "The bound's own arithmetic").

/// The float format a companion runs in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Format {
    /// IEEE binary64.
    F64,
    /// IEEE binary32.
    F32,
    /// The kernel in IEEE binary32, its bound in binary64 ([`super::wide`]): the kernel's `u` and
    /// rounding rules, the bound's own arithmetic in `f64` (which loses less per operation
    /// than the proof allows for `u = 2^-24`, and cannot overflow where `f32` would).
    F32Wide,
}

impl Format {
    /// `log2 u`: `-53`, `-24`.
    pub(crate) fn roundoff_exponent(self) -> i32 {
        match self {
            Format::F64 => -53,
            Format::F32 | Format::F32Wide => -24,
        }
    }

    /// The unit roundoff `u`.
    pub fn unit_roundoff(self) -> f64 {
        2f64.powi(self.roundoff_exponent())
    }

    /// The magnitude floor `s`: `2^-480` (`f64`), `2^-51` (`f32`), so that `s^2 u` is normal
    /// and `u s` is above the subnormal half-spacing; `2^-126` for [`Format::F32Wide`]
    /// (`u s = 2^-150`, the `f32` subnormal half-spacing; `s^2 u` is normal in `f64`).
    pub fn floor(self) -> f64 {
        match self {
            Format::F64 => 2f64.powi(-480),
            Format::F32 => 2f64.powi(-51),
            Format::F32Wide => 2f64.powi(-126),
        }
    }

    /// Whether the bound is evaluated in `f64` (every format but [`Format::F32`]).
    pub fn bound_in_f64(self) -> bool {
        !matches!(self, Format::F32)
    }

    /// `F(d) = 1 + (d + 2) 2u`, exact in the format for `d < 2^22`.
    pub fn inflation(self, depth: u32) -> f64 {
        assert!(depth < 1 << 22, "depth {depth} out of range");
        1.0 + f64::from(depth + 2) * 2.0 * self.unit_roundoff()
    }

    /// The smallest float of the format at least `x` (`x` an `f64` upper bound).
    pub(crate) fn up(self, x: f64) -> f64 {
        match self {
            Format::F64 | Format::F32Wide => x,
            Format::F32 => {
                let y = x as f32;
                if f64::from(y) >= x {
                    f64::from(y)
                } else {
                    f64::from(f32::from_bits(y.to_bits() + 1))
                }
            }
        }
    }

    /// The float the kernel holds for an exact constant.
    pub(crate) fn round(self, value: &num_rational::BigRational) -> f64 {
        let (x64, x32) = crate::literal::nearest_floats(value);
        match self {
            Format::F64 => x64,
            Format::F32 | Format::F32Wide => f64::from(x32),
        }
    }
}
