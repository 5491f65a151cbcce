//! A cell grid for random placement: the overlap test of a candidate centre visits only the
//! balls (or obstacles) of the `3^n` cells around it, so placing `N` balls costs `O(N)` tests
//! at a fixed packing instead of `O(N^2)`.
//!
//! Cells are at least `reach (1 + 2^-20)` wide along every axis, where `reach` is the largest
//! distance at which two items can overlap; two centres closer than `reach` (minimum image on
//! periodic axes) are then in the same or adjacent cells, with a margin of `2^-20` of a cell
//! for the rounding of `x_k (1 / width_k)` (the cell coordinates are below `2^26`, and the
//! product is within two roundings of the quotient, so below `2^-26` of a cell). Of the `3^n`
//! cells around a point only those that come within `reach` of it are visited. The grid has
//! at most `2 capacity + 16` cells (wider cells in a large box), so its memory is
//! `O(capacity)` whatever the box.
//!
//! Each cell holds its first item in place (centre, radius, index) and links to the others,
//! kept apart: with cells about one contact distance wide a cell rarely holds two balls, so a
//! test reads the cells around the point and little else, all of which can be fetched from
//! memory before it.

/// Squared distance with the minimum image on periodic axes: `sum_k d_k^2` with `d_k = |a_k -
/// b_k|`, replaced by `min(d_k, L_k - d_k)` on a periodic axis.
pub fn distance2<const N: usize>(
    a: &[f64; N],
    b: &[f64; N],
    size: &[f64; N],
    periodic: &[bool; N],
) -> f64 {
    (0..N)
        .map(|k| {
            let mut d = (a[k] - b[k]).abs();
            if periodic[k] {
                d = d.min(size[k] - d);
            }
            d * d
        })
        .sum()
}

/// A placed ball or obstacle, in its cell or in the overflow: its centre, its radius, its
/// index + 1 (0: an empty cell) and the next item of the cell in the overflow (`+ 1`, 0 for
/// none).
#[derive(Clone, Debug)]
struct Slot<const N: usize> {
    centre: [f64; N],
    radius: f64,
    index: u32,
    next: u32,
}

impl<const N: usize> Slot<N> {
    /// An empty cell.
    const EMPTY: Self = Slot {
        centre: [0.0; N],
        radius: 0.0,
        index: 0,
        next: 0,
    };
}

/// The cells, each with its first item in place, and the overflow of the others.
#[derive(Clone, Debug)]
pub struct Cells<const N: usize> {
    reach: f64,
    n: [usize; N],
    width: [f64; N],
    /// `1 / width_k`: a coordinate's cell is `floor(x_k (1 / width_k))`.
    inverse: [f64; N],
    size: [f64; N],
    periodic: [bool; N],
    /// Per axis, the flat index's stride (row-major, axis `N - 1` fastest).
    stride: [usize; N],
    cells: Vec<Slot<N>>,
    overflow: Vec<Slot<N>>,
    len: usize,
}

impl<const N: usize> Cells<N> {
    /// A grid of the box `[0, size_k]` for up to `capacity` items that overlap only within
    /// `reach` (`reach > 0`).
    pub fn new(size: [f64; N], periodic: [bool; N], reach: f64, capacity: usize) -> Self {
        let budget = (2 * capacity + 16) as f64;
        let count = |w: f64| -> [usize; N] {
            std::array::from_fn(|k| ((size[k] / w).floor().min(1e15) as usize).max(1))
        };
        let cells = |n: &[usize; N]| n.iter().map(|&x| x as f64).product::<f64>();
        // Start from the width that gives `budget` cells in the box, then widen until it does.
        let log_volume: f64 = size.iter().map(|l| l.ln()).sum();
        let mut w = (reach * (1.0 + 1.0 / (1u64 << 20) as f64))
            .max(((log_volume - budget.ln()) / N as f64).exp());
        let mut n = count(w);
        while cells(&n) > budget {
            w *= 1.25;
            n = count(w);
        }
        let width: [f64; N] = std::array::from_fn(|k| size[k] / n[k] as f64);
        let mut stride = [1; N];
        for k in (0..N - 1).rev() {
            stride[k] = stride[k + 1] * n[k + 1];
        }
        Cells {
            reach,
            n,
            width,
            inverse: std::array::from_fn(|k| 1.0 / width[k]),
            size,
            periodic,
            stride,
            cells: vec![Slot::EMPTY; n.iter().product()],
            overflow: Vec::new(),
            len: 0,
        }
    }

