//! A scene's exact numbers as the engine's floats.

use num_rational::BigRational;
use num_traits::ToPrimitive;

/// The nearest f64 (scene numbers are validated finite rationals).
pub fn f(x: &BigRational) -> f64 {
    x.to_f64().unwrap_or(f64::NAN)
}
