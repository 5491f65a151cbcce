//! Resolving a contact: the pair's map ([`crate::law`]: the generated no-slip kernel, the
//! specular one or the rough one, under the TC model) at the contact normal, the counters,
//! and the re-prediction of the balls involved.

use super::{Contact, Event, Simulation};
use crate::canonical::{image_f64, obstacle_image, pair_offset};
use crate::last_contact::LastContact;
use crate::law::{self, tc_law, ContactKind};
use crate::left_table::{leaves, LeftTable};
use crate::no_contact::QUIET_BOX_LENGTHS;
use crate::normal::unit;
use crate::orientation::{exp_skew, mul};
use crate::PairKernels;
use collision_core::BodyState;

impl<const N: usize, const S: usize, K: PairKernels<f64, N, S>> Simulation<N, S, K> {
    /// After a contact at local time `t` changed the velocities of `balls`: raise the speed
    /// bound and re-base the clock at `t` if the lowered re-basing time is past (every ball
    /// is then predicted again), else predict the balls involved.
    pub(super) fn after_contact(&mut self, balls: [usize; 2], t: f64) {
        if self.clock.contact(balls.map(|b| self.speed2_of(b)), t) {
            self.rebase(t, false);
            return;
        }
        self.predict(balls[0]);
        if balls[1] != balls[0] {
            self.predict(balls[1]);
        }
    }

