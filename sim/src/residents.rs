//! The balls' flight records stored by cell: the records of a cell's balls are one contiguous
//! list, and the lists lie in one array (the slab) in the order of the cells' flat indices,
//! so the neighbour scan reads a few stretches of memory (in 3D, nine rows of three adjacent
//! cells) instead of one allocation per cell or one record per ball it meets; each of those
//! was a cache miss, the most expensive part of a prediction from a few thousand balls up.
//!
//! **Room.** Cell `c`'s list is `slab[start_c .. start_c + len_c]`, with room for `cap_c`
//! records. [`Residents::compact`] lays every list out again in cell order with room for one
//! more record than it holds (an empty cell gets room for one); the engine compacts at every
//! re-basing. The engine's first slab is laid out that way at once
//! ([`Residents::laid_out`]), so the first compaction finds nothing to do. A ball arriving
//! in a full cell moves that cell's list to the end of the slab with twice the room (its old
//! place is left unused); when the unused places outnumber the used ones the slab is
//! compacted at once, so memory stays `O(balls + cells)`.
//!
//! **Homes.** Where a ball's record lies in the slab (its *home*) is kept by the owner,
//! in the ball's own record beside its other fields ([`Homes`]: the engine's event then
//! reads one per-ball record, not a separate array of homes too); the methods that move
//! records are given the homes to update.
//!
//! **Order.** A ball leaving a cell is swap-removed (the cell's last ball takes its slot) and
//! appended to its new cell; moves and compaction keep each list's order: the order of every
//! list is the order in which a plain list of ball indices kept by the same moves would hold
//! them, so scans meet the balls in the same order as such a list.

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
    /// The ball's counter `count_i` (its contacts so far, as in its own record): a
    /// prediction keeps it with the contact it finds, from the record it has just read
    /// instead of from the partner's own record elsewhere in memory.
    pub count: u32,
}

/// Where a cell's list lies in the slab: `slab[start .. start + len]`, room for `cap`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Span {
    start: u32,
    len: u32,
    cap: u32,
}

/// Where each ball's record lies in the slab, kept by the owner of the [`Residents`]
/// (module docs, "Homes").
pub(crate) trait Homes {
    /// Ball `ball`'s record's index in the slab.
    fn home(&self, ball: usize) -> u32;
    /// Ball `ball`'s record is now at index `at` of the slab.
    fn set_home(&mut self, ball: usize, at: u32);
}

/// Every ball's flight record, by cell (module docs).
#[derive(Debug)]
pub(crate) struct Residents<const N: usize> {
    /// The lists, with their room and the places left by lists that moved.
    slab: Vec<Resident<N>>,
    /// Per cell: its list's place in the slab.
    spans: Vec<Span>,
    /// The number of balls.
    balls: usize,
    /// The room of the lists, `sum_c cap_c` (the rest of the slab is unused).
    room: usize,
    /// Whether the slab is laid out as [`Residents::compact`] would lay it out (no record
    /// moved since it was laid out): compacting it again would change nothing.
    compact: bool,
}

/// The lists of `spans` (their lengths as they are) placed one after another from the slab's
/// start, in cell order, each with room for one more record than it holds: `start_c = sum_{c'
/// < c} cap_c'`, `cap_c = len_c + 1`, the layout of [`Residents::compact`]. Returns the room,
/// `sum_c cap_c`.
fn lay_out(spans: &mut [Span]) -> usize {
    let mut room = 0;
    for span in spans {
        span.start = room;
        span.cap = span.len + 1;
        room += span.cap;
    }
    room as usize
}

/// A placeholder for a slot no ball holds.
fn vacant<const N: usize>() -> Resident<N> {
    Resident {
        motion: Motion {
            pos: [0.0; N],
            since: 0.0,
            velocity: [0.0; N],
            radius: 0.0,
        },
        wraps: [0; N],
        ball: u32::MAX,
        count: 0,
    }
}

impl<const N: usize> Residents<N> {
    /// Ball `i` (of `cell_of.len()`), its flight `motion(i)`, in cell `cell_of[i]`: the
    /// slab laid out at once as [`Residents::compact`] lays it out (the lists in cell order,
    /// each in ball order with room for one more record), its homes set in `homes`.
    /// The records pushed one by one (`Residents::push`, in the tests) and compacted give
    /// the same slab; this allocates it once and writes each record once, where pushing
    /// moves the lists that fill up and compacting copies the whole slab (at `10^6` balls a
    /// third of the time to the first contact and a quarter of its peak memory;
    /// docs/benchmarks.md, "The start at `10^6` balls").
    pub(crate) fn laid_out(
        cells: usize,
        cell_of: &[u32],
        motion: impl Fn(usize) -> Motion<N>,
        homes: &mut (impl Homes + ?Sized),
    ) -> Self {
        let mut spans = vec![Span::default(); cells];
        for &c in cell_of {
            spans[c as usize].len += 1;
        }
        let room = lay_out(&mut spans);
        // Each list filled again below, ball by ball.
        for span in &mut spans {
            span.len = 0;
        }
        let mut slab = vec![vacant(); room];
        for (ball, &c) in cell_of.iter().enumerate() {
            let span = &mut spans[c as usize];
            let at = span.start + span.len;
            span.len += 1;
            slab[at as usize] = Resident {
                motion: motion(ball),
                wraps: [0; N],
                ball: ball as u32,
                count: 0,
            };
            homes.set_home(ball, at);
        }
        Residents {
            slab,
            spans,
            balls: cell_of.len(),
            room,
            compact: true,
        }
    }

