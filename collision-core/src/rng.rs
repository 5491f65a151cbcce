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

    /// The place in the stream: the count of 32-bit words drawn since its start (a word of
    /// [`Rng::next_u64`] or [`Rng::uniform`] takes two).
    #[inline]
    pub fn word_pos(&self) -> u128 {
        self.0.get_word_pos()
    }

    /// Continue from word `pos` of the stream (a [`Rng::word_pos`]): the words drawn next are
    /// the same as after `pos` words from the start, wherever the stream is now. Costs one
    /// refill of the stream's buffer (four ChaCha blocks).
    pub fn set_word_pos(&mut self, pos: u128) {
        self.0.set_word_pos(pos);
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Setting the word position gives the same words as drawing there from the start: for
    /// every position up to 300 words (both parities, across the 64-word buffer's ends),
    /// from streams that stand before, at and after it, the next 80 words of `next_u64` and
    /// `uniform` equal the reference's, and `word_pos` reads the position back.
    #[test]
    fn a_set_word_position_continues_the_stream_drawn_from_the_start() {
        let mut reference = Rng::new(7);
        let words: Vec<u32> = (0..400)
            .flat_map(|_| {
                let w = reference.next_u64();
                [w as u32, (w >> 32) as u32]
            })
            .collect();
        let word = |i: usize| u64::from(words[i]) | u64::from(words[i + 1]) << 32;
        for pos in 0..300usize {
            for from in [0, pos / 2, pos, pos + 41] {
                let mut rng = Rng::new(7);
                for _ in 0..from / 2 {
                    rng.next_u64();
                }
                rng.set_word_pos(pos as u128);
                assert_eq!(rng.word_pos(), pos as u128);
                for k in 0..40 {
                    assert_eq!(rng.next_u64(), word(pos + 2 * k), "{pos} {from} {k}");
                }
                let unit = (word(pos + 80) >> 11) as f64 * (1.0 / (1u64 << 53) as f64);
                assert_eq!(rng.uniform(2.0, 5.0), 2.0 + 3.0 * unit);
                assert_eq!(rng.word_pos(), pos as u128 + 82);
            }
        }
    }
}
