//! The list engine: an event loop with a neighbour list per ball (shells, as in Donev,
//! Torquato and Stillinger, J. Comput. Phys. 202, 737 (2005), and the `Single` variant of
//! Smallenburg's EDMD), for gases of balls in a box. It writes the same event log as the cell
//! engine ([`crate::Simulation`]) and the all-pairs reference, byte for byte: every contact
//! time is canonical (`canonical.rs`, docs/engine.md), so the engines differ only in
//! how they find the pairs to ask.
//!
//! **Shells.** Ball `i` has a shell of radius `delta` around a centre `c_i` (its position
//! when the shell was drawn) and a list of the balls whose shells' centres lie within `d_max
//! + 2 delta` of `c_i` (`shells.rs`); a pair can touch only while listed, as long as both stay
//! in their shells. Leaving its shell is an event of the ball (keyed as a cell crossing: it moves
//! no record): the shell is drawn again around its position, its list rebuilt from the
//! centres' own cell list, and it is predicted again. There are no cell crossings, and a
//! prediction after a contact asks the list (about `phi 2^n (1 + 2 delta / d)^n` balls) where
//! the cell engine asks its `3^n` cells.
//!
//! **Images.** Ball `i`'s record coordinates are the box's plus `W_i L`, `W_i` found when its
//! record moves (the record's centre against its shell's, whole box lengths: the ball is
//! within `delta` of `c_i + W_i L`). A listed neighbour `j` at shell image `m` is then at
//! image `k = m - W_j + W_i` in `i`'s record coordinates, the image the cell engine names
//! (`s - W_j + W_i` for its cell shift `s`); with at least three centre cells a periodic
//! side (`L_k >= 3 (d_max + 2 delta)`), it is the only image within reach.
//!
//! **Slots.** The balls' records lie in slots in the order of their shells' cells, laid out
//! again at the start and at every re-basing (`ListSimulation::reorder`), so that a list's
//! balls lie near each other in memory whatever the balls' indices; the indices (the log's,
//! the events' keys, body 1 of a pair) are kept with the records.
//!
//! **The rest** is the cell engine's: one pending event per ball in the same calendar
//! (`queue.rs`), the canonical order of `(time, key)`, counters that make a partner's
//! old contact stale, the rule against repeating a contact still touching
//! (`last_contact.rs`), the box walls, the laws under the TC model, and the re-basing
//! of the clock at the canonical times (every record moved there, every ball predicted
//! again), the decision that no contact will happen again ([`crate::Step::Never`]) and the
//! notices of long stretches without one ([`crate::Step::Quiet`], `quiet.rs`). Not here:
//! obstacles, table boundaries, orientations and the thermostat's kicks:
//! [`ListSimulation::new`] refuses a setup that has them.

mod ahead;
mod ball;
mod contacts;
mod lanes;
mod predict;
mod quiet;
mod shells;
mod strided;
#[cfg(test)]
mod tests;

use crate::canonical::{clock_span2, d_max};
use crate::cells::Grid;
use crate::clock::Clock;
use crate::engine::SetupError;
use crate::motion::Motion;
use crate::no_contact::{NoContact, QUIET_BOX_LENGTHS};
use crate::queue::Calendar;
use crate::residents::Resident;
use crate::{PairKernels, Setup, Step, Table};
use ball::{Next, Own};
use collision_core::{Ball, BodyState};
use shells::Shells;
use std::fmt;

/// The shell radius `delta` in units of the largest contact distance `d_max`, unless the
/// caller chooses ([`ListSimulation::with_skin`]); measured in docs/benchmarks.md ("The list
/// engine").
pub const SKIN: f64 = 0.3;

/// The size of the flight records and lists from which the next events' memory is requested
/// ahead (`ahead.rs`): 4 MiB, several times a core's L2 cache, as the cell engine's rule.
const PREFETCH_FROM_BYTES: usize = 4 << 20;

/// The least skin: a shell of `1e-6 d_max` still holds a ball for many ulps of its flight.
pub const MIN_SKIN: f64 = 1e-6;

