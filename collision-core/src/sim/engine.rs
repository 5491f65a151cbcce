//! The event loop.
//!
//! State: per ball a centre `a_i` valid at its own time `t_i` (balls are advanced lazily, only
//! when they take part in an event), its velocity state, species, cell and a collision
//! counter `count_i` that increases whenever its velocity changes.
//!
//! Queue invariant: every moving ball has in the queue an entry for its earliest predicted
//! event, made when it was last predicted, and nothing later than its true next event.
//! Popping an entry:
//! - if the owner's counter changed since, the entry is dropped (the owner was re-predicted);
//! - a ball-ball entry whose partner's counter changed is no longer an event: the owner is
//!   re-predicted from now (its own trajectory is unchanged, so no event of it was missed);
//! - a cell crossing moves the ball to the next cell (wrapping on a periodic axis) and
//!   re-predicts it against its new neighbours;
//! - a contact advances the balls to now, applies the pair's no-slip map, bumps the counters
//!   and re-predicts the balls involved.

use super::cells::Grid;
use super::observe::Observables;
use super::orientation::{exp_skew, identity, mul, Matrix};
use super::predict::{contact_time, exit_time};
use super::queue::{Entry, What};
use super::{Body, FixedBall, PairKernels, Setup};
use crate::{Ball, BodyState};
use std::collections::BinaryHeap;
use std::fmt;

/// A contact: ball-ball (`i` is body 1), ball-wall or ball-obstacle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Contact {
    Ball { i: usize, j: usize },
    Wall { i: usize, axis: usize, upper: bool },
    Obstacle { i: usize, obstacle: usize },
}

/// One contact with the states around it. Index 0 is ball `i`, index 1 ball `j` of a
/// ball-ball contact (for a wall or an obstacle, index 1 repeats index 0). `nu` is the unit
/// normal from body 1 (ball `i`, the wall or the obstacle) to body 2 (ball `j`, or ball `i`).
#[derive(Clone, Debug, PartialEq)]
pub struct Event<const N: usize, const S: usize> {
    pub time: f64,
    pub contact: Contact,
    pub nu: [f64; N],
    pub position: [[f64; N]; 2],
    pub pre: [BodyState<f64, N, S>; 2],
    pub post: [BodyState<f64, N, S>; 2],
}

/// A setup the engine cannot run.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SetupError(pub String);

