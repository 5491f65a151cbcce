//! The pair times of a gathered neighbourhood, [`LANES`] partners at a time, in front of
//! the scalar offer.
//!
//! A full scan in 3D meets about a dozen partners (27 cells of 0.4 balls at `phi` 0.2) and
//! keeps one. The scalar path spent about a hundred instructions on each (the canonical
//! [`crate::canonical::pair_time`], its loads one record at a time, and a branch on each
//! result). Here a first pass computes the times of all of them, [`LANES`] records at once,
//! component by component, in arrays the compiler keeps in vector registers (compiled for
//! AVX2 where the CPU has it, detected once), and keeps the least; a second pass offers to
//! the scalar path only the partners whose time is at most that least time (or the best
//! already held, if earlier): in general one.
//!
//! **Same events, same bits.** The lanes spell [`crate::canonical::pair_time`]'s operations
//! in its order (`Motion::at`, `(q - p) + k L`, the dot products summed over `k = 0, 1, ...`
//! from `0.0`, `1 / a`, the closest-approach root), each an IEEE operation on one lane, and
//! Rust never fuses a product into a sum, so a lane's time is the scalar time (NaN exactly
//! where the scalar is NaN; `max` and `sqrt` give the same numbers, up to the sign of a zero,
//! which no comparison sees): the test below checks it on 400 000 pairs. The passes only
//! *drop* partners whose time is later than another's (or NaN), which the scalar loop's
//! `may_beat` would have refused or replaced; every partner at the least time is offered
//! with its lane's time, and the scalar offer keeps the least `(t, key)`, which does not
//! depend on the order of the offers. The time offered is `t_ref + t`, whose bits do not
//! depend on the sign of a zero `t` unless `t_ref` is `-0`, which no record time is (they
//! start at `+0` and move to event times and to `+0`): the same bits as the scalar time
//! (asserted on every offer in the tests, and below). So the events taken, their times and
//! their order are the scalar loop's, and logs are unchanged (the reference tests compare the
//! cell engine's log with the all-pairs engine's, byte for byte).
//!
//! A neighbourhood of at most one chunk (a layer in 3D) goes straight to the scalar offer, and
//! 2D scans never come here (two to five balls a neighbourhood): there the padding and the
//! second pass cost more than they save.

use crate::cells::Odometer;
use crate::motion::Motion;
use crate::residents::{Resident, Residents};

/// Partners per chunk.
pub(crate) const LANES: usize = 4;

/// What [`Gathered::least`] meets the places with: the scanning ball's flight, the records,
/// and the box's sides.
pub(super) struct Flight<'a, const N: usize>(
    pub(super) &'a Motion<N>,
    pub(super) &'a Residents<N>,
    pub(super) &'a [f64; N],
);

/// The slab places of the balls a scan meets, the image of each one's cell, and their pair
/// times, kept between scans (no allocation per event once they have grown).
#[derive(Debug)]
pub(super) struct Gathered<const N: usize> {
    /// The places ([`crate::residents::Residents::gather_cells`], [`Self::gather_walk`]),
    /// padded to whole chunks.
    pub(super) places: Vec<u32>,
    /// Per place, in a scan with shifted cells: the index of its cell's image in `bases`.
    codes: Vec<u16>,
    /// The cells' images `s + W_i` in the scanning ball's record coordinates: the first for
    /// the whole scan, or one per cell if some cell is shifted (a periodic image); it only
    /// grows.
    bases: Vec<[f64; N]>,
    /// Whether the cells have images of their own (`codes` is then set).
    shifted: bool,
    /// The pair time of each place.
    times: Vec<f64>,
    /// The padded length, a multiple of [`LANES`].
    len: usize,
    /// Whether this CPU runs AVX2, detected once: the chunks' loop is then compiled for it
    /// (four lanes in one register; the same IEEE operations, so the same numbers).
    avx2: bool,
}

impl<const N: usize> Default for Gathered<N> {
    fn default() -> Self {
        Gathered {
            places: Vec::new(),
            codes: Vec::new(),
            bases: Vec::new(),
            shifted: false,
            times: Vec::new(),
            len: 0,
            #[cfg(target_arch = "x86_64")]
            avx2: is_x86_feature_detected!("avx2"),
            #[cfg(not(target_arch = "x86_64"))]
            avx2: false,
        }
    }
}

