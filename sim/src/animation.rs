//! The browser animation of a run (`noslip simulate --html FILE`): frames of the balls'
//! centres and orientations recorded as the run goes, bounded whatever its length, and turned
//! into one self-contained HTML page by [`crate::animation_page`].
//!
//! **Frames.** Frame `k` shows every drawn ball at time `t_0 + k dt`. Between its contacts a
//! ball flies freely, `a(t) = a_e + (t - t_e) u` and `A(t) = exp((t - t_e) U) A_e` from its
//! last contact `e`, so a frame is computed exactly from each ball's last contact before it
//! (wrapped into the box on periodic axes), not interpolated. `dt` starts at the time the
//! fastest ball takes to cross 1/64 of the shortest box side (`dt_0`); whenever the frames
//! would exceed the cap, every other frame is dropped and `dt` doubles, up to `16 dt_0`
//! (a quarter of the side a frame: beyond, the motion is no longer seen). A run short enough
//! is kept whole, in between half the cap and the cap of frames evenly spaced in time; of a
//! longer one, the frames show its beginning, `cap x 16 dt_0` time units (about 100 box
//! crossings of the fastest ball), and the rest of the run only enters the phase portrait.
//! The cap is [`MAX_FRAMES`], lowered to [`BALL_FRAMES`]` / balls` for many balls; at most
//! [`MAX_BALLS`] balls are drawn (the first ones by index).
//!
//! **Spin.** Each ball carries a mark, the body-fixed axis `A e_0` (its first column) drawn
//! from the centre to the rim: in 2D it turns at the angular velocity `c`; in 3D its
//! projection shows the axis turning (shorter when it points at the viewer).
//!
//! **Projection.** 2D: the plane itself. n >= 3: the first three coordinates, orthographic,
//! seen obliquely (turned by [`YAW`] about axis 2, tilted by [`PITCH`]), axis 2 up; the other
//! coordinates are not shown. Balls are drawn far to near.
//!
//! **Trails** of the first [`TRAILS`] balls: the frame positions and, between two frames,
//! the ball's contact positions (at most [`TRAIL_POINTS`] per frame interval, thinned evenly
//! beyond), so a trail follows the path through its corners.
//!
//! **Phase portrait** (a table with one ball): the Birkhoff coordinates `(s, sin phi)` of the
//! contacts with the table's bodies ([`crate::boundary_map`]): every `2^k`-th contact, at
//! most [`CLOUD_POINTS`], and per frame the contact in effect (the last one before it), which
//! the page highlights.

use crate::boundary_map::{self, Body};
use crate::orientation::{exp_skew, identity, mul, Matrix};
use crate::portrait::Axes;
use crate::{Event, PairKernels, Simulation};

/// The most balls drawn.
pub const MAX_BALLS: usize = 1000;
/// The most frames kept.
pub const MAX_FRAMES: usize = 400;
/// The most (ball, frame) pairs kept: the frame cap is `BALL_FRAMES / balls` for many balls.
pub const BALL_FRAMES: usize = 120_000;
/// The balls with a trail (the first ones).
pub const TRAILS: usize = 4;
/// The most contact positions of a trail between two frames.
pub const TRAIL_POINTS: usize = 8;
/// The most contacts of the phase portrait's cloud.
pub const CLOUD_POINTS: usize = 4000;
/// How far `dt` may grow: this many times its start (see the module docs).
pub const MAX_SLOWDOWN: f64 = 16.0;
/// The view of n >= 3: the turn about axis 2, radians.
pub const YAW: f64 = 0.6;
/// The view of n >= 3: the tilt towards axis 2, radians.
pub const PITCH: f64 = 0.4;

/// A drawn ball's last contact: what its frames are computed from.
#[derive(Clone, Debug)]
struct Key<const N: usize> {
    time: f64,
    position: [f64; N],
    velocity: [f64; N],
    spin: Vec<f64>,
    orientation: Matrix<N>,
}

/// One contact of the phase portrait: time, body (index into [`Animation::bodies`]),
/// coordinate `s`, `sin phi`.
pub type CloudPoint = (f64, usize, f64, f64);

