//! The event loop.
//!
//! State: per ball its flight record (`Motion`: centre `a_i` at its own time `t_i`, velocity,
//! radius), which moves only at its contacts and at re-basings of the clock
//! (`canonical.rs`), its velocity state, species, cell, a collision counter `count_i`
//! that increases whenever its velocity changes, and its wraps `W_i` across periodic faces
//! since its record moved, so that its centre in the box is `a_i + (t - t_i) u_i - W_i L`.
//! Every contact time is canonical: a function of the records of the bodies that meet, so
//! that the all-pairs reference of the tests writes the same log byte for byte (docs/engine.md).
//!
//! Queue invariant: every moving ball has exactly one pending event in the queue (a
//! `Calendar` (`queue.rs`), keyed by ball: setting a ball's event replaces the one it had,
//! so no stale entry is ever kept), its earliest predicted event as of its last prediction,
//! and nothing later than its true next event. Events are taken in the canonical order of
//! `(time, key)` (the key orders the events of one time by their lowest ball, kind, other
//! body and image, so that exactly simultaneous events are taken alike by every engine); the
//! ball whose event is taken is always re-predicted before the next one:
//! - a ball-ball event whose partner's counter changed is no longer an event: the owner is
//!   re-predicted (its record is unchanged, so no event of it was missed);
//! - a cell crossing moves the ball to the next cell (counting a wrap on a periodic axis) and
//!   re-predicts it: its best contact so far (kept per ball, valid while that partner's
//!   counter is unchanged) against the newly reached layer of cells only (`scan.rs`); its
//!   record does not move, so the times it finds are the ones any other prediction finds;
//! - a contact moves the records of the balls involved to its time, applies the pair's map
//!   (body 1 the lower index), bumps the counters and re-predicts them.
//!
//! **Layout.** What an event reads and writes of its own ball is one record per ball
//! (`BallRecord`, `record.rs`; one `Vec`, aligned to a cache line, hot fields first): the
//! calendar's slot (its time and place; the calendar keeps only the order, `queue::Slots`),
//! the kept contact, the cell, the counter, the home of its flight in the slab
//! (`residents::Homes`) and the pending crossing share one 64-byte line in 2D and 3D; the
//! state, species, last boundary and previous contact (a contact's reads) follow. The
//! pending event is the crossing if it beat the kept contact, else the kept contact, and an
//! event's key is computed from the ball and the event when two times tie: neither is
//! stored twice. At `10^6` balls an event so costs one miss for its ball where the separate
//! arrays cost five or six (docs/benchmarks.md, "The per-ball records gathered into one").
//! What a prediction reads of every neighbour (its flight and its wraps) is stored
//! by cell (`Residents`, `residents.rs`): a cell's records are one list, and the lists lie in
//! one slab in the order of the cells, laid out again at the start and at every re-basing
//! (which also predict the balls cell after cell), so a scan of the `3^n` cells within reach
//! (`Grid::near`, no division; an interior cell's from a table of flat offsets) reads a few
//! stretches of memory. Without obstacles, a scan gathers its neighbours' slab places first
//! (`Residents::gather_cells`; a cell at a periodic face tags its places with its image,
//! `Gathered::gather_walk`), then
//! computes their pair times four at a time in vector registers (`lanes.rs`, AVX2 where the
//! CPU has it) and offers only those at the least time to the scalar path, which recomputes
//! the canonical time: one loop exit per scan instead of a mispredicted one per cell, and
//! no branch per partner. The velocity there
//! is a copy of the ball's state's, written at each contact. Contact times in the scan are
//! taken without branches (`predict::contact_time_or_nan`, the same bits as
//! `contact_time`). The calendar's lists, the slab and the scan reuse their memory:
//! nothing is allocated per event once they have grown. When the cell list outgrows the
//! caches (`PREFETCH_FROM_BYTES` of slab, 4 MiB), the records of the next two events in the
//! calendar and, for a scan of at most nine cells (a 2D neighbourhood, a 3D crossing's
//! layer), its cells' places and first records are requested one link per event ahead
//! (`ahead.rs`); a larger scan first prefetches its cells' places in the slab, then their
//! first records, so that the cache misses of the `3^n` cells overlap instead of following
//! one another. The scans themselves are the same. Likewise, when the calendar's buckets
//! outgrow a core's L2 cache, its changes to them wait a few events while their blocks load
//! (`stage.rs`).
//!
//! **Images.** A ball-ball entry stores its partner's image in the owner's record
//! coordinates, `k = s - W_j + W_i` for the cell shift `s` it was predicted with: the partner
//! may cross a periodic face (a cell crossing, which leaves its counter and its record, and
//! so the entry, valid) before the contact, and the image stays the one the contact time was
//! solved for, with no minimum-image guess (which could be ambiguous on a periodic side
//! shorter than two contact distances). An obstacle's image is `s + W_i`.
//!
//! **Clock.** Times are kept on a local clock `t` whose origin (an absolute time, kept as a
//! compensated sum) is moved forward ("re-based") at the canonical time
//! `T = CLOCK_CELLS w_min / v_max` (`canonical::rebase_at`; `v_max` an upper bound of
//! the speeds, `w_min` the narrowest cell, lowered by a contact that raises `v_max`, doubled
//! after quiet re-basings on a table without a periodic axis): every record moves to `T`,
//! folded into the box, the clock restarts at 0 and every ball is predicted again (the
//! calendar's bucket width chosen again for the current event rate). Rounding a local time
//! then moves a ball by at most `CLOCK_CELLS` ulps of a cell width, whatever the absolute
//! time, so contacts stay at contact distance in long runs and after long quiet stretches (a
//! gas started almost at rest), and a ball wraps at most `CLOCK_CELLS + 1` times between two
//! moves of its record. A re-basing costs one prediction per ball, once per `CLOCK_CELLS` cell
//! widths travelled by the fastest ball.
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

