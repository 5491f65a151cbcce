//! The covered voxels of random placement: a bitmap over the box of the voxels that lie wholly
//! inside the exclusion ball of one placed ball or obstacle, so that a candidate centre falling
//! in one is refused by reading one bit instead of searching the cells around it.
//!
//! Near saturation most candidates are refused (3D at a packing of 0.3: 35 draws per ball, 34
//! of them overlapping), and with `10^6` balls each search reads scattered memory. A voxel is
//! marked only when every point of it is closer than `e = r_min + r_i` to the centre `c_i` of
//! item `i` (`r_min` the least radius still to be placed), so a candidate of any radius `r >=
//! r_min` in it overlaps item `i`: the bitmap refuses exactly candidates that the overlap test
//! ([`crate::place::Cells::clear_of`]) refuses, and the placed centres are the same bits.
//!
//! Voxels have `m_k` per axis and width `w_k = L_k / m_k` about `e_min / 4` (`e_min = 2 r_min`),
//! with at most `128 capacity + 4096` voxels (wider in a large box), `m_k < 2^26`. Voxel `v` is
//! marked for a centre `c` when `sum_k F_k^2 <= e^2 (1 - 2^-20)`, with `F_k` the farthest
//! distance along axis `k` from `c_k` to the voxel's side (the nearest image on a periodic
//! axis) plus `2^-20 w_k`. That slack covers the roundings: a candidate `x` is in voxel
//! `floor(x_k (1 / w_k))` up to `2^-26 w_k` (the product, below `2^26`, is within two
//! roundings of `x_k / w_k`), the minimum
//! image `L_k - d_k` is within `eps L_k < 2^-26 w_k` of the true one, and the overlap test's
//! `|x - c|^2 < (r + r_i)^2` is computed with a relative error below `2^-50`.
//!
//! In 4 or more dimensions the cover is off (every candidate goes to the overlap test): the
//! voxels a ball marks grow as `(2 e / w + 1)^(n - 1)` rows, and a voxel inside a ball needs a
//! diagonal `sqrt(n) w` well below `e`.

/// Voxels per least exclusion distance `e_min` along an axis (before widening for memory).
const VOXELS_PER_EXCLUSION: f64 = 4.0;

/// Voxels per axis of a block, one `u64` word (`B^N = 64` for `N <= 3`: 64, 8, 4): the
/// voxels a ball marks lie in a few words, near each other in memory.
const fn block_side(n: usize) -> usize {
    match n {
        1 => 64,
        2 => 8,
        _ => 4,
    }
}

/// The relative slack `2^-20` of the marking rule.
const SLACK: f64 = 1.0 / (1u64 << 20) as f64;

/// The bitmap of covered voxels (empty when the cover is off).
#[derive(Clone, Debug)]
pub struct Cover<const N: usize> {
    m: [usize; N],
    /// Blocks per axis, `ceil(m_k / B)` with `B` voxels per axis of a block ([`block_side`]).
    blocks: [usize; N],
    width: [f64; N],
    /// `1 / w_k`: a coordinate's voxel is `floor(x_k (1 / w_k))`.
    inverse: [f64; N],
    periodic: [bool; N],
    bits: Vec<u64>,
    /// Room for the per-axis runs of [`Cover::mark`].
    scratch: Vec<Entry>,
}

impl<const N: usize> Cover<N> {
    const B: usize = block_side(N);

