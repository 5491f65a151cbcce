//! The float formats of the emitted kernels, IEEE binary64 and binary32: each one's C type
//! and the suffix of its functions' names.

/// A float format of the emitted kernels.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Precision {
    /// IEEE binary64 (`double`).
    F64,
    /// IEEE binary32 (`float`).
    F32,
}

impl Precision {
    /// Both, in emission order.
    pub const ALL: [Precision; 2] = [Precision::F64, Precision::F32];

    /// The suffix of the function names: `f64`, `f32`.
    pub fn suffix(self) -> &'static str {
        match self {
            Precision::F64 => "f64",
            Precision::F32 => "f32",
        }
    }

    /// The C type: `double`, `float`.
    pub fn c_type(self) -> &'static str {
        match self {
            Precision::F64 => "double",
            Precision::F32 => "float",
        }
    }
}
