//! The neighbour lists of the list engine: every ball's shell and the balls whose shells
//! come near it.
//!
//! Ball `i` stays within `delta` of its shell's centre `c_i` (its position when the shell was
//! drawn, folded into the box); when it would leave, the shell is drawn again around it (an
//! event of the engine). Balls `i` and `j` can touch while both stay in their shells only if
//! `|c_j + m L - c_i| <= R_i + R_j + 2 delta` for some image `m`, so ball `i`'s list holds every
//! `(j, m)` with `|c_j + m L - c_i| <= reach`, `reach = d_max + 2 delta` plus a slack for
//! rounding (`d_max` the largest contact distance). The relation is kept symmetric: a pair
//! is put in, or taken out of, both lists at once, from one computed distance, and each entry
//! knows where its twin lies in the other list, so taking a ball out of its neighbours'
//! lists costs `O(1)` a neighbour.
//!
//! The centres are found through a cell list of their own ([`Grid`], cells wider than
//! `reach`): a centre moves only when its shell is drawn again, so there are no crossing
//! events. A cell's members (each ball with a copy of its centre) lie together, as the lists
//! do ([`Strided`]).
//!
//! With at least three cells along every periodic axis (`L_k >= 3 reach`), a neighbour cell
//! is met once, and a pair has at most one image within `reach`.

use super::strided::Strided;
use crate::cells::Grid;

/// `u32::MAX`: no ball.
const NONE: u32 = u32::MAX;

/// A ball `j` of a list, the image `m` of its shell's centre near the owner's (box lengths on
/// periodic axes, `-1`, `0` or `1`), and the index of the owner in `j`'s list.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Neighbour<const N: usize> {
    pub j: u32,
    pub twin: u32,
    pub image: [i8; N],
}

/// A ball of a cell and its shell's centre.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Member<const N: usize> {
    ball: u32,
    centre: [f64; N],
}

/// Every ball's shell and neighbour list (module docs).
#[derive(Debug)]
pub(super) struct Shells<const N: usize> {
    /// The cells of the centres (wider than `reach`).
    grid: Grid<N>,
    /// `reach^2`: a pair is listed when its centres' squared distance is at most this.
    reach2: f64,
    /// Per ball: its shell's centre `c_i`, in the box.
    centre: Vec<[f64; N]>,
    /// Per ball: its cell (flat index; `NONE` before it is placed) and its index there.
    cell: Vec<(u32, u32)>,
    /// Per cell: its members.
    members: Strided<Member<N>>,
    /// Per ball: its list.
    lists: Strided<Neighbour<N>>,
    /// The pairs a drawing finds, kept between drawings.
    found: Vec<(u32, [i8; N])>,
    /// The last drawing's entries of balls new to the list ([`Shells::fresh`]).
    fresh: Vec<Neighbour<N>>,
    /// Per ball: the drawing that last saw it in the drawn ball's old list, and that
    /// drawing's number.
    seen: Vec<u32>,
    drawing: u32,
}

impl<const N: usize> Shells<N> {
    /// No shells yet for `balls` balls, centres listed when within `reach` (`grid`'s cells
    /// are wider).
    pub(super) fn new(grid: Grid<N>, balls: usize, reach: f64) -> Self {
        let per_cell = balls.div_ceil(grid.cells().max(1));
        let member = Member {
            ball: NONE,
            centre: [0.0; N],
        };
        let neighbour = Neighbour {
            j: NONE,
            twin: NONE,
            image: [0; N],
        };
        Shells {
            members: Strided::new(grid.cells(), 2 * per_cell + 2, member),
            grid,
            reach2: reach * reach,
            centre: vec![[0.0; N]; balls],
            cell: vec![(NONE, 0); balls],
            lists: Strided::new(balls, 16, neighbour),
            found: Vec::new(),
            fresh: Vec::new(),
            seen: vec![0; balls],
            drawing: 0,
        }
    }

    /// Ball `i`'s list.
    #[inline]
    pub(super) fn list(&self, i: usize) -> &[Neighbour<N>] {
        self.lists.row(i)
    }

    /// Ball `i`'s shell's centre.
    #[inline]
    pub(super) fn centre(&self, i: usize) -> &[f64; N] {
        &self.centre[i]
    }

    /// Requests ball `i`'s list (its first two cache lines: the lists are a few tens of
    /// 12-byte entries).
    #[inline]
    pub(super) fn prefetch_list(&self, i: usize) {
        self.lists.prefetch_row(i);
    }

    /// The bytes a ball's list takes in the slab (its row's room).
    pub(super) fn list_bytes(&self) -> usize {
        self.lists.row_bytes()
    }

