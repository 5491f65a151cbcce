//! Run time per collision: repeated timed passes over an in-cache batch.
//!
//! One pass applies the kernel to every case of the batch (inputs and outputs through
//! `black_box`). Passes are grouped into samples of at least [`MIN_SAMPLE`] so that the
//! clock's resolution does not matter; the report gives the median over samples and the
//! 25th and 75th percentiles as the spread. These are report figures, not benchmarks: the
//! criterion benches (`cargo bench -p collision-core`) are the controlled measurement.

use serde::Serialize;
use std::hint::black_box;
use std::time::{Duration, Instant};

/// Shortest timed sample.
pub const MIN_SAMPLE: Duration = Duration::from_micros(200);

/// Nanoseconds per collision over timed passes of an in-cache batch (module docs).
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Timing {
    /// Median nanoseconds per collision.
    pub median_ns: f64,
    /// 25th percentile of nanoseconds per collision over the samples.
    pub p25_ns: f64,
    /// 75th percentile of nanoseconds per collision over the samples.
    pub p75_ns: f64,
    /// Timed samples, and passes over the batch in each.
    pub samples: usize,
    /// Passes over the batch in each sample (as many as fill about [`MIN_SAMPLE`]).
    pub passes_per_sample: usize,
    /// Cases in the batch.
    pub batch: usize,
}

/// Time `pass` (one pass over `batch` cases): `samples` samples after one warm-up pass.
pub fn time(batch: usize, samples: usize, mut pass: impl FnMut()) -> Timing {
    let start = Instant::now();
    pass();
    let once = start.elapsed().max(Duration::from_nanos(1));
    let passes = (MIN_SAMPLE.as_nanos() / once.as_nanos()).max(1) as usize;
    let mut per_case: Vec<f64> = (0..samples.max(1))
        .map(|_| {
            let t = Instant::now();
            for _ in 0..passes {
                pass();
            }
            t.elapsed().as_nanos() as f64 / (passes * batch.max(1)) as f64
        })
        .collect();
    per_case.sort_by(f64::total_cmp);
    let at = |q: f64| per_case[((per_case.len() - 1) as f64 * q).round() as usize];
    Timing {
        median_ns: at(0.5),
        p25_ns: at(0.25),
        p75_ns: at(0.75),
        samples: per_case.len(),
        passes_per_sample: passes,
        batch,
    }
}

/// One pass of `kernel` over `cases`, results kept from the optimiser.
#[inline(always)]
pub fn pass_over<C, R>(cases: &[C], kernel: impl Fn(&C) -> R) {
    for c in cases {
        black_box(kernel(black_box(c)));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quartiles_bracket_the_median() {
        let cases: Vec<u64> = (0..64).collect();
        let t = time(cases.len(), 9, || pass_over(&cases, |x| x.wrapping_mul(3)));
        assert!(t.p25_ns <= t.median_ns && t.median_ns <= t.p75_ns);
        assert!(t.median_ns > 0.0 && t.samples == 9 && t.batch == 64);
    }
}
