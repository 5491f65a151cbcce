//! The FMA entry point: the FMA kernels on FMA instructions wherever the CPU has them.

use super::dispatch;
use crate::kernels::{Generated, Kernel};
use crate::{Ball, BodyState, Scalar};

/// [`collide_unchecked`](super::collide_unchecked) with the FMA kernels (`free_fma`, `fixed_fma`), run on FMA
/// instructions wherever the CPU has them ([`fma_in_hardware`]): on x86 and x86-64 the
/// kernels are compiled a second time inside a `#[target_feature(enable = "fma")]` function,
/// chosen at run time by `is_x86_feature_detected!("fma")` (detected once and cached by std);
/// on AArch64 `mul_add` is always an instruction. Elsewhere, and on x86 CPUs without FMA
/// (older or low-end ones), `mul_add` is a libm call: the same bits, several times slower
/// than [`collide_unchecked`](super::collide_unchecked) (`docs/accuracy.md` has the figures).
///
/// Both paths give the same bits: an FMA instruction and libm's `fma` both round `a b + c`
/// once, correctly, and the rest of the kernel is the same IEEE operations in the same order
/// (Rust never contracts `a * b + c` by itself).
#[inline]
pub fn collide_unchecked_fma<T, const N: usize, const S: usize>(
    nu: &[T; N],
    balls: [&Ball<T>; 2],
    states: [&BodyState<T, N, S>; 2],
) -> [BodyState<T, N, S>; 2]
where
    T: Scalar,
    Generated: Kernel<T, N, S>,
{
    #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
    if !cfg!(target_feature = "fma") && std::arch::is_x86_feature_detected!("fma") {
        // SAFETY: the CPU has FMA (detected just now).
        return unsafe { x86::collide_unchecked_fma(nu, balls, states) };
    }
    collide_unchecked_fma_as_compiled(nu, balls, states)
}

/// [`collide_unchecked_fma`] compiled for the crate's target as configured, without run-time
/// dispatch: on x86-64 without `-C target-feature=+fma` every `mul_add` is a libm call.
/// Always inlined, so inside [`x86::collide_unchecked_fma`] it is compiled with FMA.
#[inline(always)]
fn collide_unchecked_fma_as_compiled<T, const N: usize, const S: usize>(
    nu: &[T; N],
    balls: [&Ball<T>; 2],
    states: [&BodyState<T, N, S>; 2],
) -> [BodyState<T, N, S>; 2]
where
    T: Scalar,
    Generated: Kernel<T, N, S>,
{
    dispatch::<true, T, N, S>(nu, balls, states)
}

#[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
mod x86 {
    use super::*;

    /// The FMA kernels (always inlined) compiled with FMA instructions.
    ///
    /// # Safety
    /// The CPU must support FMA.
    #[target_feature(enable = "fma")]
    pub(super) unsafe fn collide_unchecked_fma<T, const N: usize, const S: usize>(
        nu: &[T; N],
        balls: [&Ball<T>; 2],
        states: [&BodyState<T, N, S>; 2],
    ) -> [BodyState<T, N, S>; 2]
    where
        T: Scalar,
        Generated: Kernel<T, N, S>,
    {
        collide_unchecked_fma_as_compiled(nu, balls, states)
    }
}