    /// Ball `i`'s cell (flat index).
    #[inline]
    pub(super) fn cell_of(&self, i: usize) -> u32 {
        self.cell[i].0
    }

    /// Moves every ball from slot `order[s]` to slot `s`: its centre, cell and list, and every
    /// list entry and cell member naming it.
    pub(super) fn permute(&mut self, order: &[u32]) {
        let mut new_of = vec![0u32; order.len()];
        for (new, &old) in order.iter().enumerate() {
            new_of[old as usize] = new as u32;
        }
        self.centre = order.iter().map(|&s| self.centre[s as usize]).collect();
        self.cell = order.iter().map(|&s| self.cell[s as usize]).collect();
        self.lists.permute_rows(order);
        self.lists.for_each_mut(|n| n.j = new_of[n.j as usize]);
        self.members
            .for_each_mut(|m| m.ball = new_of[m.ball as usize]);
        self.seen.fill(0);
        self.fresh.clear();
    }

    /// The entries of the last drawn ball's list whose balls were not in its list before.
    #[inline]
    pub(super) fn fresh(&self) -> &[Neighbour<N>] {
        &self.fresh
    }

    /// Draws ball `i`'s shell around `centre` (in the box): `i` leaves its old neighbours'
    /// lists and its cell, and is listed with every ball already placed whose centre is
    /// within reach of the new one, both ways; the balls new to its list are noted
    /// ([`Shells::fresh`]).
    pub(super) fn draw(&mut self, i: usize, centre: [f64; N]) {
        if self.drawing == u32::MAX {
            // Numbers start again: no ball may look seen by an old drawing.
            self.seen.fill(0);
            self.drawing = 0;
        }
        self.drawing += 1;
        for k in 0..self.lists.len(i) {
            let j = self.lists.row(i)[k].j;
            self.seen[j as usize] = self.drawing;
        }
        self.detach(i);
        self.centre[i] = centre;
        let c = self.grid.cell_of(&centre);
        let cell = self.grid.flat(&c);
        let at = self.members.push(
            cell,
            Member {
                ball: i as u32,
                centre,
            },
        );
        self.cell[i] = (cell as u32, at as u32);
        let mut found = std::mem::take(&mut self.found);
        self.for_cells_within_reach(&c, &centre, |members, shift, base| {
            for m in members {
                let mut d2 = 0.0;
                for (c, b) in m.centre.iter().zip(&base) {
                    let d = c + b;
                    d2 += d * d;
                }
                if d2 <= self.reach2 && m.ball != i as u32 {
                    found.push((m.ball, shift));
                }
            }
        });
        for &(j, image) in &found {
            let (at_i, at_j) = (self.lists.len(i) as u32, self.lists.len(j as usize) as u32);
            self.lists.push(
                i,
                Neighbour {
                    j,
                    twin: at_j,
                    image,
                },
            );
            self.lists.push(
                j as usize,
                Neighbour {
                    j: i as u32,
                    twin: at_i,
                    image: image.map(|s| -s),
                },
            );
        }
        found.clear();
        self.found = found;
        self.fresh.clear();
        let (seen, drawing) = (&self.seen, self.drawing);
        let fresh = self
            .lists
            .row(i)
            .iter()
            .filter(|n| seen[n.j as usize] != drawing);
        self.fresh.extend(fresh);
    }

