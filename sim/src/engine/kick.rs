//! Kicks: the white-noise thermostat's velocity increments ([`crate::thermostat`]), applied
//! to every ball at once between events.
//!
//! A kick at the clock's time `t` (where [`Simulation::step`] left it on [`super::Step::Until`]
//! or [`super::Step::Never`]) first takes the canonical re-basings due before `t` (those that
//! the next event would have taken), then moves every record to `t` (with the old
//! velocities), changes the velocities, and re-bases the clock at `t`: every ball is predicted
//! again from its moved record, as after a re-basing. So every contact time stays a function
//! of the records of the bodies that meet, and the all-pairs reference, kicking alike,
//! writes the same log.

use super::Simulation;
use crate::last_contact::LastContact;
use crate::PairKernels;

impl<const N: usize, const S: usize, K: PairKernels<f64, N, S>> Simulation<N, S, K> {
    /// Adds `dv[i]` to ball `i`'s velocity now, for every ball (spins unchanged), and returns
    /// the kinetic energy this adds, `sum_i m_i (|u_i + dv_i|^2 - |u_i|^2) / 2` (each ball's
    /// term as `m_i sum_k (u'_k - u_k) (u'_k + u_k) / 2`).
    ///
    /// Call it where [`Simulation::step`] stopped at the kick's time (`Step::Until` or
    /// `Step::Never` with `until` that time): no contact is pending before it. Every ball's
    /// contact counter moves on (its velocity changed), and its last contact is forgotten (a
    /// kick may turn it back towards that boundary or ball: `sim/src/last_contact.rs`).
    ///
    /// # Panics
    ///
    /// If `dv` does not hold one increment per ball.
    pub fn kick(&mut self, dv: &[[f64; N]]) -> f64 {
        assert_eq!(dv.len(), self.len(), "one velocity increment per ball");
        while self.now > self.clock.rebase_at() {
            self.rebase(self.clock.rebase_at(), true);
        }
        let t = self.now;
        let mut added = 0.0;
        for (i, d) in dv.iter().enumerate() {
            self.move_record(i, t);
            let ball = &mut self.balls[i];
            let m = 1.0 / self.species[ball.kind as usize].inv_mass;
            let u = &mut ball.state.velocity;
            let mut twice = 0.0;
            for k in 0..N {
                let before = u[k];
                u[k] += d[k];
                twice += (u[k] - before) * (u[k] + before);
            }
            added += 0.5 * m * twice;
            ball.last = LastContact::NONE;
            let (home, velocity) = (ball.home, ball.state.velocity);
            self.motion.get_mut(home).velocity = velocity;
            self.count_change(i);
        }
        self.rebase(t, false);
        added
    }
}