    /// No balls yet, `cells` empty cells.
    #[cfg(test)]
    pub(crate) fn new(cells: usize) -> Self {
        Self::laid_out(
            cells,
            &[],
            |_| unreachable!("no balls"),
            &mut Vec::<u32>::new(),
        )
    }

    /// Adds the next ball (index `len()`) to `cell`; its home is set in `homes`.
    #[cfg(test)]
    pub(crate) fn push(
        &mut self,
        homes: &mut (impl Homes + ?Sized),
        cell: usize,
        motion: Motion<N>,
    ) {
        let ball = self.balls as u32;
        self.balls += 1;
        self.append(
            homes,
            cell,
            Resident {
                motion,
                wraps: [0; N],
                ball,
                count: 0,
            },
        );
    }

    /// Appends `resident` to `cell`'s list, moving the list to the end of the slab with twice
    /// the room when it is full (module docs).
    fn append(&mut self, homes: &mut (impl Homes + ?Sized), cell: usize, resident: Resident<N>) {
        self.compact = false;
        if self.spans[cell].len == self.spans[cell].cap {
            self.regrow(homes, cell);
        }
        let span = &mut self.spans[cell];
        let at = (span.start + span.len) as usize;
        span.len += 1;
        self.slab[at] = resident;
        homes.set_home(resident.ball as usize, at as u32);
    }

    /// Moves full `cell`'s list to the end of the slab with room for `2 len + 1`, or
    /// compacts the slab if the unused places would outnumber the used ones.
    fn regrow(&mut self, homes: &mut (impl Homes + ?Sized), cell: usize) {
        let span = self.spans[cell];
        let cap = 2 * span.len + 1;
        if self.slab.len() + cap as usize > 2 * (self.room + cap as usize) {
            // Compaction leaves room for one more in every list.
            return self.compact(homes);
        }
        let start = self.slab.len();
        let (from, len) = (span.start as usize, span.len as usize);
        self.slab.extend_from_within(from..from + len);
        self.slab.resize(start + cap as usize, vacant());
        for (k, r) in self.slab[start..start + len].iter().enumerate() {
            homes.set_home(r.ball as usize, (start + k) as u32);
        }
        self.room += (cap - span.cap) as usize;
        self.spans[cell] = Span {
            start: start as u32,
            len: span.len,
            cap,
        };
    }

    /// Lays every list out again in the order of the cells, each with room for one more
    /// record than it holds (module docs). `O(balls + cells)`; nothing to do if no record
    /// moved since the slab was last laid out.
    ///
    /// The lists are laid out in the slab's own memory: the records are first copied out in
    /// cell order (a copy of the balls, not of the room), so the peak is the slab and the
    /// records, not two slabs. The new room, `balls + cells`, never exceeds the slab's length
    /// (a list's room only grows, from `len + 1` at the last layout).
    pub(crate) fn compact(&mut self, homes: &mut (impl Homes + ?Sized)) {
        if self.compact {
            return;
        }
        let mut records = Vec::with_capacity(self.balls);
        for span in &self.spans {
            let (from, len) = (span.start as usize, span.len as usize);
            records.extend_from_slice(&self.slab[from..from + len]);
        }
        let room = lay_out(&mut self.spans);
        self.slab.clear();
        let mut next = 0;
        for span in &self.spans {
            let len = span.len as usize;
            debug_assert_eq!(self.slab.len(), span.start as usize);
            self.slab.extend_from_slice(&records[next..next + len]);
            self.slab.push(vacant());
            next += len;
        }
        drop(records);
        self.slab.shrink_to(room);
        for (k, r) in self.slab.iter().enumerate() {
            if r.ball != u32::MAX {
                homes.set_home(r.ball as usize, k as u32);
            }
        }
        self.room = room;
        self.compact = true;
    }

    /// The number of balls.
    pub(crate) fn len(&self) -> usize {
        self.balls
    }