    /// Calls `f` with the members of every cell that has a point within reach of `centre`
    /// (in cell `c`), the cell's image shift `s` and `s L - centre` (a member's offset from
    /// `centre` is its centre plus that): of the `3^n` cells around `c`, those whose nearest
    /// point is within reach, per axis the distance to the face crossed (none for the axis's
    /// own cell) squared and summed; about 18 of the 27 in 3D. A cell beyond a walled side is
    /// skipped.
    #[inline]
    fn for_cells_within_reach(
        &self,
        c: &[usize; N],
        centre: &[f64; N],
        mut f: impl FnMut(&[Member<N>], [i8; N], [f64; N]),
    ) {
        let grid = &self.grid;
        // Per axis and offset -1, 0, 1: the cell index (NONE beyond a wall), its shift, and
        // the squared distance from the centre to that cell.
        let mut axes = [[(0u32, 0i8, 0.0f64); 3]; N];
        for k in 0..N {
            let (n, w) = (grid.n[k], grid.width[k]);
            let lower = centre[k] - c[k] as f64 * w;
            let upper = (c[k] + 1) as f64 * w - centre[k];
            for (o, axis) in axes[k].iter_mut().enumerate() {
                let at = c[k] as i64 + o as i64 - 1;
                let (index, shift) = if at < 0 {
                    (n as i64 - 1, -1)
                } else if at >= n as i64 {
                    (0, 1)
                } else {
                    (at, 0)
                };
                let gap = match o {
                    0 => lower.max(0.0),
                    1 => 0.0,
                    _ => upper.max(0.0),
                };
                let beyond_wall = shift != 0 && !grid.periodic[k];
                let index = if beyond_wall { NONE } else { index as u32 };
                *axis = (index, shift, gap * gap);
            }
        }
        let size = grid.size;
        for code in 0..3usize.pow(N as u32) {
            let (mut rest, mut gap2) = (code, 0.0);
            let mut cell = [0usize; N];
            let mut shift = [0i8; N];
            let mut outside = false;
            for k in (0..N).rev() {
                let (index, s, g) = axes[k][rest % 3];
                rest /= 3;
                outside |= index == NONE;
                cell[k] = index as usize;
                shift[k] = s;
                gap2 += g;
            }
            if outside || gap2 > self.reach2 {
                continue;
            }
            let base = std::array::from_fn(|k| f64::from(shift[k]) * size[k] - centre[k]);
            f(self.members.row(grid.flat(&cell)), shift, base);
        }
    }

    /// Takes ball `i` out of its neighbours' lists (each entry's twin removed; the entry
    /// moved into its place has its own twin told) and out of its cell, and empties its list.
    fn detach(&mut self, i: usize) {
        for k in 0..self.lists.len(i) {
            let entry = self.lists.row(i)[k];
            let j = entry.j as usize;
            if let Some(moved) = self.lists.swap_remove(j, entry.twin as usize) {
                // `j`'s entry of ball `x = moved.j` now sits at `entry.twin`.
                self.lists
                    .get_mut(moved.j as usize, moved.twin as usize)
                    .twin = entry.twin;
            }
        }
        self.lists.clear(i);
        let (cell, at) = self.cell[i];
        if cell == NONE {
            return;
        }
        if let Some(moved) = self.members.swap_remove(cell as usize, at as usize) {
            self.cell[moved.ball as usize].1 = at;
        }
        self.cell[i].0 = NONE;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Every list is exactly the balls within reach (by a direct all-pairs, all-images
    /// search), with the image that brings them there, every entry's twin is where it says,
    /// and every ball is where its cell says, after random redraws and a random permutation of
    /// the slots.
    #[test]
    fn the_lists_are_the_pairs_within_reach_after_every_redraw() {
        let size = [7.0, 9.0];
        let reach = 1.3;
        let grid = Grid::new(size, [true, false], reach, 200).unwrap();
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let balls = 60;
        let mut shells = Shells::new(grid, balls, reach);
        let random = |rng: &mut ChaCha8Rng| -> [f64; 2] {
            std::array::from_fn(|k| rng.random_range(0.0..size[k]))
        };
        for i in 0..balls {
            shells.draw(i, random(&mut rng));
        }
        for round in 0..400 {
            if round == 200 {
                // The slots laid out again in a random order.
                let mut order: Vec<u32> = (0..balls as u32).collect();
                for k in 0..balls {
                    order.swap(k, rng.random_range(k..balls));
                }
                shells.permute(&order);
            }
            let i = rng.random_range(0..balls);
            shells.draw(i, random(&mut rng));
            if round % 40 != 0 {
                continue;
            }
            for a in 0..balls {
                let mut want = Vec::new();
                for b in (0..balls).filter(|&b| b != a) {
                    for m in -1i8..=1 {
                        let d = [
                            (shells.centre[b][0] + f64::from(m) * size[0]) - shells.centre[a][0],
                            shells.centre[b][1] - shells.centre[a][1],
                        ];
                        if d[0] * d[0] + d[1] * d[1] <= reach * reach {
                            want.push((b as u32, [m, 0]));
                        }
                    }
                }
                let mut got: Vec<_> = shells.list(a).iter().map(|n| (n.j, n.image)).collect();
                got.sort();
                want.sort();
                assert_eq!(got, want, "ball {a} after {round} redraws");
                for (k, n) in shells.list(a).iter().enumerate() {
                    let twin = shells.list(n.j as usize)[n.twin as usize];
                    assert_eq!((twin.j, twin.twin), (a as u32, k as u32));
                }
                let (cell, at) = shells.cell[a];
                assert_eq!(
                    shells.members.row(cell as usize)[at as usize].ball,
                    a as u32
                );
            }
        }
    }
}
