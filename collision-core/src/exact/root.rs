//! The square root of the exact types, for the Walton kernels ([`crate::ScalarRoot`]): the
//! exact root of a rational square; otherwise the one rounding exact arithmetic does, the
//! root truncated to [`ROOT_BITS`] bits.
//!
//! The Walton kernels take one root, of `rho = C / L` while the contact slides
//! (`docs/derivation.md` §15.1). It is rational exactly when `|t|` is (for rational inputs),
//! as at the points `verify` draws for its sliding checks, which therefore check the kernel
//! with no rounding at all; elsewhere the result is within a relative `2^-ROOT_BITS` of the
//! true root, far below any float's resolution, which is what the accuracy report needs
//! of its ground truth.

use super::{Backend, Exact, Rational};
use crate::scalar::ScalarRoot;
use dashu_int::{ops::SquareRoot, UBig};

/// The bits kept of an irrational root: `|r - sqrt(x)| < 2^-ROOT_BITS sqrt(x)`.
pub const ROOT_BITS: usize = 256;

impl Exact {
    /// `sqrt(self)`, `self >= 0`: exact when `self` is the square of a rational
    /// ([`Exact::exact_sqrt`]), else `floor(sqrt(p q) 2^k) / (q 2^k)` for `self = p/q`
    /// reduced and `k =` [`ROOT_BITS`], below the root by less than `2^-k` of it (`p q >= 1`).
    /// Panics for a negative value (the kernels' roots are of ratios of squares). Not named
    /// `root`: `noslip_dynamics::root::Root::root` (`None` unless exact) is a trait method on
    /// the same type, which an inherent `root` would silently shadow.
    pub fn sqrt_rounded(&self) -> Exact {
        if let Some(r) = self.exact_sqrt() {
            return r;
        }
        let (p, q) = self.parts();
        let p: UBig = p.parse().expect("the square root of a negative rational");
        let q: UBig = q.parse().expect("a positive denominator");
        let scaled = (&p * &q) << (2 * ROOT_BITS);
        let den = q << ROOT_BITS;
        Exact::from_decimal(&scaled.sqrt().to_string(), &den.to_string())
            .expect("decimal digits of integers")
    }
}

impl<B: Backend> ScalarRoot for Rational<B> {
    fn sqrt(a: &Self) -> Self {
        a.reduced().sqrt_rounded().convert()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn squares_have_exact_roots_and_others_are_close_from_below() {
        let q = |p, d| Exact::checked_ratio(p, d).unwrap();
        assert_eq!(q(9, 4).sqrt_rounded(), q(3, 2));
        assert_eq!(q(0, 1).sqrt_rounded(), q(0, 1));
        let r = q(2, 1).sqrt_rounded();
        let err = &(&r * &r) - &q(2, 1);
        // r < sqrt 2 and r^2 > 2 (1 - 2^-255): the truncation, and nothing coarser.
        assert!(err < q(0, 1));
        assert!(-err < Exact::pow2(-(ROOT_BITS as i32) + 2));
    }
}
