//! The certified companions of the FMA kernels, run on FMA instructions wherever the CPU has
//! them, as [`crate::collide_unchecked_fma`] runs the plain FMA kernels.

use super::{dispatch, CertifiedKernel, Certify, Companion};
use crate::{Ball, BodyState, Generated};

/// [`crate::collide_unchecked_fma`] with certified companions (`certified::free_fma`,
/// `fixed_fma`, or the fast `free_fma_fast`, `fixed_fma_fast`): the same dispatch, the same
/// outputs bit for bit, and per body the bound of every component (an immovable body is
/// returned unchanged, bound 0). Each fused step `fl(a b + c)` is bounded with its one
/// rounding (`docs/accuracy.md`, "The FMA companions"). On x86 and x86-64 the companions
/// are compiled a second time with FMA enabled and chosen at run time, as for the plain FMA
/// kernels; on a CPU without FMA, `mul_add` is a libm call (the same bits, slower).
#[allow(clippy::type_complexity)]
#[inline]
pub fn collide_certified_fma_by<T, const N: usize, const S: usize>(
    companion: Companion,
    nu: &[T; N],
    balls: [&Ball<T>; 2],
    states: [&BodyState<T, N, S>; 2],
) -> ([BodyState<T, N, S>; 2], [BodyState<T, N, S>; 2])
where
    T: crate::Scalar + Certify,
    Generated: CertifiedKernel<T, N, S>,
{
    #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
    if !cfg!(target_feature = "fma") && std::arch::is_x86_feature_detected!("fma") {
        // SAFETY: the CPU has FMA (detected just now).
        return unsafe { with_fma(companion, nu, balls, states) };
    }
    dispatch::<true, T, N, S>(companion, nu, balls, states)
}

/// The FMA companions (always inlined) compiled with FMA instructions.
///
/// # Safety
/// The CPU must support FMA.
#[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
#[target_feature(enable = "fma")]
#[allow(clippy::type_complexity)]
unsafe fn with_fma<T, const N: usize, const S: usize>(
    companion: Companion,
    nu: &[T; N],
    balls: [&Ball<T>; 2],
    states: [&BodyState<T, N, S>; 2],
) -> ([BodyState<T, N, S>; 2], [BodyState<T, N, S>; 2])
where
    T: crate::Scalar + Certify,
    Generated: CertifiedKernel<T, N, S>,
{
    dispatch::<true, T, N, S>(companion, nu, balls, states)
}
