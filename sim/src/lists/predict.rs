//! Predicting a ball's next event from its list, its walls and its shell; drawing a shell
//! again; moving a record.

use super::ball::{key_of, Next};
use super::lanes::list_times;
use super::ListSimulation;
use crate::canonical::{self, image_f64, key, kind, order, pair_key, pair_offset, Key};
use crate::last_contact::LastContact;
use crate::motion::Motion;
use crate::predict::exit_time;
use crate::PairKernels;

/// The time at which a flight `m` leaves the ball of radius `delta` around `centre` (in its
/// record coordinates): `t_i + tau` for the root `tau >= 0` of `|e + tau u| = delta`, `e =
/// a_i - centre`, taken from the closest approach as the contact times are
/// ([`crate::predict`]): `tau_0 = -(e . u) / |u|^2`, `h = e + tau_0 u`, `tau = tau_0 +
/// sqrt((delta^2 - |h|^2) / |u|^2)`, at least 0 (the radicand at least 0: a ball outside its
/// shell by rounding leaves at its closest approach, or at once). A record older than the
/// shell puts `a_i` far from the centre; this form rounds only numbers of the size of `|e|`,
/// where the textbook root loses `|e|^2 / delta` to cancellation. `None` at rest. Not a
/// canonical time: leaving a shell moves no record, so no contact time depends on it.
#[inline]
pub(super) fn shell_exit<const N: usize>(
    m: &Motion<N>,
    centre: &[f64; N],
    delta: f64,
) -> Option<f64> {
    let e: [f64; N] = std::array::from_fn(|k| m.pos[k] - centre[k]);
    let (mut a, mut b) = (0.0, 0.0);
    for (u, e) in m.velocity.iter().zip(&e) {
        a += u * u;
        b += e * u;
    }
    if a <= 0.0 {
        return None;
    }
    let tau_0 = -b / a;
    let h2: f64 = (0..N).map(|k| (e[k] + tau_0 * m.velocity[k]).powi(2)).sum();
    let tau = tau_0 + ((delta * delta - h2) / a).max(0.0).sqrt();
    Some(m.since + tau.max(0.0))
}

/// A ball's best contact found: its time, key and what it is.
type Found<const N: usize> = Option<(f64, Key, Next<N>)>;

/// Whether `(t, key)` comes before `found`'s (or `found` is none).
#[inline]
fn beats<const N: usize>(found: &Found<N>, t: f64, key: Key) -> bool {
    found.is_none_or(|(b, bk, _)| order((t, key), (b, bk)).is_lt())
}

impl<const N: usize, const S: usize, K: PairKernels<f64, N, S>> ListSimulation<N, S, K> {
    /// Ball `i`'s earliest event: the contacts with its list's balls at their canonical
    /// times, its box walls, and leaving its shell, in the canonical order of `(time, key)`;
    /// put in the calendar.
    pub(super) fn predict(&mut self, i: usize) {
        let found = self.best_contact(i, None);
        self.schedule(i, found);
    }

    /// Predicts ball `i` after its shell was drawn again: its record has not moved, so its
    /// pairs with the balls it kept in its list have the times they had, and the least of them
    /// is its kept contact, valid while that partner's counter is unchanged (a partner whose
    /// counter changed predicted its pair with `i` itself). Only the balls new to its list are
    /// asked ([`super::shells::Shells::fresh`]); a stale kept contact needs them all (the
    /// second best was not kept).
    pub(super) fn predict_after_draw(&mut self, i: usize) {
        let kept = self.balls[i].found;
        if let Some((_, Next::Ball { j, count, .. })) = kept {
            if count != self.flights[j as usize].count {
                return self.predict(i);
            }
        }
        let id = self.balls[i].id as usize;
        let kept = kept.map(|(t, next)| (t, key_of(id, &next), next));
        let found = self.best_contact(i, Some(kept));
        self.schedule(i, found);
    }

    /// Keeps `found` as ball `i`'s best contact and schedules the earliest of it, its walls and
    /// leaving its shell.
    fn schedule(&mut self, i: usize, found: Found<N>) {
        let m = self.flights[i].motion;
        let id = self.balls[i].id as usize;
        let mut best = found;
        let w_i = self.flights[i].wraps;
        let c = self.shells.centre(i);
        let centre = std::array::from_fn(|k| c[k] + f64::from(w_i[k]) * self.size[k]);
        if let Some(t) = shell_exit(&m, &centre, self.delta) {
            let key = key(id, kind::CELL, 0, &[0; N]);
            if beats(&best, t, key) {
                best = Some((t, key, Next::Shell));
            }
        }
        for axis in (0..N).filter(|&k| !self.periodic[k]) {
            let wall = exit_time(
                m.pos[axis],
                m.velocity[axis],
                m.radius,
                self.size[axis] - m.radius,
            );
            if let Some((tau, upper)) = wall {
                let t = m.since + tau;
                let key = key(id, kind::WALL, 2 * axis as u32 + u32::from(upper), &[0; N]);
                if beats(&best, t, key) {
                    let axis = axis as u8;
                    best = Some((t, key, Next::Wall { axis, upper }));
                }
            }
        }
        let own = &mut self.balls[i];
        own.found = found.map(|(t, _, next)| (t, next));
        own.next = best.map(|(_, _, next)| next);
        match best {
            Some((t, _, _)) => self.queue.set(self.balls.as_mut_slice(), i, t),
            None => self.queue.remove(self.balls.as_mut_slice(), i),
        }
    }

