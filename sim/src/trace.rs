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

    /// Draw the straight flight from `p` (in the box) to `q` (unwrapped), which starts at
    /// `t0` and lasts `dt`.
    ///
    /// The copy of the box the flight is in is counted in whole box lengths per axis
    /// (`copy`), starting at 0 and stepped by one at each face crossed: the next face along
    /// axis `k` is `(copy_k + 1) L_k` moving up, `copy_k L_k` moving down, at parameter
    /// `s = (face - p_k) / (q_k - p_k)`. Counting the copies, instead of recomputing them
    /// from rounded positions, crosses every face exactly once (a crossing recomputed from
    /// `p + s (q - p)` near a face could be missed, drawing a chord across the box). A flight
    /// that does not start where the last one was drawn (its start was wrapped onto the
    /// opposite face) starts a new piece.
    fn segment(&mut self, b: usize, p: [f64; 2], q: [f64; 2], t0: f64, dt: f64) {
        let at = |s: f64| [p[0] + s * (q[0] - p[0]), p[1] + s * (q[1] - p[1])];
        let mut copy = [0i64; 2];
        let size = self.size;
        let into_box = |x: [f64; 2], copy: [i64; 2]| -> [f64; 2] {
            // Clamped: the shift is exact only up to rounding.
            std::array::from_fn(|k| (x[k] - copy[k] as f64 * size[k]).clamp(0.0, size[k]))
        };
        let last = *self.paths[b]
            .last()
            .and_then(|piece| piece.last())
            .expect("a point");
        if (0..2).any(|k| (last[k] - p[k]).abs() > 0.5 * self.size[k]) {
            self.paths[b].push(vec![p]);
            self.cost += PIECE_COST + 1;
        }
        let mut s0 = 0.0;
        loop {
            let mut next: Option<(f64, usize, i64)> = None;
            for k in 0..2 {
                let d = q[k] - p[k];
                if d == 0.0 {
                    continue;
                }
                let (face, step) = if d > 0.0 {
                    ((copy[k] + 1) as f64 * self.size[k], 1)
                } else {
                    (copy[k] as f64 * self.size[k], -1)
                };
                let s = ((face - p[k]) / d).max(s0);
                if s < 1.0 && next.is_none_or(|(t, _, _)| s < t) {
                    next = Some((s, k, step));
                }
            }
            let s1 = next.map_or(1.0, |(s, _, _)| s);
            self.point(b, into_box(at(s1), copy));
            if let Some((_, k, step)) = next {
                copy[k] += step;
                self.paths[b].push(vec![into_box(at(s1), copy)]);
                self.cost += PIECE_COST + 1;
            }
            if self.cost >= PATH_BUDGET || self.ink >= INK {
                self.full = true;
                self.until = t0 + s1 * dt;
                return;
            }
            if next.is_none() {
                return;
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

    /// Whether every segment of `pieces` runs along `v` (a chord across a wrap does not).
    fn along(pieces: &[Vec<[f64; 2]>], v: [f64; 2]) -> bool {
        pieces.iter().all(|piece| {
            piece.windows(2).all(|w| {
                let d = [w[1][0] - w[0][0], w[1][1] - w[0][1]];
                (d[0] * v[1] - d[1] * v[0]).abs() <= 1e-12 * d[0].hypot(d[1]) * v[0].hypot(v[1])
            })
        })
    }

    /// A flight crossing many faces, where the crossing parameter recomputed from the
    /// rounded position `p + s (q - p)` lands just before the face already crossed (the
    /// previous rule then found no next face and drew a chord across the box): a Sinai
    /// flight of the shipped scene, from a failing run.
    #[test]
    fn every_face_of_a_long_flight_is_crossed_once() {
        let (p, v, t0, t1) = (
            [0.16196002475981514, 0.5907136987428863],
            [-0.05821657120666317, 0.7547763269326635],
            6.669279276005103,
            12.929340250892938,
        );
        let end = [0.797520739257204, 0.31565952774323586];
        let mut t = Tracer::new([1.0, 1.0], t0, &[(p, v)]);
        t.flight(0, t1, end, [0.0, 0.0]);
        // One x face and five y faces: seven pieces, each along the flight.
        assert_eq!(t.paths[0].len(), 7, "{:?}", t.paths[0]);
        assert!(along(&t.paths[0], v), "{:?}", t.paths[0]);
        let last = *t.paths[0].last().unwrap().last().unwrap();
        assert!((last[0] - end[0]).abs() < 1e-12 && (last[1] - end[1]).abs() < 1e-12);
    }

    #[test]
    fn a_flight_starting_on_the_opposite_face_starts_a_new_piece() {
        // The first flight ends on the face y = 0; the engine wrapped the ball, which starts
        // its next flight from y = 1 (= 0): no segment may join (0.5, 0) to (0.5, 1).
        let mut t = Tracer::new([1.0, 1.0], 0.0, &[([0.5, 0.5], [0.0, -1.0])]);
        t.flight(0, 0.5, [0.5, 1.0], [0.25, -0.5]);
        t.flight(0, 1.0, [0.625, 0.75], [0.0, 0.0]);
        assert_eq!(
            t.paths[0],
            vec![
                vec![[0.5, 0.5], [0.5, 0.0]],
                vec![[0.5, 1.0], [0.625, 0.75]]
            ]
        );
    }

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
