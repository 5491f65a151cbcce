//! Prediction: a ball's earliest event among its neighbour cells' balls and obstacles, the
//! table's boundaries, the box walls and its cell's faces, every contact time canonical
//! ([`crate::canonical`]); and the cell crossings, which move no record.

use super::lanes::{cell_image, Flight, Gathered, LANES};
use super::record::key_of;
use super::Simulation;
use crate::canonical::{self, obstacle_offset, obstacle_time, pair_offset, pair_time};
use crate::cells::Listing;
use crate::last_contact::LastContact;
use crate::motion::Motion;
use crate::predict::exit_time;
use crate::queue::What;
use crate::residents::Resident;
use crate::PairKernels;
use collision_core::batch::prefetch;

/// How many predictions ahead [`Simulation::predict_all`] asks for a ball's record.
const RECORDS_AHEAD: usize = 8;

/// Ball `i`'s earliest event offered so far, least `(t, key)` (the key, [`key_of`], made
/// only for a tie).
struct Best<const N: usize> {
    i: usize,
    best: Option<(f64, What<N>)>,
}

impl<const N: usize> Best<N> {
    /// Whether an event at `t` can beat the best (a tie is decided by the keys).
    #[inline]
    fn may_beat(&self, t: f64) -> bool {
        self.best.as_ref().is_none_or(|&(b, _)| t <= b)
    }

    /// The best time so far (infinite if none): an event later than it cannot beat it.
    #[inline]
    fn bound(&self) -> f64 {
        self.best.as_ref().map_or(f64::INFINITY, |&(b, _)| b)
    }

    /// Offers event `what` at `t` (the least `(t, key)` stays, `canonical::order`).
    #[inline]
    fn offer(&mut self, t: f64, what: impl FnOnce() -> What<N>) {
        match self.best {
            Some((b, _)) if t > b => {}
            Some((b, old)) if t == b => {
                // The keys are made only for a tie.
                let what = what();
                if key_of(self.i, &what) < key_of(self.i, &old) {
                    self.best = Some((t, what));
                }
            }
            _ => self.best = Some((t, what())),
        }
    }
}

impl<const N: usize, const S: usize, K: PairKernels<f64, N, S>> Simulation<N, S, K> {
    /// Schedule ball `i`'s earliest event from a full scan of the cells within reach (its
    /// record does not move).
    pub(super) fn predict(&mut self, i: usize) {
        let mut best = Best::<N> { i, best: None };
        let c = self.balls[i].cell();
        self.scan(i, &mut best, &c, None);
        self.fixed_bodies(i, &mut best);
        self.schedule(i, best);
    }

    /// Lays the records out in cell order ([`crate::residents::Residents::compact`]; at the
    /// start they already are) and predicts every ball, cell after cell (so that neighbouring
    /// predictions read the same lists; each ball's record, scattered in that order, asked for
    /// [`RECORDS_AHEAD`] predictions early), then sizes the calendar for them: the start and
    /// every re-basing. The calendar is opened first ([`crate::queue::Calendar::open`]): the
    /// new times are placed once.
    pub(super) fn predict_all(&mut self) {
        self.queue.open(self.balls.as_mut_slice());
        self.motion.compact(self.balls.as_mut_slice());
        let order: Vec<usize> = self.motion.in_cell_order().collect();
        for (k, &i) in order.iter().enumerate() {
            // Balls in cell order are scattered in ball order: each one's record is asked
            // for a few predictions before its own.
            if let Some(&ahead) = order.get(k + RECORDS_AHEAD) {
                prefetch(self.balls.get(ahead));
            }
            self.predict(i);
        }
        self.queue.rebuild(self.balls.as_mut_slice(), 0.0);
    }

    /// Schedule ball `i`'s earliest event after it crossed into its cell along `axis` (moving
    /// `up` or down): its best contact so far, if still valid (a partner's counter unchanged),
    /// against the newly reached layer of cells only: every contact time is canonical, so the
    /// cells it saw before would give the same times again. A stale best contact needs the full
    /// scan (the second best was not kept).
    pub(super) fn predict_after_crossing(&mut self, i: usize, axis: usize, up: bool) {
        let kept = self.balls[i].found;
        if let Some((_, What::Ball { j, count, .. })) = kept {
            if count != self.balls[j as usize].count {
                return self.predict(i);
            }
        }
        let mut best = Best::<N> { i, best: kept };
        let c = self.balls[i].cell();
        self.scan(i, &mut best, &c, Some(self.grid.reached(axis, up)));
        self.schedule(i, best);
    }

