//! The reference engine of the tests: all pairs, no cells, a plain binary heap. It shares
//! with the cell engine ([`crate::engine`]) only the canonical definitions
//! ([`crate::canonical`]: the records, the contact times, the order of events, the fold and
//! the re-basing time) and the pair maps, so that its event log equal to the cell engine's,
//! byte for byte, checks everything else of the cell engine: the cell list, the neighbour
//! scan, the wraps and images, the calendar, the invalidations.
//!
//! Ball `i` is predicted against every other ball and obstacle at every image its relative
//! flight can reach within a horizon `h` (the images of each axis from the flight's extent,
//! [`images`]), the box walls and the table's boundaries; a ball with nothing before
//! `now + h` gets a re-prediction there instead (a re-prediction moves no record, so it
//! changes no time). One heap entry per prediction, stale ones (an older prediction of the
//! ball) skipped at their pop.

use crate::canonical::{
    self, image_f64, key, kind, obstacle_image, obstacle_offset, obstacle_time, order, pair_offset,
    pair_time, rebase_at, Key,
};
use crate::cells::Grid;
use crate::engine::{Contact, Event};
use crate::last_contact::LastContact;
use crate::law::{self, tc_law};
use crate::left_table::{leaves, LeftTable};
use crate::motion::Motion;
use crate::normal::unit;
use crate::predict::exit_time;
use crate::table::Table;
use crate::{FixedBall, PairKernels, Setup};
use collision_core::{Ball, BodyState};
use std::cmp::{Ordering, Reverse};
use std::collections::BinaryHeap;

#[cfg(test)]
mod kick_tests;
#[cfg(test)]
mod tests;

/// What a ball's prediction found.
#[derive(Clone, Copy, Debug)]
enum Next<const N: usize> {
    Ball {
        j: usize,
        count: u64,
        image: [i16; N],
    },
    Obstacle {
        o: usize,
        image: [i16; N],
    },
    Wall {
        axis: usize,
        upper: bool,
    },
    Boundary {
        b: usize,
    },
    /// Nothing before the horizon: predict again.
    Again,
}

/// A heap entry: `(time, key, ball, prediction number)`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Entry(f64, Key, usize, u64);

impl Eq for Entry {}

impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Entry {
    fn cmp(&self, other: &Self) -> Ordering {
        order((self.0, self.1), (other.0, other.1))
            .then(self.2.cmp(&other.2))
            .then(self.3.cmp(&other.3))
    }
}

/// The all-pairs engine (module docs).
pub(crate) struct Reference<const N: usize, const S: usize, K> {
    kernels: K,
    species: Vec<Ball<f64>>,
    obstacles: Vec<FixedBall<N>>,
    table: Table<N>,
    size: [f64; N],
    periodic: [bool; N],
    kind: Vec<usize>,
    records: Vec<Motion<N>>,
    state: Vec<BodyState<f64, N, S>>,
    count: Vec<u64>,
    /// Per ball: the absolute time of its last contact (`-inf` before the first).
    previous: Vec<f64>,
    /// Per ball: its last contact, whose repeat at once is refused ([`crate::last_contact`]).
    last: Vec<LastContact>,
    next: Vec<(u64, Next<N>)>,
    heap: BinaryHeap<Reverse<Entry>>,
    predictions: u64,
    now: f64,
    origin: f64,
    origin_low: f64,
    speed2: f64,
    span2: f64,
    rebase_at: f64,
    quiet_rebases: u32,
    /// A ball that left the table through a container ([`crate::left_table`]): no contact
    /// comes after it.
    left: Option<LeftTable>,
}