/// A recorded animation: what the page draws, in screen coordinates (`x` right, `y` up, in
/// the scene's length unit).
#[derive(Clone, Debug, PartialEq)]
pub struct Animation {
    /// The page's title (the scene file's name).
    pub title: String,
    /// The dimension `n`.
    pub dim: usize,
    /// The balls of the run.
    pub balls: usize,
    /// Each drawn ball's radius.
    pub radius: Vec<f64>,
    /// Each drawn ball's species index.
    pub species: Vec<usize>,
    /// The time of frame 0.
    pub t0: f64,
    /// The time between frames.
    pub dt: f64,
    /// Per frame, per drawn ball, `[x, y, depth, mark_x, mark_y]` (depth 0 in 2D).
    pub frames: Vec<Vec<[f64; 5]>>,
    /// Per frame, the contacts up to it.
    pub contacts: Vec<u64>,
    /// The run's end time and contacts (the frames may show only its beginning).
    pub end: (f64, u64),
    /// Per frame, per trailed ball, its contact positions `[x, y]` since the frame before.
    pub trails: Vec<Vec<Vec<[f64; 2]>>>,
    /// The view, `[x_min, y_min, x_max, y_max]`, and depth range `[min, max]`.
    pub view: [f64; 4],
    /// The depth range `[near, far]` of the box (0 in 2D).
    pub depth: [f64; 2],
    /// The table's segments `[x0, y0, x1, y1]` (box edges, walls, polygon edges).
    pub segments: Vec<[f64; 4]>,
    /// The table's round bodies `[x, y, r]` (obstacles, containers, spheres).
    pub circles: Vec<[f64; 3]>,
    /// The bodies of the phase portrait (one-ball tables), with their axes labels.
    pub bodies: Vec<(Body, [&'static str; 2])>,
    /// The portrait's cloud.
    pub cloud: Vec<CloudPoint>,
    /// Per frame, the portrait's contact in effect: `(body, s, sin phi)`.
    pub current: Vec<Option<(usize, f64, f64)>>,
}

/// The rows of the projection (`x`, `y`, depth) for dimension `n`.
fn projection<const N: usize>() -> [[f64; N]; 3] {
    let mut p = [[0.0; N]; 3];
    if N == 2 {
        p[0][0] = 1.0;
        p[1][1] = 1.0;
        return p;
    }
    let (sa, ca) = YAW.sin_cos();
    let (sb, cb) = PITCH.sin_cos();
    // Orthonormal rows; x cross y = -depth, so larger depth is farther from the viewer.
    p[0][..3].copy_from_slice(&[ca, -sa, 0.0]);
    p[1][..3].copy_from_slice(&[sb * sa, sb * ca, cb]);
    p[2][..3].copy_from_slice(&[cb * sa, cb * ca, -sb]);
    p
}

fn apply<const N: usize>(p: &[[f64; N]; 3], x: &[f64; N]) -> [f64; 3] {
    p.map(|row| row.iter().zip(x).map(|(a, b)| a * b).sum())
}

/// Records an [`Animation`] as a run goes: [`Recorder::observe`] after each contact,
/// [`Recorder::finish`] at the end.
#[derive(Clone, Debug)]
pub struct Recorder<const N: usize> {
    title: String,
    cap: usize,
    project: [[f64; N]; 3],
    origin: [f64; N],
    size: [f64; N],
    periodic: [bool; N],
    keys: Vec<Key<N>>,
    shown: usize,
    balls: usize,
    radius: Vec<f64>,
    species: Vec<usize>,
    t0: f64,
    dt: f64,
    dt_max: f64,
    full: bool,
    frames: Vec<Vec<[f64; 5]>>,
    contacts_at: Vec<u64>,
    trails: Vec<Vec<Vec<[f64; 2]>>>,
    pending: Vec<Vec<[f64; 2]>>,
    contacts: u64,
    portrait: bool,
    bodies: Vec<(Body, [&'static str; 2])>,
    cloud: Vec<CloudPoint>,
    stride: u64,
    seen: u64,
    now_contact: Option<(usize, f64, f64)>,
    current: Vec<Option<(usize, f64, f64)>>,
}

impl<const N: usize> Recorder<N> {
    /// Start recording `sim` (at its present time) under `title`.
    pub fn new<const S: usize, K: PairKernels<f64, N, S>>(
        sim: &Simulation<N, S, K>,
        species: &[collision_core::Ball<f64>],
        title: &str,
    ) -> Self {
        let shown = sim.len().min(MAX_BALLS);
        let cap = (BALL_FRAMES / shown.max(1)).clamp(2, MAX_FRAMES);
        let keys: Vec<Key<N>> = (0..shown)
            .map(|i| Key {
                time: sim.now(),
                position: sim.position(i),
                velocity: sim.state(i).velocity,
                spin: sim.state(i).spin.to_vec(),
                orientation: identity::<N>(),
            })
            .collect();
        let size = sim.box_size();
        let speed = keys
            .iter()
            .map(|k| k.velocity.iter().map(|v| v * v).sum::<f64>().sqrt())
            .fold(0.0, f64::max);
        let side = size.iter().copied().fold(f64::INFINITY, f64::min);
        let dt = if speed > 0.0 && side.is_finite() {
            side / speed / 64.0
        } else {
            1.0
        };
        let mut rec = Recorder {
            title: title.to_string(),
            cap,
            project: projection::<N>(),
            origin: sim.table().origin,
            size,
            periodic: sim.periodic(),
            shown,
            balls: sim.len(),
            radius: (0..shown)
                .map(|i| species[sim.species_of(i)].radius)
                .collect(),
            species: (0..shown).map(|i| sim.species_of(i)).collect(),
            t0: sim.now(),
            dt,
            dt_max: MAX_SLOWDOWN * dt,
            full: false,
            frames: Vec::new(),
            contacts_at: Vec::new(),
            trails: Vec::new(),
            pending: vec![Vec::new(); shown.min(TRAILS)],
            contacts: 0,
            portrait: sim.len() == 1,
            bodies: Vec::new(),
            cloud: Vec::new(),
            stride: 1,
            seen: 0,
            now_contact: None,
            current: Vec::new(),
            keys,
        };
        rec.frames_until(sim.now());
        rec
    }

    /// The frame time of frame `k`.
    fn time_of(&self, k: usize) -> f64 {
        self.t0 + k as f64 * self.dt
    }

    /// A point in the picture: from the table's origin, wrapped on periodic axes, projected.
    fn screen(&self, x: &[f64; N]) -> [f64; 3] {
        let local: [f64; N] = std::array::from_fn(|k| {
            let v = x[k] - self.origin[k];
            if self.periodic[k] {
                v.rem_euclid(self.size[k])
            } else {
                v
            }
        });
        apply(&self.project, &local)
    }

    /// Emit the frames at times `<= t` not yet emitted (none once the frames are full).
    fn frames_until(&mut self, t: f64) {
        while !self.full && self.time_of(self.frames.len()) <= t {
            if self.frames.len() >= self.cap {
                if 2.0 * self.dt <= self.dt_max {
                    self.thin_frames();
                } else {
                    self.full = true;
                }
                continue;
            }
            let at = self.time_of(self.frames.len());
            let frame: Vec<[f64; 5]> = self
                .keys
                .iter()
                .map(|k| {
                    let dt = at - k.time;
                    let x: [f64; N] = std::array::from_fn(|j| k.position[j] + dt * k.velocity[j]);
                    let a = mul(&exp_skew::<N>(&k.spin, dt), &k.orientation);
                    let axis: [f64; N] = std::array::from_fn(|j| a[j][0]);
                    let s = self.screen(&x);
                    let m = apply(&self.project, &axis);
                    [s[0], s[1], s[2], m[0], m[1]]
                })
                .collect();
            self.frames.push(frame);
            self.contacts_at.push(self.contacts);
            let trail = std::mem::take(&mut self.pending);
            self.trails.push(trail.into_iter().map(thin).collect());
            self.pending = vec![Vec::new(); self.shown.min(TRAILS)];
            self.current.push(self.now_contact);
        }
    }

    /// Drop every other frame (keep frames `0, 2, 4, ..`) and double `dt`; a dropped frame's
    /// trail points and positions move into the next kept frame's (or the pending) trail.
    fn thin_frames(&mut self) {
        let frames = std::mem::take(&mut self.frames);
        let trails = std::mem::take(&mut self.trails);
        let mut carry: Vec<Vec<[f64; 2]>> = vec![Vec::new(); self.shown.min(TRAILS)];
        for (k, (frame, mut trail)) in frames.into_iter().zip(trails).enumerate() {
            if k % 2 == 1 {
                for (b, c) in carry.iter_mut().enumerate() {
                    c.append(&mut trail[b]);
                    c.push([frame[b][0], frame[b][1]]);
                }
                continue;
            }
            for (b, c) in carry.iter_mut().enumerate() {
                c.append(&mut trail[b]);
                trail[b] = thin(std::mem::take(c));
            }
            self.frames.push(frame);
            self.trails.push(trail);
        }
        for (b, c) in carry.into_iter().enumerate() {
            let mut merged = c;
            merged.append(&mut self.pending[b]);
            self.pending[b] = thin(merged);
        }
        every_other(&mut self.contacts_at);
        every_other(&mut self.current);
        self.dt *= 2.0;
    }

    /// Take the contact `e` (the `index`-th of the run), `sim` at its time.
    pub fn observe<const S: usize, K: PairKernels<f64, N, S>>(
        &mut self,
        index: u64,
        e: &Event<N, S>,
        sim: &Simulation<N, S, K>,
        species: &[collision_core::Ball<f64>],
    ) {
        self.frames_until(e.time);
        self.contacts = index;
        if self.portrait {
            if let Some(row) = boundary_map::row(index, e, sim, species) {
                self.portrait_point(sim, &row);
            }
        }
        if self.full {
            return;
        }
        for i in e.contact.balls().filter(|&i| i < self.shown) {
            let key = &mut self.keys[i];
            let turn = exp_skew::<N>(&key.spin, e.time - key.time);
            key.orientation = mul(&turn, &key.orientation);
            key.time = e.time;
            key.position = sim.position(i);
            key.velocity = sim.state(i).velocity;
            key.spin = sim.state(i).spin.to_vec();
            let position = key.position;
            if i < self.pending.len() {
                let s = self.screen(&position);
                self.pending[i].push([s[0], s[1]]);
                if self.pending[i].len() > 2 * TRAIL_POINTS {
                    self.pending[i] = thin(std::mem::take(&mut self.pending[i]));
                }
            }
        }
    }

    fn portrait_point<const S: usize, K: PairKernels<f64, N, S>>(
        &mut self,
        sim: &Simulation<N, S, K>,
        row: &boundary_map::Row,
    ) {
        let body = match self.bodies.iter().position(|(b, _)| *b == row.body) {
            Some(k) => k,
            None => {
                let labels = Axes::of(sim.table(), row.body).labels()[0];
                self.bodies.push((row.body, labels));
                self.bodies.len() - 1
            }
        };
        let point = (body, row.coordinate, row.reflection.sin());
        self.now_contact = Some(point);
        if self.seen % self.stride == 0 {
            self.cloud.push((row.time, point.0, point.1, point.2));
            if self.cloud.len() > CLOUD_POINTS {
                every_other(&mut self.cloud);
                self.stride *= 2;
            }
        }
        self.seen += 1;
    }

    /// The animation, with the frames up to `sim`'s present time.
    pub fn finish<const S: usize, K: PairKernels<f64, N, S>>(
        mut self,
        sim: &Simulation<N, S, K>,
    ) -> Animation {
        self.frames_until(sim.now());
        let (segments, circles, view, depth) = self.table_lines(sim);
        Animation {
            title: self.title,
            dim: N,
            balls: self.balls,
            radius: self.radius,
            species: self.species,
            t0: self.t0,
            dt: self.dt,
            frames: self.frames,
            contacts: self.contacts_at,
            end: (sim.now(), self.contacts),
            trails: self.trails,
            view,
            depth,
            segments,
            circles,
            bodies: self.bodies,
            cloud: self.cloud,
            current: self.current,
        }
    }
}

/// Keep items `0, 2, 4, ..` of `v`.
fn every_other<T>(v: &mut Vec<T>) {
    let mut k = 0;
    v.retain(|_| {
        k += 1;
        k % 2 == 1
    });
}

/// Keep at most [`TRAIL_POINTS`] of `points`, evenly (the last one always).
fn thin(points: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    let n = points.len();
    if n <= TRAIL_POINTS {
        return points;
    }
    (1..=TRAIL_POINTS)
        .map(|k| points[k * n / TRAIL_POINTS - 1])
        .collect()
}

#[path = "animation_table.rs"]
mod table;
#[cfg(test)]
#[path = "animation_tests.rs"]
mod tests;