mod ahead;
mod contacts;
mod events;
mod kick;
pub(crate) mod lanes;
#[cfg(target_arch = "x86_64")]
pub(crate) mod lanes3;
mod quiet;
mod record;
mod scan;

pub use events::{Contact, Event, SetupError, Step};

use super::canonical::{clock_span2, d_max};
use super::cells::Grid;
use super::clock::Clock;
use super::left_table::LeftTable;
use super::motion::Motion;
use super::no_contact::{NoContact, QUIET_BOX_LENGTHS};
use super::observe::Observables;
use super::orientation::{exp_skew, identity, mul, Matrix};
use super::queue::{Calendar, What};
use super::residents::{Resident, Residents};
use super::table::{ContactKind, Geometry, Table};
use super::{FixedBall, PairKernels, Setup};
use collision_core::{Ball, BodyState};
use record::BallRecord;

/// The size of the slab of records (`(balls + cells)` records: each list has room for one
/// more) from which a prediction prefetches its neighbour cells' lists: 4 MiB, several times a
/// core's L2 cache. Below it the lists are mostly cached and the extra passes cost more than
/// they save; above it they save up to half the time (docs/benchmarks.md, "The slab").
const PREFETCH_FROM_BYTES: usize = 4 << 20;

/// An event-driven simulation; see the module docs.
pub struct Simulation<const N: usize, const S: usize, K> {
    kernels: K,
    species: Vec<Ball<f64>>,
    obstacles: Vec<FixedBall<N>>,
    table: Table<N>,
    grid: Grid<N>,
    /// Per ball: what its events read and write, in one record (`record.rs`): the
    /// calendar's slot, its pending event, its kept contact, cell, counter, state, species,
    /// last boundary and previous contact.
    balls: Vec<BallRecord<N, S>>,
    /// Per ball: centre, its time, velocity and radius (the neighbour scan's reads), stored
    /// by cell (the cell lists).
    motion: Residents<N>,
    /// Per cell: the obstacles whose centres lie in it (empty, no cells, without obstacles).
    fixed_members: Vec<Vec<u32>>,
    /// `A_i` at the ball's time minus `unturned_i`: the flight time (at constant `U_i`) not
    /// applied to it yet, kept by rebases so that they need no matrix exponential.
    orientation: Option<Vec<Matrix<N>>>,
    unturned: Vec<f64>,
    /// Whether the next events' memory is looked ahead and a prediction prefetches its
    /// neighbour cells' lists: a cell list larger than the caches ([`PREFETCH_FROM_BYTES`]).
    prefetch: bool,
    /// The slab places of the balls a scan meets ([`Residents::gather_cells`]), kept between scans.
    near: std::cell::RefCell<lanes::Gathered<N>>,
    /// The order of the balls' pending events (their slots are in `balls`).
    queue: Calendar,
    /// The local clock's time; the absolute time is `clock.absolute(now)`.
    now: f64,
    /// The clock's origin and re-basing rule.
    clock: Clock,
    /// The local time of the last contact (or of the start).
    last_contact: f64,
    /// Events (crossings, re-predictions) since the last contact, and when to check next
    /// whether contacts can still happen.
    quiet: u64,
    next_check: u64,
    /// A ball that left the table through a container at the last contact
    /// ([`crate::left_table`]): every later step returns it.
    left: Option<LeftTable>,
    /// The travel (box lengths) at which the next [`Step::Quiet`] notice is due.
    next_notice: f64,
    contacts: u64,
    crossings: u64,
    /// Ball-ball events found stale (the partner's counter changed) so far.
    stale: u64,
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
        let d_max = d_max(r_ball, r_obstacle);
        let grid = if table.boxed {
            Grid::new(size, periodic, d_max, bodies.len() + obstacles.len())?
        } else {
            Grid::single(size)
        };
        let mut balls = Vec::with_capacity(bodies.len());
        let mut cell_of = Vec::with_capacity(bodies.len());
        for (i, b) in bodies.iter().enumerate() {
            let outside = (0..N).find(|&k| !(0.0..=size[k]).contains(&b.position[k]));
            if let (Some(k), true) = (outside, table.boxed) {
                return Err(SetupError::Outside { ball: i, axis: k });
            }
            let c = grid.cell_of(&b.position);
            balls.push(BallRecord::new(b.state.clone(), b.species, c));
            cell_of.push(grid.flat(&c) as u32);
        }
        let flight = |i: usize| {
            let b = &bodies[i];
            Motion {
                pos: b.position,
                since: 0.0,
                velocity: b.state.velocity,
                radius: species[b.species].radius,
            }
        };
        let motion = Residents::laid_out(grid.cells(), &cell_of, flight, balls.as_mut_slice());
        drop(cell_of);
        // Read only by the scans of a table with obstacles.
        let cells_with_obstacles = if obstacles.is_empty() {
            0
        } else {
            grid.cells()
        };
        let mut fixed_members = vec![Vec::new(); cells_with_obstacles];
        for (o, f) in obstacles.iter().enumerate() {
            let c = grid.cell_of(&f.position);
            fixed_members[grid.flat(&c)].push(o as u32);
        }
        let n = bodies.len();
        let slab = (bodies.len() + grid.cells()) * std::mem::size_of::<Resident<N>>();
        let prefetch = slab >= PREFETCH_FROM_BYTES;
        let span2 = clock_span2(&grid.width);
        // The clock from the starting velocities; periodic only in a box.
        let velocities = bodies.iter().map(|b| &b.state.velocity);
        let table_periodic = table.boxed && grid.periodic.contains(&true);
        let mut sim = Simulation {
            kernels,
            species,
            obstacles,
            table,
            grid,
            balls,
            motion,
            fixed_members,
            orientation: orientation.then(|| vec![identity::<N>(); n]),
            unturned: vec![0.0; if orientation { n } else { 0 }],
            prefetch,
            near: Default::default(),
            queue: Calendar::new(),
            now: 0.0,
            clock: Clock::start(span2, velocities, table_periodic),
            last_contact: 0.0,
            quiet: 0,
            next_check: 0,
            left: None,
            next_notice: QUIET_BOX_LENGTHS,
            contacts: 0,
            crossings: 0,
            stale: 0,
            rebases: 0,
        };
        sim.predict_all();
        Ok(sim)
    }

    /// Sets whether predictions prefetch and the calendar holds back its changes to the
    /// buckets (`queue.rs`): a test of both on a small setup.
    #[cfg(test)]
    pub(crate) fn set_prefetch(&mut self, on: bool) {
        self.prefetch = on;
        self.queue
            .force_staging(self.balls.as_mut_slice(), Some(on));
    }

    /// Ball `i`'s flight record (`Motion`), from its home in the slab.
    #[inline]
    fn flight(&self, i: usize) -> &Motion<N> {
        self.motion.get(self.balls[i].home)
    }

    /// The absolute time now.
    pub fn now(&self) -> f64 {
        self.absolute(self.now)
    }

    fn absolute(&self, local: f64) -> f64 {
        self.clock.absolute(local)
    }

    fn local(&self, absolute: f64) -> f64 {
        self.clock.local(absolute)
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

    /// Ball-ball events found stale so far: the partner's counter had changed, so the owner
    /// was predicted again (a full scan).
    pub fn stale_events(&self) -> u64 {
        self.stale
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
    /// boundary's, or the ball-ball pair's of the two balls' species: [`Table::ball_law`]).
    pub fn contact_kind(&self, contact: &Contact) -> ContactKind {
        match *contact {
            Contact::Ball { i, j } => self.table.ball_law(self.species_of(i), self.species_of(j)),
            Contact::Wall { .. } => self.table.box_contact,
            Contact::Obstacle { obstacle, .. } => self.table.obstacle(obstacle),
            Contact::Boundary { boundary, .. } => self.table.boundaries[boundary].contact,
        }
    }

    /// Ball `i`'s species index.
    pub fn species_of(&self, i: usize) -> usize {
        self.balls[i].kind as usize
    }

    /// Ball `i`'s state `(U, u)` (constant between contacts).
    pub fn state(&self, i: usize) -> &BodyState<f64, N, S> {
        &self.balls[i].state
    }

    /// Ball `i`'s centre now (inside the box; wrapped on periodic axes up to the crossing
    /// in progress): `a_i + (t - t_i) u_i - W_i L`.
    pub fn position(&self, i: usize) -> [f64; N] {
        let x = self.flight(i).at(self.now);
        let w = self.motion.wraps(self.balls[i].home);
        std::array::from_fn(|k| x[k] - f64::from(w[k]) * self.grid.size[k])
    }

    /// Ball `i`'s orientation `A_i` now, if the setup tracks orientations.
    pub fn orientation(&self, i: usize) -> Option<[[f64; N]; N]> {
        let a = self.orientation.as_ref()?;
        let dt = self.unturned[i] + (self.now - self.flight(i).since);
        let r = exp_skew::<N>(&self.balls[i].state.spin, dt);
        Some(mul(&r, &a[i]))
    }

    /// Energy, momentum and angular momentum now.
    pub fn observables(&self) -> Observables<N, S> {
        let positions: Vec<[f64; N]> = (0..self.len()).map(|i| self.position(i)).collect();
        Observables::of((0..self.len()).map(|i| {
            let b = &self.balls[i];
            (&self.species[b.kind as usize], &positions[i], &b.state)
        }))
    }

    /// The kinetic energy now, [`Observables::energy`] without the positions the other
    /// totals need: the same sum in the same order, so the same bits, at a fraction of the
    /// cost (a run samples it `samples` times, each `O(balls)`).
    pub fn energy(&self) -> f64 {
        (0..self.len()).fold(0.0, |e, i| {
            let b = &self.balls[i];
            e + crate::observe::energy_of(&self.species[b.kind as usize], &b.state)
        })
    }

    /// Process queue entries until the next contact at or before the absolute time `until`,
    /// and return it; [`Step::Until`] (with the clock at `until`) if there is none by then,
    /// [`Step::Never`] if there will be none at all.
    pub fn step(&mut self, until: f64) -> Step<N, S> {
        loop {
            let until = self.local(until);
            if self.quiet >= self.next_check {
                // A ball that left the table sets `next_check` to 0 (contacts.rs): no cost
                // on the hot path.
                if let Some(left) = self.left {
                    return Step::LeftTable(left);
                }
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
            let Some((time, i)) = self.queue.peek(self.balls.as_mut_slice()) else {
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
            if time > self.clock.rebase_at() {
                self.rebase(self.clock.rebase_at(), true);
                continue;
            }
            if self.prefetch {
                self.look_ahead();
            }
            // Ball i's event stays in the queue until every branch below re-predicts i.
            let what = self.balls[i]
                .next()
                .expect("a ball in the calendar has an event");
            self.now = self.now.max(time);
            match what {
                What::Cell { axis, up } => {
                    self.cross(i, axis as usize, up);
                    self.predict_after_crossing(i, axis as usize, up);
                    self.quiet += 1;
                }
                What::Ball { j, count, .. } if count != self.balls[j as usize].count => {
                    self.stale += 1;
                    self.predict(i);
                    self.quiet += 1;
                }
                What::Ball { j, image, .. } => {
                    return Step::Contact(self.ball_ball(i, j as usize, &image, time))
                }
                What::Wall { axis, upper } => {
                    return Step::Contact(self.ball_wall(i, axis as usize, upper, time))
                }
                What::Obstacle { o, image } => {
                    return Step::Contact(self.ball_obstacle(i, o as usize, &image, time))
                }
                What::Boundary { b } => {
                    return Step::Contact(self.ball_boundary(i, b as usize, time))
                }
            }
        }
    }
}