impl<const N: usize, const S: usize, K: PairKernels<f64, N, S>> Reference<N, S, K> {
    /// The reference run of `setup` (as [`crate::Simulation::new`] takes it).
    pub(crate) fn new(setup: Setup<N, S>, kernels: K) -> Self {
        let Setup {
            size,
            periodic,
            species,
            obstacles,
            bodies,
            table,
            ..
        } = setup;
        // The clock's span as the cell engine's grid rule gives it (its only use of cells).
        let r_ball = bodies
            .iter()
            .map(|b| species[b.species].radius)
            .fold(0.0, f64::max);
        let r_obstacle = obstacles.iter().fold(0.0f64, |m, o| m.max(o.radius));
        let d_max = canonical::d_max(r_ball, r_obstacle);
        let grid = if table.boxed {
            Grid::new(size, periodic, d_max, bodies.len() + obstacles.len()).unwrap()
        } else {
            Grid::single(size)
        };
        let periodic = if table.boxed { periodic } else { [false; N] };
        let n = bodies.len();
        let mut sim = Reference {
            kernels,
            records: bodies
                .iter()
                .map(|b| Motion {
                    pos: b.position,
                    since: 0.0,
                    velocity: b.state.velocity,
                    radius: species[b.species].radius,
                })
                .collect(),
            kind: bodies.iter().map(|b| b.species).collect(),
            state: bodies.into_iter().map(|b| b.state).collect(),
            species,
            obstacles,
            table,
            size,
            periodic,
            count: vec![0; n],
            previous: vec![f64::NEG_INFINITY; n],
            last: vec![LastContact::NONE; n],
            next: vec![(0, Next::Again); n],
            heap: BinaryHeap::new(),
            predictions: 0,
            now: 0.0,
            origin: 0.0,
            origin_low: 0.0,
            speed2: 0.0,
            span2: canonical::clock_span2(&grid.width),
            rebase_at: f64::INFINITY,
            quiet_rebases: 0,
            left: None,
        };
        sim.speed2 = (0..n).map(|i| sim.speed2_of(i)).fold(0.0, f64::max);
        sim.rebase_at = rebase_at(sim.span2, sim.speed2, 0, sim.periodic.contains(&true));
        for i in 0..n {
            sim.predict(i);
        }
        sim
    }

    fn speed2_of(&self, i: usize) -> f64 {
        self.state[i].velocity.iter().map(|x| x * x).sum()
    }

    /// The horizon of a prediction: the fastest relative flight covers at most half the
    /// shortest periodic side in it (no horizon without a periodic axis: every image is 0,
    /// and a prediction is complete).
    fn horizon(&self) -> f64 {
        let side = (0..N)
            .filter(|&k| self.periodic[k])
            .map(|k| self.size[k])
            .fold(f64::INFINITY, f64::min);
        0.25 * side / self.speed2.sqrt()
    }

    /// The next contact (`None` if no ball will ever move again or have a contact).
    pub(crate) fn next_contact(&mut self) -> Option<Event<N, S>> {
        self.next_contact_until(f64::INFINITY)
    }

    /// The next contact at or before the absolute time `until`; `None` if there is none by
    /// then (the clock then at `until` if that is finite), as the cell engine's
    /// [`crate::Simulation::step`].
    pub(crate) fn next_contact_until(&mut self, until: f64) -> Option<Event<N, S>> {
        if self.left.is_some() {
            return None;
        }
        loop {
            let local = (until - self.origin) - self.origin_low;
            while let Some(Reverse(Entry(_, _, i, number))) = self.heap.peek() {
                if *number == self.next[*i].0 {
                    break;
                }
                self.heap.pop();
            }
            let past = self.heap.peek().is_none_or(|Reverse(e)| e.0 > local);
            if past {
                if local.is_finite() {
                    self.now = self.now.max(local);
                }
                return None;
            }
            let Reverse(Entry(time, _, i, _)) = self.heap.pop()?;
            if time > self.rebase_at {
                // Every ball is predicted again from its moved record.
                self.rebase(self.rebase_at, true);
                continue;
            }
            self.now = self.now.max(time);
            match self.next[i].1 {
                Next::Again => self.predict(i),
                Next::Ball { j, count, .. } if count != self.count[j] => self.predict(i),
                Next::Ball { j, image, .. } => return Some(self.pair(i, j, image, time)),
                Next::Wall { axis, upper } => {
                    let mut nu = [0.0; N];
                    nu[axis] = if upper { -1.0 } else { 1.0 };
                    return Some(self.fixed(i, Contact::Wall { i, axis, upper }, nu, time));
                }
                Next::Obstacle { o, image } => {
                    let p = self.records[i].at(time);
                    let b = obstacle_image(&self.obstacles[o].position, &image, &self.size);
                    let nu = unit(std::array::from_fn(|k| p[k] - b[k]));
                    let contact = Contact::Obstacle { i, obstacle: o };
                    return Some(self.fixed(i, contact, nu, time));
                }
                Next::Boundary { b } => {
                    let nu = self.table.boundaries[b]
                        .shape
                        .normal(&self.records[i].at(time));
                    let contact = Contact::Boundary { i, boundary: b };
                    return Some(self.fixed(i, contact, nu, time));
                }
            }
        }
    }

