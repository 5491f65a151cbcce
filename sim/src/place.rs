//! A cell grid for random placement: the overlap test of a candidate centre visits only the
//! balls (or obstacles) of the `3^n` cells around it, so placing `N` balls costs `O(N)` tests
//! at a fixed packing instead of `O(N^2)`.
//!
//! Cells are at least `reach (1 + 2^-20)` wide along every axis, where `reach` is the largest
//! distance at which two items can overlap; two centres closer than `reach` (minimum image on
//! periodic axes) are then in the same or adjacent cells, with a margin of `2^-20` of a cell
//! for the rounding of `x / width` (the cell coordinates are below `2^26`, so that rounding
//! is below `2^-27` of a cell). Of the `3^n` cells around a point only those that come within
//! `reach` of it are visited. The grid has at most `2 capacity + 16` cells (wider cells in a
//! large box), so its memory is `O(capacity)` whatever the box: a head per cell and a link
//! per item.

/// The cells and their items (linked lists: `head` per cell, `next` per item, both `index + 1`
/// with 0 for none).
#[derive(Clone, Debug)]
pub struct Cells<const N: usize> {
    reach: f64,
    n: [usize; N],
    width: [f64; N],
    periodic: [bool; N],
    head: Vec<u32>,
    next: Vec<u32>,
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
        let width = std::array::from_fn(|k| size[k] / n[k] as f64);
        Cells {
            reach,
            n,
            width,
            periodic,
            head: vec![0; n.iter().product()],
            next: Vec::with_capacity(capacity),
        }
    }

    /// The cell count per axis.
    pub fn shape(&self) -> [usize; N] {
        self.n
    }

    fn cell_of(&self, x: &[f64; N]) -> [usize; N] {
        std::array::from_fn(|k| {
            ((x[k] / self.width[k]).floor().max(0.0) as usize).min(self.n[k] - 1)
        })
    }

    fn flat(&self, c: &[usize; N]) -> usize {
        (0..N).fold(0, |acc, k| acc * self.n[k] + c[k])
    }

    /// Add item `self.len()` at `x`.
    pub fn insert(&mut self, x: &[f64; N]) {
        let cell = self.flat(&self.cell_of(x));
        self.next.push(self.head[cell]);
        self.head[cell] = self.next.len() as u32;
    }

    /// The number of items inserted.
    pub fn len(&self) -> usize {
        self.next.len()
    }

    /// Whether no item has been inserted.
    pub fn is_empty(&self) -> bool {
        self.next.is_empty()
    }

    /// `true` if `clear(item)` holds for every item in the cells that come within `reach` of
    /// `x` (stops at the first that fails). A neighbouring cell is visited only if the sum of
    /// the squared gaps from `x` to it along the axes where it lies beside `x`'s cell is below
    /// `reach^2` (with `2^-20` of slack for rounding): an item closer than `reach` has each
    /// coordinate offset at least that gap. Each cell is visited once, also when a periodic
    /// axis has fewer than 3 cells.
    pub fn all_near(&self, x: &[f64; N], mut clear: impl FnMut(usize) -> bool) -> bool {
        let c = self.cell_of(x);
        let reach = self.reach * (1.0 + 1.0 / (1u64 << 20) as f64);
        // Per axis up to 3 cells, each with its squared gap from x.
        let mut cells = [[0usize; 3]; N];
        let mut gaps = [[0.0f64; 3]; N];
        let mut len = [1usize; N];
        for k in 0..N {
            let (n, w) = (self.n[k], self.width[k]);
            let lo = (x[k] - c[k] as f64 * w).max(0.0);
            let hi = (w - lo).max(0.0);
            cells[k][0] = c[k];
            let mut add = |cell: usize, gap: f64| {
                if gap < reach {
                    cells[k][len[k]] = cell;
                    gaps[k][len[k]] = gap * gap;
                    len[k] += 1;
                }
            };
            if self.periodic[k] && n == 2 {
                add(1 - c[k], lo.min(hi));
            } else if self.periodic[k] && n >= 3 {
                add((c[k] + n - 1) % n, lo);
                add((c[k] + 1) % n, hi);
            } else if !self.periodic[k] {
                if c[k] > 0 {
                    add(c[k] - 1, lo);
                }
                if c[k] + 1 < n {
                    add(c[k] + 1, hi);
                }
            }
        }
        let reach2 = reach * reach;
        let mut pick = [0usize; N];
        loop {
            let gap2: f64 = (0..N).map(|k| gaps[k][pick[k]]).sum();
            if gap2 < reach2 {
                let cell: [usize; N] = std::array::from_fn(|k| cells[k][pick[k]]);
                let mut item = self.head[self.flat(&cell)];
                while item != 0 {
                    if !clear(item as usize - 1) {
                        return false;
                    }
                    item = self.next[item as usize - 1];
                }
            }
            // The next combination of per-axis choices.
            let mut k = 0;
            loop {
                if k == N {
                    return true;
                }
                pick[k] += 1;
                if pick[k] < len[k] {
                    break;
                }
                pick[k] = 0;
                k += 1;
            }
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

    #[test]
    fn every_item_within_reach_is_visited_once() {
        // Items on a lattice; for probes anywhere, the visited set must contain every item
        // within the reach (minimum image) and nothing twice, with 1, 2 and many cells.
        for (size, periodic) in [
            ([3.0, 1.5], [true, true]),
            ([2.5, 7.0], [true, false]),
            ([7.0, 7.0], [false, false]),
        ] {
            let reach = 1.0;
            let mut g = Cells::<2>::new(size, periodic, reach, 200);
            let mut items = Vec::new();
            for i in 0..14 {
                for j in 0..14 {
                    let p = [size[0] * i as f64 / 14.0, size[1] * j as f64 / 14.0];
                    g.insert(&p);
                    items.push(p);
                }
            }
            let probes = (0..=20).flat_map(|i| {
                (0..=20).map(move |j| {
                    [
                        size[0] * i as f64 / 20.0,
                        size[1] * (j as f64 + 0.37) / 21.0,
                    ]
                })
            });
            for probe in probes {
                let mut seen = vec![0; items.len()];
                assert!(g.all_near(&probe, |i| {
                    seen[i] += 1;
                    true
                }));
                for (i, p) in items.iter().enumerate() {
                    let d: f64 = (0..2)
                        .map(|k| {
                            let mut d = (p[k] - probe[k]).abs();
                            if periodic[k] {
                                d = d.min(size[k] - d);
                            }
                            d * d
                        })
                        .sum();
                    assert!(seen[i] <= 1, "item {i} visited twice");
                    if d < reach * reach {
                        assert_eq!(seen[i], 1, "item {i} at {p:?} missed from {probe:?}");
                    }
                }
            }
        }
    }
}