    /// The cell count per axis.
    pub fn shape(&self) -> [usize; N] {
        self.n
    }

    /// The cell of `x` along axis `k`: `floor(x_k (1 / width_k))` clamped to the grid (`as
    /// usize` truncates toward 0 and saturates below at 0, which is the floor for `x_k >= 0`
    /// and the clamp below; NaN goes to 0).
    fn cell(&self, x: &[f64; N], k: usize) -> usize {
        ((x[k] * self.inverse[k]) as usize).min(self.n[k] - 1)
    }

    /// Add an item of `radius` centred at `centre` (it gets the index `self.len()`).
    pub fn insert(&mut self, centre: &[f64; N], radius: f64) {
        let cell: usize = (0..N).map(|k| self.cell(centre, k) * self.stride[k]).sum();
        self.len += 1;
        let slot = Slot {
            centre: *centre,
            radius,
            index: self.len as u32,
            next: 0,
        };
        let first = &mut self.cells[cell];
        if first.index == 0 {
            *first = Slot {
                next: first.next,
                ..slot
            };
        } else {
            self.overflow.push(Slot {
                next: first.next,
                ..slot
            });
            first.next = self.overflow.len() as u32;
        }
    }

    /// The number of items inserted.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether no item has been inserted.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// `true` if a ball of radius `r` centred at `x` overlaps no item: `|x - c_i|^2 >= (r +
    /// r_i)^2` for every item `i` (minimum image on periodic axes, [`distance2`]), stopping at
    /// the first that fails. Only the items of the cells [`Cells::all_near`] visits are
    /// tested, so `r + r_i` must not exceed the grid's `reach`.
    pub fn clear_of(&self, x: &[f64; N], r: f64) -> bool {
        self.clear_near(&self.near(x), x, r)
    }

    /// [`Cells::clear_of`] with the cells around `x` found already (`near` is `self.near(x)`).
    pub(crate) fn clear_near(&self, near: &Near<N>, x: &[f64; N], r: f64) -> bool {
        self.visit(near, &mut |_, centre: &[f64; N], radius| {
            let s = r + radius;
            distance2(x, centre, &self.size, &self.periodic) >= s * s
        })
    }

    /// Ask the CPU to fetch the cells of `near` (a hint: no effect on results), so that the
    /// tests of several points wait for memory together: every combination of its per-axis
    /// cells (the corners beyond reach too), in up to 3 dimensions (none beyond).
    pub(crate) fn prefetch(&self, near: &Near<N>) {
        if N > 3 {
            return;
        }
        let last = N - 1;
        near.rows(|row, _| {
            for &term in &near.terms[last][..near.len[last]] {
                collision_core::batch::prefetch(self.cells.get(row + term));
            }
            true
        });
    }

    /// `true` if `clear(index, centre, radius)` holds for every item in the cells that come
    /// within `reach` of `x` (stops at the first that fails). A neighbouring cell is visited
    /// only if the sum of the squared gaps from `x` to it along the axes where it lies beside
    /// `x`'s cell is below `reach^2` (with `2^-20` of slack for rounding): an item closer than
    /// `reach` has each coordinate offset at least that gap. Each cell is visited once, also
    /// when a periodic axis has fewer than 3 cells; `x`'s own cell comes first.
    pub fn all_near(
        &self,
        x: &[f64; N],
        mut clear: impl FnMut(usize, &[f64; N], f64) -> bool,
    ) -> bool {
        self.visit(&self.near(x), &mut clear)
    }

    /// The items of the cells of `near` tested by `clear` (see [`Cells::all_near`]): in up to
    /// 3 dimensions row by row ([`Near::rows`], then along the last axis), else axis by axis.
    fn visit(&self, near: &Near<N>, clear: &mut impl FnMut(usize, &[f64; N], f64) -> bool) -> bool {
        if N > 3 {
            return self.walk(near, 0, 0.0, 0, clear);
        }
        let last = N - 1;
        near.rows(|row, row_gap2| {
            for c in 0..near.len[last] {
                if row_gap2 + near.gaps[last][c] < near.reach2
                    && !self.clear_cell(row + near.terms[last][c], clear)
                {
                    return false;
                }
            }
            true
        })
    }

