//! The traced paths and contact points of the 2D picture, thinned as the run goes so that
//! memory and the picture stay bounded whatever the number of events.
//!
//! **Paths.** Between its events a ball flies straight, `a(t) = a + t u`. Each flight is drawn
//! exactly: from the ball's last event position with its velocity since then, to its next
//! event position. The flight's displacement `u dt` says how many box lengths it crossed on
//! each axis (`round((a + u dt - a_event) / L)`: exact while the rounding of `u dt` is far
//! below `L / 2`), so the flight is cut where it crosses `x = j L` and each part is drawn
//! shifted back into the box, as a new piece: a wrap never draws a chord. A flight along a
//! walled axis stays inside `[R, L - R]`, so the same rule draws it unchanged; no wrap is
//! inferred from the logged positions.
//!
//! **Thinning.** A point within half a pixel of the last kept point of its piece is dropped
//! (the drawn polyline then stays within half a pixel of the path). The paths stop when they
//! have drawn [`INK`] pixels of line (beyond that the picture turns solid and shows nothing
//! more), or when the kept points and pieces reach [`PATH_BUDGET`] (a piece costing
//! [`PIECE_COST`] points, about its SVG overhead), whichever comes first; [`Tracer::until`]
//! is then the time up to which the paths are drawn (each ball's up to its last event before
//! it).
//!
//! **Contact points** are wrapped into the box (a ball-ball contact across a periodic face
//! lies up to `R` outside it; points within half a pixel of the box are only clamped) and
//! kept once per picture pixel, at most [`CONTACT_DOTS`] of them (the first ones met).

/// Pixels on the longer side of the box in the picture.
pub const PICTURE: f64 = 720.0;

/// The budget of kept path points (with [`PIECE_COST`] per piece) over all traced balls:
/// about 8 bytes of SVG per point, so at most about 400 kB of paths.
pub const PATH_BUDGET: usize = 48_000;

/// The most line drawn, in picture pixels: about 12 % of a 720 x 720 picture, where paths
/// are still told apart.
pub const INK: f64 = 60_000.0;

/// What a new piece costs in points (a polyline element's SVG overhead is about 12 points').
pub const PIECE_COST: usize = 12;

/// The most contact points drawn (one per pixel; about 90 bytes of SVG each).
pub const CONTACT_DOTS: usize = 4_000;

/// A traced ball's last event: time, position (in the box) and velocity since.
#[derive(Clone, Copy, Debug)]
struct Last {
    time: f64,
    position: [f64; 2],
    velocity: [f64; 2],
}

/// The state of the picture's traces; see the module docs.
#[derive(Clone, Debug)]
pub struct Tracer {
    size: [f64; 2],
    /// Half a pixel in box units.
    tol: f64,
    /// Picture pixels per box unit.
    scale: f64,
    /// Line drawn so far, in pixels.
    ink: f64,
    last: Vec<Last>,
    /// Per traced ball, its pieces of path.
    pub paths: Vec<Vec<Vec<[f64; 2]>>>,
    cost: usize,
    full: bool,
    /// The time up to which every path is drawn (the run's end unless the budget ran out).
    pub until: f64,
    /// The kept contact points.
    pub contacts: Vec<[f64; 2]>,
    pixels: [usize; 2],
    seen: Vec<u64>,
}

impl Tracer {
    /// Traces of balls starting at `start` (position, velocity) at time `t0`, in a box of
    /// sides `size` (first two axes).
    pub fn new(size: [f64; 2], t0: f64, start: &[([f64; 2], [f64; 2])]) -> Self {
        let scale = PICTURE / size[0].max(size[1]);
        let pixels = [
            (size[0] * scale).ceil() as usize + 1,
            (size[1] * scale).ceil() as usize + 1,
        ];
        let mut t = Tracer {
            size,
            tol: 0.5 / scale,
            scale,
            ink: 0.0,
            last: start
                .iter()
                .map(|&(position, velocity)| Last {
                    time: t0,
                    position: std::array::from_fn(|k| position[k].clamp(0.0, size[k])),
                    velocity,
                })
                .collect(),
            paths: start.iter().map(|(p, _)| vec![vec![*p]]).collect(),
            cost: 0,
            full: false,
            until: t0,
            contacts: Vec::new(),
            pixels,
            seen: vec![0; (pixels[0] * pixels[1]).div_ceil(64)],
        };
        t.cost = start.len() * (PIECE_COST + 1);
        t
    }

