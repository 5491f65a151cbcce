//! `observables.svg`: the granular temperatures of a run against time (plotters), beside the
//! CSV and Parquet rows of [`crate::granular`].
//!
//! Two panels over the same time axis: above, `T_tr` and `T_rot` (and in a mixture each
//! species' pair) on a logarithmic scale (a cooling gas falls by decades: Haff's law is
//! `T ~ t^-2` late); below, `T_rot / T_tr`, which the homogeneous cooling state holds
//! constant. Rows whose values are not positive and finite (the first row's `T_rot` of a gas
//! started without spin, `NaN` without rotating balls) are left out of the log panel.

use crate::granular::Sampler;
use plotters::prelude::*;

fn io_err(e: impl std::fmt::Display) -> std::io::Error {
    std::io::Error::other(e.to_string())
}

/// The series of the log panel: label, colour and the rows' `(time, value)` points.
type Series = (String, RGBColor, Vec<(f64, f64)>);

/// The temperatures of `sampler`'s rows as an SVG, titled `title` (see the module docs).
pub fn temperatures_svg(title: &str, sampler: &Sampler) -> std::io::Result<String> {
    let rows = sampler.rows();
    let points = |f: &dyn Fn(usize) -> f64| -> Vec<(f64, f64)> {
        (0..rows.len())
            .map(|k| (rows[k].time, f(k)))
            .filter(|p| p.0.is_finite() && p.1.is_finite() && p.1 > 0.0)
            .collect()
    };
    let mut series: Vec<Series> = vec![
        ("T_tr".into(), BLUE, points(&|k| rows[k].t_tr)),
        ("T_rot".into(), RED, points(&|k| rows[k].t_rot)),
    ];
    let species = rows.first().map_or(0, |r| r.species.len());
    let palette = [GREEN, MAGENTA, CYAN, BLACK];
    for s in 0..species {
        let colour = palette[s % palette.len()];
        series.push((
            format!("T_tr of species {s}"),
            colour,
            points(&|k| rows[k].species[s][0]),
        ));
        series.push((
            format!("T_rot of species {s} (dashed)"),
            colour,
            points(&|k| rows[k].species[s][1]),
        ));
    }
    let ratio = points(&|k| rows[k].t_rot / rows[k].t_tr);
    let t_end = rows.last().map_or(1.0, |r| r.time).max(f64::MIN_POSITIVE);
    let (lo, hi) = series
        .iter()
        .flat_map(|s| s.2.iter().map(|p| p.1))
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), y| {
            (lo.min(y), hi.max(y))
        });
    // The log panel draws log10 T on a linear axis labelled with T: ticks at even steps of
    // the exponent, however few decades the run spans.
    let (lo, hi) = if lo <= hi {
        (lo.log10() - 0.05, hi.log10() + 0.05)
    } else {
        (-1.0, 1.0)
    };
    let rmax = ratio.iter().fold(0.0f64, |m, p| m.max(p.1)).max(1e-3) * 1.1;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (800, 720)).into_drawing_area();
        root.fill(&WHITE).map_err(io_err)?;
        let (top, bottom) = root.split_vertically(460);
        let mut chart = ChartBuilder::on(&top)
            .caption(
                format!("{title}: granular temperatures"),
                ("sans-serif", 18),
            )
            .margin(12)
            .x_label_area_size(36)
            .y_label_area_size(80)
            .build_cartesian_2d(0.0..t_end, lo..hi)
            .map_err(io_err)?;
        chart
            .configure_mesh()
            .x_desc("time [T]")
            .y_desc("temperature [M L^2 T^-2] (log scale)")
            .y_label_formatter(&|y| format!("{:.2e}", 10f64.powf(*y)))
            .draw()
            .map_err(io_err)?;
        for (k, (label, colour, pts)) in series.into_iter().enumerate() {
            // Species' rotational series (odd entries after the first two) dashed.
            let dashed = k >= 2 && k % 2 == 1;
            let style = colour.stroke_width(2);
            let pts: Vec<(f64, f64)> = pts.into_iter().map(|(t, y)| (t, y.log10())).collect();
            let drawn = if dashed {
                chart.draw_series(DashedLineSeries::new(pts, 6, 4, style))
            } else {
                chart.draw_series(LineSeries::new(pts, style))
            };
            drawn
                .map_err(io_err)?
                .label(label)
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour));
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(io_err)?;
        let mut chart = ChartBuilder::on(&bottom)
            .margin(12)
            .x_label_area_size(36)
            .y_label_area_size(80)
            .build_cartesian_2d(0.0..t_end, 0.0..rmax)
            .map_err(io_err)?;
        chart
            .configure_mesh()
            .x_desc("time [T]")
            .y_desc("T_rot / T_tr")
            .draw()
            .map_err(io_err)?;
        chart
            .draw_series(LineSeries::new(ratio, BLACK.stroke_width(2)))
            .map_err(io_err)?;
        root.present().map_err(io_err)?;
    }
    Ok(svg)
}