    /// Ball `i`'s earliest event (module docs).
    fn predict(&mut self, i: usize) {
        let m = self.records[i];
        let h = self.now + self.horizon();
        let mut best: Option<(f64, Key, Next<N>)> = None;
        let mut offer = |t: f64, key: Key, next: Next<N>| {
            if best.is_none_or(|(b, k, _)| order((t, key), (b, k)).is_lt()) {
                best = Some((t, key, next));
            }
        };
        for j in (0..self.records.len()).filter(|&j| j != i) {
            let (lo, hi) = (i.min(j), i.max(j));
            let (a, b) = (&self.records[lo], &self.records[hi]);
            let t_ref = a.since.max(b.since);
            let (p, q) = (a.at(t_ref), b.at(t_ref));
            let offset = std::array::from_fn(|k| q[k] - p[k]);
            let dv = std::array::from_fn(|k| b.velocity[k] - a.velocity[k]);
            let sigma = a.radius + b.radius;
            for image in self.images(&offset, &dv, sigma, (self.now - t_ref, h - t_ref)) {
                let t = pair_time(a, b, &image_f64(&image), &self.size);
                let last_hi = || self.last[hi];
                let k = image_f64(&image);
                let offset = || pair_offset(a, b, &k, &self.size, t_ref);
                let repeat =
                    || LastContact::repeats_pair((lo, self.last[lo]), (hi, last_hi), offset, sigma);
                if !t.is_nan() && !repeat() {
                    let own = if i == lo { image } else { image.map(|k| -k) };
                    let next = Next::Ball {
                        j,
                        count: self.count[j],
                        image: own,
                    };
                    offer(t, key(lo, kind::BALL, hi as u32, &image), next);
                }
            }
        }
        for (o, f) in self.obstacles.iter().enumerate() {
            let offset = std::array::from_fn(|k| m.pos[k] - f.position[k]);
            let sigma = m.radius + f.radius;
            let window = (self.now - m.since, h - m.since);
            for minus in self.images(&offset, &m.velocity, sigma, window) {
                // The ball's image k relative to the obstacle is the obstacle's -k.
                let image = minus.map(|k| -k);
                if let Some(t) = obstacle_time(&m, &f.position, f.radius, &image, &self.size) {
                    let offset = || obstacle_offset(&m, &f.position, &image, &self.size);
                    if !self.last[i].repeats_obstacle(o, offset, sigma) {
                        let next = Next::Obstacle { o, image };
                        offer(t, key(i, kind::OBSTACLE, o as u32, &image), next);
                    }
                }
            }
        }
        for (b, boundary) in self.table.boundaries.iter().enumerate() {
            let convex = boundary.shape.convex_from_outside();
            if let Some(tau) = boundary.shape.contact_time(&m.pos, &m.velocity, m.radius) {
                if !self.last[i].repeats_boundary(b, convex, tau) {
                    let key = key(i, kind::BOUNDARY, b as u32, &[0; N]);
                    offer(m.since + tau, key, Next::Boundary { b });
                }
            }
        }
        for axis in (0..N).filter(|&k| self.table.boxed && !self.periodic[k]) {
            let wall = exit_time(
                m.pos[axis],
                m.velocity[axis],
                m.radius,
                self.size[axis] - m.radius,
            );
            if let Some((tau, upper)) = wall {
                let key = key(i, kind::WALL, 2 * axis as u32 + u32::from(upper), &[0; N]);
                offer(m.since + tau, key, Next::Wall { axis, upper });
            }
        }
        let (t, key, next) = match best {
            Some((t, _, _)) if t > h && h.is_finite() => (h, Key::MAX, Next::Again),
            Some(found) => found,
            None if h.is_finite() => (h, Key::MAX, Next::Again),
            None => return,
        };
        self.predictions += 1;
        self.next[i] = (self.predictions, next);
        self.heap.push(Reverse(Entry(t, key, i, self.predictions)));
    }