/// Whether [`collide_unchecked_fma`] runs on FMA instructions on this machine: x86 and
/// x86-64 CPUs that report FMA at run time (or a build with `-C target-feature=+fma`), and
/// every AArch64 CPU. `false` means `mul_add` is a libm call there.
pub fn fma_in_hardware() -> bool {
    #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
    {
        cfg!(target_feature = "fma") || std::arch::is_x86_feature_detected!("fma")
    }
    #[cfg(not(any(target_arch = "x86", target_arch = "x86_64")))]
    {
        cfg!(target_arch = "aarch64") || cfg!(target_feature = "fma")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collide_unchecked;
    use rand::{Rng as _, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    type Case<const N: usize, const S: usize> =
        ([f64; N], [Ball<f64>; 2], [BodyState<f64, N, S>; 2]);

    /// `2^U(-k, k)` with a random sign.
    fn scaled(rng: &mut ChaCha8Rng, k: f64) -> f64 {
        let sign = if rng.random::<bool>() { 1.0 } else { -1.0 };
        sign * rng.random_range(-k..k).exp2()
    }

    /// Seeded contacts of every kind `collide_unchecked_fma` dispatches: both bodies free
    /// (one of them a point mass a quarter of the time), body 1 immovable, body 2 immovable;
    /// entries spread over `2^-20..2^20`, so that a fused `a b + c` rounds differently from
    /// `a * b + c` in most outputs. Normals unit to rounding, approaching or not: the kernels
    /// are rational maps, and the equality of two evaluations holds for any finite inputs.
    fn cases<const N: usize, const S: usize>(seed: u64, len: usize) -> Vec<Case<N, S>> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let n = N as f64;
        (0..len)
            .map(|k| {
                let raw: [f64; N] = std::array::from_fn(|_| rng.random_range(-1.0..1.0));
                let norm = raw.iter().map(|x| x * x).sum::<f64>().sqrt();
                let nu = raw.map(|x| x / norm);
                let ball = |rng: &mut ChaCha8Rng| Ball {
                    inv_mass: scaled(rng, 4.0).abs(),
                    radius: scaled(rng, 2.0).abs(),
                    gamma2: rng.random_range(0.0..2.0 / n),
                };
                let mut balls = [ball(&mut rng), ball(&mut rng)];
                match k % 4 {
                    1 => balls[0].inv_mass = 0.0,
                    2 => balls[1].inv_mass = 0.0,
                    3 => balls[k / 4 % 2].gamma2 = 0.0,
                    _ => {}
                }
                let state = |rng: &mut ChaCha8Rng| BodyState {
                    spin: std::array::from_fn(|_| scaled(rng, 20.0)),
                    velocity: std::array::from_fn(|_| scaled(rng, 20.0)),
                };
                let states = [state(&mut rng), state(&mut rng)];
                (nu, balls, states)
            })
            .collect()
    }

    fn bits<const N: usize, const S: usize>(states: &[BodyState<f64, N, S>; 2]) -> Vec<u64> {
        states
            .iter()
            .flat_map(|s| s.spin.iter().chain(&s.velocity))
            .map(|x| x.to_bits())
            .collect()
    }

    /// The dispatched entry point (FMA instructions on this CPU if it has them) against the
    /// same kernels compiled for the default target (libm `fma` on x86-64): every output bit
    /// equal. The cases are chosen so that the FMA kernels differ from the plain ones in
    /// most of them, so the comparison would see a path that does not fuse.
    fn dispatched_equals_as_compiled<const N: usize, const S: usize>()
    where
        Generated: Kernel<f64, N, S>,
    {
        let cases = cases::<N, S>(0xf3a ^ N as u64, 400);
        let mut differ_from_plain = 0;
        for (k, (nu, [b1, b2], [s1, s2])) in cases.iter().enumerate() {
            let dispatched = collide_unchecked_fma(nu, [b1, b2], [s1, s2]);
            let as_compiled = collide_unchecked_fma_as_compiled(nu, [b1, b2], [s1, s2]);
            assert_eq!(
                bits(&dispatched),
                bits(&as_compiled),
                "n = {N}, case {k}: {dispatched:?} vs {as_compiled:?}"
            );
            let plain = collide_unchecked(nu, [b1, b2], [s1, s2]);
            differ_from_plain += usize::from(bits(&plain) != bits(&dispatched));
        }
        assert!(
            differ_from_plain * 2 > cases.len(),
            "n = {N}: only {differ_from_plain} of {} cases tell FMA from plain",
            cases.len()
        );
    }

    #[test]
    fn dispatched_fma_kernels_equal_the_default_target_build_bit_for_bit() {
        dispatched_equals_as_compiled::<2, 1>();
        dispatched_equals_as_compiled::<3, 3>();
        dispatched_equals_as_compiled::<4, 6>();
        dispatched_equals_as_compiled::<5, 10>();
        dispatched_equals_as_compiled::<6, 15>();
    }
}
