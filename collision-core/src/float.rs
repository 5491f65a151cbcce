//! The binary floating-point formats as [`Scalar`]s: `f64` and `f32`, each with its
//! unbounded-exponent form [`Wide`] for the checked path.

use crate::allowance::ULPS;
use crate::scalar::{Scalar, ScalarRoot};
use crate::wide::Wide;

impl Scalar for f64 {
    const NAME: &'static str = "f64";
    fn show(&self) -> String {
        format!("{self:?}")
    }
    const EXACT: bool = false;
    #[inline(always)]
    fn from_ratio(num: i64, den: i64) -> Self {
        num as f64 / den as f64
    }
    fn is_finite(&self) -> bool {
        f64::is_finite(*self)
    }
    fn to_f64(&self) -> f64 {
        *self
    }
    fn rounding_slack() -> Self {
        f64::from(ULPS) * f64::EPSILON
    }
    type Unbounded = Wide<f64>;
    fn unbounded(&self) -> Wide<f64> {
        Wide::from(*self)
    }
    fn from_unbounded(x: &Wide<f64>) -> Self {
        x.round()
    }
    #[inline(always)]
    fn mul_add(a: &Self, b: &Self, c: &Self) -> Self {
        a.mul_add(*b, *c)
    }
    #[inline(always)]
    fn from_literal(x64: f64, _: f32, _: &str, _: &str) -> Self {
        x64
    }
}

impl Scalar for f32 {
    const NAME: &'static str = "f32";
    fn show(&self) -> String {
        format!("{self:?}")
    }
    const EXACT: bool = false;
    #[inline(always)]
    fn from_ratio(num: i64, den: i64) -> Self {
        num as f32 / den as f32
    }
    fn is_finite(&self) -> bool {
        f32::is_finite(*self)
    }
    fn to_f64(&self) -> f64 {
        f64::from(*self)
    }
    fn rounding_slack() -> Self {
        ULPS as f32 * f32::EPSILON
    }
    type Unbounded = Wide<f32>;
    fn unbounded(&self) -> Wide<f32> {
        Wide::from(*self)
    }
    fn from_unbounded(x: &Wide<f32>) -> Self {
        x.round()
    }
    #[inline(always)]
    fn mul_add(a: &Self, b: &Self, c: &Self) -> Self {
        a.mul_add(*b, *c)
    }
    #[inline(always)]
    fn from_literal(_: f64, x32: f32, _: &str, _: &str) -> Self {
        x32
    }
}

impl ScalarRoot for f64 {
    fn sqrt(a: &Self) -> Self {
        a.sqrt()
    }
}

impl ScalarRoot for f32 {
    fn sqrt(a: &Self) -> Self {
        a.sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_unbounded_form_rounds_to_the_formats_slack() {
        assert_eq!(
            <Wide<f64> as Scalar>::rounding_slack().round(),
            f64::rounding_slack()
        );
        assert_eq!(
            <Wide<f32> as Scalar>::rounding_slack().round(),
            f32::rounding_slack()
        );
    }
}
