//! What the animation draws of the table: the box's edges, walls and polygon edges as
//! segments, round bodies as circles, in the recorder's picture coordinates; and the view.
//!
//! In 2D a periodic axis shows each obstacle's images across it too (the page clips to the
//! box). For n >= 3 the box's twelve edges (of its first three axes), the round bodies'
//! outlines and each flat wall's section by the box are drawn: the polygon where the plane
//! `(x - p) . nu = 0` cuts the box of the first three axes, the other coordinates at the
//! box's middle ([`wall_section`]).

use super::Recorder;
use crate::table::Shape;
use crate::{PairKernels, Simulation};

/// Segments, circles, the view `[x_min, y_min, x_max, y_max]` and the depth range.
type Lines = (Vec<[f64; 4]>, Vec<[f64; 3]>, [f64; 4], [f64; 2]);

impl<const N: usize> Recorder<N> {
    /// The table of `sim` in the picture's coordinates (see the module docs).
    pub(super) fn table_lines<const S: usize, K: PairKernels<f64, N, S>>(
        &self,
        sim: &Simulation<N, S, K>,
    ) -> Lines {
        let local = |x: &[f64; N]| -> [f64; N] { std::array::from_fn(|k| x[k] - self.origin[k]) };
        let project = |x: &[f64; N]| super::apply(&self.project, x);
        let mut segments = Vec::new();
        let mut circles = Vec::new();
        // The box's corners over its first (two or three) axes, from the origin.
        let axes = N.min(3);
        let corners: Vec<[f64; N]> = (0..1usize << axes)
            .map(|bits| {
                std::array::from_fn(|k| {
                    if k < axes && bits >> k & 1 == 1 {
                        self.size[k]
                    } else {
                        0.0
                    }
                })
            })
            .collect();
        if sim.table().boxed {
            for (a, ca) in corners.iter().enumerate() {
                for (b, cb) in corners.iter().enumerate().skip(a + 1) {
                    if (a ^ b).count_ones() == 1 {
                        let (p, q) = (project(ca), project(cb));
                        segments.push([p[0], p[1], q[0], q[1]]);
                    }
                }
            }
        }
        let images = |k: usize| -> Vec<f64> {
            if N == 2 && self.periodic[k] {
                vec![-self.size[k], 0.0, self.size[k]]
            } else {
                vec![0.0]
            }
        };
        let mut round = |centre: [f64; N], r: f64| {
            for sx in images(0) {
                for sy in images(1) {
                    let mut c = centre;
                    c[0] += sx;
                    c[1] += sy;
                    let p = project(&c);
                    circles.push([p[0], p[1], r]);
                }
            }
        };
        for o in sim.obstacles() {
            round(local(&o.position), o.radius);
        }
        let reach = 2.0 * self.size.iter().map(|s| s.abs()).sum::<f64>();
        for b in &sim.table().boundaries {
            match &b.shape {
                Shape::Container { centre, radius } | Shape::Sphere { centre, radius } => {
                    round(local(centre), *radius)
                }
                Shape::Edge { from, to, .. } => {
                    let (p, q) = (project(&local(from)), project(&local(to)));
                    segments.push([p[0], p[1], q[0], q[1]]);
                }
                Shape::Wall { point, normal } if N == 2 => {
                    let p = local(point);
                    let t = [normal[1], -normal[0]];
                    segments.push([
                        p[0] - reach * t[0],
                        p[1] - reach * t[1],
                        p[0] + reach * t[0],
                        p[1] + reach * t[1],
                    ]);
                }
                Shape::Wall { point, normal } => {
                    for [a, b] in wall_section(&local(point), normal, &self.size) {
                        let (p, q) = (project(&a), project(&b));
                        segments.push([p[0], p[1], q[0], q[1]]);
                    }
                }
            }
        }
        let pad = self.radius.iter().copied().fold(0.0, f64::max);
        let mut view = [
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ];
        let mut depth = [f64::INFINITY, f64::NEG_INFINITY];
        for c in &corners {
            let p = project(c);
            view = [
                view[0].min(p[0]),
                view[1].min(p[1]),
                view[2].max(p[0]),
                view[3].max(p[1]),
            ];
            depth = [depth[0].min(p[2]), depth[1].max(p[2])];
        }
        if N > 2 {
            view = [view[0] - pad, view[1] - pad, view[2] + pad, view[3] + pad];
            depth = [depth[0] - pad, depth[1] + pad];
        }
        (segments, circles, view, depth)
    }
}

/// The outline of the section of the box `[0, size_k]` (its first three axes; the other
/// coordinates `x_k = size_k / 2`) by the plane `f(x) = (x - p) . nu = 0`, `n >= 3`: on each
/// face of the 3-box, the segment between the points where the plane crosses the face's
/// edges. An edge from corner `a` to `b` is crossed where `f(a)` and `f(b)` differ in sign or
/// vanish, at `a + f(a) / (f(a) - f(b)) (b - a)` (`f` is affine along it). A face the plane
/// contains (its corners all on it) or only touches (in one point) gives no segment, nor does
/// a box edge the plane contains (drawn already).
pub(super) fn wall_section<const N: usize>(
    p: &[f64; N],
    nu: &[f64; N],
    size: &[f64; N],
) -> Vec<[[f64; N]; 2]> {
    if N < 3 {
        return Vec::new();
    }
    let corner = |bits: usize| -> [f64; N] {
        std::array::from_fn(|k| match k {
            0..=2 if bits >> k & 1 == 1 => size[k],
            0..=2 => 0.0,
            _ => size[k] / 2.0,
        })
    };
    let f = |x: &[f64; N]| (0..N).map(|k| (x[k] - p[k]) * nu[k]).sum::<f64>();
    let mut segments = Vec::new();
    // A face: the axis it is normal to and its side; its corners are the 4 with that bit.
    for axis in 0..3 {
        for side in 0..2 {
            let corners: Vec<usize> = (0..8).filter(|c| (c >> axis & 1) == side).collect();
            if corners.iter().all(|&c| f(&corner(c)) == 0.0) {
                continue;
            }
            // The crossings, each with the corner it is, if it is one.
            let mut points: Vec<([f64; N], Option<usize>)> = Vec::new();
            for (i, &a) in corners.iter().enumerate() {
                for &b in &corners[i + 1..] {
                    if (a ^ b).count_ones() != 1 {
                        continue;
                    }
                    let (ca, cb) = (corner(a), corner(b));
                    let (fa, fb) = (f(&ca), f(&cb));
                    if fa * fb > 0.0 || fa == fb {
                        continue;
                    }
                    let t = fa / (fa - fb);
                    let x: [f64; N] = std::array::from_fn(|k| ca[k] + t * (cb[k] - ca[k]));
                    let at = match t {
                        0.0 => Some(a),
                        1.0 => Some(b),
                        _ => None,
                    };
                    if !points.iter().any(|(y, _)| *y == x) {
                        points.push((x, at));
                    }
                }
            }
            match points[..] {
                [(_, Some(a)), (_, Some(b))] if (a ^ b).count_ones() == 1 => {}
                [(a, _), (b, _)] => segments.push([a, b]),
                _ => {}
            }
        }
    }
    segments
}