    /// The items of cell `flat` tested by `clear`, up to the first that fails.
    fn clear_cell(
        &self,
        flat: usize,
        clear: &mut impl FnMut(usize, &[f64; N], f64) -> bool,
    ) -> bool {
        let mut slot = &self.cells[flat];
        if slot.index == 0 {
            return true;
        }
        loop {
            if !clear(slot.index as usize - 1, &slot.centre, slot.radius) {
                return false;
            }
            if slot.next == 0 {
                return true;
            }
            slot = &self.overflow[slot.next as usize - 1];
        }
    }

    /// The cells around `x` along each axis (see [`Near`]).
    pub(crate) fn near(&self, x: &[f64; N]) -> Near<N> {
        let mut near = Near::NONE;
        self.near_into(x, &mut near);
        near
    }

    /// [`Cells::near`] written into `near` (no copy of the result; only the entries in use
    /// are written, and those are all [`Cells::visit`] reads).
    #[inline]
    pub(crate) fn near_into(&self, x: &[f64; N], near: &mut Near<N>) {
        let reach = self.reach * (1.0 + 1.0 / (1u64 << 20) as f64);
        near.reach2 = reach * reach;
        for k in 0..N {
            let (n, w, stride) = (self.n[k], self.width[k], self.stride[k]);
            let c = self.cell(x, k);
            let lo = (x[k] - c as f64 * w).max(0.0);
            let hi = (w - lo).max(0.0);
            let (terms, gaps) = (&mut near.terms[k], &mut near.gaps[k]);
            (terms[0], gaps[0]) = (c * stride, 0.0);
            let mut len = 1;
            let wrap = self.periodic[k];
            if n == 1 {
                // No other cell.
            } else if wrap && n == 2 {
                // One other cell, at the nearer gap.
                let gap = lo.min(hi);
                if gap < reach {
                    (terms[1], gaps[1], len) = ((1 - c) * stride, gap * gap, 2);
                }
            } else {
                if lo < reach && (c > 0 || wrap) {
                    let below = if c == 0 { n - 1 } else { c - 1 };
                    (terms[len], gaps[len]) = (below * stride, lo * lo);
                    len += 1;
                }
                if hi < reach && (c + 1 < n || wrap) {
                    let above = if c + 1 == n { 0 } else { c + 1 };
                    (terms[len], gaps[len]) = (above * stride, hi * hi);
                    len += 1;
                }
            }
            near.len[k] = len;
        }
    }

    /// The cells of axes `k..N` below the flat index terms `flat` of axes `0..k`, whose
    /// squared gap so far is `partial`: each cell's items tested by `clear`.
    fn walk(
        &self,
        near: &Near<N>,
        k: usize,
        partial: f64,
        flat: usize,
        clear: &mut impl FnMut(usize, &[f64; N], f64) -> bool,
    ) -> bool {
        for c in 0..near.len[k] {
            let gap2 = partial + near.gaps[k][c];
            if gap2 >= near.reach2 {
                continue;
            }
            let flat = flat + near.terms[k][c];
            if k + 1 < N {
                if !self.walk(near, k + 1, gap2, flat, clear) {
                    return false;
                }
                continue;
            }
            if !self.clear_cell(flat, clear) {
                return false;
            }
        }
        true
    }
}

/// The cells around a point: per axis up to 3 (its own first, then the neighbours within
/// reach), each as its term of the flat index (cell times the axis's stride) with its squared gap from the
/// point (0 for its own).
#[derive(Clone, Debug)]
pub(crate) struct Near<const N: usize> {
    terms: [[usize; 3]; N],
    gaps: [[f64; 3]; N],
    len: [usize; N],
    reach2: f64,
}

impl<const N: usize> Near<N> {
    /// No cells (a placeholder to be overwritten).
    pub(crate) const NONE: Self = Near {
        terms: [[0; 3]; N],
        gaps: [[0.0; 3]; N],
        len: [0; N],
        reach2: 0.0,
    };

