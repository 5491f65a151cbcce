//! The event loop.
//!
//! State: per ball a centre `a_i` valid at its own time `t_i` (balls are advanced lazily, only
//! when they take part in an event), its velocity state, species, cell, a collision counter
//! `count_i` that increases whenever its velocity changes, and wrap counters `w_i` (per axis,
//! modulo 256) that count its crossings of the periodic faces, so that its unwrapped centre is
//! `a_i + w_i L`.
//!
//! Queue invariant: every moving ball has exactly one pending event in the queue (a
//! `Calendar` (`queue.rs`), keyed by ball: setting a ball's event replaces the one it had,
//! so no stale entry is ever kept), its earliest predicted event as of its last prediction,
//! and nothing later than its true next event. Events are taken in the order of their time,
//! ties by ball index (the order among exactly simultaneous events is otherwise arbitrary);
//! the ball whose event is taken is always re-predicted before the next one:
//! - a ball-ball event whose partner's counter changed is no longer an event: the owner is
//!   re-predicted from now (its own trajectory is unchanged, so no event of it was missed);
//! - a cell crossing moves the ball to the next cell (wrapping on a periodic axis) and
//!   re-predicts it against its new neighbours;
//! - a contact advances the balls to now, applies the pair's no-slip map, bumps the counters
//!   and re-predicts the balls involved.
//!
//! **Layout.** What a prediction reads of every neighbour (centre, its time, velocity,
//! radius: a `Motion`) is stored by cell (`Residents`, `residents.rs`): a cell's records are one
//! list, in the order a list of ball indices would hold them, and a byte per cell says
//! whether it is empty, so a scan of the `3^n` cells within reach (`Grid::for_neighbours`, no
//! division) reads one list per occupied cell. The velocity there is a copy of the ball's
//! state's, written at each contact. Contact times in the scan are taken without branches
//! (`predict::contact_time_or_nan`, the same bits as `contact_time`). The calendar's lists,
//! the cells' lists and the scan reuse their memory: nothing is allocated per event once they
//! have grown. When the cell list outgrows the caches (`PREFETCH_FROM` cells, 2^16), a
//! prediction first prefetches the neighbour cells' list headers, then their first records,
//! so that the cache misses of the `3^n` cells overlap instead of following one another; the
//! scan itself is the same. The neighbourhood is scanned in full at every prediction (a
//! crossing too), so every contact time is computed from the same state as before these
//! changes and the event log is the same, bit for bit.
//!
//! **Image rule.** A ball-ball entry stores its partner's image in unwrapped coordinates,
//! `s - w_j + w_i` for the cell shift `s` it was predicted with: the partner may cross a
//! periodic face (a cell crossing, which leaves its counter and so the entry valid) before
//! the contact, and then `s` alone would name an image one box length away. At the contact
//! the image is `s' + w_j - w_i`: exactly the image the contact time was solved for, with no
//! minimum-image guess (which could be ambiguous on a periodic side shorter than two contact
//! distances). The owner itself never wraps while its entry is pending (its crossings are its
//! own entries), and obstacles never move, so obstacle entries keep the cell shift.
//!
//! **Clock.** Times are kept on a local clock `t` whose origin (an absolute time, kept as a
//! compensated sum) is moved forward ("re-based") whenever `v_max t > 16 w_min`, `v_max` an
//! upper bound of the speeds and `w_min` the narrowest cell: all centres are advanced to now
//! (orientations only note the flight time, to be applied at their next update), the queue's
//! times are shifted by `-t` (the calendar is rebuilt, its bucket width chosen again for the
//! current event rate) and the clock restarts at 0.
//! Rounding a local time then moves any ball by at most 16 ulps of a cell width, whatever the
//! absolute time, so contacts stay at contact distance in long runs and after long quiet
//! stretches (a gas started almost at rest); the check runs at each popped entry and after each
//! contact (before the new predictions), and a rebase costs `O(balls + queue)` once per 16 cell
//! widths travelled by the fastest ball, while every ball crosses a cell or meets another each
//! cell width or so: amortised over many events (per 10^5 contacts of the shipped gases 26
//! rebases in gas2d, 22 in gas3d, 242 in gas4d).
//!
//! **Boundaries.** Besides the box walls and the obstacles, every ball is predicted against
//! every boundary of the table ([`crate::table`]: walls, containers, polygon edges and
//! vertices; few, and fixed), and a contact with one applies the `fixed` kernel (or the
//! specular map) at its local normal. After a contact with boundary `b` (kept per ball until
//! its next contact), `b` is not predicted again if it is convex seen from the ball (a flat
//! wall, an edge, a sphere or point from outside: the straight flight moves away from it and
//! cannot return), and a container not at the same instant: so a corner (two walls touched at
//! once) takes its two contacts at one time and moves on, and no graze within rounding repeats
//! at `t = 0` forever (docs/tables.md, "Corners and grazing contacts").
//!
//! **No box.** A table without a box ([`crate::Table::boxed`] false) has one cell: every pair
//! of balls is a neighbour, there are no box walls and no cell crossings, and `Setup::size` is
//! the table's length scale `L` (for the clock's `w_min` and the quiet notices). Each ball is
//! then predicted against every ball and boundary, so an empty queue means no contact can
//! come: [`NoContact::Escaped`] (or [`NoContact::AtRest`]).
//!
//! **No further contact.** [`Simulation::step`] returns [`Step::Never`] when it can tell that
//! no contact will ever happen again ([`NoContact`]): checked at the first step and then after
//! `max(1024, 2 balls)`, twice, four times that many events without a contact. At those checks
//! it also returns [`Step::Quiet`], a notice, once the balls have travelled 1000, 2000, 4000
//! ... box lengths without a contact; the caller decides whether to go on.