/// The centres' cell list: cells wider than `reach`, at least three along every periodic
/// axis, the cap on cells per body ([`Grid::new`]) raised as far as that needs, up to 4096
/// times the balls; a periodic side that still holds fewer is refused.
fn centres_grid<const N: usize>(
    size: [f64; N],
    periodic: [bool; N],
    reach: f64,
    balls: usize,
) -> Result<Grid<N>, ListsRefusal> {
    let short = |axis: usize| ListsRefusal::ShortSide {
        axis,
        size: size[axis],
        reach,
    };
    let most = balls.max(1) << 12;
    let mut room = balls.max(3usize.pow(N as u32));
    loop {
        let grid = Grid::new(size, periodic, reach, room).map_err(|e| match e {
            SetupError::ShortSide { axis, .. } => short(axis),
            e => ListsRefusal::Setup(e),
        })?;
        match (0..N).find(|&k| periodic[k] && grid.n[k] < 3) {
            None => return Ok(grid),
            Some(k) if room >= most => return Err(short(k)),
            Some(_) => room = (8 * room).min(most),
        }
    }
}

/// Why the list engine refuses a setup (the cell engine takes it).
#[derive(Clone, Debug, PartialEq)]
pub enum ListsRefusal {
    /// What the cell engine refuses too.
    Setup(SetupError),
    /// The setup has obstacles.
    Obstacles,
    /// The table has boundaries besides the box, or no box.
    Table,
    /// The setup tracks orientations.
    Orientation,
    /// The table has a thermostat (the list engine takes no kicks).
    Thermostat,
    /// The skin is below [`MIN_SKIN`] or not finite.
    Skin(f64),
    /// A periodic side holds fewer than three cells of the centres' grid (cells wider than
    /// the lists' reach `d_max + 2 delta`): shorter than three reaches, or too thin beside the
    /// others for the cells the balls may have.
    ShortSide {
        /// The periodic axis `k`.
        axis: usize,
        /// The side `L_k`.
        size: f64,
        /// `d_max + 2 delta`.
        reach: f64,
    },
}

impl fmt::Display for ListsRefusal {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        match self {
            ListsRefusal::Setup(e) => write!(f, "{e}"),
            ListsRefusal::Obstacles => write!(f, "the list engine takes no obstacles"),
            ListsRefusal::Table => write!(f, "the list engine takes a box and no other boundary"),
            ListsRefusal::Orientation => write!(f, "the list engine does not track orientations"),
            ListsRefusal::Thermostat => write!(f, "the list engine takes no thermostat"),
            ListsRefusal::Skin(s) => write!(f, "skin {s} must be finite and at least {MIN_SKIN}"),
            ListsRefusal::ShortSide { axis, size, reach } => write!(
                f,
                "periodic side {axis} ({size}) holds fewer than 3 cells of the lists' reach ({reach})"
            ),
        }
    }
}

impl std::error::Error for ListsRefusal {}

impl From<SetupError> for ListsRefusal {
    fn from(e: SetupError) -> Self {
        ListsRefusal::Setup(e)
    }
}

/// An event-driven simulation with neighbour lists; see the module docs.
pub struct ListSimulation<const N: usize, const S: usize, K> {
    kernels: K,
    species: Vec<Ball<f64>>,
    table: Table<N>,
    size: [f64; N],
    periodic: [bool; N],
    /// The shell radius `delta`.
    delta: f64,
    /// Per slot: what the ball's own events read and write.
    balls: Vec<Own<N, S>>,
    /// Per ball index: its slot.
    slot_of: Vec<u32>,
    /// Whether the next events' memory is requested ahead ([`PREFETCH_FROM_BYTES`]).
    prefetch: bool,
    /// Per slot: what a neighbour's prediction reads (its flight record, its wraps `W_i`,
    /// with record coordinates the box's plus `W_i L` while its record stays, and its
    /// counter).
    flights: Vec<Resident<N>>,
    /// The pair times of a prediction's list, kept between predictions.
    times: Vec<f64>,
    /// Whether this CPU runs AVX2 (a prediction's pair times are then computed in its
    /// registers, four at a time).
    avx2: bool,
    shells: Shells<N>,
    queue: Calendar,
    /// The local clock's time; the absolute time is `clock.absolute(now)`.
    now: f64,
    /// The clock's origin and re-basing rule (the span of the cell engine's grid rule).
    clock: Clock,
    contacts: u64,
    redraws: u64,
    stale: u64,
    rebases: u64,
    /// Events (redraws, stale contacts) since the last contact, and when to check next
    /// whether contacts can still happen (`quiet.rs`).
    quiet: u64,
    next_check: u64,
    /// The local time of the last contact (or of the start).
    last_contact: f64,
    /// The travel (box lengths) at which the next [`Step::Quiet`] notice is due.
    next_notice: f64,
}

