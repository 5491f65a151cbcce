//! The figures plotted per variant ([`Entry`]): its median time, its max normwise relative
//! error in the typical regime and in its worst one, its non-finite results; and the Pareto
//! frontier of the typical points (no other point both faster and more accurate).

use super::marker::{Shape, COLOURS, SHAPES};
use crate::report::{DimResult, MethodResult};
use plotters::prelude::RGBColor;

/// A variant's place in the plot.
pub(super) struct Entry {
    pub(super) name: String,
    pub(super) colour: RGBColor,
    pub(super) shape: Shape,
    /// Median ns per collision.
    pub(super) time: f64,
    /// Max normwise relative error, typical regime (0 for the exact kernel).
    pub(super) typical: f64,
    /// The largest over all regimes, and that regime's name.
    pub(super) worst: (f64, String),
    /// Cases with a NaN or infinite result over all regimes, and those regimes.
    pub(super) non_finite: (usize, Vec<String>),
}

/// Max normwise relative error of a variant's run (normwise eps times the format's eps).
fn error(v: &MethodResult) -> Option<f64> {
    (v.evaluated > 0).then(|| v.normwise_eps.max * v.variant.epsilon())
}

/// The entry of every variant of `dim` with a timing and a result, in report order.
pub(super) fn entries(dim: &DimResult) -> Vec<Entry> {
    let typical = &dim.regimes[0];
    typical
        .variants
        .iter()
        .enumerate()
        .filter_map(|(k, v)| {
            let time = v.timing?.median_ns;
            let typical_error = error(v)?;
            let mut worst = (typical_error, typical.name.clone());
            let mut non_finite = (0, Vec::new());
            for r in &dim.regimes {
                let Some(w) = r.variants.iter().find(|w| w.variant == v.variant) else {
                    continue;
                };
                if w.non_finite > 0 {
                    non_finite.0 += w.non_finite;
                    non_finite.1.push(r.name.clone());
                }
                if let Some(e) = error(w).filter(|e| *e > worst.0) {
                    worst = (e, r.name.clone());
                }
            }
            Some(Entry {
                name: v.name.clone(),
                colour: COLOURS[k % COLOURS.len()],
                shape: SHAPES[k % SHAPES.len()],
                time,
                typical: typical_error,
                worst,
                non_finite,
            })
        })
        .collect()
}

/// Indices of the points on the Pareto frontier (minimal time and error), by time.
pub fn frontier(points: &[(f64, f64)]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_by(|&a, &b| points[a].0.total_cmp(&points[b].0));
    let mut best = f64::INFINITY;
    order
        .into_iter()
        .filter(|&i| {
            let keep = points[i].1 < best;
            best = best.min(points[i].1);
            keep
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_frontier_keeps_only_undominated_points() {
        // (time, error): b is dominated by a (slower and less accurate).
        let pts = [(1.0, 1e-16), (2.0, 1e-15), (3.0, 1e-30), (0.5, 1e-7)];
        assert_eq!(frontier(&pts), vec![3, 0, 2]);
    }
}
