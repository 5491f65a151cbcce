//! The region a scene's table occupies: its box, or without one the bounding box of its
//! defining points, widened. The engine's length scale and the pictures' frame.

use crate::nearest::f;
use noslip_scene::Scene;
use num_rational::BigRational;

/// The region a table without a box is drawn in and measured by: the bounding box of its
/// defining points (wall points, containers, polygon vertices, obstacles, balls with their
/// radii), widened by a tenth of its largest side on each end: `(lower corner, sides)`. With a
/// box: `([0; N], box sides)`.
pub fn extent<const N: usize>(scene: &Scene) -> ([f64; N], [f64; N]) {
    let (lo, size) = extent_dyn(scene);
    (
        std::array::from_fn(|k| lo[k]),
        std::array::from_fn(|k| size[k]),
    )
}

/// [`extent`] for any dimension (`scene.dim` components).
pub fn extent_dyn(scene: &Scene) -> (Vec<f64>, Vec<f64>) {
    let n = scene.dim;
    if !scene.size.is_empty() {
        return (vec![0.0; n], scene.size.iter().map(f).collect());
    }
    let mut lo = vec![f64::INFINITY; n];
    let mut hi = vec![f64::NEG_INFINITY; n];
    let mut add = |p: &[BigRational], r: f64| {
        for k in 0..n {
            let x = f(&p[k]);
            lo[k] = lo[k].min(x - r);
            hi[k] = hi[k].max(x + r);
        }
    };
    for b in &scene.boundaries {
        match &b.shape {
            noslip_scene::Shape::Wall { point, .. } | noslip_scene::Shape::Vertex { point } => {
                add(point, 0.0)
            }
            noslip_scene::Shape::Container { centre, radius } => add(centre, f(radius)),
            noslip_scene::Shape::Edge { from, to, .. } => {
                add(from, 0.0);
                add(to, 0.0);
            }
        }
    }
    for o in &scene.obstacles {
        add(&o.position, f(&o.radius));
    }
    for b in &scene.balls {
        add(&b.position, f(&scene.species[b.species].radius));
    }
    let side = (0..n).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
    let margin = 0.1 * side;
    let lo: Vec<f64> = (0..n).map(|k| lo[k] - margin).collect();
    let size = (0..n)
        .map(|k| (hi[k] + margin - lo[k]).max(0.2 * side))
        .collect();
    (lo, size)
}
