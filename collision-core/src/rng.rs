//! A seeded random stream, reproducible across platforms and crate versions: the one source
//! of randomness for the verification points, the accuracy report's cases and the scenes'
//! random placement, so that every report and every scene run is reproducible from its seed.

use rand::{Rng as _, RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::ops::RangeInclusive;

/// A seeded ChaCha8 stream. A clone continues from the same place: it draws the same words.
#[derive(Clone)]
pub struct Rng(ChaCha8Rng);

impl Rng {
    /// The stream of `seed`.
    pub fn new(seed: u64) -> Self {
        Rng(ChaCha8Rng::seed_from_u64(seed))
    }

    /// The next 64 random bits.
    #[inline]
    pub fn next_u64(&mut self) -> u64 {
        self.0.next_u64()
    }

    /// Uniform in `[lo, hi)`: `lo + (hi - lo) k 2^-53` for `k` the top 53 bits of the next
    /// word.
    #[inline]
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        let unit = (self.0.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64);
        lo + (hi - lo) * unit
    }

    /// `true` with probability 1/2 (the top bit of the next word).
    pub fn coin(&mut self) -> bool {
        self.0.next_u64() >> 63 == 1
    }

    /// Uniform on the integers of `range` (rejection sampling: exactly uniform).
    pub fn integer(&mut self, range: RangeInclusive<u64>) -> u64 {
        self.0.random_range(range)
    }
}