    /// Keeps `best` as ball `i`'s best contact and schedules the earlier of it and the next
    /// crossing of its cell's faces.
    fn schedule(&mut self, i: usize, mut best: Best<N>) {
        let found = best.best;
        self.crossing(i, &mut best);
        let crossing = match best.best {
            Some((_, What::Cell { axis, up })) => Some((axis, up)),
            _ => None,
        };
        // The record first: the calendar reads the new key (and never the old one).
        let record = &mut self.balls[i];
        record.found = found;
        record.crossing = crossing;
        match best.best {
            Some((t, _)) => self.queue.set(self.balls.as_mut_slice(), i, t),
            None => self.queue.remove(self.balls.as_mut_slice(), i),
        }
    }

    /// Offers ball `i`'s contacts with the balls and obstacles of the cells within reach of
    /// cell `c`, or of its layer `only` ([`crate::cells::Grid::near`]). Without obstacles the
    /// neighbours' places are first gathered ([`crate::residents::Residents::gather_cells`],
    /// [`super::lanes::Gathered::gather_walk`]): in 2D
    /// (interior cells) they are met in one scalar loop; from 3D on, every cell's, then their
    /// times are computed [`LANES`] at a time ([`super::lanes`]).
    #[inline]
    fn scan(&self, i: usize, best: &mut Best<N>, c: &[usize; N], only: Option<(usize, i64)>) {
        let near = &mut *self.near.borrow_mut();
        let home = self.balls[i].home;
        let m = *self.motion.get(home);
        let w_i = self.motion.wraps(home);
        if self.prefetch && !self.looks_ahead(only) {
            // Start the loads of the cells' lists together, in two rounds (the headers, then
            // the records they point to), instead of one after another as the scan meets them
            // (a scan of a few cells had them requested an event or two ago: `ahead.rs`).
            let grid = &self.grid;
            grid.for_cells(c, only, |nb| self.motion.prefetch_header(nb.cell));
            grid.for_cells(c, only, |nb| self.motion.prefetch_list(nb.cell));
        }
        let obstacles = !self.obstacles.is_empty();
        let cells = self.grid.near(c, only);
        if let (2, Listing::Interior(flat, offsets), false) = (N, cells.listing(), obstacles) {
            // In 2D a neighbourhood holds two or three balls at `phi` 0.2, five at 0.4: the
            // lanes would not pay (callgrind: 6 % more instructions, 9 % more mispredicted
            // branches); the gathered places go to the scalar offer in one loop.
            // SAFETY: an interior cell's neighbours, and room for every ball and four more.
            let count = unsafe {
                self.motion
                    .gather_cells(flat, offsets, near.room(self.motion.len()))
            };
            let base: [f64; N] = w_i.map(f64::from);
            for &at in &near.places[..count] {
                self.offer_ball(i, best, &m, &base, self.motion.at(at));
            }
            return;
        }
        if N > 2 && !obstacles {
            let count = match cells.listing() {
                Listing::Interior(flat, offsets) => {
                    near.unshifted(w_i.map(f64::from));
                    let room = near.room(self.motion.len());
                    // SAFETY: as above.
                    unsafe { self.motion.gather_cells(flat, offsets, room) }
                }
                Listing::Edge(walk) => near.gather_walk(&self.motion, walk, &w_i),
            };
            if count <= LANES {
                // One chunk or less (a layer): the lanes would not pay.
                for p in 0..count {
                    let resident = self.motion.at(near.places[p]);
                    self.offer_ball(i, best, &m, near.base(p), resident);
                }
            } else {
                near.pad(count, home);
                self.offer_gathered(i, best, &m, near, count);
            }
            return;
        }
        for nb in cells {
            let base = cell_image(&nb.shift, &w_i);
            for resident in self.motion.cell(nb.cell) {
                self.offer_ball(i, best, &m, &base, resident);
            }
            if !obstacles {
                continue;
            }
            for &o in &self.fixed_members[nb.cell] {
                let image: [i16; N] = std::array::from_fn(|k| i16::from(nb.shift[k]) + w_i[k]);
                let f = &self.obstacles[o as usize];
                let size = &self.grid.size;
                if let Some(t) = obstacle_time(&m, &f.position, f.radius, &image, size) {
                    let offset = || obstacle_offset(&m, &f.position, &image, size);
                    let sigma = m.radius + f.radius;
                    if !self.balls[i]
                        .last
                        .repeats_obstacle(o as usize, offset, sigma)
                    {
                        best.offer(t, || What::Obstacle { o, image });
                    }
                }
            }
        }
    }