    /// The cover of the box `[0, size_k]` for up to `capacity` balls whose least exclusion
    /// distance is `e_min > 0` (twice the least radius to place); off (nothing is ever
    /// covered) in 4 or more dimensions, without balls to place, or when the widest voxel
    /// allowed has a diagonal above `e_min`.
    pub fn new(size: [f64; N], periodic: [bool; N], e_min: f64, capacity: usize) -> Self {
        let off = Cover {
            m: [1; N],
            blocks: [1; N],
            width: size,
            inverse: [0.0; N],
            periodic,
            bits: Vec::new(),
            scratch: Vec::new(),
        };
        if N > 3 || capacity == 0 || e_min.is_nan() || e_min <= 0.0 {
            return off;
        }
        let budget = (128 * capacity + 4096) as f64;
        let count = |w: f64| -> [usize; N] {
            std::array::from_fn(|k| {
                ((size[k] / w).floor().min((1 << 26) as f64 - 1.0) as usize).max(1)
            })
        };
        let voxels = |m: &[usize; N]| m.iter().map(|&x| x as f64).product::<f64>();
        let log_volume: f64 = size.iter().map(|l| l.ln()).sum();
        let mut w =
            (e_min / VOXELS_PER_EXCLUSION).max(((log_volume - budget.ln()) / N as f64).exp());
        let mut m = count(w);
        while voxels(&m) > budget {
            w *= 1.25;
            m = count(w);
        }
        let width: [f64; N] = std::array::from_fn(|k| size[k] / m[k] as f64);
        if width.iter().map(|w| w * w).sum::<f64>() > e_min * e_min {
            return off;
        }
        let blocks: [usize; N] = std::array::from_fn(|k| m[k].div_ceil(Self::B));
        Cover {
            m,
            blocks,
            width,
            inverse: std::array::from_fn(|k| 1.0 / width[k]),
            periodic,
            bits: vec![0; blocks.iter().product()],
            scratch: Vec::new(),
        }
    }

    /// Whether the cover is on (it has voxels).
    pub fn is_on(&self) -> bool {
        !self.bits.is_empty()
    }

    /// The voxel count per axis.
    pub fn shape(&self) -> [usize; N] {
        self.m
    }

    /// The word and bit of voxel `v` (per-axis indices below `m_k`): the word of its block
    /// (row-major over blocks, axis `N - 1` fastest), the bit of its place in the block.
    fn bit(&self, v: &[usize; N]) -> (usize, usize) {
        let word = (0..N).fold(0, |acc, k| acc * self.blocks[k] + v[k] / Self::B);
        let bit = (0..N).fold(0, |acc, k| acc * Self::B + v[k] % Self::B);
        (word, bit)
    }

    /// The voxel of `x` along axis `k`, `floor(x_k (1 / w_k))` clamped to the grid (`as
    /// usize` truncates toward 0 and saturates at 0; NaN goes to 0).
    fn voxel(&self, x: &[f64; N], k: usize) -> usize {
        ((x[k] * self.inverse[k]) as usize).min(self.m[k] - 1)
    }

    /// Where the bit of `x`'s voxel is: its word and the bit in it (word 0 when the cover is
    /// off).
    pub fn locate(&self, x: &[f64; N]) -> (usize, usize) {
        if self.bits.is_empty() {
            return (0, 0);
        }
        self.bit(&std::array::from_fn(|k| self.voxel(x, k)))
    }

    /// Ask the CPU to fetch the word of a [`Cover::locate`] (a hint: no effect on results),
    /// so that candidates drawn ahead wait for memory together.
    pub fn prefetch(&self, (word, _): (usize, usize)) {
        collision_core::batch::prefetch(self.bits.get(word));
    }

    /// Whether the voxel at `(word, bit)` from [`Cover::locate`] is covered: then a ball of
    /// radius `r >= r_min` centred anywhere in it overlaps an item marked with `e = r_min +
    /// r_i`. Never when the cover is off.
    pub fn is_covered(&self, (word, bit): (usize, usize)) -> bool {
        self.bits.get(word).is_some_and(|w| w >> bit & 1 == 1)
    }

    /// Whether `x` lies in a covered voxel ([`Cover::locate`] and [`Cover::is_covered`]).
    pub fn covered(&self, x: &[f64; N]) -> bool {
        self.is_covered(self.locate(x))
    }

