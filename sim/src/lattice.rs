//! The lattice start: sites of the checkerboard lattice `D_n` (the points of a grid whose
//! indices have an even sum; the square lattice turned by 45 degrees in 2D, face-centred cubic
//! in 3D) scaled to fill the box, for packings that random placement cannot reach.
//!
//! The grid has `m_k` points along axis `k` with step `h_k >= h`; a site is a grid point
//! `i` with `i_0 + .. + i_{n-1}` even. Two distinct sites differ by an integer vector `d`
//! with an even sum: either two of its components are nonzero (distance at least
//! `sqrt(h_j^2 + h_k^2) >= sqrt(2) h`) or one is, and is even (distance at least
//! `2 h_k >= 2 h`). So sites are at least `sqrt(2) h` apart, and balls of radii up to
//! `R_max` do not overlap when `h >= sqrt(2) R_max`. On a periodic axis `m_k` is even (or 1),
//! so the parity rule holds across the face (the minimum image of `d_k` keeps its parity)
//! and sites are at `(i_k + 1/2) L_k / m_k`; between walls they run from `R_max` to `L_k -
//! R_max` (the first and last layers touch the walls when `m_k > 1`; a single site is at
//! `L_k / 2`).
//!
//! `D_n` fills a fraction `V_n 2^(-n/2) / 2` of space with balls of radius `sqrt(2) h / 2`:
//! `pi/4 = 0.785`, `pi/(3 sqrt 2) = 0.740`, `pi^2/16 = 0.617`, `pi^2/(15 sqrt 2) = 0.465`,
//! `pi^3/96 = 0.323` for `n = 2..6` (the cubic lattice: 0.785, 0.524, 0.308, 0.164, 0.081); a
//! finite box holds fewer, as `m_k` is a whole number.

use collision_core::rng::Rng;

/// A grid along the box's axes; its sites are the points with an even index sum.
#[derive(Clone, Debug, PartialEq)]
pub struct Lattice<const N: usize> {
    /// Points per axis, `m_k >= 1`.
    pub m: [usize; N],
    /// The first point's coordinate per axis.
    origin: [f64; N],
    /// The step per axis (0 when `m_k = 1`).
    step: [f64; N],
    /// The largest coordinate a site may have per axis (`L_k - R_max` between walls).
    top: [f64; N],
    /// The least coordinate a site may have per axis (`R_max` between walls, else 0).
    bottom: [f64; N],
}

impl<const N: usize> Lattice<N> {
    /// The grid of the box `[0, size_k]` with steps at least `h` (`h > 0`) for balls of radius
    /// at most `r_max` (`2 r_max < size_k`): `m_k` is the largest even number (1 if none)
    /// with `L_k / m_k >= h` on a periodic axis, `floor((L_k - 2 r_max) / h) + 1` between
    /// walls.
    pub fn new(size: &[f64; N], periodic: &[bool; N], r_max: f64, h: f64) -> Self {
        let mut m = [1usize; N];
        let mut origin = [0.0; N];
        let mut step = [0.0; N];
        let mut top = [0.0; N];
        let mut bottom = [0.0; N];
        for k in 0..N {
            let fit = |length: f64| (length / h).floor().clamp(0.0, 1e15) as usize;
            if periodic[k] {
                let q = fit(size[k]);
                m[k] = if q >= 2 { q - q % 2 } else { 1 };
                step[k] = size[k] / m[k] as f64;
                origin[k] = step[k] / 2.0;
                top[k] = size[k];
            } else {
                let usable = size[k] - 2.0 * r_max;
                m[k] = fit(usable) + 1;
                if m[k] == 1 {
                    origin[k] = size[k] / 2.0;
                } else {
                    origin[k] = r_max;
                    step[k] = usable / (m[k] - 1) as f64;
                }
                bottom[k] = r_max;
                top[k] = size[k] - r_max;
            }
        }
        Lattice {
            m,
            origin,
            step,
            top,
            bottom,
        }
    }

    /// The number of grid points, `prod m_k` (saturating).
    pub fn points(&self) -> u64 {
        self.m.iter().fold(1u64, |p, &m| p.saturating_mul(m as u64))
    }

