//! The cell list: the box cut into `n_k` cells of width `w_k = L_k / n_k` per axis.
//!
//! **Reach.** A ball in cell `c` and one in cell `c + delta` (unwrapped: `shift =
//! floor((c + delta) / n)` box lengths on a periodic axis) have, along each axis, a centre
//! offset in `((|delta| - 1) w, (|delta| + 1) w)` (up to the rounding `delta_x` by which a
//! centre can stray out of its cell), so they can touch only if `(|delta| - 1) w - 2 delta_x <
//! d_max`, the largest contact distance `R_i + R_j`. With `w_k > d_max + s_k`, the slack
//! `s_k = 1e-9 d_max + 64 eps L_k` covering `2 delta_x` (a centre is computed from the crossing
//! that put it in its cell within a few ulps of `L_k`), only `|delta| <= 1` can touch: the reach
//! is 1 and `3^n` cells are scanned, each periodic image once. Every axis gets cells wider than
//! `d_max + s_k` when its side allows (`n_k = 1` otherwise: a periodic side shorter than
//! `d_max + s_k` then needs a reach `K = ceil((d_max + s_k) / L_k) <= 2`, more is refused).
//!
//! **Size.** The number of cells is capped at [`CELLS_PER_BODY`] times the number of bodies
//! (balls and obstacles): when the finest reach-1 grid `m_k = max{n : L_k / n > d_max + s_k}`
//! has more cells than that, the cells are widened to a common width `w` (the least for which
//! `prod_k min(m_k, floor(L_k / w)) <= cap`, found by bisection), then the widest are split
//! again one axis at a time while the cap allows; so memory is `O(bodies)` whatever the box,
//! no cell count overflows, and the reach stays 1.

use crate::select::select;
use crate::SetupError;

/// The cap on the number of cells per body (ball or obstacle); see the module docs.
pub(crate) const CELLS_PER_BODY: usize = 4;

#[derive(Debug)]
pub(crate) struct Grid<const N: usize> {
    pub n: [usize; N],
    pub width: [f64; N],
    pub size: [f64; N],
    pub periodic: [bool; N],
    /// The reach `K_k` of each axis (at most 2): the cell offsets scanned are
    /// `[-K_0, K_0] x .. x [-K_{n-1}, K_{n-1}]`.
    reach: [i64; N],
    /// `prod_{l > k} n_l`: the flat index is `sum_k c_k stride_k`.
    stride: [usize; N],
    /// The flat offsets `sum_k delta_k stride_k` of every `delta` within reach, in
    /// [`Grid::for_cells`]' order: the neighbours of an interior cell without the odometer.
    offsets: Vec<isize>,
    /// The same for each layer, at `2 axis` (offset `-K_axis` along `axis`) and `2 axis + 1`
    /// (`+K_axis`).
    layers: Vec<Vec<isize>>,
}

/// A neighbouring cell: its flat index and the image shift of its contents.
pub(crate) struct Neighbour<const N: usize> {
    pub cell: usize,
    pub shift: [i8; N],
}

/// The slack `s_k = 1e-9 d_max + 64 eps L_k` added to `d_max` in the width rule.
fn slack(d_max: f64, side: f64) -> f64 {
    1e-9 * d_max + 64.0 * f64::EPSILON * side
}

/// `prod_k n_k`, saturating.
fn cells_of(n: &[usize]) -> u128 {
    n.iter().fold(1u128, |p, &x| p.saturating_mul(x as u128))
}