    /// Ask the CPU to fetch the words [`Cover::mark`] will change for `centre` and `e` (a
    /// hint: no effect on results): marking a ball then need not wait for memory.
    pub fn prefetch_around(&self, centre: &[f64; N], e: f64) {
        if self.bits.is_empty() || e.is_nan() || e <= 0.0 {
            return;
        }
        // Per axis the blocks from the one of `c - e` to the one of `c + e` (wrapped; at most
        // 4 per axis: beyond, this is only a hint and stops).
        let mut blocks = [[0usize; 4]; N];
        let mut len = [0usize; N];
        for k in 0..N {
            let (m, b) = (self.m[k] as i64, Self::B as i64);
            let reach = |x: f64| (x * self.inverse[k]).floor() as i64;
            let (lo, hi) = (reach(centre[k] - e), reach(centre[k] + e));
            let (lo, hi) = if self.periodic[k] {
                (lo, hi)
            } else {
                (lo.max(0), hi.min(m - 1))
            };
            for v in (lo..=hi).step_by(Self::B).chain([hi]) {
                let block = (v.rem_euclid(m) / b) as usize;
                if len[k] < 4 && (len[k] == 0 || blocks[k][len[k] - 1] != block) {
                    blocks[k][len[k]] = block;
                    len[k] += 1;
                }
            }
            if len[k] == 0 {
                return;
            }
        }
        let mut pick = [0usize; N];
        'all: loop {
            let word = (0..N).fold(0, |acc, k| acc * self.blocks[k] + blocks[k][pick[k]]);
            collision_core::batch::prefetch(self.bits.get(word));
            for k in 0..N {
                pick[k] += 1;
                if pick[k] < len[k] {
                    continue 'all;
                }
                pick[k] = 0;
            }
            return;
        }
    }

    /// Mark the voxels wholly within `e` of `centre` (see the module's rule).
    pub fn mark(&mut self, centre: &[f64; N], e: f64) {
        if self.bits.is_empty() || e.is_nan() || e <= 0.0 {
            return;
        }
        // Per axis a run of voxels that can lie within e, each with its F_k^2 and its terms of
        // the word and bit index (`start[k]..end[k]` in `entries`; the voxel holding the centre,
        // where F_k is least, at `own[k]` of the run).
        let mut entries = std::mem::take(&mut self.scratch);
        entries.clear();
        let (mut start, mut end, mut own) = ([0usize; N], [0usize; N], [0usize; N]);
        let (mut word_stride, mut bit_stride) = (1, 1);
        for k in (0..N).rev() {
            let (w, m) = (self.width[k], self.m[k] as i64);
            // Only voxels of the box between walls; on a periodic axis the images within
            // `L_k` of the centre, among them every voxel's nearest (so at most `2 m_k + 1`).
            let centre_voxel = (centre[k] / w).floor() as i64;
            let (least, most) = if self.periodic[k] {
                (centre_voxel - m, centre_voxel + m)
            } else {
                (0, m - 1)
            };
            let first = (((centre[k] - e) / w).floor() as i64).max(least);
            let last = (((centre[k] + e) / w).floor() as i64).min(most);
            start[k] = entries.len();
            own[k] = (centre_voxel.clamp(first, last.max(first)) - first) as usize;
            entries.extend((first..=last).map(|j| {
                let a = (j as f64 * w - centre[k]).abs();
                let b = ((j + 1) as f64 * w - centre[k]).abs();
                let f = a.max(b) + SLACK * w;
                let v = j.rem_euclid(m) as usize;
                Entry {
                    far2: f * f,
                    word: v / Self::B * word_stride,
                    bit: v % Self::B * bit_stride,
                }
            }));
            end[k] = entries.len();
            word_stride *= self.blocks[k];
            bit_stride *= Self::B;
        }
        let runs = Runs {
            entries: &entries,
            start,
            end,
            own,
            limit: e * e * (1.0 - SLACK),
        };
        self.fill(&runs, 0, 0.0, 0, 0);
        self.scratch = entries;
    }

    /// Mark the voxels of axes `k..N` below the word and bit index terms `word`, `bit` of
    /// axes `0..k`, whose partial sum of `F^2` is `partial`: along axis `k` outward from the
    /// centre's voxel, each way until the sum exceeds the limit (`F_k` grows away from it).
    fn fill(&mut self, runs: &Runs<'_, N>, k: usize, partial: f64, word: usize, bit: usize) {
        let run = &runs.entries[runs.start[k]..runs.end[k]];
        let own = runs.own[k];
        if own >= run.len() || partial + run[own].far2 > runs.limit {
            return;
        }
        let mut lo = own;
        while lo > 0 && partial + run[lo - 1].far2 <= runs.limit {
            lo -= 1;
        }
        let mut hi = own;
        while hi + 1 < run.len() && partial + run[hi + 1].far2 <= runs.limit {
            hi += 1;
        }
        if k + 1 < N {
            for entry in &run[lo..=hi] {
                let sum = partial + entry.far2;
                self.fill(runs, k + 1, sum, word + entry.word, bit + entry.bit);
            }
            return;
        }
        // The last axis: consecutive voxels of one block are consecutive bits of one word.
        let mut current = (word + run[lo].word, 0u64);
        for entry in &run[lo..=hi] {
            let at = word + entry.word;
            if at != current.0 {
                self.bits[current.0] |= current.1;
                current = (at, 0);
            }
            current.1 |= 1 << (bit + entry.bit);
        }
        self.bits[current.0] |= current.1;
    }
}