    /// The number of sites: half the grid points when some `m_k` is even, else
    /// `(prod m_k + 1) / 2` (the corner `0` is a site and the parities alternate).
    pub fn sites(&self) -> u64 {
        let p = self.points();
        if self.m.iter().any(|m| m % 2 == 0) {
            p / 2
        } else {
            p / 2 + 1
        }
    }

    /// The grid point of flat index `g < points()` (the last axis fastest), if it is a site.
    pub fn site(&self, mut g: u64) -> Option<[usize; N]> {
        let mut index = [0usize; N];
        for k in (0..N).rev() {
            index[k] = (g % self.m[k] as u64) as usize;
            g /= self.m[k] as u64;
        }
        (index.iter().sum::<usize>() % 2 == 0).then_some(index)
    }

    /// The centre of grid point `index`: `origin_k + i_k step_k`, kept within
    /// `[R_max, L_k - R_max]` between walls and below `L_k` on periodic axes (`L_k > 0`).
    pub fn position(&self, index: &[usize; N]) -> [f64; N] {
        std::array::from_fn(|k| {
            let x = self.origin[k] + index[k] as f64 * self.step[k];
            if self.bottom[k] > 0.0 {
                x.clamp(self.bottom[k], self.top[k])
            } else {
                // Below L_k (a rounding of (m - 1/2) L/m up to L would leave the box).
                x.min(f64::from_bits(self.top[k].to_bits() - 1))
            }
        })
    }

