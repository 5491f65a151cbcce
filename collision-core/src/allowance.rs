//! The rounding allowance: the one rule for every bound that rounded inputs may cross.
//!
//! A quantity `x` that must lie in `[lo, hi]` (or satisfy one side of it) is **accepted when
//! it is within `a = ULPS eps s` of its range, and then clamped to the range**; beyond that it
//! is refused. Here
//!
//! - `eps` is the epsilon of the arithmetic the case runs in: `2^-52` in `f64`, `2^-23` in
//!   `f32`, and `0` in exact rationals, so exact input must meet its bounds exactly;
//! - `s` is the scale of `x`: the size of the quantities it is computed from;
//! - [`ULPS`] `= 8` covers the rounding of an input written in decimal plus the few
//!   operations between the inputs and `x`.
//!
//! | quantity | range | scale `s` | clamping |
//! |---|---|---|---|
//! | `lambda` | `[0, R^2/n]` | `R^2/n` | to the bound |
//! | `gamma2`, given or `2 lambda / R^2` | `[0, 2/n]` | `2/n` | to the bound |
//! | `\|nu\|^2` | `{1}` | `\|nu\|^2`, with `ULPS + 2n` for `ULPS` (rounding of `d / \|d\|` in `n` dimensions) | `nu` is renormalised |
//! | `U_ij + U_ji`, `U_ii` | `{0}` | `max \|U_kl\|` | `U` is replaced by its skew part `(U - U^T)/2` |
//! | `(u_2 - u_1) . nu` | `<= 0` | `sum_k \|nu_k\| (\|u_1k\| + \|u_2k\|)` | grazing: the relative velocity loses its normal part, shared so that momentum is kept |
//!
//! Scenes are exact rationals but run in `f64`, and their decimals are often `f64` values
//! printed in full: scene validation applies the rule with the `f64` epsilon to the exact
//! values and clamps them exactly (`lambda = "8.333333333333334"` with `R = 5` in 3D is
//! `R^2/n = 25/3`, so `gamma2 = 2/3`).
//!
//! This file is compiled into collision-core (the checked `collide`, `Ball::new`,
//! `skew_entries`) and, by path, into noslip-codegen (scene validation), which cannot depend
//! on collision-core: collision-core builds with it.

use std::ops::Add;

/// The allowance in units of the arithmetic's epsilon, relative to the quantity's scale.
pub const ULPS: u32 = 8;

/// `x` under the rule for `x <= hi`: itself if it holds, `hi` if `x` exceeds it by at most
/// `allowance`, `None` beyond.
pub fn at_most<T: Clone + PartialOrd + Add<Output = T>>(x: &T, hi: &T, allowance: &T) -> Option<T> {
    if x <= hi {
        Some(x.clone())
    } else if *x <= hi.clone() + allowance.clone() {
        Some(hi.clone())
    } else {
        None
    }
}

/// `x` under the rule for `x >= lo`: itself if it holds, `lo` if `x` falls short by at most
/// `allowance`, `None` beyond.
pub fn at_least<T: Clone + PartialOrd + Add<Output = T>>(
    x: &T,
    lo: &T,
    allowance: &T,
) -> Option<T> {
    if x >= lo {
        Some(x.clone())
    } else if x.clone() + allowance.clone() >= *lo {
        Some(lo.clone())
    } else {
        None
    }
}

/// `x` under the rule for `lo <= x <= hi` (`lo <= hi`).
pub fn within<T: Clone + PartialOrd + Add<Output = T>>(
    x: &T,
    lo: &T,
    hi: &T,
    allowance: &T,
) -> Option<T> {
    at_least(x, lo, allowance).and_then(|x| at_most(&x, hi, allowance))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inside_is_kept_within_the_allowance_is_clamped_beyond_is_refused() {
        let a = 0.25;
        assert_eq!(within(&0.5, &0.0, &1.0, &a), Some(0.5));
        assert_eq!(within(&1.25, &0.0, &1.0, &a), Some(1.0));
        assert_eq!(within(&-0.25, &0.0, &1.0, &a), Some(0.0));
        assert_eq!(within(&1.5, &0.0, &1.0, &a), None);
        assert_eq!(within(&-0.5, &0.0, &1.0, &a), None);
        assert_eq!(at_most(&0.0, &0.0, &0.0), Some(0.0));
        assert_eq!(at_most(&1e-300, &0.0, &0.0), None);
        // NaN is never accepted.
        assert_eq!(within(&f64::NAN, &0.0, &1.0, &a), None);
    }
}
