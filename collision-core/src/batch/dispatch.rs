//! Run-time choice of the instruction set: the same generic kernel compiled three times,
//! for the default target (x86-64: SSE2), with AVX2 + FMA and with AVX-512F enabled, and
//! picked by `is_x86_feature_detected!`.
//!
//! The kernels are `#[inline(always)]` and are inlined into `#[target_feature]` wrappers,
//! where LLVM's loop vectorizer widens the lane loop to the wider registers. Enabling `fma`
//! lets LLVM use FMA instructions only where the source asks for them: Rust never contracts
//! `a * b + c` on its own, so every level rounds exactly like the scalar kernel.

use std::fmt;

/// An instruction-set level the batch kernels are compiled for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Isa {
    /// The crate's compilation target as configured (x86-64 default: SSE2, 2 `f64` lanes).
    Baseline,
    /// AVX2 and FMA (4 `f64` lanes).
    Avx2,
    /// AVX-512F, with AVX2 and FMA (8 `f64` lanes).
    Avx512,
}

impl Isa {
    /// Every level, narrowest first.
    pub const ALL: [Isa; 3] = [Isa::Baseline, Isa::Avx2, Isa::Avx512];

    /// Whether this CPU runs the level (`Baseline` always).
    pub fn is_available(self) -> bool {
        match self {
            Isa::Baseline => true,
            #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
            Isa::Avx2 => is_x86_feature_detected!("avx2") && is_x86_feature_detected!("fma"),
            #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
            Isa::Avx512 => Isa::Avx2.is_available() && is_x86_feature_detected!("avx512f"),
            #[cfg(not(any(target_arch = "x86", target_arch = "x86_64")))]
            Isa::Avx2 | Isa::Avx512 => false,
        }
    }

    /// The widest available level.
    pub fn detect() -> Isa {
        Isa::available().last().unwrap_or(Isa::Baseline)
    }

    /// The available levels, narrowest first.
    pub fn available() -> impl DoubleEndedIterator<Item = Isa> {
        Isa::ALL.into_iter().filter(|isa| isa.is_available())
    }

    /// `"baseline"`, `"avx2"`, `"avx512"`.
    pub fn name(self) -> &'static str {
        match self {
            Isa::Baseline => "baseline",
            Isa::Avx2 => "avx2",
            Isa::Avx512 => "avx512",
        }
    }
}