    /// The lattice with the largest `h >= h_min` whose site count is at least `target`, or
    /// `None` if even `h_min` gives fewer (bisection on `h`: the count only falls as `h`
    /// grows).
    pub fn widest(
        size: &[f64; N],
        periodic: &[bool; N],
        r_max: f64,
        h_min: f64,
        target: u64,
    ) -> Option<Self> {
        let lattice = |h: f64| Lattice::new(size, periodic, r_max, h);
        if lattice(h_min).sites() < target {
            return None;
        }
        // The count is 1 once h exceeds every side.
        let mut hi = size.iter().fold(h_min, |a, &b| a.max(b)) * 2.0;
        if lattice(hi).sites() >= target {
            return Some(lattice(hi));
        }
        let mut lo = h_min;
        for _ in 0..200 {
            let mid = lo + (hi - lo) / 2.0;
            if mid <= lo || mid >= hi {
                break;
            }
            if lattice(mid).sites() >= target {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Some(lattice(lo))
    }
}

/// `2^-30`: sites are at least `2 R_max (1 + MARGIN)` apart, so that the rounding of the
/// steps and coordinates (relative `2^-52` of a side) cannot make two balls overlap.
pub const MARGIN: f64 = 1.0 / (1u64 << 30) as f64;

/// The most grid points a lattice start enumerates (to count its usable sites): `2^32`.
pub const MAX_POINTS: u64 = 1 << 32;

/// The widest lattice (steps at least `sqrt(2) r_max (1 + MARGIN)`) with at least `count`
/// sites where `usable` holds, or why there is none. Without obstacles of any kind every
/// site is usable (`all_usable`) and the site count decides; else the usable sites are
/// counted and the target raised in proportion to the shortfall, at most 64 times.
pub fn start<const N: usize>(
    size: &[f64; N],
    periodic: &[bool; N],
    r_max: f64,
    count: usize,
    all_usable: bool,
    usable: impl Fn(&[f64; N]) -> bool,
) -> Result<Lattice<N>, String> {
    let h_min = std::f64::consts::SQRT_2 * r_max * (1.0 + MARGIN);
    let count = count as u64;
    let usable_sites = |l: &Lattice<N>| -> u64 {
        (0..l.points())
            .filter_map(|g| l.site(g))
            .filter(|i| usable(&l.position(i)))
            .count() as u64
    };
    let densest = Lattice::new(size, periodic, r_max, h_min);
    let refuse = |have: u64, what: &str| {
        Err(format!(
            "the lattice start holds {have} balls{what} with centres at least 2 R_max = {} \
             apart (the checkerboard lattice D_{N} on a {:?} grid), fewer than the {count} to \
             place: give a larger box or fewer balls",
            2.0 * r_max,
            densest.m
        ))
    };
    if densest.sites() < count {
        return refuse(densest.sites(), "");
    }
    let mut target = count;
    for _ in 0..64 {
        let Some(l) = Lattice::widest(size, periodic, r_max, h_min, target) else {
            break;
        };
        if all_usable {
            return Ok(l);
        }
        if l.points() > MAX_POINTS {
            return Err(format!(
                "the lattice start would need more than 2^32 grid points to find {count} sites \
                 clear of the table's boundaries, obstacles and explicit balls"
            ));
        }
        let have = usable_sites(&l);
        if have >= count {
            return Ok(l);
        }
        let next = if have == 0 {
            target.saturating_mul(2)
        } else {
            ((target as f64 * count as f64 / have as f64).ceil() as u64).max(target + 1)
        };
        if next > densest.sites() {
            if l == densest {
                break;
            }
            target = densest.sites();
        } else {
            target = next;
        }
    }
    if densest.points() > MAX_POINTS {
        return refuse(0, " (too many grid points to count)");
    }
    refuse(
        usable_sites(&densest),
        " clear of the table's boundaries, obstacles and explicit balls",
    )
}

/// A seeded random order of `0..total`, drawn lazily: the Fisher-Yates shuffle, position
/// `j` swapping with a position uniform in `j..total`. The positions are a vector when
/// `total <= DENSE` and else a map of the swapped ones (memory `O(draws)`); both hold the
/// same permutation, so the order depends on the seed and `total` alone.
#[derive(Debug, Default)]
pub struct Shuffle {
    drawn: u64,
    dense: Vec<u32>,
    swapped: std::collections::HashMap<u64, u64>,
}

/// The largest `total` a [`Shuffle`] keeps as a vector: `2^26` positions of 4 bytes, 256 MB
/// at most.
pub const DENSE: u64 = 1 << 26;

impl Shuffle {
    /// No draws yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// The next of `0..total` in the order (`total` the same at every call), or `None` once
    /// all are drawn.
    pub fn draw(&mut self, rng: &mut Rng, total: u64) -> Option<u64> {
        if total <= DENSE {
            self.draw_dense(rng, total)
        } else {
            self.draw_sparse(rng, total)
        }
    }

    fn draw_dense(&mut self, rng: &mut Rng, total: u64) -> Option<u64> {
        let j = self.drawn;
        if j >= total {
            return None;
        }
        let k = rng.integer(j..=total - 1);
        self.drawn += 1;
        if j == 0 {
            // total <= DENSE < 2^32: every position fits a u32.
            self.dense = (0..total as u32).collect();
        }
        self.dense.swap(j as usize, k as usize);
        Some(u64::from(self.dense[j as usize]))
    }

    fn draw_sparse(&mut self, rng: &mut Rng, total: u64) -> Option<u64> {
        let j = self.drawn;
        if j >= total {
            return None;
        }
        let k = rng.integer(j..=total - 1);
        self.drawn += 1;
        let at = |s: &Self, i: u64| s.swapped.get(&i).copied().unwrap_or(i);
        let (value_j, value_k) = (at(self, j), at(self, k));
        self.swapped.insert(k, value_j);
        self.swapped.remove(&j);
        Some(value_k)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn distance2<const N: usize>(
        a: &[f64; N],
        b: &[f64; N],
        size: &[f64; N],
        p: &[bool; N],
    ) -> f64 {
        (0..N)
            .map(|k| {
                let mut d = (a[k] - b[k]).abs();
                if p[k] {
                    d = d.min(size[k] - d);
                }
                d * d
            })
            .sum()
    }

    /// Every site, by enumeration.
    fn all_sites<const N: usize>(l: &Lattice<N>) -> Vec<[f64; N]> {
        (0..l.points())
            .filter_map(|g| l.site(g))
            .map(|i| l.position(&i))
            .collect()
    }

    #[test]
    fn the_site_count_is_that_of_the_enumeration() {
        for m in [
            [1, 1, 1],
            [3, 3, 3],
            [2, 3, 5],
            [4, 1, 1],
            [3, 5, 7],
            [6, 6, 2],
        ] {
            let l = Lattice::<3> {
                m,
                origin: [0.0; 3],
                step: [1.0; 3],
                top: [1e9; 3],
                bottom: [0.0; 3],
            };
            let counted = (0..l.points()).filter(|&g| l.site(g).is_some()).count() as u64;
            assert_eq!(l.sites(), counted, "{m:?}");
        }
    }

    #[test]
    fn sites_are_sqrt2_h_apart_and_inside_the_box() {
        // Periodic and walled axes, sides that are and are not multiples of h.
        let r_max = 0.5;
        let h = std::f64::consts::SQRT_2 * r_max;
        for (size, periodic) in [
            ([6.0, 7.3, 5.0], [true, true, true]),
            ([6.0, 7.3, 5.0], [false, true, false]),
            ([1.2, 9.9, 4.4], [true, false, true]),
            ([3.0, 3.0, 1.1], [false, false, false]),
        ] {
            let l = Lattice::<3>::new(&size, &periodic, r_max, h);
            for k in 0..3 {
                if periodic[k] {
                    assert!(l.m[k] == 1 || l.m[k] % 2 == 0, "{:?}", l.m);
                    assert!(size[k] / l.m[k] as f64 >= h);
                }
            }
            let sites = all_sites(&l);
            assert_eq!(sites.len() as u64, l.sites());
            for (i, a) in sites.iter().enumerate() {
                for k in 0..3 {
                    if periodic[k] {
                        assert!((0.0..size[k]).contains(&a[k]), "{a:?}");
                    } else {
                        assert!(r_max <= a[k] && a[k] <= size[k] - r_max, "{a:?}");
                    }
                }
                for b in &sites[..i] {
                    let d2 = distance2(a, b, &size, &periodic);
                    // 2 h^2 = 4 r_max^2 up to the rounding of the steps (a few ulps).
                    assert!(
                        d2 >= 4.0 * r_max * r_max * (1.0 - 1e-12),
                        "{a:?} {b:?} {d2}"
                    );
                }
            }
        }
    }

    #[test]
    fn the_widest_lattice_has_enough_sites_and_a_wider_one_too_few() {
        // 28 x 19 points at h_min (10 / 0.354 = 28.3; 6.5 / 0.354 = 18.4, plus 1): 266 sites.
        let (size, periodic) = ([10.0, 7.0], [true, false]);
        let r_max = 0.25;
        let h_min = std::f64::consts::SQRT_2 * r_max;
        for target in [1, 2, 7, 40, 100, 266] {
            let l = Lattice::<2>::widest(&size, &periodic, r_max, h_min, target).unwrap();
            assert!(l.sites() >= target);
            // The steps of the chosen lattice are its h; a slightly wider h loses sites.
            let h = (0..2)
                .filter(|&k| l.m[k] > 1)
                .map(|k| l.step[k])
                .fold(f64::INFINITY, f64::min);
            if h.is_finite() {
                let wider = Lattice::<2>::new(&size, &periodic, r_max, h * (1.0 + 1e-9));
                assert!(wider.sites() < target, "{target}: {:?} {:?}", l.m, wider.m);
            }
        }
        let most = Lattice::<2>::new(&size, &periodic, r_max, h_min).sites();
        assert_eq!(most, 266);
        assert!(Lattice::<2>::widest(&size, &periodic, r_max, h_min, most).is_some());
        assert!(Lattice::<2>::widest(&size, &periodic, r_max, h_min, most + 1).is_none());
    }

    #[test]
    fn the_shuffle_is_a_seeded_permutation() {
        for total in [1u64, 2, 7, 100] {
            let order = |seed| {
                let (mut rng, mut s) = (Rng::new(seed), Shuffle::new());
                std::iter::from_fn(|| s.draw(&mut rng, total)).collect::<Vec<_>>()
            };
            let mut sorted = order(3);
            assert_eq!(order(3), sorted);
            sorted.sort();
            assert_eq!(sorted, (0..total).collect::<Vec<_>>());
            if total == 100 {
                assert_ne!(order(3), order(4));
                assert_ne!(order(3), sorted);
            }
        }
        // The map (beyond DENSE) holds the same permutation as the vector.
        for total in [1u64, 5, 300] {
            let (mut a, mut b) = (Rng::new(9), Rng::new(9));
            let (mut dense, mut sparse) = (Shuffle::new(), Shuffle::new());
            let d: Vec<u64> = std::iter::from_fn(|| dense.draw_dense(&mut a, total)).collect();
            let s: Vec<u64> = std::iter::from_fn(|| sparse.draw_sparse(&mut b, total)).collect();
            assert_eq!(d, s);
        }
    }
}
