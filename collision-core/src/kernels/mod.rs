//! The generated kernels, one module per dimension, and a trait that picks them by
//! dimension for generic code.
//!
//! Each module `dN` holds `free` (both bodies move) and `fixed` (body 1 immovable), and
//! their FMA forms `free_fma` and `fixed_fma` (single-use products fused), emitted
//! by noslip-codegen from the general SO(n) formulas at build time; their doc comments state
//! the formula and the op counts. They are the unchecked fast path: no validation, no
//! branches. Preconditions (which [`crate::collide`] checks): finite inputs, `|nu| = 1`,
//! parameters as documented on [`crate::Ball`], and for `free` `w_1 + w_2 > 0` and
//! `D = w_1 g_2 (1 + g_1) + w_2 g_1 (1 + g_2) > 0` (not both `gamma2` zero; a body with
//! `gamma2 = 0` is movable). Violations give NaN or infinities, never a panic (floats).

use crate::{Ball, BodyState, RefArith, Scalar};

#[cfg(test)]
mod energy_drift;
mod rough;
mod walton;

pub use rough::RoughKernel;
pub use walton::WaltonKernel;

/// One method of `CertifiedKernel`: the running companion `$running` or the fast one `$fast`
/// of `kernels::$module::certified::$format`, as `companion` picks.
macro_rules! certified_method {
    ($module:ident $format:ident $name:ident: $running:ident | $fast:ident
        ($($arg:ident: $ty:ty),*) -> $ret:ty) => {
        #[inline(always)]
        fn $name(companion: crate::certified::Companion, $($arg: $ty),*) -> $ret {
            use $module::certified::$format as c;
            match companion {
                crate::certified::Companion::Running => c::$running($($arg),*),
                crate::certified::Companion::Fast => c::$fast($($arg),*),
            }
        }
    };
}

/// `CertifiedKernel<$t>` for dimension `$n` from the companions' per-format names
/// (`kernels::dN::certified::in_f64`, `in_f32`).
macro_rules! certified_kernel_impl {
    ($module:ident $n:literal $s:literal $t:ident $format:ident) => {
        impl crate::certified::CertifiedKernel<$t, $n, $s> for Generated {
            certified_method!($module $format free: free | free_fast
                (nu: &[$t; $n], ball1: &Ball<$t>, ball2: &Ball<$t>,
                 state1: &BodyState<$t, $n, $s>, state2: &BodyState<$t, $n, $s>)
                -> ([BodyState<$t, $n, $s>; 2], [BodyState<$t, $n, $s>; 2]));
            certified_method!($module $format fixed: fixed | fixed_fast
                (nu: &[$t; $n], radius1: &$t, ball2: &Ball<$t>,
                 state1: &BodyState<$t, $n, $s>, state2: &BodyState<$t, $n, $s>)
                -> (BodyState<$t, $n, $s>, BodyState<$t, $n, $s>));
            certified_method!($module $format free_fma: free_fma | free_fma_fast
                (nu: &[$t; $n], ball1: &Ball<$t>, ball2: &Ball<$t>,
                 state1: &BodyState<$t, $n, $s>, state2: &BodyState<$t, $n, $s>)
                -> ([BodyState<$t, $n, $s>; 2], [BodyState<$t, $n, $s>; 2]));
            certified_method!($module $format fixed_fma: fixed_fma | fixed_fma_fast
                (nu: &[$t; $n], radius1: &$t, ball2: &Ball<$t>,
                 state1: &BodyState<$t, $n, $s>, state2: &BodyState<$t, $n, $s>)
                -> (BodyState<$t, $n, $s>, BodyState<$t, $n, $s>));
        }
    };
}