    /// The number of kept path points.
    pub fn points(&self) -> usize {
        self.paths.iter().flatten().map(Vec::len).sum()
    }

    /// Ball `b` reaches `end` (in the box) at `time` and flies on with `velocity`.
    pub fn flight(&mut self, b: usize, time: f64, end: [f64; 2], velocity: [f64; 2]) {
        // Positions are in the box up to rounding; clamped, a rounding never draws a piece.
        let end: [f64; 2] = std::array::from_fn(|k| end[k].clamp(0.0, self.size[k]));
        let last = self.last[b];
        let dt = time - last.time;
        let mut to = end;
        for k in 0..2 {
            let moved = last.position[k] + last.velocity[k] * dt;
            to[k] = end[k] + ((moved - end[k]) / self.size[k]).round() * self.size[k];
        }
        if !self.full {
            self.segment(b, last.position, to, last.time, dt);
            if !self.full {
                self.until = self.until.max(time);
            }
        }
        self.last[b] = Last {
            time,
            position: end,
            velocity,
        };
    }

    /// Draw every ball's flight in progress up to `now`, where ball `b` is at `ends[b]` (in
    /// the box).
    pub fn finish(&mut self, now: f64, ends: &[[f64; 2]]) {
        for (b, &end) in ends.iter().enumerate() {
            let v = self.last[b].velocity;
            self.flight(b, now, end, v);
        }
    }

    /// The next parameter `s` in `(after, 1)` at which `p + s (q - p)` crosses `x_k = j L_k`.
    fn next_crossing(&self, k: usize, p: f64, q: f64, after: f64) -> Option<f64> {
        if p == q {
            return None;
        }
        let l = self.size[k];
        let x = p + after * (q - p);
        let j = if q > p {
            (x / l).floor() + 1.0
        } else {
            (x / l).ceil() - 1.0
        };
        let s = (j * l - p) / (q - p);
        (s > after && s < 1.0).then_some(s)
    }

    /// Draw the straight flight from `p` (in the box) to `q` (unwrapped), which starts at
    /// `t0` and lasts `dt`.
    fn segment(&mut self, b: usize, p: [f64; 2], q: [f64; 2], t0: f64, dt: f64) {
        let at = |s: f64| [p[0] + s * (q[0] - p[0]), p[1] + s * (q[1] - p[1])];
        let mut offset = [0.0f64; 2];
        let mut s0 = 0.0;
        while s0 < 1.0 {
            let s1 = [0, 1]
                .iter()
                .filter_map(|&k| self.next_crossing(k, p[k], q[k], s0))
                .fold(1.0, f64::min);
            if s1 > s0 {
                let mid = at(0.5 * (s0 + s1));
                let o: [f64; 2] = std::array::from_fn(|k| (mid[k] / self.size[k]).floor());
                // Back into the box (clamped: the shift is exact only up to rounding).
                let shift = |x: [f64; 2]| -> [f64; 2] {
                    std::array::from_fn(|k| (x[k] - o[k] * self.size[k]).clamp(0.0, self.size[k]))
                };
                if o != offset {
                    offset = o;
                    self.paths[b].push(vec![shift(at(s0))]);
                    self.cost += PIECE_COST + 1;
                }
                self.point(b, shift(at(s1)));
                if self.cost >= PATH_BUDGET || self.ink >= INK {
                    self.full = true;
                    self.until = t0 + s1 * dt;
                    return;
                }
            }
            s0 = s1;
        }
    }

    /// Keep `x` unless it is within half a pixel of the last kept point.
    fn point(&mut self, b: usize, x: [f64; 2]) {
        let piece = self.paths[b].last_mut().expect("a piece");
        let last = piece.last().expect("a point");
        let length = (x[0] - last[0]).hypot(x[1] - last[1]);
        if length >= self.tol {
            piece.push(x);
            self.cost += 1;
            self.ink += length * self.scale;
        }
    }