impl fmt::Display for Isa {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A batch kernel to be compiled inside a `#[target_feature]` wrapper, holding what is
/// shared by the whole call. Implementations mark `run` `#[inline(always)]`, so that the
/// kernel is inlined there and compiled for the wrapper's instruction set.
///
/// The blocks and the output are arguments of the wrappers, never fields of the job: as
/// function arguments, `&[B]` and `&mut [O]` are known not to alias, which the loop
/// vectorizer needs (through a struct field that knowledge is lost and the lane loop stays
/// scalar).
pub(crate) trait Job<B, O> {
    /// The block kernel on `blocks`, `W` lanes at a time.
    fn run<const W: usize>(&self, blocks: &[B], out: &mut [O]);
}

/// Lanes per step at the baseline level: 1 (LLVM may still vectorize across the lanes). On
/// SSE2 width 1 measured within noise of width 8 for n = 3..5, slower at n = 2 and 1.7x
/// faster at n = 6, where 2 and 8 spill; docs/batch.md has the figures.
pub const BASELINE_WIDTH: usize = 1;

/// Lanes per step at AVX2: 4, one `f64` register per value (with 8, every value took two
/// of the 16 registers and n = 5, 6 spilled).
pub const AVX2_WIDTH: usize = 4;

/// Lanes per step at AVX-512: 8, one `f64` register (of 32) per value.
pub const AVX512_WIDTH: usize = 8;

/// Run `job` on `blocks` and `out`, compiled for `isa` when this CPU has it, else for the
/// baseline, at the level's width. Every level runs in a function of its own that takes the
/// blocks and the output as arguments (so they are known not to alias; the baseline was
/// once inlined into its caller, lost that knowledge and ran 1.4-1.8x slower than the
/// scalar kernel).
#[inline(always)]
pub(crate) fn run_on<B, O>(isa: Isa, job: &impl Job<B, O>, blocks: &[B], out: &mut [O]) {
    #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
    match isa {
        // SAFETY: the CPU has AVX-512F, AVX2 and FMA (checked just now by `is_available`,
        // which `is_x86_feature_detected!` caches).
        Isa::Avx512 if isa.is_available() => unsafe { x86::avx512(job, blocks, out) },
        // SAFETY: the CPU has AVX2 and FMA (as above).
        Isa::Avx2 if isa.is_available() => unsafe { x86::avx2(job, blocks, out) },
        _ => baseline(job, blocks, out),
    }
    #[cfg(not(any(target_arch = "x86", target_arch = "x86_64")))]
    {
        let _ = isa;
        baseline(job, blocks, out)
    }
}

/// Work compiled for one instruction-set level at a time, as the kernels are: `run::<W>` is
/// `#[inline(always)]` in its implementations, so [`at_level`] compiles it inside each level's
/// `#[target_feature]` wrapper, where LLVM vectorises it for that level (the gather and
/// scatter of row-major arrays, `rows/`). `W` is the level's lane width.
pub(crate) trait AtLevel {
    /// What the work returns.
    type Output;
    /// The work, at lane width `W`.
    fn run<const W: usize>(self) -> Self::Output;
}

/// Run `work` compiled for `isa` when this CPU has it, else for the baseline (as [`run_on`]).
#[inline(always)]
pub(crate) fn at_level<J: AtLevel>(isa: Isa, work: J) -> J::Output {
    #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
    match isa {
        // SAFETY: the CPU has AVX-512F, AVX2 and FMA (checked just now by `is_available`).
        Isa::Avx512 if isa.is_available() => unsafe { x86::avx512_work(work) },
        // SAFETY: the CPU has AVX2 and FMA (as above).
        Isa::Avx2 if isa.is_available() => unsafe { x86::avx2_work(work) },
        _ => baseline_work(work),
    }
    #[cfg(not(any(target_arch = "x86", target_arch = "x86_64")))]
    {
        let _ = isa;
        baseline_work(work)
    }
}

/// [`AtLevel`] work at the baseline level, in a function of its own.
#[inline(never)]
fn baseline_work<J: AtLevel>(work: J) -> J::Output {
    work.run::<BASELINE_WIDTH>()
}

/// The baseline level: the default target (x86-64: SSE2), [`BASELINE_WIDTH`] lanes at a
/// time.
#[inline(never)]
fn baseline<B, O>(job: &impl Job<B, O>, blocks: &[B], out: &mut [O]) {
    job.run::<BASELINE_WIDTH>(blocks, out)
}

#[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
mod x86 {
    use super::{AtLevel, Job};

    /// # Safety
    /// The CPU must support AVX2 and FMA.
    #[target_feature(enable = "avx2,fma")]
    pub(super) unsafe fn avx2_work<J: AtLevel>(work: J) -> J::Output {
        work.run::<{ super::AVX2_WIDTH }>()
    }

    /// # Safety
    /// The CPU must support AVX-512F, AVX2 and FMA.
    #[target_feature(enable = "avx512f,avx2,fma")]
    pub(super) unsafe fn avx512_work<J: AtLevel>(work: J) -> J::Output {
        work.run::<{ super::AVX512_WIDTH }>()
    }

    /// # Safety
    /// The CPU must support AVX2 and FMA.
    #[target_feature(enable = "avx2,fma")]
    pub(super) unsafe fn avx2<B, O>(job: &impl Job<B, O>, blocks: &[B], out: &mut [O]) {
        job.run::<{ super::AVX2_WIDTH }>(blocks, out)
    }

    /// # Safety
    /// The CPU must support AVX-512F, AVX2 and FMA.
    #[target_feature(enable = "avx512f,avx2,fma")]
    pub(super) unsafe fn avx512<B, O>(job: &impl Job<B, O>, blocks: &[B], out: &mut [O]) {
        job.run::<{ super::AVX512_WIDTH }>(blocks, out)
    }
}