mod contacts;
mod events;
mod quiet;

pub use events::{Contact, Event, SetupError, Step};

use super::cells::Grid;
use super::motion::Motion;
use super::no_contact::{NoContact, QUIET_BOX_LENGTHS};
use super::observe::Observables;
use super::orientation::{exp_skew, identity, mul, Matrix};
use super::predict::{contact_time, contact_time_or_nan, exit_time};
use super::queue::{Calendar, What};
use super::residents::Residents;
use super::table::{ContactKind, Geometry, Table};
use super::{Body, FixedBall, PairKernels, Setup};
use collision_core::{Ball, BodyState};

/// The number of cells from which a prediction prefetches its neighbour cells' lists: a
/// list header and a record per occupied cell, about 2 MiB of cell list from here, more than
/// a core's L2 cache. Below it the lists are cached and the extra passes cost more than they
/// save (docs/benchmarks.md, "The event loop").
const PREFETCH_FROM: usize = 1 << 16;

/// The local clock is re-based when the fastest ball could have moved this many widths of
/// the narrowest cell on it (module docs).
const CLOCK_CELLS: f64 = 16.0;

/// An event-driven simulation; see the module docs.
pub struct Simulation<const N: usize, const S: usize, K> {
    kernels: K,
    species: Vec<Ball<f64>>,
    obstacles: Vec<FixedBall<N>>,
    table: Table<N>,
    /// Per ball: `b + 1` if its last contact was with boundary `b`, else 0. A boundary convex
    /// seen from the ball cannot be touched again before another contact; a container not
    /// at the same instant (module docs, "Boundaries").
    last: Vec<u32>,
    grid: Grid<N>,
    kind: Vec<usize>,
    /// Per ball: centre, its time, velocity and radius (the neighbour scan's reads), stored
    /// by cell (the cell lists).
    motion: Residents<N>,
    state: Vec<BodyState<f64, N, S>>,
    count: Vec<u32>,
    wraps: Vec<[i8; N]>,
    cell: Vec<[usize; N]>,
    fixed_members: Vec<Vec<u32>>,
    /// `A_i` at the ball's time minus `unturned_i`: the flight time (at constant `U_i`) not
    /// applied to it yet, kept by rebases so that they need no matrix exponential.
    orientation: Option<Vec<Matrix<N>>>,
    unturned: Vec<f64>,
    /// Whether a prediction prefetches its neighbour cells' lists: a cell list larger than
    /// the caches ([`PREFETCH_FROM`]).
    prefetch: bool,
    /// Per ball: the time of its pending event (`Calendar`) and what it is (`next`).
    queue: Calendar,
    next: Vec<What<N>>,
    /// The local clock; the absolute time is `origin + origin_low + now`.
    now: f64,
    origin: f64,
    origin_low: f64,
    /// An upper bound of `|u_i|^2` (exact at the last rebase).
    speed2: f64,
    /// `(CLOCK_CELLS w_min)^2`.
    span2: f64,
    /// The local time of the last contact (or of the start).
    last_contact: f64,
    /// Events (crossings, re-predictions) since the last contact, and when to check next
    /// whether contacts can still happen.
    quiet: u64,
    next_check: u64,
    /// The travel (box lengths) at which the next [`Step::Quiet`] notice is due.
    next_notice: f64,
    contacts: u64,
    crossings: u64,
    rebases: u64,
}