    /// Moves ball `b`'s record to the contact's time `t` and turns its orientation there
    /// (by the spin before the contact).
    fn settle(&mut self, b: usize, t: f64) {
        self.move_record(b, t);
        if let Some(a) = &mut self.orientation {
            let dt = std::mem::take(&mut self.unturned[b]);
            if dt != 0.0 {
                a[b] = mul(&exp_skew::<N>(&self.balls[b].state.spin, dt), &a[b]);
            }
        }
    }

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
        let (lo, hi, image) = if i < j {
            (i, j, *image)
        } else {
            (j, i, image.map(|k| -k))
        };
        let d = pair_offset(
            self.flight(lo),
            self.flight(hi),
            &image_f64(&image),
            &self.grid.size,
            t,
        );
        let nu = unit(d);
        self.settle(lo, t);
        self.settle(hi, t);
        let pre = [self.balls[lo].state.clone(), self.balls[hi].state.clone()];
        let species = [self.balls[lo].kind as usize, self.balls[hi].kind as usize];
        let pair_law = self.table.ball_law(species[0], species[1]);
        let kind = self.law(pair_law, [lo, hi], t);
        let [s1, s2] = law::pair(&self.kernels, &self.species, kind, species, &nu, &pre);
        self.balls[lo].last = LastContact::ball(hi);
        self.balls[hi].last = LastContact::ball(lo);
        self.balls[lo].state = s1;
        self.balls[hi].state = s2;
        let event = self.finish(Contact::Ball { i: lo, j: hi }, nu, [lo, hi], pre, t);
        self.after_contact([lo, hi], t);
        event
    }

    pub(super) fn ball_wall(&mut self, i: usize, axis: usize, upper: bool, t: f64) -> Event<N, S> {
        self.settle(i, t);
        let nu = std::array::from_fn(|k| {
            if k != axis {
                0.0
            } else if upper {
                -1.0
            } else {
                1.0
            }
        });
        let pre = [self.balls[i].state.clone(), self.balls[i].state.clone()];
        let kind = self.law(self.table.box_contact, [i, i], t);
        self.balls[i].state = self.fixed(kind, i, Some((axis, upper)), &nu, &pre[0]);
        self.balls[i].last = LastContact::NONE;
        let event = self.finish(Contact::Wall { i, axis, upper }, nu, [i, i], pre, t);
        self.after_contact([i, i], t);
        event
    }

    /// The contact of ball `i` with obstacle `o` at image `image` at local time `t`.
    pub(super) fn ball_obstacle(
        &mut self,
        i: usize,
        o: usize,
        image: &[i16; N],
        t: f64,
    ) -> Event<N, S> {
        let p = self.flight(i).at(t);
        let b = obstacle_image(&self.obstacles[o].position, image, &self.grid.size);
        let nu = unit(std::array::from_fn(|k| p[k] - b[k]));
        self.settle(i, t);
        let pre = [self.balls[i].state.clone(), self.balls[i].state.clone()];
        let kind = self.law(self.table.obstacle(o), [i, i], t);
        self.balls[i].state = self.fixed(kind, i, None, &nu, &pre[0]);
        self.balls[i].last = LastContact::obstacle(o);
        let event = self.finish(Contact::Obstacle { i, obstacle: o }, nu, [i, i], pre, t);
        self.after_contact([i, i], t);
        event
    }

    /// A contact with boundary `b`: the `fixed` kernel (no-slip) or the specular map
    /// (smooth) at the boundary's local normal (see [`crate::table`]).
    pub(super) fn ball_boundary(&mut self, i: usize, b: usize, t: f64) -> Event<N, S> {
        let p = self.flight(i).at(t);
        let nu = self.table.boundaries[b].shape.normal(&p);
        self.settle(i, t);
        let pre = [self.balls[i].state.clone(), self.balls[i].state.clone()];
        let kind = self.law(self.table.boundaries[b].contact, [i, i], t);
        self.balls[i].state = self.fixed(kind, i, None, &nu, &pre[0]);
        self.balls[i].last = LastContact::boundary(b);
        let event = self.finish(Contact::Boundary { i, boundary: b }, nu, [i, i], pre, t);
        self.after_contact([i, i], t);
        let shape = &self.table.boundaries[b].shape;
        if let Some(outward_speed) = leaves(shape, &event.position[0], &event.post[0].velocity) {
            self.left = Some(LeftTable {
                ball: i,
                boundary: b,
                time: event.time,
                outward_speed,
            });
            // The next step's check returns it (mod.rs).
            self.next_check = 0;
        }
        event
    }

    /// The law of a contact of `balls` at local time `t` whose kind is `kind`: under the TC
    /// model ([`tc_law`]), from the balls' previous contact times.
    fn law(&self, kind: ContactKind, balls: [usize; 2], t: f64) -> ContactKind {
        let previous = balls.map(|b| self.balls[b].previous);
        tc_law(kind, self.table.tc, self.absolute(t), previous)
    }

    /// Ball `i`'s state after a contact of law `kind` with an immovable body ([`law::fixed`]).
    fn fixed(
        &self,
        kind: ContactKind,
        i: usize,
        wall: Option<(usize, bool)>,
        nu: &[f64; N],
        pre: &BodyState<f64, N, S>,
    ) -> BodyState<f64, N, S> {
        law::fixed(
            &self.kernels,
            &self.species,
            kind,
            self.balls[i].kind as usize,
            wall,
            nu,
            pre,
        )
    }

    /// Counts a change of ball `b`'s velocity (`count_b += 1`) in its record and in its flight
    /// record in the slab (`Resident::count`, which the scans keep with a contact they find):
    /// the two must agree, or a contact found would be taken as stale forever.
    pub(super) fn count_change(&mut self, b: usize) {
        let ball = &mut self.balls[b];
        ball.count += 1;
        *self.motion.count_mut(ball.home) = ball.count;
    }

    pub(super) fn finish(
        &mut self,
        contact: Contact,
        nu: [f64; N],
        balls: [usize; 2],
        pre: [BodyState<f64, N, S>; 2],
        t: f64,
    ) -> Event<N, S> {
        for b in balls {
            self.motion.get_mut(self.balls[b].home).velocity = self.balls[b].state.velocity;
        }
        self.count_change(balls[0]);
        if balls[1] != balls[0] {
            self.count_change(balls[1]);
        }
        self.contacts += 1;
        self.last_contact = t;
        let time = self.absolute(t);
        for b in balls {
            self.balls[b].previous = time;
        }
        self.quiet = 0;
        self.next_check = self.first_check();
        self.next_notice = QUIET_BOX_LENGTHS;
        Event {
            time,
            contact,
            nu,
            position: balls.map(|b| self.flight(b).pos),
            pre,
            post: balls.map(|b| self.balls[b].state.clone()),
        }
    }
}
