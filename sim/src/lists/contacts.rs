//! Resolving a contact and re-basing the clock, as the cell engine does
//! (`crate::engine`): the records moved to the contact's time, the pair's map at the
//! canonical normal, the counters, the re-predictions.

use super::ListSimulation;
use crate::canonical::{image_f64, pair_offset};
use crate::engine::{Contact, Event};
use crate::last_contact::LastContact;
use crate::law::{self, tc_law, ContactKind};
use crate::no_contact::QUIET_BOX_LENGTHS;
use crate::normal::unit;
use crate::PairKernels;
use collision_core::BodyState;

impl<const N: usize, const S: usize, K: PairKernels<f64, N, S>> ListSimulation<N, S, K> {
    /// The contact of balls `i` and `j` (`j` at image `image` in `i`'s record coordinates)
    /// at local time `t`: body 1 is the lower index, `nu` along the canonical offset
    /// ([`pair_offset`]).
    pub(super) fn ball_ball(
        &mut self,
        i: usize,
        j: usize,
        image: &[i16; N],
        t: f64,
    ) -> Event<N, S> {
        // Body 1 is the lower index (not slot).
        let (lo, hi, image) = if self.balls[i].id < self.balls[j].id {
            (i, j, *image)
        } else {
            (j, i, image.map(|k| -k))
        };
        let ids = [self.balls[lo].id as usize, self.balls[hi].id as usize];
        let d = pair_offset(
            &self.flights[lo].motion,
            &self.flights[hi].motion,
            &image_f64(&image),
            &self.size,
            t,
        );
        let nu = unit(d);
        self.move_record(lo, t);
        self.move_record(hi, t);
        let pre = [self.balls[lo].state.clone(), self.balls[hi].state.clone()];
        let species = [self.balls[lo].kind as usize, self.balls[hi].kind as usize];
        let kind = self.law(self.table.ball_law(species[0], species[1]), [lo, hi], t);
        let [s1, s2] = law::pair(&self.kernels, &self.species, kind, species, &nu, &pre);
        self.balls[lo].last = LastContact::ball(ids[1]);
        self.balls[hi].last = LastContact::ball(ids[0]);
        self.balls[lo].state = s1;
        self.balls[hi].state = s2;
        let contact = Contact::Ball {
            i: ids[0],
            j: ids[1],
        };
        let event = self.finish(contact, nu, [lo, hi], pre, t);
        self.after_contact([lo, hi], t);
        event
    }

    /// The contact of ball `i` with the box wall of `axis` (at `L_k` if `upper`) at local
    /// time `t`.
    pub(super) fn ball_wall(&mut self, i: usize, axis: usize, upper: bool, t: f64) -> Event<N, S> {
        self.move_record(i, t);
        let nu = std::array::from_fn(|k| match (k == axis, upper) {
            (false, _) => 0.0,
            (true, true) => -1.0,
            (true, false) => 1.0,
        });
        let pre = [self.balls[i].state.clone(), self.balls[i].state.clone()];
        let kind = self.law(self.table.box_contact, [i, i], t);
        self.balls[i].state = law::fixed(
            &self.kernels,
            &self.species,
            kind,
            self.balls[i].kind as usize,
            Some((axis, upper)),
            &nu,
            &pre[0],
        );
        self.balls[i].last = LastContact::NONE;
        let id = self.balls[i].id as usize;
        let event = self.finish(Contact::Wall { i: id, axis, upper }, nu, [i, i], pre, t);
        self.after_contact([i, i], t);
        event
    }

    /// The law of a contact of `balls` at local time `t` whose kind is `kind`, under the TC
    /// model ([`tc_law`]).
    fn law(&self, kind: ContactKind, balls: [usize; 2], t: f64) -> ContactKind {
        let previous = balls.map(|b| self.balls[b].previous);
        tc_law(kind, self.table.tc, self.absolute(t), previous)
    }

    /// The new velocities into the flight records, the counters moved on, the event.
    fn finish(
        &mut self,
        contact: Contact,
        nu: [f64; N],
        balls: [usize; 2],
        pre: [BodyState<f64, N, S>; 2],
        t: f64,
    ) -> Event<N, S> {
        for b in balls {
            self.flights[b].motion.velocity = self.balls[b].state.velocity;
        }
        self.flights[balls[0]].count += 1;
        if balls[1] != balls[0] {
            self.flights[balls[1]].count += 1;
        }
        self.contacts += 1;
        self.quiet = 0;
        self.next_check = self.first_check();
        self.last_contact = t;
        self.next_notice = QUIET_BOX_LENGTHS;
        let time = self.absolute(t);
        for b in balls {
            self.balls[b].previous = time;
        }
        Event {
            time,
            contact,
            nu,
            position: balls.map(|b| self.flights[b].motion.pos),
            pre,
            post: balls.map(|b| self.balls[b].state.clone()),
        }
    }

    /// After a contact at local time `t`: the speed bound raised, and the clock re-based at
    /// `t` if the lowered re-basing time is past (every ball predicted again), else the balls
    /// involved predicted.
    fn after_contact(&mut self, balls: [usize; 2], t: f64) {
        if self.clock.contact(balls.map(|b| self.speed2_of(b)), t) {
            self.rebase(t, false);
            return;
        }
        self.predict(balls[0]);
        if balls[1] != balls[0] {
            self.predict(balls[1]);
        }
    }

    /// Re-bases the clock at local time `t` (`crate::canonical`): every record moved to `t`
    /// and folded, the origin moved on by `t`, the clock restarted at 0 and every ball
    /// predicted again. The shells stay: they are drawn in the box.
    pub(super) fn rebase(&mut self, t: f64, quiet: bool) {
        let mut speed2: f64 = 0.0;
        for i in 0..self.len() {
            self.move_record(i, t);
            self.flights[i].motion.since = 0.0;
            speed2 = speed2.max(self.speed2_of(i));
        }
        self.clock.rebase(t, quiet, speed2);
        self.last_contact -= t;
        self.now = (self.now - t).max(0.0);
        self.predict_all();
        self.rebases += 1;
    }
}
