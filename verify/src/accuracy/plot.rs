//! The error-against-run-time plot of one dimension (SVG, via plotters): one point per
//! variant, filled for the typical regime and hollow for its worst regime, and the Pareto
//! frontier of the typical points (no other variant is both faster and more accurate).

use super::run::{DimResult, VariantResult};
use plotters::prelude::*;

/// Where the exact variant (zero error) sits on the log error axis.
const EXACT_FLOOR: f64 = 1e-20;

/// `(time in ns, max normwise relative error)` of a variant in one regime.
fn point(v: &VariantResult) -> Option<(f64, f64)> {
    let t = v.timing?.median_ns;
    let eps = v.variant.epsilon();
    let err = if eps == 0.0 {
        EXACT_FLOOR
    } else {
        (v.normwise_eps.max * eps).max(EXACT_FLOOR)
    };
    (v.evaluated > 0 && err.is_finite()).then_some((t, err))
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

/// The SVG text of the plot for one dimension.
pub fn svg(dim: &DimResult) -> Result<String, String> {
    let typical = &dim.regimes[0];
    let labelled: Vec<(String, (f64, f64))> = typical
        .variants
        .iter()
        .filter_map(|v| Some((v.name.clone(), point(v)?)))
        .collect();
    let worst: Vec<(f64, f64)> = typical
        .variants
        .iter()
        .filter_map(|v| {
            let t = v.timing?.median_ns;
            let err = dim
                .regimes
                .iter()
                .filter_map(|r| r.variants.iter().find(|w| w.variant == v.variant))
                .filter_map(point)
                .map(|p| p.1)
                .fold(f64::NAN, f64::max);
            err.is_finite().then_some((t, err))
        })
        .collect();
    let pts: Vec<(f64, f64)> = labelled.iter().map(|l| l.1).collect();
    let all = pts.iter().chain(&worst);
    let (mut x0, mut x1, mut y1) = (f64::INFINITY, 0.0f64, 0.0f64);
    for &(x, y) in all {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y1 = y1.max(y);
    }
    if pts.is_empty() {
        return Err("no timed variant to plot".into());
    }
    let err = |e: &dyn std::fmt::Display| e.to_string();
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, (860, 520)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(&e))?;
        let title = format!(
            "n = {}: max normwise error against median time per collision",
            dim.dim
        );
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 18))
            .margin(16)
            .x_label_area_size(44)
            .y_label_area_size(70)
            .build_cartesian_2d(
                (x0 / 2.0..x1 * 3.0).log_scale(),
                (EXACT_FLOOR / 10.0..(y1 * 100.0).max(1e-3)).log_scale(),
            )
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc("median ns per collision (log)")
            .y_desc("max normwise relative error (log; exact at 1e-20)")
            .y_label_formatter(&|y| format!("{y:.0e}"))
            .x_label_formatter(&|x| format!("{x:.0}"))
            .draw()
            .map_err(|e| err(&e))?;
        let front: Vec<(f64, f64)> = frontier(&pts).into_iter().map(|i| pts[i]).collect();
        chart
            .draw_series(LineSeries::new(front, RED.stroke_width(2)))
            .map_err(|e| err(&e))?
            .label("Pareto frontier (typical regime)")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], RED));
        chart
            .draw_series(pts.iter().map(|&p| Circle::new(p, 5, BLUE.filled())))
            .map_err(|e| err(&e))?
            .label("typical regime")
            .legend(|(x, y)| Circle::new((x + 9, y), 5, BLUE.filled()));
        chart
            .draw_series(
                worst
                    .iter()
                    .map(|&p| Cross::new(p, 6, BLACK.stroke_width(2))),
            )
            .map_err(|e| err(&e))?
            .label("worst regime")
            .legend(|(x, y)| Cross::new((x + 9, y), 6, BLACK.stroke_width(2)));
        chart
            .draw_series(
                labelled
                    .iter()
                    .map(|(name, p)| Text::new(name.clone(), *p, ("sans-serif", 13).into_font())),
            )
            .map_err(|e| err(&e))?;
        chart
            .configure_series_labels()
            .border_style(BLACK)
            .background_style(WHITE.mix(0.9))
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(|e| err(&e))?;
        root.present().map_err(|e| err(&e))?;
    }
    Ok(out)
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