    /// The images `k` (box lengths on periodic axes, 0 on the others) at which a body `offset`
    /// from another, moving at `dv` relative to it, can come within `sigma` of it in the
    /// times `window` after the offset's: per axis `k L` in `[-offset - sigma - max(dv t),
    /// -offset + sigma - min(dv t)]` over the window, widened by `1e-6` image for rounding.
    fn images(
        &self,
        offset: &[f64; N],
        dv: &[f64; N],
        sigma: f64,
        (from, to): (f64, f64),
    ) -> Vec<[i16; N]> {
        let mut ranges = [(0i16, 0i16); N];
        for k in (0..N).filter(|&k| self.periodic[k]) {
            let (a, b) = (dv[k] * from.max(0.0), dv[k] * to);
            let lo = (-offset[k] - sigma - a.max(b)) / self.size[k];
            let hi = (-offset[k] + sigma - a.min(b)) / self.size[k];
            ranges[k] = ((lo - 1e-6).ceil() as i16, (hi + 1e-6).floor() as i16);
        }
        let mut all = vec![[0i16; N]];
        for (k, &(lo, hi)) in ranges.iter().enumerate() {
            all = all
                .iter()
                .flat_map(|image| {
                    (lo..=hi).map(move |x| {
                        let mut next = *image;
                        next[k] = x;
                        next
                    })
                })
                .collect();
        }
        all
    }

    /// Moves ball `i`'s record to `t`, folded into the box.
    fn move_record(&mut self, i: usize, t: f64) {
        let m = &mut self.records[i];
        m.pos = canonical::fold(&m.at(t), &self.size, &self.periodic);
        m.since = t;
    }

    fn pair(&mut self, i: usize, j: usize, image: [i16; N], t: f64) -> Event<N, S> {
        let (lo, hi, image) = if i < j {
            (i, j, image)
        } else {
            (j, i, image.map(|k| -k))
        };
        let (a, b) = (&self.records[lo], &self.records[hi]);
        let d = pair_offset(a, b, &image_f64(&image), &self.size, t);
        let nu = unit(d);
        self.move_record(lo, t);
        self.move_record(hi, t);
        let pre = [self.state[lo].clone(), self.state[hi].clone()];
        let species = [self.kind[lo], self.kind[hi]];
        let kind = self.law(self.table.ball_law(species[0], species[1]), [lo, hi], t);
        let post = law::pair(&self.kernels, &self.species, kind, species, &nu, &pre);
        self.last[lo] = LastContact::ball(hi);
        self.last[hi] = LastContact::ball(lo);
        self.finish(Contact::Ball { i: lo, j: hi }, nu, [lo, hi], pre, post, t)
    }

    fn fixed(&mut self, i: usize, contact: Contact, nu: [f64; N], t: f64) -> Event<N, S> {
        self.move_record(i, t);
        let pre = [self.state[i].clone(), self.state[i].clone()];
        let kind = match contact {
            Contact::Wall { .. } => self.table.box_contact,
            Contact::Obstacle { obstacle, .. } => self.table.obstacle(obstacle),
            Contact::Boundary { boundary, .. } => self.table.boundaries[boundary].contact,
            Contact::Ball { .. } => unreachable!("a pair is not fixed"),
        };
        let kind = self.law(kind, [i, i], t);
        let wall = match contact {
            Contact::Wall { axis, upper, .. } => Some((axis, upper)),
            _ => None,
        };
        let after = law::fixed(
            &self.kernels,
            &self.species,
            kind,
            self.kind[i],
            wall,
            &nu,
            &pre[0],
        );
        self.last[i] = match contact {
            Contact::Boundary { boundary, .. } => LastContact::boundary(boundary),
            Contact::Obstacle { obstacle, .. } => LastContact::obstacle(obstacle),
            _ => LastContact::NONE,
        };
        let event = self.finish(contact, nu, [i, i], pre, [after.clone(), after], t);
        if let Contact::Boundary { boundary, .. } = contact {
            let shape = &self.table.boundaries[boundary].shape;
            if let Some(outward_speed) = leaves(shape, &event.position[0], &event.post[0].velocity)
            {
                self.left = Some(LeftTable {
                    ball: i,
                    boundary,
                    time: event.time,
                    outward_speed,
                });
            }
        }
        event
    }

