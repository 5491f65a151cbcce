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

    /// The chi-square statistic of `counts` against equal expected counts.
    fn chi2(counts: &[usize]) -> f64 {
        let total: usize = counts.iter().sum();
        let expected = total as f64 / counts.len() as f64;
        counts
            .iter()
            .map(|&o| (o as f64 - expected).powi(2) / expected)
            .sum()
    }

    /// The counts of `centres` in `bins^N` equal boxes of the box of sides `size`.
    fn histogram<const N: usize>(centres: &[[f64; N]], size: [f64; N], bins: usize) -> Vec<usize> {
        let mut counts = vec![0; bins.pow(N as u32)];
        for c in centres {
            let cell = (0..N).fold(0, |acc, k| {
                acc * bins + ((c[k] / size[k] * bins as f64) as usize).min(bins - 1)
            });
            counts[cell] += 1;
        }
        counts
    }

    /// The centres of random placement (the whole of `setup`, cover and batches included)
    /// are uniform over a periodic box: the box's translations leave the placement's law
    /// unchanged, so every centre is uniform whatever the packing. Over 10 seeds the
    /// histograms of the centres in `b^n` boxes (joint, `b = 4`) and along each axis (`b =
    /// 16`) must have a chi-square below `k - 1 + 6 sqrt(2 (k - 1))` for `k` boxes, the
    /// multinomial mean plus 6 of its standard deviations (hard-core exclusion makes the
    /// counts less variable than independent draws, so this bound is generous; the chance
    /// that uniform centres exceed it is below 1e-6). A bias of the density by a few percent
    /// fails it: the same centres with one coordinate mapped `x -> L (x / L)^1.1` do.
    fn uniform<const N: usize, const S: usize>(count: usize, fraction: f64) {
        let ball = match N {
            2 => std::f64::consts::PI / 4.0,
            _ => std::f64::consts::PI / 6.0,
        };
        let side = (count as f64 * ball / fraction).powf(1.0 / N as f64);
        let mut centres: Vec<[f64; N]> = Vec::new();
        let mut size = [0.0; N];
        for seed in 0..10 {
            let axes = vec![format!("\"{side:.12}\""); N].join(", ");
            let periodic = vec!["\"periodic\""; N].join(", ");
            let text = format!(
                "dim = {N}\n[box]\nsize = [{axes}]\nboundary = [{periodic}]\n\
                 [[species]]\nmass = 1\nradius = \"1/2\"\ncount = {count}\n\
                 [random]\nseed = {seed}\n"
            );
            let scene = noslip_scene::Scene::from_toml(&text, "uniform").unwrap();
            let placed = crate::setup::setup::<N, S>(&scene).unwrap();
            size = placed.size;
            centres.extend(placed.bodies.iter().map(|b| b.position));
        }
        let bound = |k: usize| (k - 1) as f64 + 6.0 * (2.0 * (k - 1) as f64).sqrt();
        let joint = histogram(&centres, size, 4);
        assert!(
            chi2(&joint) < bound(joint.len()),
            "{N}D joint: {}",
            chi2(&joint)
        );
        for k in 0..N {
            let axis: Vec<[f64; 1]> = centres.iter().map(|c| [c[k]]).collect();
            let counts = histogram(&axis, [size[k]], 16);
            assert!(
                chi2(&counts) < bound(16),
                "{N}D axis {k}: {}",
                chi2(&counts)
            );
        }
        let biased: Vec<[f64; 1]> = centres
            .iter()
            .map(|c| [size[0] * (c[0] / size[0]).powf(1.1)])
            .collect();
        let counts = histogram(&biased, [size[0]], 16);
        assert!(chi2(&counts) > bound(16), "{N}D biased: {}", chi2(&counts));
    }

    #[test]
    fn random_centres_are_uniform_over_a_periodic_box() {
        // Close to saturation (0.54 in 2D, 0.39 in 3D), where most draws are refused.
        uniform::<2, 1>(2000, 0.45);
        uniform::<3, 3>(3000, 0.3);
    }
}