    /// In up to 3 dimensions, the rows along the last axis: every combination of the cells
    /// of axes `0..N-1` as its flat index terms and squared gap summed (`terms[0][a] +
    /// terms[1][b]`, `gaps[0][a] + gaps[1][b]` in 3D), the own first, then with axis 0's
    /// cell varying fastest, each given to `row` until it returns `false`; whether none did.
    /// Nothing is built: the rows are sums made as they are visited.
    #[inline(always)]
    fn rows(&self, mut row: impl FnMut(usize, f64) -> bool) -> bool {
        match N {
            1 => row(0, 0.0),
            2 => (0..self.len[0]).all(|a| row(self.terms[0][a], self.gaps[0][a])),
            _ => (0..self.len[1]).all(|b| {
                (0..self.len[0]).all(|a| {
                    row(
                        self.terms[0][a] + self.terms[1][b],
                        self.gaps[0][a] + self.gaps[1][b],
                    )
                })
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_are_wide_enough_and_bounded_by_the_capacity() {
        // A box of 1e6 x 1e6 for 10 items of reach 1: 36 cells at most, not 1e12.
        let g = Cells::<2>::new([1e6, 1e6], [true, false], 1.0, 10);
        assert!(g.shape().iter().product::<usize>() <= 36, "{:?}", g.shape());
        // A small box: cells of width >= reach, so 10 / 1.0000001 -> 9 per axis.
        let g = Cells::<2>::new([10.0, 10.0], [true, true], 1.0, 1000);
        assert_eq!(g.shape(), [9, 9]);
        // Narrower than the reach: one cell.
        let g = Cells::<3>::new([0.5, 10.0, 10.0], [true; 3], 1.0, 1000);
        assert_eq!(g.shape()[0], 1);
    }

    /// Items on a lattice of `per_axis^N` points (several per cell), probes at `probes` random
    /// points of the box: the visited set must contain every item within the reach (minimum
    /// image) once and nothing twice, with the item's own centre and radius; and `clear_of`
    /// must agree with the test against every item.
    fn visited_once<const N: usize>(size: [f64; N], periodic: [bool; N], per_axis: usize) {
        use collision_core::rng::Rng;
        let reach = 1.0;
        let count = per_axis.pow(N as u32);
        let mut g = Cells::<N>::new(size, periodic, reach, count / 4);
        let mut items = Vec::new();
        for i in 0..count {
            let mut rest = i;
            let p: [f64; N] = std::array::from_fn(|k| {
                let j = rest % per_axis;
                rest /= per_axis;
                size[k] * j as f64 / per_axis as f64
            });
            let radius = 0.5 * (i % 3) as f64 / 2.0;
            g.insert(&p, radius);
            items.push((p, radius));
        }
        assert_eq!(g.len(), count);
        let mut rng = Rng::new(5);
        for _ in 0..400 {
            let probe: [f64; N] = std::array::from_fn(|k| rng.uniform(0.0, size[k]));
            let mut seen = vec![0; items.len()];
            assert!(g.all_near(&probe, |i, centre, radius| {
                assert_eq!((*centre, radius), items[i], "item {i}");
                seen[i] += 1;
                true
            }));
            for (i, (p, _)) in items.iter().enumerate() {
                assert!(seen[i] <= 1, "item {i} visited twice");
                if distance2(p, &probe, &size, &periodic) < reach * reach {
                    assert_eq!(seen[i], 1, "item {i} at {p:?} missed from {probe:?}");
                }
            }
            let r = rng.uniform(0.0, 0.5);
            let clear = items.iter().all(|(p, radius)| {
                let s = r + radius;
                distance2(p, &probe, &size, &periodic) >= s * s
            });
            assert_eq!(g.clear_of(&probe, r), clear, "{probe:?} {r}");
            g.prefetch(&g.near(&probe));
        }
    }

    #[test]
    fn every_item_within_reach_is_visited_once() {
        // 1, 2 and many cells per axis, periodic and walled; 2 and 3 dimensions go row by
        // row, 4 axis by axis.
        visited_once([3.0, 1.5], [true, true], 14);
        visited_once([2.5, 7.0], [true, false], 14);
        visited_once([7.0, 7.0], [false, false], 14);
        visited_once([3.0, 1.5, 4.5], [true, true, false], 7);
        visited_once([2.5, 5.0, 5.0], [true, false, true], 7);
        visited_once([2.5, 1.5, 4.0, 3.5], [true, true, false, true], 5);
    }
}
