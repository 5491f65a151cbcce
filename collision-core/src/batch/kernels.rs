//! The generated batch kernels, one module per dimension (`batch_{n}.rs` from
//! `noslip_codegen::batch`), and a trait that picks them by dimension for generic code.
//!
//! Each module `dN` holds `free`, `fixed`, `free_shared` and `fixed_shared` over slices of
//! blocks; their doc comments state the formula and the op counts per contact and per call.
//! Like the scalar kernels they are unchecked: no validation, no branches on the values.

use super::lanes::{ContactLanes, FixedLanes, FreeLanes, StateLanes};
use crate::kernels::Generated;
use crate::{Ball, RefArith, Scalar};

macro_rules! generated {
    ($($module:ident $feature:literal $n:literal $s:literal $file:literal;)*) => {$(
        #[doc = concat!("Generated batch kernels for n = ", stringify!($n), ".")]
        #[cfg(feature = $feature)]
        pub mod $module {
            include!(concat!(env!("OUT_DIR"), "/", $file));
        }

        #[cfg(feature = $feature)]
        impl<T: Scalar> BatchKernel<T, $n, $s> for Generated
        where
            for<'a> &'a T: RefArith<T>,
        {
            #[inline(always)]
            fn free_blocks<const W: usize>(blocks: &[FreeLanes<T, $n, $s>], out: &mut [[StateLanes<T, $n, $s>; 2]]) {
                $module::free::<T, W>(blocks, out)
            }

            #[inline(always)]
            fn fixed_blocks<const W: usize>(blocks: &[FixedLanes<T, $n, $s>], out: &mut [StateLanes<T, $n, $s>]) {
                $module::fixed::<T, W>(blocks, out)
            }

            #[inline(always)]
            fn free_shared_blocks<const W: usize>(
                balls: [&Ball<T>; 2],
                blocks: &[ContactLanes<T, $n, $s>],
                out: &mut [[StateLanes<T, $n, $s>; 2]],
            ) {
                $module::free_shared::<T, W>(balls[0], balls[1], blocks, out)
            }

            #[inline(always)]
            fn fixed_shared_blocks<const W: usize>(
                radius1: &T,
                ball2: &Ball<T>,
                blocks: &[ContactLanes<T, $n, $s>],
                out: &mut [StateLanes<T, $n, $s>],
            ) {
                $module::fixed_shared::<T, W>(radius1, ball2, blocks, out)
            }
        }
    )*};
}

/// The generated batch kernels of one dimension `N` (`S = N(N-1)/2`), for generic code.
/// Each processes `min(blocks.len(), out.len())` blocks, `W` lanes at a time (`W` divides
/// `LANES`; the register width in `f64` of the instruction set it is compiled for, or 1 for
/// lane-by-lane scalar code). Every `W` gives the same results, bit for bit.
pub trait BatchKernel<T, const N: usize, const S: usize> {
    /// Both bodies free, parameters per contact: `out[k]` = `[body 1+, body 2+]` lanes.
    fn free_blocks<const W: usize>(
        blocks: &[FreeLanes<T, N, S>],
        out: &mut [[StateLanes<T, N, S>; 2]],
    );
    /// Body 1 immovable, parameters per contact: `out[k]` = body 2+ lanes.
    fn fixed_blocks<const W: usize>(
        blocks: &[FixedLanes<T, N, S>],
        out: &mut [StateLanes<T, N, S>],
    );
    /// Both bodies free, one pair of balls for every contact.
    fn free_shared_blocks<const W: usize>(
        balls: [&Ball<T>; 2],
        blocks: &[ContactLanes<T, N, S>],
        out: &mut [[StateLanes<T, N, S>; 2]],
    );
    /// Body 1 immovable, one `radius1` and `ball2` for every contact.
    fn fixed_shared_blocks<const W: usize>(
        radius1: &T,
        ball2: &Ball<T>,
        blocks: &[ContactLanes<T, N, S>],
        out: &mut [StateLanes<T, N, S>],
    );
}

generated! {
    d2 "d2" 2 1 "batch_2.rs";
    d3 "d3" 3 3 "batch_3.rs";
    d4 "d4" 4 6 "batch_4.rs";
    d5 "d5" 5 10 "batch_5.rs";
    d6 "d6" 6 15 "batch_6.rs";
}