impl<const N: usize, const S: usize, K: PairKernels<f64, N, S>> Simulation<N, S, K> {
    /// Checks that every ball is in the box and its species exists; overlaps are the
    /// caller's business (scene validation and placement refuse them).
    pub fn new(setup: Setup<N, S>, kernels: K) -> Result<Self, SetupError> {
        let Setup {
            size,
            periodic,
            species,
            obstacles,
            bodies,
            orientation,
            table,
        } = setup;
        if let Some(k) = (0..N).find(|&k| !(size[k] > 0.0 && size[k].is_finite())) {
            return Err(SetupError::BoxSize {
                axis: k,
                size: size[k],
            });
        }
        let mut r_ball = 0.0f64;
        for (i, b) in bodies.iter().enumerate() {
            let s = species.get(b.species).ok_or(SetupError::Species {
                ball: i,
                species: b.species,
            })?;
            r_ball = r_ball.max(s.radius);
        }
        let r_obstacle = obstacles.iter().fold(0.0f64, |m, o| m.max(o.radius));
        let d_max = (2.0 * r_ball)
            .max(r_ball + r_obstacle)
            .max(f64::MIN_POSITIVE);
        let grid = if table.boxed {
            Grid::new(size, periodic, d_max, bodies.len() + obstacles.len())?
        } else {
            Grid::single(size)
        };
        let mut motion = Residents::new(grid.cells());
        let mut fixed_members = vec![Vec::new(); grid.cells()];
        let mut cell = Vec::with_capacity(bodies.len());
        for (i, b) in bodies.iter().enumerate() {
            let outside = (0..N).find(|&k| !(0.0..=size[k]).contains(&b.position[k]));
            if let (Some(k), true) = (outside, table.boxed) {
                return Err(SetupError::Outside { ball: i, axis: k });
            }
            let c = grid.cell_of(&b.position);
            motion.push(
                grid.flat(&c),
                Motion {
                    pos: b.position,
                    since: 0.0,
                    velocity: b.state.velocity,
                    radius: species[b.species].radius,
                },
            );
            cell.push(c);
        }
        for (o, f) in obstacles.iter().enumerate() {
            let c = grid.cell_of(&f.position);
            fixed_members[grid.flat(&c)].push(o as u32);
        }
        let n = bodies.len();
        let prefetch = grid.cells() >= PREFETCH_FROM;
        let w_min = grid.width.iter().copied().fold(f64::INFINITY, f64::min);
        let mut sim = Simulation {
            kernels,
            species,
            obstacles,
            table,
            last: vec![0; n],
            grid,
            kind: bodies.iter().map(|b| b.species).collect(),
            motion,
            state: bodies.into_iter().map(|b: Body<N, S>| b.state).collect(),
            count: vec![0; n],
            wraps: vec![[0; N]; n],
            cell,
            fixed_members,
            orientation: orientation.then(|| vec![identity::<N>(); n]),
            unturned: vec![0.0; if orientation { n } else { 0 }],
            prefetch,
            queue: Calendar::new(n),
            next: vec![
                What::Wall {
                    axis: 0,
                    upper: false
                };
                n
            ],
            now: 0.0,
            origin: 0.0,
            origin_low: 0.0,
            speed2: 0.0,
            span2: (CLOCK_CELLS * w_min).powi(2),
            last_contact: 0.0,
            quiet: 0,
            next_check: 0,
            next_notice: QUIET_BOX_LENGTHS,
            contacts: 0,
            crossings: 0,
            rebases: 0,
        };
        sim.speed2 = (0..n).map(|i| sim.speed2_of(i)).fold(0.0, f64::max);
        for i in 0..n {
            sim.predict(i);
        }
        sim.queue.rebuild(0.0);
        Ok(sim)
    }

    /// Sets whether predictions prefetch (a test of the prefetching scan on a small setup).
    #[cfg(test)]
    pub(crate) fn set_prefetch(&mut self, on: bool) {
        self.prefetch = on;
    }

    /// The absolute time now.
    pub fn now(&self) -> f64 {
        self.absolute(self.now)
    }