macro_rules! generated {
    ($($module:ident $feature:literal $n:literal $s:literal $file:literal $rough:literal $walton:literal $certified:literal;)*) => {$(
        #[doc = concat!("Generated kernels for n = ", stringify!($n), ".")]
        #[cfg(feature = $feature)]
        pub mod $module {
            include!(concat!(env!("OUT_DIR"), "/", $file));

            /// The rough-ball kernels (normal and tangential restitution `e`, `beta` as
            /// run-time parameters; `docs/derivation.md` §15), generated like the no-slip ones.
            pub mod rough {
                include!(concat!(env!("OUT_DIR"), "/", $rough));
            }

            /// The Walton kernels (`e`, friction `mu`, sticking `beta0` as run-time
            /// parameters; `docs/derivation.md` §15.1), generated like the rough ones.
            pub mod walton {
                include!(concat!(env!("OUT_DIR"), "/", $walton));
            }

            /// The certified companions of [`free`] and [`fixed`] (`f64`; `free_f32`,
            /// `fixed_f32`): the same outputs, bit for bit, and a rigorous bound on each
            /// output's absolute error for these inputs (`noslip_codegen::certify`,
            /// `docs/accuracy.md` "Certified companions"); and the fast companions
            /// `free_fast`, `fixed_fast` (`_f32`), whose bound is a constant times a
            /// magnitude carried beside each value (`noslip_codegen::certify::fast`); and
            /// the companions of [`free_fma`] and [`fixed_fma`] (`free_fma`, `free_fma_fast`,
            /// ..., each fused step bounded with its one rounding); `free_rounded`,
            /// `fixed_rounded` (and `_fma`, `_f32` forms), whose bound also covers the
            /// rounding of the normal and `gamma2` given
            /// ([`crate::certified::InputRounding`]); `free_f32_wide`, `fixed_f32_wide`
            /// (and `_fma`), the `f32` kernels with the bound computed in `f64`; and
            /// `rough_free`, `rough_fixed` (and `_fma`, `_f32` forms), the running
            /// companions of the rough-ball kernels [`rough`] (constant `(e, beta)`).
            pub mod certified {
                include!(concat!(env!("OUT_DIR"), "/", $certified));
            }
        }

        #[cfg(feature = $feature)]
        rough::rough_kernel_impl!($module $n $s);

        #[cfg(feature = $feature)]
        walton::walton_kernel_impl!($module $n $s);

        #[cfg(feature = $feature)]
        certified_kernel_impl!($module $n $s f64 in_f64);

        #[cfg(feature = $feature)]
        certified_kernel_impl!($module $n $s f32 in_f32);

        #[cfg(feature = $feature)]
        impl<T: Scalar> Kernel<T, $n, $s> for Generated
        where
            for<'a> &'a T: RefArith<T>,
        {
            #[inline(always)]
            fn free(
                nu: &[T; $n],
                ball1: &Ball<T>,
                ball2: &Ball<T>,
                state1: &BodyState<T, $n, $s>,
                state2: &BodyState<T, $n, $s>,
            ) -> [BodyState<T, $n, $s>; 2] {
                $module::free(nu, ball1, ball2, state1, state2)
            }

            #[inline(always)]
            fn fixed(
                nu: &[T; $n],
                radius1: &T,
                ball2: &Ball<T>,
                state1: &BodyState<T, $n, $s>,
                state2: &BodyState<T, $n, $s>,
            ) -> BodyState<T, $n, $s> {
                $module::fixed(nu, radius1, ball2, state1, state2)
            }

            #[inline(always)]
            fn free_fma(
                nu: &[T; $n],
                ball1: &Ball<T>,
                ball2: &Ball<T>,
                state1: &BodyState<T, $n, $s>,
                state2: &BodyState<T, $n, $s>,
            ) -> [BodyState<T, $n, $s>; 2] {
                $module::free_fma(nu, ball1, ball2, state1, state2)
            }

            #[inline(always)]
            fn fixed_fma(
                nu: &[T; $n],
                radius1: &T,
                ball2: &Ball<T>,
                state1: &BodyState<T, $n, $s>,
                state2: &BodyState<T, $n, $s>,
            ) -> BodyState<T, $n, $s> {
                $module::fixed_fma(nu, radius1, ball2, state1, state2)
            }
        }
    )*};
}

/// The generated kernels of one dimension `N` (`S = N(N-1)/2`), for generic code.
pub trait Kernel<T, const N: usize, const S: usize> {
    /// Both bodies free: `[body 1+, body 2+]`.
    fn free(
        nu: &[T; N],
        ball1: &Ball<T>,
        ball2: &Ball<T>,
        state1: &BodyState<T, N, S>,
        state2: &BodyState<T, N, S>,
    ) -> [BodyState<T, N, S>; 2];

    /// Body 1 immovable: body 2+.
    fn fixed(
        nu: &[T; N],
        radius1: &T,
        ball2: &Ball<T>,
        state1: &BodyState<T, N, S>,
        state2: &BodyState<T, N, S>,
    ) -> BodyState<T, N, S>;

    /// [`Kernel::free`] with fused multiply-adds.
    fn free_fma(
        nu: &[T; N],
        ball1: &Ball<T>,
        ball2: &Ball<T>,
        state1: &BodyState<T, N, S>,
        state2: &BodyState<T, N, S>,
    ) -> [BodyState<T, N, S>; 2];

    /// [`Kernel::fixed`] with fused multiply-adds.
    fn fixed_fma(
        nu: &[T; N],
        radius1: &T,
        ball2: &Ball<T>,
        state1: &BodyState<T, N, S>,
        state2: &BodyState<T, N, S>,
    ) -> BodyState<T, N, S>;
}

/// The generated kernels: `Generated: Kernel<T, N, S>` for `N = 2..6` (each dimension behind
/// its cargo feature `dN`, all on by default).
pub struct Generated;

generated! {
    d2 "d2" 2 1 "kernels_2.rs" "rough_2.rs" "walton_2.rs" "certified_2.rs";
    d3 "d3" 3 3 "kernels_3.rs" "rough_3.rs" "walton_3.rs" "certified_3.rs";
    d4 "d4" 4 6 "kernels_4.rs" "rough_4.rs" "walton_4.rs" "certified_4.rs";
    d5 "d5" 5 10 "kernels_5.rs" "rough_5.rs" "walton_5.rs" "certified_5.rs";
    d6 "d6" 6 15 "kernels_6.rs" "rough_6.rs" "walton_6.rs" "certified_6.rs";
}