impl<const N: usize> Gathered<N> {
    /// Starts a scan whose cells all have the image `base` (no periodic shift): the first
    /// of `bases` (which only grows: no allocation per scan).
    #[inline]
    pub(super) fn unshifted(&mut self, base: [f64; N]) {
        match self.bases.first_mut() {
            Some(first) => *first = base,
            None => self.bases.push(base),
        }
        self.shifted = false;
    }

    /// Starts a scan whose cells each have their own image, and gathers the places of the cells of
    /// `walk` (a cell at the grid's edge: [`crate::cells::Near::listing`]) with their images
    /// `s + W_i` (`s` the cell's shift, `w_i` the scanning ball's wraps): per cell, four
    /// places and codes whatever its length, as in
    /// [`crate::residents::Residents::gather_cells`], in one loop with the odometer's
    /// position in locals; returns the number of places. The room is made once, before the
    /// loop, and each axis's terms `s_k + W_ik` are converted once, not once per cell.
    #[inline(always)]
    pub(super) fn gather_walk(
        &mut self,
        residents: &Residents<N>,
        walk: &Odometer<N>,
        w_i: &[i16; N],
    ) -> usize {
        self.shifted = true;
        if walk.done {
            return 0;
        }
        // Distinct cells hold at most every ball once; a cell listed at several images, as
        // often as it is listed (counted first: only in a grid of a few cells an axis).
        let listed = if walk.distinct {
            residents.len()
        } else {
            walk.clone().map(|nb| residents.span(nb.cell).1).sum()
        };
        let room = listed + LANES;
        if self.places.len() < room {
            self.places.resize(room, 0);
        }
        if self.codes.len() < room {
            self.codes.resize(room, 0);
        }
        // Per axis, each of its cells' image term, exact in f64.
        let terms: [[f64; 5]; N] = std::array::from_fn(|k| {
            std::array::from_fn(|a| f64::from(walk.shifts[k][a]) + f64::from(w_i[k]))
        });
        let cells: usize = walk.len.iter().product();
        if self.bases.len() < cells {
            self.bases.resize(cells, [0.0; N]);
        }
        let (places, codes) = (&mut self.places[..room], &mut self.codes[..room]);
        let mut count = 0;
        let mut code = 0;
        let mut at = [0usize; N];
        loop {
            let cell: usize = (0..N).map(|k| walk.part[k][at[k]]).sum();
            self.bases[code] = std::array::from_fn(|k| terms[k][at[k]]);
            let (start, len) = residents.span(cell);
            let first: &mut [u32; LANES] = (&mut places[count..count + LANES]).try_into().unwrap();
            *first = [start, start + 1, start + 2, start + 3];
            let first: &mut [u16; LANES] = (&mut codes[count..count + LANES]).try_into().unwrap();
            *first = [code as u16; LANES];
            for k in LANES..len {
                places[count + k] = start + k as u32;
                codes[count + k] = code as u16;
            }
            count += len;
            code += 1;
            let mut k = N;
            loop {
                if k == 0 {
                    return count;
                }
                k -= 1;
                at[k] += 1;
                if at[k] < walk.len[k] {
                    break;
                }
                at[k] = 0;
            }
        }
    }

    /// The places, with room for at least `balls + 4` of them (for
    /// [`crate::residents::Residents::gather_cells`]; they grow once, then stay).
    #[inline]
    pub(super) fn room(&mut self, balls: usize) -> &mut [u32] {
        if self.places.len() < balls + LANES {
            self.places.resize(balls + LANES, 0);
        }
        &mut self.places
    }

    /// The image of place `p`'s cell.
    #[inline(always)]
    pub(super) fn base(&self, p: usize) -> &[f64; N] {
        if self.shifted {
            &self.bases[self.codes[p] as usize]
        } else {
            &self.bases[0]
        }
    }