    /// Offers ball `i` (flight `m`) meeting the balls of the first `count` places of `near`:
    /// their times [`LANES`] at a time ([`super::lanes`]), then to [`Self::offer_timed`],
    /// with the lane's time, only those at the least time found (or the best's, if earlier).
    #[inline(always)]
    fn offer_gathered(
        &self,
        i: usize,
        best: &mut Best<N>,
        m: &Motion<N>,
        near: &mut Gathered<N>,
        count: usize,
    ) {
        let bound = near.least(best.bound(), Flight(m, &self.motion, &self.grid.size));
        let offer = |best: &mut Best<N>, p: usize| {
            let resident = self.motion.at(near.places[p]);
            let image = image_of(near.base(p), resident);
            self.offer_timed(i, best, m, &image, resident, near.time(p))
        };
        let mut refused = false;
        for p in 0..count {
            // NaN (no contact) compares false.
            if near.time(p) <= bound {
                refused |= offer(best, p);
            }
        }
        if refused {
            // The least time was a refused repeat ([`crate::last_contact`]): the others as the
            // scalar loop meets them (rare: a pair left touching, its residue pointing inwards).
            for p in 0..count {
                if near.time(p) > bound {
                    offer(best, p);
                }
            }
        }
    }

    /// Offers ball `i` (flight `m`) meeting the ball of record `resident`, whose cell's
    /// image in `i`'s record coordinates is `base` (`s + W_i`); true if the contact was
    /// refused as a repeat at zero flight time ([`crate::last_contact`]).
    #[inline(always)]
    fn offer_ball(
        &self,
        i: usize,
        best: &mut Best<N>,
        m: &Motion<N>,
        base: &[f64; N],
        resident: &Resident<N>,
    ) -> bool {
        if resident.ball as usize == i {
            return false;
        }
        let image = image_of(base, resident);
        // The same bits as from j's side (canonical::pair_time): no ordering here.
        let t = pair_time(m, &resident.motion, &image, &self.grid.size);
        self.offer_timed(i, best, m, &image, resident, t)
    }

    /// [`Self::offer_ball`] with the pair's canonical time `t` already computed ([`pair_time`]
    /// of `m` and the resident at `image`, NaN if they never meet): by the scalar offer, or
    /// by the lanes, whose times are the same bits ([`super::lanes`]; checked here on every
    /// offer in the tests).
    #[inline(always)]
    fn offer_timed(
        &self,
        i: usize,
        best: &mut Best<N>,
        m: &Motion<N>,
        image: &[f64; N],
        resident: &Resident<N>,
        t: f64,
    ) -> bool {
        #[cfg(test)]
        assert_eq!(
            t.to_bits(),
            pair_time(m, &resident.motion, image, &self.grid.size).to_bits(),
            "a lane's time is the canonical time, bit for bit"
        );
        let j = resident.ball as usize;
        // NaN: no contact (never better; a ball's time with itself is NaN).
        if t.is_nan() || !best.may_beat(t) {
            return false;
        }
        if self.balls[i].last.is_ball(j) && self.repeats(i, j, m, image, resident) {
            return true;
        }
        best.offer(t, || What::Ball {
            j: j as u32,
            count: resident.count,
            image: image.map(|k| k as i16),
        });
        false
    }

    /// Whether ball `i`'s contact with ball `j` (record `resident`, at `image` in `i`'s record
    /// coordinates) is a repeat to refuse ([`crate::last_contact`]); out of line, as it is
    /// asked only of the partner of `i`'s last contact.
    #[cold]
    #[inline(never)]
    fn repeats(
        &self,
        i: usize,
        j: usize,
        m: &Motion<N>,
        image: &[f64; N],
        resident: &Resident<N>,
    ) -> bool {
        let last_j = || self.balls[j].last;
        let offset = || {
            let t_ref = m.since.max(resident.motion.since);
            pair_offset(m, &resident.motion, image, &self.grid.size, t_ref)
        };
        let sigma = m.radius + resident.motion.radius;
        LastContact::repeats_pair((i, self.balls[i].last), (j, last_j), offset, sigma)
    }