    /// Lays the balls out in the order of their shells' cells ([`ListSimulation::reorder`])
    /// and predicts every ball, in a new calendar sized for the new times after (the start and
    /// every re-basing).
    pub(super) fn predict_all(&mut self) {
        self.reorder();
        // The old calendar's places name old slots: every ball starts with none.
        self.queue = crate::queue::Calendar::new();
        for own in &mut self.balls {
            own.slot = crate::queue::Slot::EMPTY;
        }
        self.queue.open(self.balls.as_mut_slice());
        for i in 0..self.len() {
            self.predict(i);
        }
        self.queue.rebuild(self.balls.as_mut_slice(), 0.0);
    }

    /// Ball `i`'s best contact with the balls of its list (`kept = None`), or with the balls
    /// new to it and the `kept` contact. The pair times are computed first
    /// ([`list_times`]); only the partners at the least time are looked at further (their
    /// keys, the rule against repeats), unless every one of them is refused: then all are.
    fn best_contact(&mut self, i: usize, kept: Option<Found<N>>) -> Found<N> {
        let mut times = std::mem::take(&mut self.times);
        let list = match kept {
            None => self.shells.list(i),
            Some(_) => self.shells.fresh(),
        };
        let least = list_times(self.avx2, i, list, &self.flights, &self.size, &mut times);
        let mut found = self.offer(i, list, &times, least);
        if found.is_none() && least.is_finite() {
            found = self.offer(i, list, &times, f64::INFINITY);
        }
        self.times = times;
        match (found, kept.flatten()) {
            (Some((t, key, _)), kept @ Some(_)) if !beats(&kept, t, key) => kept,
            (None, kept) => kept,
            (found, _) => found,
        }
    }

    /// The best of the partners of `list` whose `times` are at most `at_most` (NaN never
    /// is), as the canonical order and the rule against repeats have it; `None` if none is.
    fn offer(
        &self,
        i: usize,
        list: &[super::shells::Neighbour<N>],
        times: &[f64],
        at_most: f64,
    ) -> Found<N> {
        let mut best = None;
        for (p, &t) in times.iter().enumerate() {
            // NaN (no contact) is never at most anything; in general one partner is.
            if t <= at_most {
                best = self.consider(i, &list[p], t, best);
            }
        }
        best
    }

    /// Ball `i`'s contact at `t` with the partner `near` of its list, if it beats `best`
    /// (the canonical order) and is no repeat ([`LastContact::repeats_pair`]); else `best`.
    #[inline(never)]
    fn consider(
        &self,
        i: usize,
        near: &super::shells::Neighbour<N>,
        t: f64,
        best: Found<N>,
    ) -> Found<N> {
        let me = &self.flights[i];
        let (m, w_i) = (&me.motion, &me.wraps);
        let id_i = self.balls[i].id as usize;
        let j = near.j as usize;
        let other = &self.flights[j];
        let image: [i16; N] =
            std::array::from_fn(|k| i16::from(near.image[k]) - other.wraps[k] + w_i[k]);
        let id_j = other.ball as usize;
        let key = pair_key(id_i, id_j, &image);
        if !beats(&best, t, key) {
            return best;
        }
        let k = image_f64(&image);
        let sigma = m.radius + other.motion.radius;
        let t_ref = m.since.max(other.motion.since);
        let offset = || pair_offset(m, &other.motion, &k, &self.size, t_ref);
        let last_j = || self.balls[j].last;
        let last_i = self.balls[i].last;
        if LastContact::repeats_pair((id_i, last_i), (id_j, last_j), offset, sigma) {
            return best;
        }
        let next = Next::Ball {
            j: j as u32,
            id: other.ball,
            count: other.count,
            image,
        };
        Some((t, key, next))
    }

    /// Draws ball `i`'s shell again around its position now, `c_i` that position folded into
    /// the box and `W_i` the box lengths folded off ([`super::shells::Shells::draw`]).
    pub(super) fn draw(&mut self, i: usize) {
        let x = self.flights[i].motion.at(self.now);
        let mut wraps = [0i16; N];
        let centre = std::array::from_fn(|k| {
            if self.periodic[k] {
                let q = (x[k] / self.size[k]).floor();
                wraps[k] = q as i16;
                x[k] - q * self.size[k]
            } else {
                x[k]
            }
        });
        self.flights[i].wraps = wraps;
        self.shells.draw(i, centre);
    }

    /// Moves ball `i`'s record to local time `t` (a contact of `i`, or a re-basing): its
    /// centre flown there and folded into the box ([`canonical::fold`]), and `W_i` found
    /// again, the whole box lengths between the record's centre and its shell's.
    pub(super) fn move_record(&mut self, i: usize, t: f64) {
        let flight = &mut self.flights[i];
        let m = &mut flight.motion;
        m.pos = canonical::fold(&m.at(t), &self.size, &self.periodic);
        m.since = t;
        let c = self.shells.centre(i);
        // Both in `[0, L]` and within `delta` of each other up to a wrap: `-1`, `0` or `1`.
        flight.wraps = std::array::from_fn(|k| {
            let (d, half) = (m.pos[k] - c[k], 0.5 * self.size[k]);
            if !self.periodic[k] || d.abs() <= half {
                0
            } else if d > 0.0 {
                1
            } else {
                -1
            }
        });
    }
}