impl<const N: usize> Grid<N> {
    /// The grid for a box of sides `size` holding `bodies` balls and obstacles whose largest
    /// contact distance is `d_max`; an error if a periodic side is shorter than
    /// `(d_max + s_k) / 2` (a reach above 2).
    pub(crate) fn new(
        size: [f64; N],
        periodic: [bool; N],
        d_max: f64,
        bodies: usize,
    ) -> Result<Self, SetupError> {
        let cap = CELLS_PER_BODY.saturating_mul(bodies.max(1));
        let reach_width: [f64; N] = std::array::from_fn(|k| d_max + slack(d_max, size[k]));
        // m_k: the most cells of width > d_max + s_k (at least 1), capped at the cell cap.
        let most: [usize; N] = std::array::from_fn(|k| {
            let q = (size[k] / reach_width[k]).floor().min(cap as f64);
            let mut m = (q as usize).max(1);
            if m > 1 && size[k] / m as f64 <= reach_width[k] {
                m -= 1;
            }
            m
        });
        let n = if cells_of(&most) <= cap as u128 {
            most
        } else {
            let fit = |w: f64| -> [usize; N] {
                std::array::from_fn(|k| ((size[k] / w).floor() as usize).clamp(1, most[k]))
            };
            // cells_of(fit(w)) falls as w grows: > cap at the narrowest reach-1 width,
            // 1 at the longest side. Bisect geometrically between them.
            let mut lo = (0..N)
                .map(|k| size[k] / most[k] as f64)
                .fold(f64::INFINITY, f64::min);
            let mut hi = size.iter().copied().fold(0.0, f64::max);
            for _ in 0..200 {
                let mid = (lo * hi).sqrt();
                if !(mid > lo && mid < hi) {
                    break;
                }
                if cells_of(&fit(mid)) <= cap as u128 {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            // Then more cells where the cap still allows (on sides of equal length the
            // common width leaves up to a factor 2^n unused), widest cells first.
            let mut n = fit(hi);
            let mut grown = true;
            while grown {
                grown = false;
                let mut axes: [usize; N] = std::array::from_fn(|k| k);
                axes.sort_by(|&a, &b| (size[b] / n[b] as f64).total_cmp(&(size[a] / n[a] as f64)));
                for k in axes {
                    let mut more = n;
                    more[k] += 1;
                    if more[k] <= most[k] && cells_of(&more) <= cap as u128 {
                        n = more;
                        grown = true;
                    }
                }
            }
            n
        };
        let width: [f64; N] = std::array::from_fn(|k| size[k] / n[k] as f64);
        let mut reach = [0i64; N];
        for k in 0..N {
            reach[k] = if n[k] == 1 && !periodic[k] {
                0
            } else if width[k] > reach_width[k] {
                1
            } else {
                // n_k = 1 on a periodic axis shorter than d_max + s_k.
                let r = (reach_width[k] / width[k]).ceil();
                if r > 2.0 {
                    return Err(SetupError::ShortSide {
                        axis: k,
                        size: size[k],
                        d_max,
                    });
                }
                r as i64
            };
        }
        Ok(Grid::with(n, width, size, periodic, reach))
    }

    /// The grid of `n` cells of `width`, with its strides and offset tables.
    fn with(
        n: [usize; N],
        width: [f64; N],
        size: [f64; N],
        periodic: [bool; N],
        reach: [i64; N],
    ) -> Self {
        let stride = strides(&n);
        let offsets = offsets_of(&reach, &stride, None);
        let layers = (0..2 * N)
            .map(|l| {
                let delta = if l % 2 == 1 {
                    reach[l / 2]
                } else {
                    -reach[l / 2]
                };
                offsets_of(&reach, &stride, Some((l / 2, delta)))
            })
            .collect();
        Grid {
            n,
            width,
            size,
            periodic,
            reach,
            stride,
            offsets,
            layers,
        }
    }

    /// One cell of sides `size`, neither walled nor periodic (a table without a box: every
    /// pair is a neighbour; the cell's bounds are never crossed or checked).
    pub(crate) fn single(size: [f64; N]) -> Self {
        Grid::with([1; N], size, size, [false; N], [0; N])
    }

    /// The reach `K_k` of each axis.
    #[cfg(test)]
    fn reach(&self) -> [i64; N] {
        self.reach
    }

    pub(crate) fn cells(&self) -> usize {
        self.n.iter().product()
    }

    pub(crate) fn flat(&self, c: &[usize; N]) -> usize {
        (0..N).map(|k| c[k] * self.stride[k]).sum()
    }

    /// The cell of a point inside the box (clamped, for points on the far boundary):
    /// `min(floor(max(x_k / w_k, 0)), n_k - 1)`, the floor being the conversion's
    /// truncation of a number at least 0 (no library call).
    pub(crate) fn cell_of(&self, x: &[f64; N]) -> [usize; N] {
        std::array::from_fn(|k| ((x[k] / self.width[k]).max(0.0) as usize).min(self.n[k] - 1))
    }

    /// Calls `f` for every cell within reach of cell `c` (with its image shift), in the order
    /// of the offsets `[-K_0, K_0] x .. x [-K_{n-1}, K_{n-1}]` with the last axis fastest
    /// (offsets outside a walled side skipped). No division: per axis, the at most `2 K_k + 1`
    /// cells (and shifts, `floor((c_k + delta) / n_k)`) are listed first, then combined.
    #[cfg(test)]
    pub(crate) fn for_neighbours(&self, c: &[usize; N], f: impl FnMut(Neighbour<N>)) {
        self.for_cells(c, None, f);
    }

    /// Calls `f` for the cells newly within reach after a move from cell `c - step e_axis`
    /// to `c` (`step` = +1 or -1 along `axis`): the layer of offset `step K_axis` along `axis`,
    /// every offset within reach along the others, in [`Grid::for_neighbours`]' order. With
    /// the cells within reach of the cell left, they are every cell within reach of `c`.
    #[cfg(test)]
    pub(crate) fn for_layer(
        &self,
        c: &[usize; N],
        axis: usize,
        step: i64,
        f: impl FnMut(Neighbour<N>),
    ) {
        self.for_cells(c, Some(self.layer(axis, step)), f);
    }

    /// The number of cells [`Grid::near`] lists for a cell away from the grid's edges:
    /// `prod_k (2 K_k + 1)`, or with `only` (a layer along its axis) the same without that
    /// axis's factor. At an edge there may be fewer (none beyond a wall).
    #[inline]
    pub(crate) fn near_len(&self, only: Option<(usize, i64)>) -> usize {
        match only {
            None => self.offsets.len(),
            Some((axis, delta)) => self.layers[2 * axis + usize::from(delta > 0)].len(),
        }
    }

    /// The cell a ball in cell `c` enters when it crosses a face along `axis`, moving `up` or
    /// down (wrapping around the grid: a crossing is scheduled only where the axis is
    /// periodic or the face is not the box's), and whether it wrapped.
    #[inline]
    pub(crate) fn crossed(&self, c: &[usize; N], axis: usize, up: bool) -> ([usize; N], bool) {
        let (n, from) = (self.n[axis], c[axis]);
        let mut next = *c;
        // `(c + 1) mod n` and `(c - 1) mod n` without a division, chosen without a branch on
        // the direction ([`crate::select`]).
        let (top, bottom) = (from + 1 == n, from == 0);
        let above = select(top, 0, from + 1);
        let below = select(bottom, n - 1, from.wrapping_sub(1));
        next[axis] = select(up, above, below);
        let wrapped = (up & top) | (!up & bottom);
        (next, wrapped)
    }

    /// The layer a crossing along `axis` (moving `up` or down) newly brings within reach of
    /// the cell entered: [`Grid::layer`] on that side.
    #[inline]
    pub(crate) fn reached(&self, axis: usize, up: bool) -> (usize, i64) {
        self.layer(axis, select(up, 1, -1))
    }

    /// The restriction of [`Grid::for_cells`] to the layer of `Grid::for_layer` (in the tests).
    #[inline]
    pub(crate) fn layer(&self, axis: usize, step: i64) -> (usize, i64) {
        (axis, step * self.reach[axis])
    }

    /// `Grid::for_neighbours` (in the tests), or with `only = (axis, delta)` the offset
    /// `delta` alone along `axis`: `f` for each of [`Grid::near`]'s cells.
    #[inline]
    pub(crate) fn for_cells(
        &self,
        c: &[usize; N],
        only: Option<(usize, i64)>,
        f: impl FnMut(Neighbour<N>),
    ) {
        self.near(c, only).for_each(f);
    }

    /// The cells of [`Grid::for_cells`], as an iterator (a scan's loop body is then inlined
    /// once). A cell whose every neighbour lies inside the grid (no wrap, no wall) walks the
    /// precomputed flat offsets, in the same order and with shift 0; others take the
    /// [`Odometer`].
    #[inline]
    pub(crate) fn near(&self, c: &[usize; N], only: Option<(usize, i64)>) -> Near<'_, N> {
        let interior = (0..N).all(|k| {
            c[k] as i64 >= self.reach[k] && c[k] as i64 + self.reach[k] < self.n[k] as i64
        });
        if !interior {
            return Near {
                flat: 0,
                offsets: [].iter(),
                odometer: Some(self.odometer(c, only)),
            };
        }
        let offsets = match only {
            None => &self.offsets,
            Some((axis, delta)) => &self.layers[2 * axis + usize::from(delta > 0)],
        };
        Near {
            flat: self.flat(c) as isize,
            offsets: offsets.iter(),
            odometer: None,
        }
    }

    /// The cells of [`Grid::for_cells`] for any cell: per axis, the at most `2 K_k + 1` cells
    /// and shifts (wrapped on a periodic axis, skipped beyond a wall), to be combined. No
    /// division: the shifts `floor((c_k + delta) / n_k)` are counted.
    fn odometer(&self, c: &[usize; N], only: Option<(usize, i64)>) -> Odometer<N> {
        let mut part = [[0usize; 5]; N];
        let mut shifts = [[0i8; 5]; N];
        let mut len = [0usize; N];
        for k in 0..N {
            let n = self.n[k] as i64;
            let deltas = match only {
                Some((axis, delta)) if axis == k => delta..=delta,
                _ => -self.reach[k]..=self.reach[k],
            };
            for delta in deltas {
                let (mut t, mut s) = (c[k] as i64 + delta, 0i8);
                if self.periodic[k] {
                    while t < 0 {
                        t += n;
                        s -= 1;
                    }
                    while t >= n {
                        t -= n;
                        s += 1;
                    }
                } else if !(0..n).contains(&t) {
                    continue;
                }
                part[k][len[k]] = t as usize * self.stride[k];
                shifts[k][len[k]] = s;
                len[k] += 1;
            }
        }
        Odometer {
            part,
            shifts,
            len,
            at: [0; N],
            // Each axis lists at least c_k itself, but a layer beyond a wall lists nothing.
            done: len.contains(&0),
            // An axis lists a cell twice (two images) only if it lists more than it has.
            distinct: (0..N).all(|k| len[k] <= self.n[k]),
        }
    }
}

/// The cells within reach of one cell ([`Grid::near`]): the flat offsets of an interior cell,
/// or the odometer.
pub(crate) struct Near<'a, const N: usize> {
    flat: isize,
    offsets: std::slice::Iter<'a, isize>,
    odometer: Option<Odometer<N>>,
}