    /// The balls of cell `cell`, in their order.
    #[inline]
    pub(crate) fn cell(&self, cell: usize) -> &[Resident<N>] {
        let span = self.spans[cell];
        let start = span.start as usize;
        &self.slab[start..start + span.len as usize]
    }

    /// Where cell `cell`'s list starts in the slab, and its length.
    #[inline(always)]
    pub(crate) fn span(&self, cell: usize) -> (u32, usize) {
        let span = self.spans[cell];
        (span.start, span.len as usize)
    }

    /// Writes the slab places of the records of the cells `flat + offsets[..]` to `out` from
    /// its start, and returns their number. Four places are written per cell whatever its
    /// length (one store, and no branch on a length that varies from cell to cell: a scan's
    /// loop over the places has one trip count instead of one per cell).
    ///
    /// Unchecked: with a bounds check on each cell and each store the loop ran 6 % more
    /// instructions of a whole 3D run at `phi` 0.1 (callgrind, docs/benchmarks.md, session
    /// 55); the compiler kept `count` in memory across the checks' exits.
    ///
    /// # Safety
    /// Every `flat + offsets[k]` is a cell of the grid and they are distinct cells (an
    /// interior cell's neighbourhood, [`crate::cells::Listing::Interior`]): distinct cells
    /// hold at most every ball once, so with `out` holding `balls + 4` places (asserted) the
    /// four stores of the last cell end within it.
    #[inline(always)]
    pub(crate) unsafe fn gather_cells(
        &self,
        flat: usize,
        offsets: &[isize],
        out: &mut [u32],
    ) -> usize {
        // Checked once a call (the stores below rely on it).
        assert!(
            out.len() >= self.balls + 4,
            "room for every ball and four more"
        );
        debug_assert!(offsets.iter().all(|&o| flat
            .checked_add_signed(o)
            .is_some_and(|c| c < self.spans.len())));
        debug_assert!(offsets.windows(2).all(|w| w[0] < w[1]), "distinct cells");
        let spans = self.spans.as_ptr();
        let out = out.as_mut_ptr();
        let mut count = 0;
        for &offset in offsets {
            // SAFETY: a cell of the grid, and `count + len <= balls` (the doc's conditions).
            unsafe {
                let span = *spans.add(flat.wrapping_add_signed(offset));
                let (start, len) = (span.start, span.len as usize);
                out.add(count).cast::<[u32; 4]>().write_unaligned([
                    start,
                    start + 1,
                    start + 2,
                    start + 3,
                ]);
                for k in 4..len {
                    *out.add(count + k) = start + k as u32;
                }
                count += len;
            }
        }
        count
    }

    /// The record at slab place `at` (from [`Residents::gather_cells`]).
    #[inline]
    pub(crate) fn at(&self, at: u32) -> &Resident<N> {
        &self.slab[at as usize]
    }

