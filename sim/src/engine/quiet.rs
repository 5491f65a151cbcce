//! The engine's clock and its quiet stretches: re-basing the local clock, the checks that no
//! contact can come ([`NoContact`]) and the travel since the last contact.

use super::{Simulation, Step};
use crate::no_contact::{slowest, Flight, NoContact};
use crate::PairKernels;

impl<const N: usize, const S: usize, K: PairKernels<f64, N, S>> Simulation<N, S, K> {
    /// [`Step::Never`], with the clock moved on to `until` (local) if that is finite: free
    /// flight to it is all that happens.
    pub(super) fn never(&mut self, why: NoContact, until: f64) -> Step<N, S> {
        if until.is_finite() {
            self.now = self.now.max(until);
        }
        Step::Never(why)
    }

    /// Events without a contact before the first no-contact check after a contact.
    pub(super) fn first_check(&self) -> u64 {
        (2 * self.len() as u64).max(1024)
    }

    /// Whether no contact can happen again ([`NoContact`]); the exact pair test is run when
    /// its cost (balls x bodies) is at most `max(2^20, 16 quiet)`, so `O(1)` per event.
    pub(super) fn no_contact(&self) -> Option<NoContact> {
        let position = |i: usize| self.position(i);
        let velocity = |i: usize| self.balls[i].state.velocity;
        let radius = |i: usize| self.species[self.balls[i].kind as usize].radius;
        let flight = Flight {
            size: self.grid.size,
            periodic: self.grid.periodic,
            position: &position,
            velocity: &velocity,
            radius: &radius,
            balls: self.len(),
            obstacles: &self.obstacles,
        };
        // Without a box the empty queue decides (step); with boundaries every axis is
        // walled, and a moving ball may still meet them.
        let pairs = self.table.boxed && self.table.boundaries.is_empty();
        flight.decide(self.quiet, pairs)
    }

    /// Box lengths (the longest side) the slowest moving ball travelled since the last
    /// contact (0 if every ball is at rest).
    pub(super) fn quiet_travel(&self) -> f64 {
        self.slowest_speed().map_or(0.0, |slowest| {
            (self.now - self.last_contact) * slowest / self.longest_side()
        })
    }

    /// The speed `|u|` of the slowest moving ball, `None` if every ball is at rest.
    pub(crate) fn slowest_speed(&self) -> Option<f64> {
        slowest((0..self.len()).map(|i| self.speed2_of(i)))
    }

    /// The longest side of the box, the unit of box lengths.
    pub(crate) fn longest_side(&self) -> f64 {
        self.grid.size.iter().copied().fold(0.0, f64::max)
    }

    /// Ball `i`'s speed `|u_i|`.
    pub(crate) fn speed_of(&self, i: usize) -> f64 {
        self.speed2_of(i).sqrt()
    }

    pub(super) fn speed2_of(&self, i: usize) -> f64 {
        self.balls[i].state.velocity.iter().map(|x| x * x).sum()
    }

    /// Re-base the clock at local time `t` (the canonical time of [`crate::canonical`]): every
    /// record moves to `t` and folds into the box, the origin moves by `t` (a compensated
    /// sum), the local clock restarts at 0, and every ball is predicted again from its moved
    /// record (the queue's widths chosen again for the current event rate). `O(balls)`
    /// predictions, once per `CLOCK_CELLS` cell widths travelled by the fastest ball. `quiet`:
    /// no contact since the last re-basing.
    pub(super) fn rebase(&mut self, t: f64, quiet: bool) {
        let mut speed2: f64 = 0.0;
        for i in 0..self.len() {
            self.move_record(i, t);
            self.motion.get_mut(self.balls[i].home).since = 0.0;
            speed2 = speed2.max(self.speed2_of(i));
        }
        self.clock.rebase(t, quiet, speed2);
        self.last_contact -= t;
        self.now = (self.now - t).max(0.0);
        self.predict_all();
        self.rebases += 1;
    }
}
