//! The Walton kernels picked by dimension for generic code: [`WaltonKernel`], implemented
//! by [`super::Generated`] with the generated `kernels::dN::walton` functions.
//!
//! Each takes the balls' parameters, the law `(e, mu, beta0)` and the states; while the
//! contact sticks the outputs are the rough kernels' at `beta = beta0`, bit for bit
//! (`docs/derivation.md` §15.1). Preconditions are those of the rough kernels, and `law` in
//! range ([`crate::Walton::new`] checks it).

use crate::{Ball, BodyState, Walton};

/// The generated Walton kernels of one dimension `N` (`S = N(N-1)/2`), for generic code.
pub trait WaltonKernel<T, const N: usize, const S: usize> {
    /// Both bodies free: `[body 1+, body 2+]`.
    fn walton_free(
        nu: &[T; N],
        ball1: &Ball<T>,
        ball2: &Ball<T>,
        law: &Walton<T>,
        state1: &BodyState<T, N, S>,
        state2: &BodyState<T, N, S>,
    ) -> [BodyState<T, N, S>; 2];

    /// Body 1 immovable: body 2+.
    fn walton_fixed(
        nu: &[T; N],
        radius1: &T,
        ball2: &Ball<T>,
        law: &Walton<T>,
        state1: &BodyState<T, N, S>,
        state2: &BodyState<T, N, S>,
    ) -> BodyState<T, N, S>;

    /// [`WaltonKernel::walton_free`] with fused multiply-adds.
    fn walton_free_fma(
        nu: &[T; N],
        ball1: &Ball<T>,
        ball2: &Ball<T>,
        law: &Walton<T>,
        state1: &BodyState<T, N, S>,
        state2: &BodyState<T, N, S>,
    ) -> [BodyState<T, N, S>; 2];

    /// [`WaltonKernel::walton_fixed`] with fused multiply-adds.
    fn walton_fixed_fma(
        nu: &[T; N],
        radius1: &T,
        ball2: &Ball<T>,
        law: &Walton<T>,
        state1: &BodyState<T, N, S>,
        state2: &BodyState<T, N, S>,
    ) -> BodyState<T, N, S>;
}

/// `impl WaltonKernel<T, n, s> for Generated` with `module::walton`'s functions.
macro_rules! walton_kernel_impl {
    ($module:ident $n:literal $s:literal) => {
        impl<T: $crate::ScalarRoot> $crate::kernels::WaltonKernel<T, $n, $s> for Generated
        where
            for<'a> &'a T: $crate::RefArith<T>,
        {
            #[inline(always)]
            fn walton_free(
                nu: &[T; $n],
                ball1: &Ball<T>,
                ball2: &Ball<T>,
                law: &$crate::Walton<T>,
                state1: &BodyState<T, $n, $s>,
                state2: &BodyState<T, $n, $s>,
            ) -> [BodyState<T, $n, $s>; 2] {
                $module::walton::free(nu, ball1, ball2, law, state1, state2)
            }

            #[inline(always)]
            fn walton_fixed(
                nu: &[T; $n],
                radius1: &T,
                ball2: &Ball<T>,
                law: &$crate::Walton<T>,
                state1: &BodyState<T, $n, $s>,
                state2: &BodyState<T, $n, $s>,
            ) -> BodyState<T, $n, $s> {
                $module::walton::fixed(nu, radius1, ball2, law, state1, state2)
            }

            #[inline(always)]
            fn walton_free_fma(
                nu: &[T; $n],
                ball1: &Ball<T>,
                ball2: &Ball<T>,
                law: &$crate::Walton<T>,
                state1: &BodyState<T, $n, $s>,
                state2: &BodyState<T, $n, $s>,
            ) -> [BodyState<T, $n, $s>; 2] {
                $module::walton::free_fma(nu, ball1, ball2, law, state1, state2)
            }

            #[inline(always)]
            fn walton_fixed_fma(
                nu: &[T; $n],
                radius1: &T,
                ball2: &Ball<T>,
                law: &$crate::Walton<T>,
                state1: &BodyState<T, $n, $s>,
                state2: &BodyState<T, $n, $s>,
            ) -> BodyState<T, $n, $s> {
                $module::walton::fixed_fma(nu, radius1, ball2, law, state1, state2)
            }
        }
    };
}
pub(crate) use walton_kernel_impl;