    fn absolute(&self, local: f64) -> f64 {
        self.origin + (self.origin_low + local)
    }

    fn local(&self, absolute: f64) -> f64 {
        (absolute - self.origin) - self.origin_low
    }

    /// The number of cells of the cell list (at most 4 per ball and obstacle).
    pub fn cells(&self) -> usize {
        self.grid.cells()
    }

    /// Times the local clock was re-based (module docs).
    pub fn rebases(&self) -> u64 {
        self.rebases
    }

    /// Contacts processed so far.
    pub fn contacts(&self) -> u64 {
        self.contacts
    }

    /// Cell crossings processed so far.
    pub fn crossings(&self) -> u64 {
        self.crossings
    }

    /// The number of balls.
    pub fn len(&self) -> usize {
        self.motion.len()
    }

    /// Whether there are no balls.
    pub fn is_empty(&self) -> bool {
        self.motion.len() == 0
    }

    /// The box sides `L_k` (without a box: the table's length scale on every axis).
    pub fn box_size(&self) -> [f64; N] {
        self.grid.size
    }

    /// Which axes of the box are periodic (none without a box).
    pub fn periodic(&self) -> [bool; N] {
        if self.table.boxed {
            self.grid.periodic
        } else {
            [false; N]
        }
    }

    /// The fixed ball obstacles.
    pub fn obstacles(&self) -> &[FixedBall<N>] {
        &self.obstacles
    }

    /// The table: its boundaries and contact kinds.
    pub fn table(&self) -> &Table<N> {
        &self.table
    }

    /// The local geometry of `contact` (what the derivative of the flight needs): a box wall
    /// or a wall is [`Geometry::Flat`], an obstacle [`Geometry::Outside`] of its radius, two
    /// balls [`Geometry::Pair`], a boundary that of its shape ([`crate::table::Shape::geometry`]).
    pub fn geometry(&self, contact: &Contact) -> Geometry {
        match *contact {
            Contact::Ball { .. } => Geometry::Pair,
            Contact::Wall { .. } => Geometry::Flat,
            Contact::Obstacle { obstacle, .. } => Geometry::Outside {
                radius: self.obstacles[obstacle].radius,
            },
            Contact::Boundary { boundary, .. } => self.table.boundaries[boundary].shape.geometry(),
        }
    }

    /// The contact kind of `contact` as the table sets it (the box's, an obstacle's, a
    /// boundary's, or the ball-ball pairs').
    pub fn contact_kind(&self, contact: &Contact) -> ContactKind {
        match *contact {
            Contact::Ball { .. } => self.table.ball_contact,
            Contact::Wall { .. } => self.table.box_contact,
            Contact::Obstacle { obstacle, .. } => self.table.obstacle(obstacle),
            Contact::Boundary { boundary, .. } => self.table.boundaries[boundary].contact,
        }
    }

    /// Ball `i`'s species index.
    pub fn species_of(&self, i: usize) -> usize {
        self.kind[i]
    }

    /// Ball `i`'s state `(U, u)` (constant between contacts).
    pub fn state(&self, i: usize) -> &BodyState<f64, N, S> {
        &self.state[i]
    }

    /// Ball `i`'s centre now (inside the box; wrapped on periodic axes up to the crossing
    /// in progress).
    pub fn position(&self, i: usize) -> [f64; N] {
        self.motion.get(i).at(self.now)
    }

    /// Ball `i`'s orientation `A_i` now, if the setup tracks orientations.
    pub fn orientation(&self, i: usize) -> Option<[[f64; N]; N]> {
        let a = self.orientation.as_ref()?;
        let dt = self.unturned[i] + (self.now - self.motion.get(i).since);
        let r = exp_skew::<N>(&self.state[i].spin, dt);
        Some(mul(&r, &a[i]))
    }

    /// Energy, momentum and angular momentum now.
    pub fn observables(&self) -> Observables<N, S> {
        let positions: Vec<[f64; N]> = (0..self.len()).map(|i| self.position(i)).collect();
        Observables::of(
            (0..self.len()).map(|i| (&self.species[self.kind[i]], &positions[i], &self.state[i])),
        )
    }

    /// Move ball `i` (and its orientation) to now.
    fn advance(&mut self, i: usize) {
        self.fly(i);
        if let Some(a) = &mut self.orientation {
            let dt = std::mem::take(&mut self.unturned[i]);
            if dt != 0.0 {
                a[i] = mul(&exp_skew::<N>(&self.state[i].spin, dt), &a[i]);
            }
        }
    }