    /// Offers ball `i`'s contacts with the table's boundaries and the box walls.
    fn fixed_bodies(&self, i: usize, best: &mut Best<N>) {
        let m = self.flight(i);
        let last = self.balls[i].last;
        for (b, boundary) in self.table.boundaries.iter().enumerate() {
            // Right after a contact with b: a convex b cannot be met again, a container not at
            // the same instant (a graze within rounding would repeat forever at t = 0).
            let convex = boundary.shape.convex_from_outside();
            if let Some(tau) = boundary.shape.contact_time(&m.pos, &m.velocity, m.radius) {
                if !last.repeats_boundary(b, convex, tau) {
                    best.offer(m.since + tau, || What::Boundary { b: b as u32 });
                }
            }
        }
        if !self.table.boxed {
            return;
        }
        for k in 0..N {
            if self.grid.periodic[k] {
                continue;
            }
            let wall = exit_time(
                m.pos[k],
                m.velocity[k],
                m.radius,
                self.grid.size[k] - m.radius,
            );
            if let Some((tau, upper)) = wall {
                best.offer(m.since + tau, || What::Wall {
                    axis: k as u8,
                    upper,
                });
            }
        }
    }

    /// Offers ball `i`'s next crossing of its cell's faces.
    fn crossing(&self, i: usize, best: &mut Best<N>) {
        let home = self.balls[i].home;
        let m = self.motion.get(home);
        let w_i = self.motion.wraps(home);
        let c = self.balls[i].cell();
        for k in 0..N {
            if !self.grid.periodic[k] && self.grid.n[k] == 1 {
                continue;
            }
            let w = self.grid.width[k];
            // The cell's faces in record coordinates: c w + W L.
            let lo = c[k] as f64 * w + f64::from(w_i[k]) * self.grid.size[k];
            if let Some((tau, up)) = exit_time(m.pos[k], m.velocity[k], lo, lo + w) {
                let last = c[k] + 1 == self.grid.n[k];
                // `&` and `|` after the axis's test: no branch on the direction.
                let blocked = !self.grid.periodic[k] && ((up & last) | (!up & (c[k] == 0)));
                if !blocked {
                    best.offer(m.since + tau, || What::Cell { axis: k as u8, up });
                }
            }
        }
    }

    /// Ball `i` crosses its cell's face along `axis`: it moves to the next cell (wrapping on a
    /// periodic axis, counted in `W_i`); its record does not move.
    pub(super) fn cross(&mut self, i: usize, axis: usize, up: bool) {
        let c = self.balls[i].cell();
        let home = self.balls[i].home;
        let (c2, wrapped) = self.grid.crossed(&c, axis, up);
        if wrapped {
            self.motion.wraps_mut(home)[axis] += if up { 1 } else { -1 };
        }
        self.balls[i].cell = c2.map(|x| x as u32);
        let (from, to) = (self.grid.flat(&c), self.grid.flat(&c2));
        self.motion.relocate(self.balls.as_mut_slice(), i, from, to);
        self.crossings += 1;
    }

    /// Moves ball `i`'s record to local time `t` (a contact of `i`, or a re-basing): its
    /// centre flown there and folded into the box ([`canonical::fold`]), its orientation's
    /// flight time noted, no wraps since, and the cell of the folded centre.
    pub(super) fn move_record(&mut self, i: usize, t: f64) {
        let (size, periodic) = (self.grid.size, self.periodic());
        let home = self.balls[i].home;
        let m = self.motion.get_mut(home);
        let dt = t - m.since;
        m.pos = canonical::fold(&m.at(t), &size, &periodic);
        m.since = t;
        let pos = m.pos;
        if self.orientation.is_some() {
            self.unturned[i] += dt;
        }
        *self.motion.wraps_mut(home) = [0; N];
        if self.table.boxed {
            let c = self.grid.cell_of(&pos);
            let old = self.balls[i].cell();
            if c != old {
                self.balls[i].cell = c.map(|x| x as u32);
                let (from, to) = (self.grid.flat(&old), self.grid.flat(&c));
                self.motion.relocate(self.balls.as_mut_slice(), i, from, to);
            }
        }
    }
}

/// The image of `resident`'s ball in the scanning ball's record coordinates, `s - W_j + W_i`,
/// from its cell's image `base = s + W_i` (whole numbers, exact in `f64`).
#[inline(always)]
fn image_of<const N: usize>(base: &[f64; N], resident: &Resident<N>) -> [f64; N] {
    std::array::from_fn(|k| base[k] - f64::from(resident.wraps[k]))
}