    /// The ball that left the table through a container, if one did (the cell engine's
    /// [`crate::Step::LeftTable`]); no contact comes after it.
    pub(crate) fn left(&self) -> Option<LeftTable> {
        self.left
    }

    /// `kind` under the TC model for a contact of `balls` at local time `t`.
    fn law(&self, kind: law::ContactKind, balls: [usize; 2], t: f64) -> law::ContactKind {
        let time = self.origin + (self.origin_low + t);
        tc_law(kind, self.table.tc, time, balls.map(|b| self.previous[b]))
    }

    fn finish(
        &mut self,
        contact: Contact,
        nu: [f64; N],
        balls: [usize; 2],
        pre: [BodyState<f64, N, S>; 2],
        post: [BodyState<f64, N, S>; 2],
        t: f64,
    ) -> Event<N, S> {
        self.state[balls[0]] = post[0].clone();
        self.state[balls[1]] = post[1].clone();
        for b in balls {
            self.records[b].velocity = self.state[b].velocity;
            self.speed2 = self.speed2.max(self.speed2_of(b));
        }
        self.count[balls[0]] += 1;
        if balls[1] != balls[0] {
            self.count[balls[1]] += 1;
        }
        let time = self.origin + (self.origin_low + t);
        for b in balls {
            self.previous[b] = time;
        }
        let event = Event {
            time,
            contact,
            nu,
            position: balls.map(|b| self.records[b].pos),
            pre,
            post,
        };
        self.quiet_rebases = 0;
        self.rebase_at = rebase_at(self.span2, self.speed2, 0, self.periodic.contains(&true));
        if t > self.rebase_at {
            self.rebase(t, false);
        } else {
            self.predict(balls[0]);
            if balls[1] != balls[0] {
                self.predict(balls[1]);
            }
        }
        event
    }

    /// The cell engine's [`crate::Simulation::kick`] at the clock's time: the re-basings due
    /// before it, every record moved there, the velocities changed, the counters moved on, the
    /// last boundaries forgotten, and a re-basing there.
    pub(crate) fn kick(&mut self, dv: &[[f64; N]]) {
        while self.now > self.rebase_at {
            self.rebase(self.rebase_at, true);
        }
        let t = self.now;
        for (i, d) in dv.iter().enumerate() {
            self.move_record(i, t);
            for (u, dk) in self.state[i].velocity.iter_mut().zip(d) {
                *u += dk;
            }
            self.records[i].velocity = self.state[i].velocity;
            self.count[i] += 1;
            self.last[i] = LastContact::NONE;
        }
        self.rebase(t, false);
    }

    /// The canonical re-basing at `t` ([`crate::canonical`]).
    fn rebase(&mut self, t: f64, quiet: bool) {
        for i in 0..self.records.len() {
            self.move_record(i, t);
            self.records[i].since = 0.0;
        }
        (self.origin, self.origin_low) = canonical::moved_origin(self.origin, self.origin_low, t);
        self.now = (self.now - t).max(0.0);
        self.speed2 = (0..self.records.len())
            .map(|i| self.speed2_of(i))
            .fold(0.0, f64::max);
        self.quiet_rebases = if quiet { self.quiet_rebases + 1 } else { 0 };
        let periodic = self.periodic.contains(&true);
        self.rebase_at = rebase_at(self.span2, self.speed2, self.quiet_rebases, periodic);
        self.heap.clear();
        for i in 0..self.records.len() {
            self.predict(i);
        }
    }
}
