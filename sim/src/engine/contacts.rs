//! Resolving a contact: the pair's map (the generated no-slip kernel or the specular one) at
//! the contact normal, the counters, and the re-prediction of the balls involved.

use super::{Contact, Event, Simulation};
use crate::no_contact::QUIET_BOX_LENGTHS;
use crate::normal::unit;
use crate::smooth;
use crate::table::ContactKind;
use crate::PairKernels;
use collision_core::BodyState;

impl<const N: usize, const S: usize, K: PairKernels<f64, N, S>> Simulation<N, S, K> {
    /// After a contact changed the velocities of `balls`: raise the speed bound and re-base
    /// the clock if it is due, before the new predictions.
    pub(super) fn after_contact(&mut self, balls: [usize; 2]) {
        for b in balls {
            self.speed2 = self.speed2.max(self.speed2_of(b));
        }
        if self.clock_due() {
            self.rebase();
        }
        self.predict(balls[0]);
        if balls[1] != balls[0] {
            self.predict(balls[1]);
        }
    }

    pub(super) fn ball_ball(&mut self, i: usize, j: usize, unwrapped: &[i8; N]) -> Event<N, S> {
        self.advance(i);
        self.advance(j);
        // The image the contact was predicted with: s' + w_j - w_i (module docs).
        let shift = std::array::from_fn(|k| {
            unwrapped[k]
                .wrapping_add(self.wraps[j][k])
                .wrapping_sub(self.wraps[i][k])
        });
        let b = self.image(j, &shift);
        let nu = unit(std::array::from_fn(|k| b[k] - self.motion.get(i).pos[k]));
        let pre = [self.state[i].clone(), self.state[j].clone()];
        let [si, sj] = match self.table.ball_contact {
            ContactKind::NoSlip => {
                self.kernels
                    .ball_ball(self.kind[i], self.kind[j], &nu, &pre[0], &pre[1])
            }
            ContactKind::Smooth => {
                let (w1, w2) = (
                    self.species[self.kind[i]].inv_mass,
                    self.species[self.kind[j]].inv_mass,
                );
                smooth::pair(&nu, &w1, &w2, &pre[0], &pre[1])
            }
        };
        self.last[i] = 0;
        self.last[j] = 0;
        self.state[i] = si;
        self.state[j] = sj;
        let event = self.finish(Contact::Ball { i, j }, nu, [i, j], pre);
        self.after_contact([i, j]);
        event
    }

    pub(super) fn ball_wall(&mut self, i: usize, axis: usize, upper: bool) -> Event<N, S> {
        self.advance(i);
        let nu = std::array::from_fn(|k| {
            if k != axis {
                0.0
            } else if upper {
                -1.0
            } else {
                1.0
            }
        });
        let pre = [self.state[i].clone(), self.state[i].clone()];
        self.state[i] = match self.table.box_contact {
            ContactKind::NoSlip => self.kernels.ball_wall(self.kind[i], axis, upper, &pre[0]),
            ContactKind::Smooth => smooth::fixed(&nu, &pre[0]),
        };
        self.last[i] = 0;
        let event = self.finish(Contact::Wall { i, axis, upper }, nu, [i, i], pre);
        self.after_contact([i, i]);
        event
    }

    pub(super) fn ball_obstacle(&mut self, i: usize, o: usize, shift: &[i8; N]) -> Event<N, S> {
        self.advance(i);
        let b = self.obstacle_image(o, shift);
        let nu = unit(std::array::from_fn(|k| self.motion.get(i).pos[k] - b[k]));
        let pre = [self.state[i].clone(), self.state[i].clone()];
        self.state[i] = match self.table.obstacle(o) {
            ContactKind::NoSlip => self.kernels.ball_obstacle(self.kind[i], &nu, &pre[0]),
            ContactKind::Smooth => smooth::fixed(&nu, &pre[0]),
        };
        self.last[i] = 0;
        let event = self.finish(Contact::Obstacle { i, obstacle: o }, nu, [i, i], pre);
        self.after_contact([i, i]);
        event
    }

    /// A contact with boundary `b`: the `fixed` kernel (no-slip) or the specular map
    /// (smooth) at the boundary's local normal (see [`crate::table`]).
    pub(super) fn ball_boundary(&mut self, i: usize, b: usize) -> Event<N, S> {
        self.advance(i);
        let boundary = &self.table.boundaries[b];
        let nu = boundary.shape.normal(&self.motion.get(i).pos);
        let pre = [self.state[i].clone(), self.state[i].clone()];
        self.state[i] = match boundary.contact {
            ContactKind::NoSlip => self.kernels.ball_obstacle(self.kind[i], &nu, &pre[0]),
            ContactKind::Smooth => smooth::fixed(&nu, &pre[0]),
        };
        self.last[i] = b as u32 + 1;
        let event = self.finish(Contact::Boundary { i, boundary: b }, nu, [i, i], pre);
        self.after_contact([i, i]);
        event
    }

    pub(super) fn finish(
        &mut self,
        contact: Contact,
        nu: [f64; N],
        balls: [usize; 2],
        pre: [BodyState<f64, N, S>; 2],
    ) -> Event<N, S> {
        for b in balls {
            self.motion.get_mut(b).velocity = self.state[b].velocity;
        }
        self.count[balls[0]] += 1;
        if balls[1] != balls[0] {
            self.count[balls[1]] += 1;
        }
        self.contacts += 1;
        self.last_contact = self.now;
        self.quiet = 0;
        self.next_check = self.first_check();
        self.next_notice = QUIET_BOX_LENGTHS;
        Event {
            time: self.absolute(self.now),
            contact,
            nu,
            position: balls.map(|b| self.motion.get(b).pos),
            pre,
            post: balls.map(|b| self.state[b].clone()),
        }
    }
}
