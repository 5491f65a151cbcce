//! The balls' flight records stored by cell: the records of a cell's balls are one contiguous
//! list, so the neighbour scan reads a list per cell instead of one record per ball it meets
//! (at large `N` each of those was a cache miss).
//!
//! Each ball knows its cell and its slot in the cell's list. A ball leaving a cell is
//! swap-removed (the cell's last ball takes its slot) and appended to its new cell: the order
//! of every list is the order in which a plain list of ball indices kept by the same moves
//! would hold them, so scans meet the balls in the same order as such a list.

use crate::motion::Motion;
use collision_core::batch::prefetch;

/// A ball's record in its cell's list.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Resident<const N: usize> {
    /// Its flight.
    pub motion: Motion<N>,
    /// Its wraps `W_i` across periodic faces since its record moved: its centre in the box
    /// is `a_i + (t - t_i) u_i - W_i L` (`crate::canonical`).
    pub wraps: [i16; N],
    /// The ball's index.
    pub ball: u32,
}

/// Every ball's flight record, by cell (module docs).
#[derive(Debug)]
pub(crate) struct Residents<const N: usize> {
    cells: Vec<Vec<Resident<N>>>,
    /// Per cell: whether it holds a ball. Compact (one byte a cell, where a list's header
    /// takes 24), so a scan skips the empty cells (most of them in a dilute gas) without
    /// reading their lists' headers.
    occupied: Vec<bool>,
    /// Per ball: its cell's flat index and its slot in that cell's list.
    home: Vec<(u32, u32)>,
}

impl<const N: usize> Residents<N> {
    /// No balls yet, `cells` empty cells.
    pub(crate) fn new(cells: usize) -> Self {
        Residents {
            cells: vec![Vec::new(); cells],
            occupied: vec![false; cells],
            home: Vec::new(),
        }
    }

    /// Adds the next ball (index `len()`) to `cell`.
    pub(crate) fn push(&mut self, cell: usize, motion: Motion<N>) {
        let ball = self.home.len() as u32;
        self.home.push((cell as u32, self.cells[cell].len() as u32));
        self.append(
            cell,
            Resident {
                motion,
                wraps: [0; N],
                ball,
            },
        );
    }

    /// Appends `resident` to `cell`'s list, growing it by one record when full (a list's
    /// capacity is the most balls its cell has held: a cell of a dilute gas holds one or two,
    /// and the default growth to 4 records would spread the records over 2-4 times the
    /// memory); a list never shrinks, so this allocates only while a cell reaches a new most.
    fn append(&mut self, cell: usize, resident: Resident<N>) {
        let list = &mut self.cells[cell];
        if list.len() == list.capacity() {
            list.reserve_exact(1);
        }
        list.push(resident);
        self.occupied[cell] = true;
    }

    /// The number of balls.
    pub(crate) fn len(&self) -> usize {
        self.home.len()
    }

    /// The balls of cell `cell`, in their order.
    #[inline]
    pub(crate) fn cell(&self, cell: usize) -> &[Resident<N>] {
        if self.occupied[cell] {
            &self.cells[cell]
        } else {
            &[]
        }
    }

    /// Asks the CPU to start loading what a scan of `cell` reads first: its occupancy byte
    /// and its list's header (a hint: nothing changes, and it is free if they are cached).
    #[inline]
    pub(crate) fn prefetch_header(&self, cell: usize) {
        prefetch(Some(&self.occupied[cell]));
        prefetch(Some(&self.cells[cell]));
    }

    /// Asks the CPU to start loading `cell`'s first record, if it has one.
    #[inline]
    pub(crate) fn prefetch_list(&self, cell: usize) {
        prefetch(self.cell(cell).first());
    }

    /// Ball `ball`'s flight.
    #[inline]
    pub(crate) fn get(&self, ball: usize) -> &Motion<N> {
        let (c, s) = self.home[ball];
        &self.cells[c as usize][s as usize].motion
    }

    /// Ball `ball`'s flight, to change.
    #[inline]
    pub(crate) fn get_mut(&mut self, ball: usize) -> &mut Motion<N> {
        &mut self.resident_mut(ball).motion
    }

    /// Ball `ball`'s wraps since its record moved.
    #[inline]
    pub(crate) fn wraps(&self, ball: usize) -> [i16; N] {
        let (c, s) = self.home[ball];
        self.cells[c as usize][s as usize].wraps
    }

    /// Ball `ball`'s wraps, to change.
    #[inline]
    pub(crate) fn wraps_mut(&mut self, ball: usize) -> &mut [i16; N] {
        &mut self.resident_mut(ball).wraps
    }

    fn resident_mut(&mut self, ball: usize) -> &mut Resident<N> {
        let (c, s) = self.home[ball];
        &mut self.cells[c as usize][s as usize]
    }

    /// Moves ball `ball` to cell `to`: swap-removed from its cell, appended to `to`.
    pub(crate) fn relocate(&mut self, ball: usize, to: usize) {
        let (c, s) = self.home[ball];
        let list = &mut self.cells[c as usize];
        let resident = list.swap_remove(s as usize);
        if let Some(moved) = list.get(s as usize) {
            self.home[moved.ball as usize].1 = s;
        }
        self.occupied[c as usize] = !list.is_empty();
        self.home[ball] = (to as u32, self.cells[to].len() as u32);
        self.append(to, resident);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn motion(x: f64) -> Motion<2> {
        Motion {
            pos: [x, -x],
            since: 0.0,
            velocity: [1.0, 0.0],
            radius: 0.5,
        }
    }

    #[test]
    fn moves_keep_the_order_of_index_lists_and_every_record_with_its_ball() {
        // The reference: lists of indices under the same moves (swap_remove, push).
        let cells = 5;
        let mut residents = Residents::<2>::new(cells);
        let mut lists: Vec<Vec<u32>> = vec![Vec::new(); cells];
        let mut home = Vec::new();
        for b in 0..40u32 {
            let c = (b as usize * 7) % cells;
            residents.push(c, motion(b as f64));
            lists[c].push(b);
            home.push(c);
        }
        let mut state = 12345u64;
        for _ in 0..2000 {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let b = (state >> 33) as usize % 40;
            let to = (state >> 20) as usize % cells;
            residents.relocate(b, to);
            let from = &mut lists[home[b]];
            let at = from.iter().position(|&x| x as usize == b).unwrap();
            from.swap_remove(at);
            lists[to].push(b as u32);
            home[b] = to;
            residents.get_mut(b).since += 1.0;
        }
        for (c, list) in lists.iter().enumerate() {
            let got: Vec<u32> = residents.cell(c).iter().map(|r| r.ball).collect();
            assert_eq!(&got, list);
            assert_eq!(residents.occupied[c], !list.is_empty());
        }
        for b in 0..40 {
            assert_eq!(residents.get(b).pos, motion(b as f64).pos);
        }
        assert_eq!(residents.len(), 40);
    }
}
