//! The Rust certified companions of one dimension as a table of function pointers
//! (`collision_core::kernels::dN::certified::{free,fixed}{,_fma}_rounded{,_f32}`,
//! `..._f32_wide`, `rough_free`, `walton_fixed_fma_f32`, ...), for the C and OpenCL
//! faithfulness tests (`c_certified.rs`, `opencl_certified.rs`): [`of!`] builds one.

use collision_core::certified::InputRounding;
use collision_core::{Ball, BodyState, Restitution, Walton};

/// A rounded-input `free` companion in `T`.
pub type RoundedFree<T, const N: usize, const S: usize> =
    fn(
        &[T; N],
        &Ball<T>,
        &Ball<T>,
        &BodyState<T, N, S>,
        &BodyState<T, N, S>,
        &InputRounding<T>,
    ) -> ([BodyState<T, N, S>; 2], [BodyState<T, N, S>; 2]);

/// A rounded-input `fixed` companion in `T`.
pub type RoundedFixed<T, const N: usize, const S: usize> =
    fn(
        &[T; N],
        &T,
        &Ball<T>,
        &BodyState<T, N, S>,
        &BodyState<T, N, S>,
        &InputRounding<T>,
    ) -> (BodyState<T, N, S>, BodyState<T, N, S>);

/// A wide `free` companion: `f32` outputs, `f64` bounds.
pub type WideFree<const N: usize, const S: usize> =
    fn(
        &[f32; N],
        &Ball<f32>,
        &Ball<f32>,
        &BodyState<f32, N, S>,
        &BodyState<f32, N, S>,
    ) -> ([BodyState<f32, N, S>; 2], [BodyState<f64, N, S>; 2]);

/// A wide `fixed` companion.
pub type WideFixed<const N: usize, const S: usize> =
    fn(
        &[f32; N],
        &f32,
        &Ball<f32>,
        &BodyState<f32, N, S>,
        &BodyState<f32, N, S>,
    ) -> (BodyState<f32, N, S>, BodyState<f64, N, S>);

/// A rough-family `free` companion in `T` with the law `L`.
pub type LawFree<T, L, const N: usize, const S: usize> =
    fn(
        &[T; N],
        &Ball<T>,
        &Ball<T>,
        &L,
        &BodyState<T, N, S>,
        &BodyState<T, N, S>,
    ) -> ([BodyState<T, N, S>; 2], [BodyState<T, N, S>; 2]);

/// A rough-family `fixed` companion.
pub type LawFixed<T, L, const N: usize, const S: usize> =
    fn(
        &[T; N],
        &T,
        &Ball<T>,
        &L,
        &BodyState<T, N, S>,
        &BodyState<T, N, S>,
    ) -> (BodyState<T, N, S>, BodyState<T, N, S>);

/// The `(free, fixed)` companions of one law family, `[plain, FMA]`, in `f64` and `f32`.
pub struct Family<L64, L32, const N: usize, const S: usize> {
    /// In `f64`.
    pub f64: [(LawFree<f64, L64, N, S>, LawFixed<f64, L64, N, S>); 2],
    /// In `f32`.
    pub f32: [(LawFree<f32, L32, N, S>, LawFixed<f32, L32, N, S>); 2],
}

/// The Rust companions of dimension `N`, plain then FMA: `(free, fixed)` each.
pub struct Extra<const N: usize, const S: usize> {
    /// `rough_free`, `rough_fixed`, ...
    pub rough: Family<Restitution<f64>, Restitution<f32>, N, S>,
    /// `walton_free`, `walton_fixed`, ...
    pub walton: Family<Walton<f64>, Walton<f32>, N, S>,
    /// `free_rounded`, `fixed_rounded` (`f64`), then `free_fma_rounded`, ....
    pub rounded64: [(RoundedFree<f64, N, S>, RoundedFixed<f64, N, S>); 2],
    /// Their `f32` forms (`free_rounded_f32`, ...).
    pub rounded32: [(RoundedFree<f32, N, S>, RoundedFixed<f32, N, S>); 2],
    /// `free_f32_wide`, `fixed_f32_wide`, then `free_fma_f32_wide`, ....
    pub wide: [(WideFree<N, S>, WideFixed<N, S>); 2],
}

/// The [`Extra`] of the module `kernels::$m`.
// Not every test that includes `backend` uses it.
#[allow(unused_macros)]
macro_rules! of {
    ($m:ident) => {{
        use collision_core::kernels::$m::certified as c;
        $crate::backend::companions::Extra {
            rounded64: [
                (c::free_rounded, c::fixed_rounded),
                (c::free_fma_rounded, c::fixed_fma_rounded),
            ],
            rounded32: [
                (c::free_rounded_f32, c::fixed_rounded_f32),
                (c::free_fma_rounded_f32, c::fixed_fma_rounded_f32),
            ],
            wide: [
                (c::free_f32_wide, c::fixed_f32_wide),
                (c::free_fma_f32_wide, c::fixed_fma_f32_wide),
            ],
            rough: $crate::backend::companions::Family {
                f64: [
                    (c::rough_free, c::rough_fixed),
                    (c::rough_free_fma, c::rough_fixed_fma),
                ],
                f32: [
                    (c::rough_free_f32, c::rough_fixed_f32),
                    (c::rough_free_fma_f32, c::rough_fixed_fma_f32),
                ],
            },
            walton: $crate::backend::companions::Family {
                f64: [
                    (c::walton_free, c::walton_fixed),
                    (c::walton_free_fma, c::walton_fixed_fma),
                ],
                f32: [
                    (c::walton_free_f32, c::walton_fixed_f32),
                    (c::walton_free_fma_f32, c::walton_fixed_fma_f32),
                ],
            },
        }
    }};
}
#[allow(unused_imports)]
pub(crate) use of;