/// One voxel of a run along an axis: `F_k^2` and its terms of the word and bit index.
#[derive(Clone, Debug)]
struct Entry {
    far2: f64,
    word: usize,
    bit: usize,
}

/// The per-axis runs of voxels around one centre that [`Cover::mark`] considers.
struct Runs<'a, const N: usize> {
    entries: &'a [Entry],
    start: [usize; N],
    end: [usize; N],
    own: [usize; N],
    limit: f64,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::place::distance2;
    use collision_core::rng::Rng;

    /// Marks `centres` with exclusion `e` in a cover for `e_min` and returns it, after checking that every
    /// probe (random points, and the corners of every voxel approached from inside) that is
    /// covered is closer than `e` to a centre as the overlap test computes it.
    fn sound<const N: usize>(
        size: [f64; N],
        periodic: [bool; N],
        centres: &[[f64; N]],
        e_min: f64,
        e: f64,
    ) -> Cover<N> {
        let mut cover = Cover::new(size, periodic, e_min, 1000);
        assert!(cover.is_on(), "{size:?}");
        for c in centres {
            cover.prefetch_around(c, e);
            cover.mark(c, e);
        }
        let overlaps = |x: &[f64; N]| {
            centres
                .iter()
                .any(|c| distance2(x, c, &size, &periodic) < e * e)
        };
        let mut rng = Rng::new(3);
        for _ in 0..20_000 {
            let x: [f64; N] = std::array::from_fn(|k| rng.uniform(0.0, size[k]));
            assert!(!cover.covered(&x) || overlaps(&x), "{x:?}");
        }
        // Every corner of every voxel, approached from inside it (the top side one float
        // below the next voxel).
        let m = cover.shape();
        let count: usize = m.iter().product();
        let below = |x: f64| f64::from_bits(x.to_bits() - 1);
        for v in 0..count {
            let mut rest = v;
            let j: [usize; N] = std::array::from_fn(|k| {
                let j = rest % m[k];
                rest /= m[k];
                j
            });
            for corner in 0..1 << N {
                let x: [f64; N] = std::array::from_fn(|k| {
                    let w = cover.width[k];
                    if corner >> k & 1 == 0 {
                        j[k] as f64 * w
                    } else {
                        below((j[k] + 1) as f64 * w)
                    }
                });
                assert!(!cover.covered(&x) || overlaps(&x), "{x:?}");
            }
        }
        cover
    }

    /// The share of random points of the box within `0.99 e` of `c` (nearest image) that are
    /// covered.
    fn share<const N: usize>(cover: &Cover<N>, c: [f64; N], e: f64) -> f64 {
        let mut rng = Rng::new(4);
        let (mut inside, mut covered) = (0, 0);
        while inside < 20_000 {
            let d: [f64; N] = std::array::from_fn(|_| rng.uniform(-e, e));
            let x: [f64; N] = std::array::from_fn(|k| {
                let size = cover.width[k] * cover.m[k] as f64;
                let x = c[k] + d[k];
                if cover.periodic[k] {
                    x.rem_euclid(size)
                } else {
                    x
                }
            });
            let in_box = (0..N).all(|k| x[k] >= 0.0 && x[k] < cover.width[k] * cover.m[k] as f64);
            if in_box && d.iter().map(|x| x * x).sum::<f64>() < 0.98 * e * e {
                inside += 1;
                covered += cover.covered(&x) as usize;
            }
        }
        covered as f64 / inside as f64
    }

    #[test]
    fn a_covered_voxel_lies_wholly_within_the_exclusion() {
        // Centres inside, on faces and corners, across periodic faces and against walls; one
        // axis of a single voxel's width and one of two.
        let c2 = [[0.0, 0.0], [3.9, 1.0], [2.0, 2.0], [0.3, 3.99]];
        let cover = sound([4.0, 4.0], [true, false], &c2, 1.0, 1.0);
        assert!(share(&cover, [2.0, 2.0], 1.0) > 0.55);
        sound(
            [0.3, 4.0],
            [true, true],
            &c2.map(|c| [c[0] * 0.07, c[1]]),
            0.9,
            0.9,
        );
        let c3 = [[0.0; 3], [5.9, 0.1, 2.0], [3.0, 3.0, 3.0], [1.0, 5.99, 0.5]];
        let cover = sound([6.0, 6.0, 6.0], [true, true, false], &c3, 1.0, 1.0);
        // With voxels a quarter of e wide, well over half of an exclusion ball is covered.
        assert!(share(&cover, [3.0, 3.0, 3.0], 1.0) > 0.45);
        assert!(share(&cover, [0.0, 0.0, 0.0], 1.0) > 0.45);
        sound(
            [0.5, 6.0, 6.0],
            [true; 3],
            &c3.map(|c| [c[0] / 12.0, c[1], c[2]]),
            1.0,
            1.0,
        );
        // On the edge: voxels 1/4 wide, and a voxel whose far corner is exactly `e` from the
        // centre (offsets 1 and 3/4 of e = 5/4; 1/4, 1/2, 1/2 of e = 3/4): that corner does
        // not overlap (`|x - c|^2 >= e^2`), so that voxel must not be marked.
        sound([6.0, 6.0], [true, true], &[[3.0, 3.0]], 1.0, 1.25);
        sound([6.0; 3], [true; 3], &[[3.0; 3]], 1.0, 0.75);
    }

    #[test]
    fn the_cover_is_off_where_it_cannot_pay() {
        // 4 dimensions; nothing to place; voxels the memory bound makes wider than `e`.
        assert!(!Cover::<4>::new([10.0; 4], [true; 4], 1.0, 100).is_on());
        assert!(!Cover::<3>::new([10.0; 3], [true; 3], 1.0, 0).is_on());
        assert!(!Cover::<3>::new([1e6; 3], [true; 3], 1.0, 100).is_on());
        // On: voxels a quarter of e wide, or wider in a large box, within the budget.
        let cover = Cover::<3>::new([10.0; 3], [true; 3], 1.0, 1000);
        assert_eq!(cover.shape(), [40; 3]);
        let cover = Cover::<2>::new([1000.0, 1000.0], [true, false], 2.0, 10_000);
        let voxels: usize = cover.shape().iter().product();
        assert!(
            cover.is_on() && voxels <= 128 * 10_000 + 4096,
            "{:?}",
            cover.shape()
        );
        // Off, nothing is covered and marking changes nothing.
        let mut off = Cover::<4>::new([10.0; 4], [true; 4], 1.0, 100);
        off.mark(&[5.0; 4], 3.0);
        assert!(!off.covered(&[5.0; 4]));
    }
}
