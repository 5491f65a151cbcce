//! The error-against-run-time plot of one dimension (SVG, via plotters), after Herbie's:
//! each variant a marker of its own colour and shape at (median time, max normwise relative
//! error) of the typical regime, filled; the same marker hollow at its worst regime's error,
//! joined to it by a line; the Pareto frontier of the typical points (no other variant both
//! faster and more accurate) as a staircase. Both axes are log10 with a label at every decade
//! (or every second one) over the whole range; the f64 and f32 epsilons are marked.
//!
//! A variant with zero error (the exact kernel) has no place on a log axis: it is drawn in a
//! separate band under the chart, "zero error", at its time. The legend beside the chart
//! names every variant with its time, its typical and worst errors and the worst regime, so
//! no label sits on a point.
//!
//! The parts: the markers (`plot/marker.rs`), the figures per variant and the frontier
//! (`entry.rs`), the log axes and their labels (`axes.rs`), the chart and its zero-error band
//! (`chart.rs`), the legend (`legend.rs`), plotters' errors as text (`error.rs`); this file
//! lays them out in one SVG.

mod axes;
mod chart;
mod entry;
mod error;
mod legend;
mod marker;

pub use entry::frontier;

use crate::report::DimResult;
use axes::decades;
use chart::{chart, zero_band};
use entry::{entries, Entry};
use error::{err, Result};
use legend::draw_legend;
use plotters::prelude::*;

const WIDTH: u32 = 1040;
const HEIGHT: u32 = 600;
/// The legend panel on the right.
const LEGEND: u32 = 360;
/// The zero-error band under the chart (with the x axis labels).
const BAND: u32 = 96;

/// The SVG text of the plot for one dimension.
pub fn svg(dim: &DimResult) -> Result<String> {
    let entries = entries(dim);
    let (zero, plotted): (Vec<&Entry>, Vec<&Entry>) =
        entries.iter().partition(|e| e.typical == 0.0);
    if plotted.is_empty() {
        return Err("no timed variant with an error to plot".into());
    }
    let (t_lo, t_hi) = entries.iter().fold((f64::INFINITY, 0.0f64), |(a, b), e| {
        (a.min(e.time), b.max(e.time))
    });
    let (e_lo, e_hi) = entries
        .iter()
        .flat_map(|e| [e.typical, e.worst.0])
        .filter(|&x| x > 0.0)
        .fold((f64::INFINITY, 0.0f64), |(a, b), x| (a.min(x), b.max(x)));
    let x_range = decades(t_lo, t_hi);
    // Room for the f64 epsilon line below the points and the f32 one above.
    let y_range = decades(e_lo.min(f64::EPSILON), e_hi.max(f32::EPSILON as f64));
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, (WIDTH, HEIGHT)).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        let (left, legend) = root.split_horizontally(WIDTH - LEGEND);
        let (top, band) = left.split_vertically(HEIGHT - BAND);
        chart(dim.dim, &top, &plotted, &zero, x_range, y_range)?;
        zero_band(&band, &zero, x_range)?;
        draw_legend(&legend, &entries)?;
        root.present().map_err(err)?;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The texts of an SVG's `<text>` elements.
    fn texts(svg: &str) -> Vec<String> {
        svg.split("<text")
            .skip(1)
            .filter_map(|t| {
                Some(
                    t.split_once('>')?
                        .1
                        .split_once("</text>")?
                        .0
                        .trim()
                        .to_string(),
                )
            })
            .collect()
    }

    #[test]
    fn the_plot_names_every_variant_and_labels_every_decade_of_its_errors() {
        use crate::{dim_result, Options};
        let opts = Options {
            dims: vec![2],
            samples: 4,
            timing_samples: 3,
            conditioned: 2,
            ..Options::default()
        };
        let dim = dim_result(2, &opts, |_| {});
        let svg = svg(&dim).unwrap();
        let texts = texts(&svg);
        // Every variant is named once, in the legend, with its time: no label on a point.
        for v in &dim.regimes[0].variants {
            let named = texts
                .iter()
                .filter(|t| t.starts_with(&format!("{}: ", v.name)));
            assert_eq!(named.count(), 1, "{}: {texts:?}", v.name);
        }
        // The exact kernel is in the zero-error band, not at a made-up error.
        assert!(texts.iter().any(|t| t.starts_with("zero error (exact)")));
        assert!(!svg.contains("1e-20"));
        // The error axis is labelled at least every second decade, from below the smallest
        // nonzero error to above the largest.
        let decades: Vec<i32> = texts
            .iter()
            .filter_map(|t| t.strip_prefix("1e")?.parse().ok())
            .collect();
        assert!(
            decades
                .windows(2)
                .all(|w| (1..=2).contains(&(w[0] - w[1]).abs())),
            "{decades:?}"
        );
        let errors: Vec<f64> = entries(&dim)
            .iter()
            .flat_map(|e| [e.typical, e.worst.0])
            .filter(|&e| e > 0.0)
            .collect();
        let lo = errors.iter().copied().fold(f64::INFINITY, f64::min).log10();
        let hi = errors.iter().copied().fold(0.0, f64::max).log10();
        let (min, max) = (
            *decades.iter().min().unwrap(),
            *decades.iter().max().unwrap(),
        );
        assert!(
            f64::from(min) <= lo + 2.0 && f64::from(max) >= hi - 2.0,
            "{decades:?} for [{lo}, {hi}]"
        );
    }
}