    /// Pads the first `count` places to whole chunks with `own`, the scanning ball's own
    /// place: its time with itself is NaN (`dv = 0`, so `d . dv` is not negative) whatever
    /// the image.
    #[inline]
    pub(super) fn pad(&mut self, count: usize, own: u32) {
        let len = count.next_multiple_of(LANES);
        if self.places.len() < len {
            self.places.resize(len, own);
        }
        self.places[count..len].fill(own);
        if self.shifted {
            if self.codes.len() < len {
                self.codes.resize(len, 0);
            }
            self.codes[count..len].fill(0);
        }
        if self.times.len() < len {
            self.times.resize(len, f64::NAN);
        }
        self.len = len;
    }

    /// The pair time of place `p` (after [`Self::least`]).
    #[inline(always)]
    pub(super) fn time(&self, p: usize) -> f64 {
        self.times[p]
    }

    /// Fills the times of the padded places with flight `a` ([`pair_times`], a chunk at a
    /// time; the records in `residents`, in a box of sides `size`), and returns the least of
    /// them and `bound` (NaNs skipped).
    #[inline(always)]
    pub(super) fn least(&mut self, bound: f64, flight: Flight<'_, N>) -> f64 {
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: the CPU runs AVX2 (detected in `default`).
            return unsafe {
                if self.shifted {
                    self.least_avx2::<true>(bound, flight)
                } else {
                    self.least_avx2::<false>(bound, flight)
                }
            };
        }
        if self.shifted {
            self.least_portable::<true>(bound, flight)
        } else {
            self.least_portable::<false>(bound, flight)
        }
    }

    /// [`Self::least`] compiled for AVX2 (`times_of` inlined into it).
    ///
    /// # Safety
    /// The CPU must run AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn least_avx2<const SHIFTED: bool>(&mut self, bound: f64, flight: Flight<'_, N>) -> f64 {
        self.least_portable::<SHIFTED>(bound, flight)
    }

    /// [`Self::least`] for the target's baseline; `SHIFTED` as `self.shifted`.
    #[inline(always)]
    fn least_portable<const SHIFTED: bool>(&mut self, bound: f64, flight: Flight<'_, N>) -> f64 {
        let Flight(a, residents, size) = flight;
        let mut least = [bound; LANES];
        for c in 0..self.len / LANES {
            let at = c * LANES;
            let chunk: &[u32; LANES] = self.places[at..at + LANES].try_into().unwrap();
            let bases: [&[f64; N]; LANES] = if SHIFTED {
                std::array::from_fn(|l| &self.bases[self.codes[at + l] as usize])
            } else {
                [&self.bases[0]; LANES]
            };
            let lanes: [&Resident<N>; LANES] = std::array::from_fn(|l| residents.at(chunk[l]));
            let t = pair_times(a, lanes, bases, size);
            for l in 0..LANES {
                // NaN compares false.
                if t[l] < least[l] {
                    least[l] = t[l];
                }
            }
            self.times[at..at + LANES].copy_from_slice(&t);
        }
        least.iter().fold(bound, |a, &b| a.min(b))
    }
}

