//! Looking ahead, as the cell engine does (`crate::engine`, `ahead.rs`): while one event
//! runs, the memory of the next two is requested, one link of the chain per event. The
//! calendar knows the next events (the current bucket's sorted list, whose balls' own
//! records it read when it sorted them):
//!
//! - for event `k + 2`: its ball's flight record and list, and for a contact the partner's
//!   own and flight records and list;
//! - for event `k + 1`: the flight records of its ball's list (the list now cached), and for a
//!   contact those of the partner's list: after a contact both balls ask their whole lists.
//!
//! Leaving a shell is not looked ahead: requesting the entries its neighbours' lists hold of
//! it and the members of the cells around its position then made 32 000 balls at `phi` 0.3
//! and 0.4 slower (docs/benchmarks.md, "The list engine").
//!
//! On only where the flight records and lists outgrow the caches
//! ([`super::ListSimulation`]'s rule). A prefetch changes no value; a wrong guess (the events
//! between change what comes next) costs a few loads.

use super::ball::Next;
use super::ListSimulation;
use crate::PairKernels;
use collision_core::batch::prefetch;

impl<const N: usize, const S: usize, K: PairKernels<f64, N, S>> ListSimulation<N, S, K> {
    /// Starts the loads of the next two events' records and lists (module docs); the earliest
    /// event is the one about to run.
    #[inline]
    pub(super) fn look_ahead(&self) {
        if let Some(i) = self.queue.upcoming(2) {
            prefetch(self.flights.get(i));
            self.shells.prefetch_list(i);
            if let Some(Next::Ball { j, .. }) = self.balls[i].next {
                let j = j as usize;
                prefetch(self.balls.get(j));
                prefetch(self.flights.get(j));
                self.shells.prefetch_list(j);
            }
        }
        if let Some(i) = self.queue.upcoming(1) {
            let list = |b: usize| self.shells.list(b).iter();
            list(i).for_each(|near| prefetch(self.flights.get(near.j as usize)));
            if let Some(Next::Ball { j, .. }) = self.balls[i].next {
                list(j as usize).for_each(|near| prefetch(self.flights.get(near.j as usize)));
            }
        }
    }
}