    /// Move ball `i`'s centre to now; the orientation's flight time is only noted.
    fn fly(&mut self, i: usize) {
        let now = self.now;
        let m = self.motion.get_mut(i);
        let dt = now - m.since;
        if dt == 0.0 {
            return;
        }
        for k in 0..N {
            m.pos[k] += m.velocity[k] * dt;
        }
        m.since = now;
        if self.orientation.is_some() {
            self.unturned[i] += dt;
        }
    }

    /// Ball `j`'s centre now, shifted by `shift` box lengths.
    fn image(&self, j: usize, shift: &[i8; N]) -> [f64; N] {
        let p = self.position(j);
        std::array::from_fn(|k| p[k] + f64::from(shift[k]) * self.grid.size[k])
    }

    fn obstacle_image(&self, o: usize, shift: &[i8; N]) -> [f64; N] {
        let p = self.obstacles[o].position;
        std::array::from_fn(|k| p[k] + f64::from(shift[k]) * self.grid.size[k])
    }

    /// Schedule ball `i`'s earliest event (ball `i` is advanced to now first).
    fn predict(&mut self, i: usize) {
        self.advance(i);
        let Motion {
            pos: a,
            velocity: v,
            radius: r,
            ..
        } = *self.motion.get(i);
        let now = self.now;
        let size = self.grid.size;
        // The earliest event offered so far (the first of equal times), if any.
        let mut best: Option<(f64, What<N>)> = None;
        let better = |best: &Option<(f64, What<N>)>, t: f64| best.is_none_or(|(b, _)| t < b);
        let offer = |best: &mut Option<(f64, What<N>)>, t: f64, what: What<N>| {
            if better(best, t) {
                *best = Some((t, what));
            }
        };
        let c = self.cell[i];
        if self.prefetch {
            // Start the loads of the neighbour cells' lists together, in two rounds (the
            // headers, then the records they point to), instead of one after another as the
            // scan meets them.
            self.grid
                .for_neighbours(&c, |nb| self.motion.prefetch_header(nb.cell));
            self.grid
                .for_neighbours(&c, |nb| self.motion.prefetch_list(nb.cell));
        }
        let obstacles = !self.obstacles.is_empty();
        self.grid.for_neighbours(&c, |nb| {
            for resident in self.motion.cell(nb.cell) {
                let j = resident.ball as usize;
                if j == i {
                    continue;
                }
                let m = &resident.motion;
                let p = m.at(now);
                let d: [f64; N] =
                    std::array::from_fn(|k| (p[k] + f64::from(nb.shift[k]) * size[k]) - a[k]);
                let dv: [f64; N] = std::array::from_fn(|k| m.velocity[k] - v[k]);
                let t = contact_time_or_nan(&d, &dv, r + m.radius);
                // NaN: no contact (never better).
                if !t.is_nan() && better(&best, t) {
                    let count = self.count[j];
                    // The image in unwrapped coordinates: s - w_j + w_i (module docs).
                    let shift = std::array::from_fn(|k| {
                        nb.shift[k]
                            .wrapping_sub(self.wraps[j][k])
                            .wrapping_add(self.wraps[i][k])
                    });
                    offer(
                        &mut best,
                        t,
                        What::Ball {
                            j: j as u32,
                            count,
                            shift,
                        },
                    );
                }
            }
            if !obstacles {
                return;
            }
            for &o in &self.fixed_members[nb.cell] {
                let b = self.obstacle_image(o as usize, &nb.shift);
                let d: [f64; N] = std::array::from_fn(|k| b[k] - a[k]);
                let dv: [f64; N] = std::array::from_fn(|k| -v[k]);
                if let Some(t) = contact_time(&d, &dv, r + self.obstacles[o as usize].radius) {
                    offer(&mut best, t, What::Obstacle { o, shift: nb.shift });
                }
            }
        });
        for (b, boundary) in self.table.boundaries.iter().enumerate() {
            // Right after a contact with b: a convex b cannot be met again, a container not at
            // the same instant (a graze within rounding would repeat forever at t = 0).
            let repeat = self.last[i] == b as u32 + 1;
            if repeat && boundary.shape.convex_from_outside() {
                continue;
            }
            if let Some(t) = boundary.shape.contact_time(&a, &v, r) {
                if !(repeat && t == 0.0) {
                    offer(&mut best, t, What::Boundary { b: b as u32 });
                }
            }
        }
        for k in 0..N {
            let w = self.grid.width[k];
            if !self.grid.periodic[k] {
                let wall = if self.table.boxed {
                    exit_time(a[k], v[k], r, self.grid.size[k] - r)
                } else {
                    None
                };
                if let Some((t, upper)) = wall {
                    offer(
                        &mut best,
                        t,
                        What::Wall {
                            axis: k as u8,
                            upper,
                        },
                    );
                }
                if self.grid.n[k] == 1 {
                    continue;
                }
            }
            let lo = c[k] as f64 * w;
            if let Some((t, up)) = exit_time(a[k], v[k], lo, lo + w) {
                let last = c[k] + 1 == self.grid.n[k];
                let blocked = !self.grid.periodic[k] && ((up && last) || (!up && c[k] == 0));
                if !blocked {
                    offer(&mut best, t, What::Cell { axis: k as u8, up });
                }
            }
        }
        match best {
            Some((t, what)) => {
                self.queue.set(i, self.now + t);
                self.next[i] = what;
            }
            None => self.queue.remove(i),
        }
    }