/// The pair times of flight `a` with the flights of `lanes` ([`crate::canonical::pair_time`],
/// lane by lane): lane `l`'s ball at image `bases[l] - W_b` (`bases[l] = s + W_a`, its
/// cell's image in `a`'s record coordinates), in a box of sides `size`; NaN where the pair
/// never meets.
#[inline(always)]
pub(crate) fn pair_times<const N: usize>(
    a: &Motion<N>,
    lanes: [&Resident<N>; LANES],
    bases: [&[f64; N]; LANES],
    size: &[f64; N],
) -> [f64; LANES] {
    let t_ref: [f64; LANES] = std::array::from_fn(|l| a.since.max(lanes[l].motion.since));
    // Motion::at's dt, for a and for b.
    let dt_a: [f64; LANES] = std::array::from_fn(|l| t_ref[l] - a.since);
    let dt_b: [f64; LANES] = std::array::from_fn(|l| t_ref[l] - lanes[l].motion.since);
    let mut d = [[0.0; LANES]; N];
    let mut dv = [[0.0; LANES]; N];
    for k in 0..N {
        for l in 0..LANES {
            let b = &lanes[l].motion;
            let p = a.pos[k] + a.velocity[k] * dt_a[l];
            let q = b.pos[k] + b.velocity[k] * dt_b[l];
            let image = bases[l][k] - f64::from(lanes[l].wraps[k]);
            d[k][l] = (q - p) + image * size[k];
            dv[k][l] = b.velocity[k] - a.velocity[k];
        }
    }
    // contact_time_or_nan, lane by lane.
    let mut aa = [0.0; LANES];
    let mut bb = [0.0; LANES];
    for k in 0..N {
        for l in 0..LANES {
            aa[l] += dv[k][l] * dv[k][l];
            bb[l] += d[k][l] * dv[k][l];
        }
    }
    let inv_a: [f64; LANES] = std::array::from_fn(|l| 1.0 / aa[l]);
    let t0: [f64; LANES] = std::array::from_fn(|l| -bb[l] * inv_a[l]);
    let mut h2 = [0.0; LANES];
    for k in 0..N {
        for l in 0..LANES {
            let h = d[k][l] + t0[l] * dv[k][l];
            h2[l] += h * h;
        }
    }
    std::array::from_fn(|l| {
        let sigma = a.radius + lanes[l].motion.radius;
        let gap = sigma * sigma - h2[l];
        let t = (t0[l] - (gap * inv_a[l]).max(0.0).sqrt()).max(0.0);
        let t = if bb[l] < 0.0 && gap >= 0.0 {
            t
        } else {
            f64::NAN
        };
        t_ref[l] + t
    })
}

/// A neighbour cell's image in the scanning ball's record coordinates, `s + W_i` (whole
/// numbers, exact in `f64`).
#[inline(always)]
pub(crate) fn cell_image<const N: usize>(shift: &[i8; N], wraps: &[i16; N]) -> [f64; N] {
    std::array::from_fn(|k| f64::from(shift[k]) + f64::from(wraps[k]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::canonical::pair_time;

    /// 400 000 pairs in 2D and 3D (near, far, receding, grazing, at rest,
    /// from records of different times, at images): each lane's time is the scalar
    /// canonical time, bit for bit (NaN where it is NaN).
    fn lanes_are_the_scalar_time<const N: usize>(seed: u64) {
        let mut state = seed;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 * 4.0 - 2.0
        };
        let size = [7.5; N];
        let mut met = 0;
        for round in 0..50_000 {
            let flight = |next: &mut dyn FnMut() -> f64| Motion::<N> {
                pos: std::array::from_fn(|_| next() * 3.0),
                since: if round % 3 == 0 { 0.0 } else { next().abs() },
                velocity: std::array::from_fn(|_| if round % 11 == 0 { 0.0 } else { next() }),
                radius: 1.0 + next().abs(),
            };
            let a = flight(&mut next);
            let residents: [Resident<N>; LANES] = std::array::from_fn(|_| Resident {
                motion: flight(&mut next),
                wraps: std::array::from_fn(|_| (next() * 1.5).round() as i16),
                ball: 1,
                count: 0,
            });
            let bases: [[f64; N]; LANES] =
                std::array::from_fn(|_| std::array::from_fn(|_| (next() * 1.5).round()));
            let lanes = std::array::from_fn(|l| &residents[l]);
            let got = pair_times(&a, lanes, std::array::from_fn(|l| &bases[l]), &size);
            for l in 0..LANES {
                let image: [f64; N] =
                    std::array::from_fn(|k| bases[l][k] - f64::from(residents[l].wraps[k]));
                let want = pair_time(&a, &residents[l].motion, &image, &size);
                assert_eq!(got[l].is_nan(), want.is_nan(), "{round} {l}");
                if !want.is_nan() {
                    met += 1;
                    assert_eq!(got[l].to_bits(), want.to_bits(), "{round} {l}");
                }
            }
        }
        // The sample meets often enough to test the times, not only the NaNs.
        assert!(met > 1_000, "{met}");
    }

    #[test]
    fn lanes_give_the_scalar_times() {
        lanes_are_the_scalar_time::<2>(0x9e37_79b9_7f4a_7c15);
        lanes_are_the_scalar_time::<3>(0x2545_f491_4f6c_dd1d);
    }
}