impl<const N: usize> Near<'_, N> {
    /// How the cells are listed: an interior cell's flat index and the flat offsets of the
    /// cells within reach (distinct cells, shift 0), or, at the grid's edge, the odometer,
    /// not yet walked; so that a scan can walk them without the iterator.
    #[inline]
    pub(crate) fn listing(&self) -> Listing<'_, N> {
        match &self.odometer {
            None => Listing::Interior(self.flat as usize, self.offsets.as_slice()),
            Some(odometer) => Listing::Edge(odometer),
        }
    }
}

/// [`Near::listing`].
pub(crate) enum Listing<'a, const N: usize> {
    Interior(usize, &'a [isize]),
    Edge(&'a Odometer<N>),
}

impl<const N: usize> Iterator for Near<'_, N> {
    type Item = Neighbour<N>;

    #[inline]
    fn next(&mut self) -> Option<Neighbour<N>> {
        if let Some(&offset) = self.offsets.next() {
            return Some(Neighbour {
                cell: (self.flat + offset) as usize,
                shift: [0; N],
            });
        }
        self.odometer.as_mut()?.next()
    }
}

/// An odometer over the product of each axis' cells (the last axis fastest).
#[derive(Clone)]
pub(crate) struct Odometer<const N: usize> {
    /// Per axis, the flat index's term `t_k stride_k` of each of its cells.
    pub(crate) part: [[usize; 5]; N],
    /// Per axis, the image shift of each of its cells.
    pub(crate) shifts: [[i8; 5]; N],
    /// Per axis, its number of cells.
    pub(crate) len: [usize; N],
    at: [usize; N],
    /// Whether the walk is over (or, before it starts, lists no cell).
    pub(crate) done: bool,
    /// Whether it lists each cell once (else some cell at several periodic images: a
    /// periodic axis of fewer than `2 K_k + 1` cells).
    pub(crate) distinct: bool,
}