impl<const N: usize, const S: usize, K: PairKernels<f64, N, S>> ListSimulation<N, S, K> {
    /// The list engine on `setup`, shells of radius [`SKIN`] `d_max`.
    pub fn new(setup: Setup<N, S>, kernels: K) -> Result<Self, ListsRefusal> {
        Self::with_skin(setup, kernels, SKIN)
    }

    /// The list engine on `setup`, shells of radius `skin d_max` (`d_max` the largest contact
    /// distance).
    pub fn with_skin(setup: Setup<N, S>, kernels: K, skin: f64) -> Result<Self, ListsRefusal> {
        let Setup {
            size,
            periodic,
            species,
            obstacles,
            bodies,
            orientation,
            table,
        } = setup;
        if !obstacles.is_empty() {
            return Err(ListsRefusal::Obstacles);
        }
        if !table.boxed || !table.boundaries.is_empty() {
            return Err(ListsRefusal::Table);
        }
        if table.thermostat.is_some() {
            return Err(ListsRefusal::Thermostat);
        }
        if orientation {
            return Err(ListsRefusal::Orientation);
        }
        if let Some(k) = (0..N).find(|&k| !(size[k] > 0.0 && size[k].is_finite())) {
            return Err(SetupError::BoxSize {
                axis: k,
                size: size[k],
            }
            .into());
        }
        let mut r_ball = 0.0f64;
        for (i, b) in bodies.iter().enumerate() {
            let s = species.get(b.species).ok_or(SetupError::Species {
                ball: i,
                species: b.species,
            })?;
            r_ball = r_ball.max(s.radius);
            if let Some(k) = (0..N).find(|&k| !(0.0..=size[k]).contains(&b.position[k])) {
                return Err(SetupError::Outside { ball: i, axis: k }.into());
            }
        }
        let d_max = d_max(r_ball, 0.0);
        // The cell engine's grid, for the canonical re-basing time alone.
        let cells = Grid::new(size, periodic, d_max, bodies.len())?;
        if !(skin >= MIN_SKIN && skin.is_finite()) {
            return Err(ListsRefusal::Skin(skin));
        }
        let delta = skin * d_max;
        // A centre is within a few ulps of its side of its shell (it is computed from the
        // ball's flight, whose coordinates reach the box's side plus the clock's span of
        // flight): the slack covers it.
        let longest = size.iter().copied().fold(0.0, f64::max);
        let span2 = clock_span2(&cells.width);
        let span = span2.sqrt();
        let reach = (d_max + 2.0 * delta) * (1.0 + 1e-9) + 64.0 * f64::EPSILON * (longest + span);
        let grid = centres_grid(size, periodic, reach, bodies.len())?;
        let n = bodies.len();
        let velocities = bodies.iter().map(|b| &b.state.velocity);
        let clock = Clock::start(span2, velocities, periodic.contains(&true));
        let flights = bodies
            .iter()
            .enumerate()
            .map(|(i, b)| Resident {
                motion: Motion {
                    pos: b.position,
                    since: 0.0,
                    velocity: b.state.velocity,
                    radius: species[b.species].radius,
                },
                wraps: [0; N],
                ball: i as u32,
                count: 0,
            })
            .collect();
        let balls = bodies
            .into_iter()
            .enumerate()
            .map(|(i, b)| Own {
                id: i as u32,
                slot: crate::queue::Slot::EMPTY,
                next: None,
                found: None,
                state: b.state,
                previous: f64::NEG_INFINITY,
                kind: b.species as u32,
                last: crate::last_contact::LastContact::NONE,
            })
            .collect();
        let mut sim = ListSimulation {
            kernels,
            species,
            table,
            size,
            periodic,
            delta,
            balls,
            slot_of: (0..n as u32).collect(),
            prefetch: false,
            flights,
            shells: Shells::new(grid, n, reach),
            times: Vec::new(),
            #[cfg(target_arch = "x86_64")]
            avx2: is_x86_feature_detected!("avx2"),
            #[cfg(not(target_arch = "x86_64"))]
            avx2: false,
            queue: Calendar::new(),
            now: 0.0,
            clock,
            contacts: 0,
            redraws: 0,
            stale: 0,
            rebases: 0,
            quiet: 0,
            next_check: 0,
            last_contact: 0.0,
            next_notice: QUIET_BOX_LENGTHS,
        };
        for i in 0..n {
            sim.draw(i);
        }
        let bytes = std::mem::size_of::<Resident<N>>() + sim.shells.list_bytes();
        sim.prefetch = n * bytes >= PREFETCH_FROM_BYTES;
        sim.predict_all();
        Ok(sim)
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

    /// The number of balls.
    pub fn len(&self) -> usize {
        self.balls.len()
    }

    /// Whether there are no balls.
    pub fn is_empty(&self) -> bool {
        self.balls.is_empty()
    }

    /// Contacts processed so far.
    pub fn contacts(&self) -> u64 {
        self.contacts
    }

    /// Shells drawn again (a ball left its shell) so far.
    pub fn redraws(&self) -> u64 {
        self.redraws
    }

    /// Ball-ball events found stale so far (the partner's counter had changed).
    pub fn stale_events(&self) -> u64 {
        self.stale
    }

    /// Times the local clock was re-based.
    pub fn rebases(&self) -> u64 {
        self.rebases
    }

    /// Sets whether the next events' memory is requested ahead (`ahead.rs`): a test of both
    /// ways on a small gas.
    #[cfg(test)]
    pub(crate) fn set_prefetch(&mut self, on: bool) {
        self.prefetch = on;
    }

    /// The mean length of the neighbour lists now.
    pub fn mean_list(&self) -> f64 {
        let total: usize = (0..self.len()).map(|i| self.shells.list(i).len()).sum();
        total as f64 / self.len().max(1) as f64
    }

    /// Ball `i`'s state `(U, u)` (constant between contacts).
    pub fn state(&self, i: usize) -> &BodyState<f64, N, S> {
        &self.balls[self.slot_of[i] as usize].state
    }

    /// Lays the balls' slots out in the order of their shells' cells (the records, the
    /// lists and the cells' members follow; the calendar is built again by the caller).
    fn reorder(&mut self) {
        let mut order: Vec<u32> = (0..self.len() as u32).collect();
        order.sort_by_key(|&s| self.shells.cell_of(s as usize));
        if order
            .iter()
            .enumerate()
            .all(|(new, &old)| new == old as usize)
        {
            return;
        }
        self.balls = order
            .iter()
            .map(|&s| self.balls[s as usize].clone())
            .collect();
        self.flights = order.iter().map(|&s| self.flights[s as usize]).collect();
        for (slot, own) in self.balls.iter().enumerate() {
            self.slot_of[own.id as usize] = slot as u32;
        }
        self.shells.permute(&order);
    }

    fn speed2_of(&self, i: usize) -> f64 {
        self.balls[i].state.velocity.iter().map(|x| x * x).sum()
    }

    /// Processes events until the next contact at or before the absolute time `until` and
    /// returns it, as [`crate::Simulation::step`]: [`Step::Until`] (the clock at `until`)
    /// if there is none by then, [`Step::Never`] if no contact can happen again, and
    /// [`Step::Quiet`] once the balls have flown 1000, 2000, 4000 ... box lengths without a
    /// contact.
    pub fn step(&mut self, until: f64) -> Step<N, S> {
        loop {
            let until = self.local(until);
            if self.quiet >= self.next_check {
                self.next_check = self.next_check.saturating_mul(2).max(self.first_check());
                if let Some(why) = self.no_contact() {
                    if until.is_finite() {
                        self.now = self.now.max(until);
                    }
                    return Step::Never(why);
                }
                let box_lengths = self.quiet_travel();
                if box_lengths >= self.next_notice {
                    self.next_notice = 2.0 * box_lengths;
                    return Step::Quiet { box_lengths };
                }
            }
            let Some((time, i)) = self.queue.peek(self.balls.as_mut_slice()) else {
                if until.is_finite() {
                    self.now = self.now.max(until);
                }
                return Step::Never(NoContact::AtRest);
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
            let next = self.balls[i]
                .next
                .expect("a ball in the calendar has an event");
            self.now = self.now.max(time);
            match next {
                Next::Shell => {
                    self.draw(i);
                    self.redraws += 1;
                    self.predict_after_draw(i);
                    self.quiet += 1;
                }
                Next::Ball { j, count, .. } if count != self.flights[j as usize].count => {
                    self.stale += 1;
                    self.predict(i);
                    self.quiet += 1;
                }
                Next::Ball { j, image, .. } => {
                    return Step::Contact(self.ball_ball(i, j as usize, &image, time))
                }
                Next::Wall { axis, upper } => {
                    return Step::Contact(self.ball_wall(i, axis as usize, upper, time))
                }
            }
        }
    }
}
