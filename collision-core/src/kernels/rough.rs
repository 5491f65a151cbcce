//! The rough-ball kernels picked by dimension for generic code: [`RoughKernel`], implemented
//! by [`super::Generated`] with the generated `kernels::dN::rough` functions.
//!
//! Each takes the balls' parameters, the restitutions `law = (e, beta)` and the states;
//! `(e, beta) = (1, 1)` is the no-slip map bit for bit, `(1, -1)` the smooth one
//! (`docs/derivation.md` §15). Preconditions are those of the no-slip kernels
//! ([`super`]), and `law` in range ([`crate::Restitution::new`] checks it).

use crate::{Ball, BodyState, Restitution};

/// The generated rough-ball kernels of one dimension `N` (`S = N(N-1)/2`), for generic code.
pub trait RoughKernel<T, const N: usize, const S: usize> {
    /// Both bodies free: `[body 1+, body 2+]`.
    fn rough_free(
        nu: &[T; N],
        ball1: &Ball<T>,
        ball2: &Ball<T>,
        law: &Restitution<T>,
        state1: &BodyState<T, N, S>,
        state2: &BodyState<T, N, S>,
    ) -> [BodyState<T, N, S>; 2];

    /// Body 1 immovable: body 2+.
    fn rough_fixed(
        nu: &[T; N],
        radius1: &T,
        ball2: &Ball<T>,
        law: &Restitution<T>,
        state1: &BodyState<T, N, S>,
        state2: &BodyState<T, N, S>,
    ) -> BodyState<T, N, S>;

    /// [`RoughKernel::rough_free`] with fused multiply-adds.
    fn rough_free_fma(
        nu: &[T; N],
        ball1: &Ball<T>,
        ball2: &Ball<T>,
        law: &Restitution<T>,
        state1: &BodyState<T, N, S>,
        state2: &BodyState<T, N, S>,
    ) -> [BodyState<T, N, S>; 2];

    /// [`RoughKernel::rough_fixed`] with fused multiply-adds.
    fn rough_fixed_fma(
        nu: &[T; N],
        radius1: &T,
        ball2: &Ball<T>,
        law: &Restitution<T>,
        state1: &BodyState<T, N, S>,
        state2: &BodyState<T, N, S>,
    ) -> BodyState<T, N, S>;
}

/// `impl RoughKernel<T, n, s> for Generated` with `module::rough`'s functions.
macro_rules! rough_kernel_impl {
    ($module:ident $n:literal $s:literal) => {
        impl<T: $crate::Scalar> $crate::kernels::RoughKernel<T, $n, $s> for Generated
        where
            for<'a> &'a T: $crate::RefArith<T>,
        {
            #[inline(always)]
            fn rough_free(
                nu: &[T; $n],
                ball1: &Ball<T>,
                ball2: &Ball<T>,
                law: &$crate::Restitution<T>,
                state1: &BodyState<T, $n, $s>,
                state2: &BodyState<T, $n, $s>,
            ) -> [BodyState<T, $n, $s>; 2] {
                $module::rough::free(nu, ball1, ball2, law, state1, state2)
            }

            #[inline(always)]
            fn rough_fixed(
                nu: &[T; $n],
                radius1: &T,
                ball2: &Ball<T>,
                law: &$crate::Restitution<T>,
                state1: &BodyState<T, $n, $s>,
                state2: &BodyState<T, $n, $s>,
            ) -> BodyState<T, $n, $s> {
                $module::rough::fixed(nu, radius1, ball2, law, state1, state2)
            }

            #[inline(always)]
            fn rough_free_fma(
                nu: &[T; $n],
                ball1: &Ball<T>,
                ball2: &Ball<T>,
                law: &$crate::Restitution<T>,
                state1: &BodyState<T, $n, $s>,
                state2: &BodyState<T, $n, $s>,
            ) -> [BodyState<T, $n, $s>; 2] {
                $module::rough::free_fma(nu, ball1, ball2, law, state1, state2)
            }

            #[inline(always)]
            fn rough_fixed_fma(
                nu: &[T; $n],
                radius1: &T,
                ball2: &Ball<T>,
                law: &$crate::Restitution<T>,
                state1: &BodyState<T, $n, $s>,
                state2: &BodyState<T, $n, $s>,
            ) -> BodyState<T, $n, $s> {
                $module::rough::fixed_fma(nu, radius1, ball2, law, state1, state2)
            }
        }
    };
}
pub(crate) use rough_kernel_impl;