impl<const N: usize> Iterator for Odometer<N> {
    type Item = Neighbour<N>;

    fn next(&mut self) -> Option<Neighbour<N>> {
        if self.done {
            return None;
        }
        let at = self.at;
        let nb = Neighbour {
            cell: (0..N).map(|k| self.part[k][at[k]]).sum(),
            shift: std::array::from_fn(|k| self.shifts[k][at[k]]),
        };
        let mut k = N;
        loop {
            if k == 0 {
                self.done = true;
                break;
            }
            k -= 1;
            self.at[k] += 1;
            if self.at[k] < self.len[k] {
                break;
            }
            self.at[k] = 0;
        }
        Some(nb)
    }
}

/// The flat offsets `sum_k delta_k stride_k` of the offsets `delta` in `[-K_0, K_0] x .. x
/// [-K_{n-1}, K_{n-1}]` (with `only = (axis, d)`, `delta_axis = d` alone), the last axis
/// fastest: [`Grid::for_cells`]' order.
fn offsets_of<const N: usize>(
    reach: &[i64; N],
    stride: &[usize; N],
    only: Option<(usize, i64)>,
) -> Vec<isize> {
    let mut out = vec![0isize];
    for k in 0..N {
        let deltas = match only {
            Some((axis, d)) if axis == k => d..=d,
            _ => -reach[k]..=reach[k],
        };
        out = out
            .iter()
            .flat_map(|&o| {
                deltas
                    .clone()
                    .map(move |d| o + d as isize * stride[k] as isize)
            })
            .collect();
    }
    out
}

/// `stride_k = prod_{l > k} n_l`.
fn strides<const N: usize>(n: &[usize; N]) -> [usize; N] {
    let mut stride = [1; N];
    for k in (0..N.saturating_sub(1)).rev() {
        stride[k] = stride[k + 1] * n[k + 1];
    }
    stride
}

#[cfg(test)]
#[path = "cells_tests.rs"]
mod tests;
