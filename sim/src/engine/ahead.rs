//! Looking ahead: the memory of the next events in the calendar loaded while this one runs.
//!
//! From a few tens of thousands of balls on, the records an event reads are mostly not in
//! the caches, and their loads form a chain: the ball's record gives its flight's place in
//! the slab, its cell and its partner; the cell gives the places of its neighbours' lists
//! (the spans), the places give the records. Taken one event at a time, each link waits for
//! the memory. The calendar already knows the next events (the current bucket's sorted list,
//! `queue.rs`), whose balls' records were read when the bucket was sorted, so the chain is
//! started one link per event ahead: while event `k` runs,
//!
//! - for event `k + 2`: its flight record, its partner's record if it is a contact, and the
//!   spans of the cells its scan will read; for a crossing also the spans of the cell it
//!   leaves and of the one it enters;
//! - for event `k + 1`: the first records of those cells' lists (their spans now cached),
//!   for a contact the partner's flight record and the spans of the partner's scan, and for
//!   a crossing the slots its move writes: the left cell's last record (moved into the
//!   ball's slot) and the slot after the entered cell's last (the ball's new one). A crossing
//!   reads neither cell in its scan (the layer it reaches lies beyond the cell entered):
//!   the move (`Residents::relocate`) held 10 % of a `perf` profile's samples at `10^6`
//!   disks, most of them waiting for those spans and slots.
//!
//! The cells are looked ahead only for a scan of at most [`AHEAD_CELLS`] cells: a 2D
//! neighbourhood, or the layer a crossing reaches in 3D. A 3D neighbourhood (27 cells, in
//! nine stretches) looked ahead for two events at once kept the miss buffers full and gained
//! nothing at `10^6` balls, where the records alone gained a little and the bounded rule the
//! most (docs/benchmarks.md, "Looking ahead").
//!
//! A scan looked ahead prefetches nothing itself; a larger one still requests its spans and
//! then its lists together when it starts (`scan.rs`).
//!
//! The events between may change what comes next: a wrong guess costs a few loads and
//! nothing else, since a prefetch changes no value (logs are the same bytes).

use super::Simulation;
use crate::queue::What;
use crate::PairKernels;
use collision_core::batch::prefetch;

/// The most cells of a scan looked ahead (module docs): `3^2`.
const AHEAD_CELLS: usize = 9;

impl<const N: usize, const S: usize, K: PairKernels<f64, N, S>> Simulation<N, S, K> {
    /// Starts the loads of the next two events' records and cells (module docs); the
    /// earliest event is the one about to run.
    #[inline]
    pub(super) fn look_ahead(&self) {
        if let Some(i) = self.queue.upcoming(2) {
            let record = &self.balls[i];
            self.motion.prefetch_record(record.home);
            let next = record.next();
            if let Some(What::Ball { j, .. }) = next {
                prefetch(self.balls.get(j as usize));
            }
            self.for_cells_ahead(i, next, |cell| self.motion.prefetch_header(cell));
            if let Some(What::Cell { axis, up }) = next {
                // The crossing moves the ball's record from its cell's list to the next's.
                let (from, to) = self.moved(i, axis, up);
                self.motion.prefetch_header(from);
                self.motion.prefetch_header(to);
            }
        }
        if let Some(i) = self.queue.upcoming(1) {
            let next = self.balls[i].next();
            self.for_cells_ahead(i, next, |cell| self.motion.prefetch_list(cell));
            if let Some(What::Cell { axis, up }) = next {
                let (from, to) = self.moved(i, axis, up);
                self.motion.prefetch_move(from, to);
            }
            if let Some(What::Ball { j, .. }) = next {
                let j = j as usize;
                self.motion.prefetch_record(self.balls[j].home);
                // After the contact the partner is predicted again by a full scan, whatever
                // its own pending event.
                self.for_cells_ahead(j, None, |cell| self.motion.prefetch_header(cell));
            }
        }
    }

    /// The flat indices of the cell ball `i` leaves and of the one it enters when it crosses
    /// along `axis` (moving `up` or down).
    #[inline]
    fn moved(&self, i: usize, axis: u8, up: bool) -> (usize, usize) {
        let c = self.balls[i].cell();
        let (next, _) = self.grid.crossed(&c, axis as usize, up);
        (self.grid.flat(&c), self.grid.flat(&next))
    }

    /// `f` for the flat index of each cell ball `i`'s scan at event `next` reads, if they are
    /// at most [`AHEAD_CELLS`]: after a crossing the layer it reaches from the cell entered,
    /// as `predict_after_crossing` scans it, else every cell within reach of its own, as
    /// `predict` does (a contact's record may move to another cell first: then the guess is
    /// off by a cell).
    #[inline]
    fn for_cells_ahead(&self, i: usize, next: Option<What<N>>, mut f: impl FnMut(usize)) {
        let c = self.balls[i].cell();
        let (c, only) = match next {
            Some(What::Cell { axis, up }) => {
                let axis = axis as usize;
                (
                    self.grid.crossed(&c, axis, up).0,
                    Some(self.grid.reached(axis, up)),
                )
            }
            _ => (c, None),
        };
        if self.looks_ahead(only) {
            self.grid.for_cells(&c, only, |nb| f(nb.cell));
        }
    }

    /// Whether a scan of the cells within reach, or of the layer `only`, is looked ahead
    /// (at most [`AHEAD_CELLS`] cells): the scan itself then prefetches nothing (`scan.rs`).
    #[inline]
    pub(super) fn looks_ahead(&self, only: Option<(usize, i64)>) -> bool {
        self.grid.near_len(only) <= AHEAD_CELLS
    }
}
