//! Random sequential addition of one ball: centres drawn uniformly in the ball's region of the
//! box until one is clear of everything placed, the first clear draw kept.
//!
//! Near saturation most draws overlap, and with many balls each test reads memory far from
//! the last. So the draws are made `ahead` at a time (up to [`AHEAD`]): the words of the
//! [`Cover`] bitmap that every draw of the batch will read are fetched together, then the
//! cells around the draws the cover does not refuse, then the draws are tested in order, a
//! covered one refused at once, the others by the full test. Drawing ahead changes nothing:
//! the kept centre is the first clear one of the stream, and the stream is left just after
//! its draws (set to the batch's start in the stream's words, [`Rng::word_pos`], plus the `2 N`
//! words of each draw up to the kept one), so velocity and spin then take the same words as when each centre was drawn and
//! tested in turn.

use crate::cover::Cover;
use crate::place::{Cells, Near};
use collision_core::rng::Rng;

/// The most draws made ahead of their tests.
pub const AHEAD: usize = 16;

/// A random centre for a ball of radius `r`: each coordinate uniform in `[0, L_k)` on a
/// periodic axis, in `[r, L_k - r)` between walls (one word of `rng` per axis).
pub fn random_position<const N: usize>(
    rng: &mut Rng,
    size: &[f64; N],
    periodic: &[bool; N],
    r: f64,
) -> [f64; N] {
    std::array::from_fn(|a| {
        if periodic[a] {
            rng.uniform(0.0, size[a])
        } else {
            rng.uniform(r, size[a] - r)
        }
    })
}

/// The box, the placed balls and what a centre must also satisfy.
pub struct Region<'a, const N: usize, F> {
    /// The box's sides.
    pub size: [f64; N],
    /// The periodic axes.
    pub periodic: [bool; N],
    /// The voxels wholly covered for every radius still to place.
    pub cover: &'a Cover<N>,
    /// The placed balls.
    pub balls: &'a Cells<N>,
    /// The test of a centre `p` for radius `r` beyond the placed balls (the table, the
    /// obstacles).
    pub inside: F,
}

impl<const N: usize, F: Fn(&[f64; N], f64) -> bool> Region<'_, N, F> {
    /// Whether a ball of radius `r` at `p` is clear: not in a covered voxel, clear of the
    /// placed balls, and `inside`.
    pub fn clear(&self, p: &[f64; N], r: f64) -> bool {
        !self.cover.covered(p) && self.balls.clear_of(p, r) && (self.inside)(p, r)
    }

    /// The first clear centre for a ball of radius `r` among at most `limit` draws from
    /// `rng`, and the number of draws it took (`None` and `limit` if none was clear). Draws
    /// are made `ahead` at a time (clamped to `1..=AHEAD`; [`AHEAD`] after the first batch)
    /// into `batch`; `rng` is left as if the draws had been made one by one up to the
    /// returned count.
    pub fn draw(
        &self,
        batch: &mut Batch<N>,
        rng: &mut Rng,
        r: f64,
        limit: usize,
        ahead: usize,
    ) -> (Option<[f64; N]>, usize) {
        let mut spent = 0;
        let mut ahead = ahead.clamp(1, AHEAD);
        while spent < limit {
            let count = ahead.min(limit - spent);
            let start = rng.word_pos();
            for (p, voxel) in batch.points[..count].iter_mut().zip(&mut batch.voxels) {
                *p = random_position(rng, &self.size, &self.periodic, r);
                *voxel = self.cover.locate(p);
                self.cover.prefetch(*voxel);
            }
            // The cells around the draws the cover does not refuse, fetched together.
            let draws = batch.points[..count].iter().zip(&batch.voxels);
            for ((p, voxel), near) in draws.zip(&mut batch.near) {
                if !self.cover.is_covered(*voxel) {
                    self.balls.near_into(p, near);
                    self.balls.prefetch(near);
                }
            }
            let draws = batch.points[..count].iter().zip(&batch.voxels);
            for (j, ((p, voxel), near)) in draws.zip(&batch.near).enumerate() {
                if !self.cover.is_covered(*voxel)
                    && self.balls.clear_near(near, p, r)
                    && (self.inside)(p, r)
                {
                    if j + 1 < count {
                        // Back to just after the kept centre's draw: `N` words of two
                        // 32-bit words each per draw.
                        rng.set_word_pos(start + (2 * N * (j + 1)) as u128);
                    }
                    return (Some(*p), spent + j + 1);
                }
            }
            spent += count;
            ahead = AHEAD;
        }
        (None, spent)
    }
}

/// Room for the draws of one batch of [`Region::draw`]: the centres, the place of their bits
/// in the cover and the cells around them (kept from ball to ball, so nothing is cleared per
/// ball).
#[derive(Clone, Debug)]
pub struct Batch<const N: usize> {
    points: [[f64; N]; AHEAD],
    voxels: [(usize, usize); AHEAD],
    near: [Near<N>; AHEAD],
}

impl<const N: usize> Default for Batch<N> {
    fn default() -> Self {
        Batch {
            points: [[0.0; N]; AHEAD],
            voxels: [(0, 0); AHEAD],
            near: [Near::NONE; AHEAD],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Drawing ahead keeps the first clear centre of the stream and leaves the stream where
    /// drawing one by one would: compared over every `ahead` with the one-by-one loop, for
    /// clear centres found at the first draw, inside a batch, at its end and not at all.
    #[test]
    fn drawing_ahead_keeps_the_first_clear_draw_and_the_stream() {
        let size = [10.0, 10.0];
        let periodic = [true, false];
        let cover = Cover::new(size, periodic, 0.0, 0);
        let balls = Cells::new(size, periodic, 1.0, 1);
        // Clear only right of x = 9 (about one draw in ten), or nowhere.
        for edge in [0.0, 9.0, 20.0] {
            let region = Region {
                size,
                periodic,
                cover: &cover,
                balls: &balls,
                inside: |p: &[f64; 2], _: f64| p[0] > edge,
            };
            for limit in [1, 5, 16, 17, 40] {
                for ahead in [0, 1, 3, 16, 100] {
                    for seed in 0..20 {
                        let mut one = Rng::new(seed);
                        let mut expected = (None, limit);
                        for spent in 1..=limit {
                            let p = random_position(&mut one, &size, &periodic, 0.5);
                            if region.clear(&p, 0.5) {
                                expected = (Some(p), spent);
                                break;
                            }
                        }
                        let mut rng = Rng::new(seed);
                        let batch = &mut Batch::default();
                        assert_eq!(region.draw(batch, &mut rng, 0.5, limit, ahead), expected);
                        assert_eq!(rng.next_u64(), one.next_u64(), "{edge} {limit} {ahead}");
                    }
                }
            }
        }
    }
}