    /// Every ball, cell after cell (in the slab's order).
    pub(crate) fn in_cell_order(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.spans.len()).flat_map(|c| self.cell(c).iter().map(|r| r.ball as usize))
    }

    /// Asks the CPU to start loading what a scan of `cell` reads first: its list's place
    /// (a hint: nothing changes, and it is free if it is cached).
    #[inline]
    pub(crate) fn prefetch_header(&self, cell: usize) {
        prefetch(Some(&self.spans[cell]));
    }

    /// Asks the CPU to start loading `cell`'s first record, if it has one.
    #[inline]
    pub(crate) fn prefetch_list(&self, cell: usize) {
        prefetch(self.cell(cell).first());
    }

    /// Asks the CPU to start loading the slot a ball's move out of cell `leaves` reads (its
    /// list's last record, moved into the leaver's slot) and the one a move into cell `enters`
    /// writes (the slot after its list's last).
    #[inline]
    pub(crate) fn prefetch_move(&self, leaves: usize, enters: usize) {
        let end = |cell: usize| {
            let span = self.spans[cell];
            (span.start + span.len) as usize
        };
        prefetch(self.slab.get(end(leaves).wrapping_sub(1)));
        prefetch(self.slab.get(end(enters)));
    }

    /// Asks the CPU to start loading the record at `at` (a hint, as above).
    #[inline]
    pub(crate) fn prefetch_record(&self, at: u32) {
        prefetch(self.slab.get(at as usize));
    }

    /// The flight of the ball whose home is `at`.
    #[inline]
    pub(crate) fn get(&self, at: u32) -> &Motion<N> {
        &self.slab[at as usize].motion
    }

    /// The flight of the ball whose home is `at`, to change.
    #[inline]
    pub(crate) fn get_mut(&mut self, at: u32) -> &mut Motion<N> {
        &mut self.slab[at as usize].motion
    }

    /// The counter of the ball whose home is `at`, to change with the ball's own.
    #[inline]
    pub(crate) fn count_mut(&mut self, at: u32) -> &mut u32 {
        &mut self.slab[at as usize].count
    }

    /// The wraps since its record moved of the ball whose home is `at`.
    #[inline]
    pub(crate) fn wraps(&self, at: u32) -> [i16; N] {
        self.slab[at as usize].wraps
    }

    /// The wraps of the ball whose home is `at`, to change.
    #[inline]
    pub(crate) fn wraps_mut(&mut self, at: u32) -> &mut [i16; N] {
        &mut self.slab[at as usize].wraps
    }

    /// Moves ball `ball` from cell `from` to cell `to`: swap-removed from `from`'s list,
    /// appended to `to`'s.
    pub(crate) fn relocate(
        &mut self,
        homes: &mut (impl Homes + ?Sized),
        ball: usize,
        from: usize,
        to: usize,
    ) {
        let at = homes.home(ball);
        let span = &mut self.spans[from];
        let last = (span.start + span.len - 1) as usize;
        debug_assert!((span.start as usize..=last).contains(&(at as usize)));
        span.len -= 1;
        let resident = self.slab[at as usize];
        if last != at as usize {
            self.slab[at as usize] = self.slab[last];
            homes.set_home(self.slab[at as usize].ball as usize, at);
        }
        self.append(homes, to, resident);
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

    impl Homes for Vec<u32> {
        fn home(&self, ball: usize) -> u32 {
            self[ball]
        }
        fn set_home(&mut self, ball: usize, at: u32) {
            if ball >= self.len() {
                self.resize(ball + 1, u32::MAX);
            }
            self[ball] = at;
        }
    }

    #[test]
    fn laid_out_at_once_is_pushed_one_by_one_and_compacted() {
        // Cells filled unevenly: empty ones, one ball, and lists that outgrow their room.
        let cells = 9;
        let cell_of: Vec<u32> = (0..60u32).map(|b| (b * b + 3 * b) % 7).collect();
        let (mut pushed, mut homes_pushed) = (Residents::<2>::new(cells), Vec::<u32>::new());
        for (b, &c) in cell_of.iter().enumerate() {
            pushed.push(&mut homes_pushed, c as usize, motion(b as f64));
        }
        pushed.compact(&mut homes_pushed);
        let mut homes = Vec::<u32>::new();
        let mut laid = Residents::<2>::laid_out(cells, &cell_of, |b| motion(b as f64), &mut homes);
        assert_eq!(laid.slab, pushed.slab);
        assert_eq!(laid.spans, pushed.spans);
        assert_eq!((laid.balls, laid.room), (pushed.balls, pushed.room));
        assert_eq!(homes, homes_pushed);
        // Compacting what is laid out changes nothing; a move makes it compact again.
        laid.compact(&mut homes);
        assert_eq!(laid.slab, pushed.slab);
        laid.relocate(&mut homes, 5, cell_of[5] as usize, 8);
        assert!(!laid.compact);
        laid.compact(&mut homes);
        assert_eq!(laid.cell(8).iter().map(|r| r.ball).collect::<Vec<_>>(), [5]);
        assert_eq!(laid.slab.len(), laid.room);
        assert_eq!(laid.spans[8].cap, 2);
    }

    #[test]
    fn moves_keep_the_order_of_index_lists_and_every_record_with_its_ball() {
        // The reference: lists of indices under the same moves (swap_remove, push).
        let cells = 5;
        let mut residents = Residents::<2>::new(cells);
        let mut lists: Vec<Vec<u32>> = vec![Vec::new(); cells];
        let mut home = Vec::new();
        let mut homes = Vec::<u32>::new();
        for b in 0..40u32 {
            let c = (b as usize * 7) % cells;
            residents.push(&mut homes, c, motion(b as f64));
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
            residents.relocate(&mut homes, b, home[b], to);
            let from = &mut lists[home[b]];
            let at = from.iter().position(|&x| x as usize == b).unwrap();
            from.swap_remove(at);
            lists[to].push(b as u32);
            home[b] = to;
            residents.get_mut(homes[b]).since += 1.0;
            if state % 97 == 0 {
                residents.compact(&mut homes);
            }
        }
        let order: Vec<u32> = residents.in_cell_order().map(|b| b as u32).collect();
        assert_eq!(order, lists.concat());
        for (c, list) in lists.iter().enumerate() {
            let got: Vec<u32> = residents.cell(c).iter().map(|r| r.ball).collect();
            assert_eq!(&got, list);
        }
        for b in 0..40 {
            assert_eq!(residents.get(homes[b]).pos, motion(b as f64).pos);
            assert_eq!(
                residents
                    .cell(home[b])
                    .iter()
                    .filter(|r| r.ball as usize == b)
                    .count(),
                1
            );
        }
        assert_eq!(residents.len(), 40);
    }
}