    /// A contact point (first two coordinates), kept if its pixel is new.
    pub fn contact(&mut self, x: [f64; 2]) {
        if self.contacts.len() >= CONTACT_DOTS {
            return;
        }
        let x: [f64; 2] = std::array::from_fn(|k| {
            let l = self.size[k];
            if (-self.tol..=l + self.tol).contains(&x[k]) {
                x[k].clamp(0.0, l)
            } else {
                x[k].rem_euclid(l)
            }
        });
        let pixel: [usize; 2] = std::array::from_fn(|k| {
            ((x[k] * self.scale).max(0.0) as usize).min(self.pixels[k] - 1)
        });
        let bit = pixel[1] * self.pixels[0] + pixel[0];
        if self.seen[bit / 64] & (1 << (bit % 64)) == 0 {
            self.seen[bit / 64] |= 1 << (bit % 64);
            self.contacts.push(x);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_wrapping_flight_is_cut_at_the_faces() {
        // From (0.9, 0.5) with velocity (0.5, 0.25) for 0.6: to (1.2, 0.65), i.e. (0.2, 0.65)
        // in the box, crossing x = 1 at s = 1/3.
        let mut t = Tracer::new([1.0, 1.0], 0.0, &[([0.9, 0.5], [0.5, 0.25])]);
        t.flight(0, 0.6, [0.2, 0.65], [0.0, 0.0]);
        let pieces = &t.paths[0];
        assert_eq!(pieces.len(), 2, "{pieces:?}");
        let close = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).abs() + (a[1] - b[1]).abs() < 1e-12;
        assert!(close(pieces[0][0], [0.9, 0.5]) && close(pieces[0][1], [1.0, 0.55]));
        assert!(close(pieces[1][0], [0.0, 0.55]) && close(pieces[1][1], [0.2, 0.65]));
    }

    /// `(cost, ink in pixels)` of the kept paths.
    fn spent(t: &Tracer) -> (usize, f64) {
        let mut ink = 0.0;
        for piece in t.paths.iter().flatten() {
            for w in piece.windows(2) {
                ink += (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]) * t.scale;
            }
        }
        (
            t.points() + PIECE_COST * t.paths.iter().map(Vec::len).sum::<usize>(),
            ink,
        )
    }

    #[test]
    fn long_flights_stop_at_the_ink_budget() {
        // A fast ball in a small periodic box: every flight wraps hundreds of times.
        let mut t = Tracer::new([1.0, 1.0], 0.0, &[([0.5, 0.5], [300.0, 170.0])]);
        for i in 1..=10_000 {
            let time = i as f64;
            let end = [
                (0.5 + 300.0 * time).rem_euclid(1.0),
                (0.5 + 170.0 * time).rem_euclid(1.0),
            ];
            t.flight(0, time, end, [300.0, 170.0]);
        }
        let (cost, ink) = spent(&t);
        // The last kept segment may pass the budget by at most a box diagonal.
        assert!(ink >= INK && ink <= INK + 2f64.sqrt() * PICTURE, "{ink}");
        assert!(cost < PATH_BUDGET, "{cost}");
        assert!(t.until > 0.0 && t.until < 1.0, "{}", t.until);
        for p in t.paths[0].iter().flatten() {
            assert!(
                (0.0..=1.0).contains(&p[0]) && (0.0..=1.0).contains(&p[1]),
                "{p:?}"
            );
        }
    }

    #[test]
    fn many_short_wrapping_flights_stop_at_the_point_budget() {
        // Back and forth across the face x = 1 (= 0): two pieces per flight, little ink.
        let mut t = Tracer::new([1.0, 1.0], 0.0, &[([0.999, 0.5], [0.002, 0.0])]);
        for i in 1..=100_000 {
            let (end, v) = if i % 2 == 1 {
                (0.001, -0.002)
            } else {
                (0.999, 0.002)
            };
            t.flight(0, i as f64, [end, 0.5], [v, 0.0]);
        }
        let (cost, ink) = spent(&t);
        assert!(
            (PATH_BUDGET..=PATH_BUDGET + PIECE_COST + 1).contains(&cost),
            "{cost}"
        );
        assert!(ink < INK, "{ink}");
        assert!(t.paths[0].len() > 1000 && t.until < 100_000.0);
    }
}