impl fmt::Display for SetupError {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for SetupError {}

/// An event-driven simulation; see the module docs.
pub struct Simulation<const N: usize, const S: usize, K> {
    kernels: K,
    species: Vec<Ball<f64>>,
    obstacles: Vec<FixedBall<N>>,
    grid: Grid<N>,
    kind: Vec<usize>,
    pos: Vec<[f64; N]>,
    since: Vec<f64>,
    state: Vec<BodyState<f64, N, S>>,
    count: Vec<u32>,
    cell: Vec<[usize; N]>,
    members: Vec<Vec<u32>>,
    fixed_members: Vec<Vec<u32>>,
    orientation: Option<Vec<Matrix<N>>>,
    queue: BinaryHeap<Entry<N>>,
    now: f64,
    contacts: u64,
    crossings: u64,
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
        } = setup;
        if let Some(k) = (0..N).find(|&k| !(size[k] > 0.0 && size[k].is_finite())) {
            return Err(SetupError(format!("box size {k} must be positive")));
        }
        let r_ball = bodies
            .iter()
            .map(|b| species.get(b.species).map(|s| s.radius))
            .try_fold(0.0f64, |m, r| r.map(|r| m.max(r)))
            .ok_or_else(|| SetupError("a ball names a species that does not exist".into()))?;
        let r_obstacle = obstacles.iter().fold(0.0f64, |m, o| m.max(o.radius));
        let d_max = (2.0 * r_ball)
            .max(r_ball + r_obstacle)
            .max(f64::MIN_POSITIVE);
        let grid = Grid::new(size, periodic, d_max);
        let mut members = vec![Vec::new(); grid.cells()];
        let mut fixed_members = vec![Vec::new(); grid.cells()];
        let mut cell = Vec::with_capacity(bodies.len());
        for (i, b) in bodies.iter().enumerate() {
            if let Some(k) = (0..N).find(|&k| !(0.0..=size[k]).contains(&b.position[k])) {
                return Err(SetupError(format!(
                    "ball {i} is outside the box along axis {k}"
                )));
            }
            let c = grid.cell_of(&b.position);
            members[grid.flat(&c)].push(i as u32);
            cell.push(c);
        }
        for (o, f) in obstacles.iter().enumerate() {
            let c = grid.cell_of(&f.position);
            fixed_members[grid.flat(&c)].push(o as u32);
        }
        let n = bodies.len();
        let mut sim = Simulation {
            kernels,
            species,
            obstacles,
            grid,
            kind: bodies.iter().map(|b| b.species).collect(),
            pos: bodies.iter().map(|b| b.position).collect(),
            since: vec![0.0; n],
            state: bodies.into_iter().map(|b: Body<N, S>| b.state).collect(),
            count: vec![0; n],
            cell,
            members,
            fixed_members,
            orientation: orientation.then(|| vec![identity::<N>(); n]),
            queue: BinaryHeap::new(),
            now: 0.0,
            contacts: 0,
            crossings: 0,
        };
        for i in 0..n {
            sim.predict(i);
        }
        Ok(sim)
    }

    pub fn now(&self) -> f64 {
        self.now
    }

    /// Contacts processed so far.
    pub fn contacts(&self) -> u64 {
        self.contacts
    }

    /// Cell crossings processed so far.
    pub fn crossings(&self) -> u64 {
        self.crossings
    }

    pub fn len(&self) -> usize {
        self.pos.len()
    }

    pub fn is_empty(&self) -> bool {
        self.pos.is_empty()
    }

    /// The box sides `L_k`.
    pub fn box_size(&self) -> [f64; N] {
        self.grid.size
    }

    pub fn species_of(&self, i: usize) -> usize {
        self.kind[i]
    }

    pub fn state(&self, i: usize) -> &BodyState<f64, N, S> {
        &self.state[i]
    }

    /// Ball `i`'s centre now (inside the box; wrapped on periodic axes up to the crossing
    /// in progress).
    pub fn position(&self, i: usize) -> [f64; N] {
        let dt = self.now - self.since[i];
        std::array::from_fn(|k| self.pos[i][k] + self.state[i].velocity[k] * dt)
    }

    /// Ball `i`'s orientation `A_i` now, if the setup tracks orientations.
    pub fn orientation(&self, i: usize) -> Option<[[f64; N]; N]> {
        let a = self.orientation.as_ref()?;
        let r = exp_skew::<N>(&self.state[i].spin, self.now - self.since[i]);
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
        let dt = self.now - self.since[i];
        if dt == 0.0 {
            return;
        }
        for k in 0..N {
            self.pos[i][k] += self.state[i].velocity[k] * dt;
        }
        if let Some(a) = &mut self.orientation {
            a[i] = mul(&exp_skew::<N>(&self.state[i].spin, dt), &a[i]);
        }
        self.since[i] = self.now;
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

    /// Push ball `i`'s earliest event (ball `i` is advanced to now first).
    fn predict(&mut self, i: usize) {
        self.advance(i);
        let (a, v) = (self.pos[i], self.state[i].velocity);
        let r = self.species[self.kind[i]].radius;
        let mut best: Option<(f64, What<N>)> = None;
        let mut offer = |t: f64, what: What<N>| {
            if best.is_none_or(|(b, _)| t < b) {
                best = Some((t, what));
            }
        };
        let c = self.cell[i];
        self.grid.for_neighbours(&c, |nb| {
            for &j in &self.members[nb.cell] {
                let j = j as usize;
                if j == i {
                    continue;
                }
                let b = self.image(j, &nb.shift);
                let d: [f64; N] = std::array::from_fn(|k| b[k] - a[k]);
                let dv: [f64; N] = std::array::from_fn(|k| self.state[j].velocity[k] - v[k]);
                let sigma = r + self.species[self.kind[j]].radius;
                if let Some(t) = contact_time(&d, &dv, sigma) {
                    let count = self.count[j];
                    offer(
                        t,
                        What::Ball {
                            j: j as u32,
                            count,
                            shift: nb.shift,
                        },
                    );
                }
            }
            for &o in &self.fixed_members[nb.cell] {
                let b = self.obstacle_image(o as usize, &nb.shift);
                let d: [f64; N] = std::array::from_fn(|k| b[k] - a[k]);
                let dv: [f64; N] = std::array::from_fn(|k| -v[k]);
                if let Some(t) = contact_time(&d, &dv, r + self.obstacles[o as usize].radius) {
                    offer(t, What::Obstacle { o, shift: nb.shift });
                }
            }
        });
        for k in 0..N {
            let w = self.grid.width[k];
            if !self.grid.periodic[k] {
                if let Some((t, upper)) = exit_time(a[k], v[k], r, self.grid.size[k] - r) {
                    offer(
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
                    offer(t, What::Cell { axis: k as u8, up });
                }
            }
        }
        if let Some((t, what)) = best {
            self.queue.push(Entry {
                time: self.now + t,
                ball: i as u32,
                count: self.count[i],
                what,
            });
        }
    }

    fn cross(&mut self, i: usize, axis: usize, up: bool) {
        self.advance(i);
        let c = self.cell[i];
        let flat = self.grid.flat(&c);
        let at = self.members[flat]
            .iter()
            .position(|&x| x as usize == i)
            .expect("ball in its cell");
        self.members[flat].swap_remove(at);
        let n = self.grid.n[axis];
        let mut c2 = c;
        if up {
            c2[axis] = (c[axis] + 1) % n;
            if c2[axis] == 0 {
                self.pos[i][axis] -= self.grid.size[axis];
            }
        } else {
            c2[axis] = (c[axis] + n - 1) % n;
            if c[axis] == 0 {
                self.pos[i][axis] += self.grid.size[axis];
            }
        }
        self.cell[i] = c2;
        let flat2 = self.grid.flat(&c2);
        self.members[flat2].push(i as u32);
        self.crossings += 1;
    }

    /// Process queue entries until the next contact at or before `until`, and return it;
    /// `None` (with the clock at `until`) if there is none by then.
    pub fn step(&mut self, until: f64) -> Option<Event<N, S>> {
        while let Some(top) = self.queue.peek() {
            if top.time > until {
                break;
            }
            let e = self.queue.pop().expect("peeked");
            let i = e.ball as usize;
            if e.count != self.count[i] {
                continue;
            }
            self.now = self.now.max(e.time);
            match e.what {
                What::Cell { axis, up } => {
                    self.cross(i, axis as usize, up);
                    self.predict(i);
                }
                What::Ball { j, count, .. } if count != self.count[j as usize] => self.predict(i),
                What::Ball { j, shift, .. } => return Some(self.ball_ball(i, j as usize, &shift)),
                What::Wall { axis, upper } => return Some(self.ball_wall(i, axis as usize, upper)),
                What::Obstacle { o, shift } => {
                    return Some(self.ball_obstacle(i, o as usize, &shift))
                }
            }
        }
        if until.is_finite() {
            self.now = self.now.max(until);
        }
        None
    }

    fn ball_ball(&mut self, i: usize, j: usize, shift: &[i8; N]) -> Event<N, S> {
        self.advance(i);
        self.advance(j);
        let b = self.image(j, shift);
        let nu = unit(std::array::from_fn(|k| b[k] - self.pos[i][k]));
        let pre = [self.state[i].clone(), self.state[j].clone()];
        let [si, sj] = self
            .kernels
            .ball_ball(self.kind[i], self.kind[j], &nu, &pre[0], &pre[1]);
        self.state[i] = si;
        self.state[j] = sj;
        let event = self.finish(Contact::Ball { i, j }, nu, [i, j], pre);
        self.predict(i);
        self.predict(j);
        event
    }

    fn ball_wall(&mut self, i: usize, axis: usize, upper: bool) -> Event<N, S> {
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
        self.state[i] = self.kernels.ball_wall(self.kind[i], axis, upper, &pre[0]);
        let event = self.finish(Contact::Wall { i, axis, upper }, nu, [i, i], pre);
        self.predict(i);
        event
    }

    fn ball_obstacle(&mut self, i: usize, o: usize, shift: &[i8; N]) -> Event<N, S> {
        self.advance(i);
        let b = self.obstacle_image(o, shift);
        let nu = unit(std::array::from_fn(|k| self.pos[i][k] - b[k]));
        let pre = [self.state[i].clone(), self.state[i].clone()];
        self.state[i] = self.kernels.ball_obstacle(self.kind[i], &nu, &pre[0]);
        let event = self.finish(Contact::Obstacle { i, obstacle: o }, nu, [i, i], pre);
        self.predict(i);
        event
    }

    fn finish(
        &mut self,
        contact: Contact,
        nu: [f64; N],
        balls: [usize; 2],
        pre: [BodyState<f64, N, S>; 2],
    ) -> Event<N, S> {
        self.count[balls[0]] += 1;
        if balls[1] != balls[0] {
            self.count[balls[1]] += 1;
        }
        self.contacts += 1;
        Event {
            time: self.now,
            contact,
            nu,
            position: balls.map(|b| self.pos[b]),
            pre,
            post: balls.map(|b| self.state[b].clone()),
        }
    }
}

/// `d / |d|`.
fn unit<const N: usize>(d: [f64; N]) -> [f64; N] {
    let norm = d.iter().map(|x| x * x).sum::<f64>().sqrt();
    d.map(|x| x / norm)
}