    fn cross(&mut self, i: usize, axis: usize, up: bool) {
        self.advance(i);
        let c = self.cell[i];
        let n = self.grid.n[axis];
        let size = self.grid.size[axis];
        let mut c2 = c;
        if up {
            c2[axis] = (c[axis] + 1) % n;
            if c2[axis] == 0 {
                self.motion.get_mut(i).pos[axis] -= size;
                self.wraps[i][axis] = self.wraps[i][axis].wrapping_add(1);
            }
        } else {
            c2[axis] = (c[axis] + n - 1) % n;
            if c[axis] == 0 {
                self.motion.get_mut(i).pos[axis] += size;
                self.wraps[i][axis] = self.wraps[i][axis].wrapping_sub(1);
            }
        }
        self.cell[i] = c2;
        self.motion.relocate(i, self.grid.flat(&c2));
        self.crossings += 1;
    }

    /// Process queue entries until the next contact at or before the absolute time `until`,
    /// and return it; [`Step::Until`] (with the clock at `until`) if there is none by then,
    /// [`Step::Never`] if there will be none at all.
    pub fn step(&mut self, until: f64) -> Step<N, S> {
        loop {
            let until = self.local(until);
            if self.quiet >= self.next_check {
                self.next_check = self.next_check.saturating_mul(2).max(self.first_check());
                if let Some(why) = self.no_contact() {
                    return self.never(why, until);
                }
                let box_lengths = self.quiet_travel();
                if box_lengths >= self.next_notice {
                    self.next_notice = 2.0 * box_lengths;
                    return Step::Quiet { box_lengths };
                }
            }
            let Some((time, i)) = self.queue.peek() else {
                // Every moving ball has an entry in a box (a crossing or a wall at least);
                // without one, an empty queue means no ball has a contact ahead.
                let moving = (0..self.len()).any(|i| self.speed2_of(i) > 0.0);
                let why = if moving && !self.table.boxed {
                    NoContact::Escaped
                } else {
                    NoContact::AtRest
                };
                return self.never(why, until);
            };
            if time > until {
                if until.is_finite() {
                    self.now = self.now.max(until);
                }
                return Step::Until;
            }
            // Ball i's event stays in the queue until every branch below re-predicts i.
            let what = self.next[i];
            self.now = self.now.max(time);
            if self.clock_due() {
                self.rebase();
            }
            match what {
                What::Cell { axis, up } => {
                    self.cross(i, axis as usize, up);
                    self.predict(i);
                    self.quiet += 1;
                }
                What::Ball { j, count, .. } if count != self.count[j as usize] => {
                    self.predict(i);
                    self.quiet += 1;
                }
                What::Ball { j, shift, .. } => {
                    return Step::Contact(self.ball_ball(i, j as usize, &shift))
                }
                What::Wall { axis, upper } => {
                    return Step::Contact(self.ball_wall(i, axis as usize, upper))
                }
                What::Obstacle { o, shift } => {
                    return Step::Contact(self.ball_obstacle(i, o as usize, &shift))
                }
                What::Boundary { b } => return Step::Contact(self.ball_boundary(i, b as usize)),
            }
        }
    }
}
