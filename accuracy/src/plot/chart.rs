//! The main chart (log10 median time against log10 max normwise relative error: the formats'
//! epsilons, the Pareto staircase, each variant's typical and worst marks) and, under it on
//! the same x axis, the band of the variants with zero error, which carries the time labels.

use super::axes::{error_label, time_label};
use super::entry::{frontier, Entry};
use super::error::{err, Result};
use super::marker::mark;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Left and right margins of both charts, so their x axes line up.
const MARGIN: u32 = 14;
const Y_LABELS: u32 = 62;

/// The main chart: log10 time against log10 error.
pub(super) fn chart<'a>(
    dim: usize,
    area: &DrawingArea<SVGBackend<'a>, Shift>,
    plotted: &[&Entry],
    zero: &[&Entry],
    x: (f64, f64),
    y: (f64, f64),
) -> Result<()> {
    let mut chart = ChartBuilder::on(area)
        .caption(
            format!("n = {dim}: max normwise relative error against median time per collision"),
            ("sans-serif", 17),
        )
        .margin(MARGIN)
        .margin_bottom(0)
        .x_label_area_size(0)
        .y_label_area_size(Y_LABELS)
        .build_cartesian_2d(x.0..x.1, y.0..y.1)
        .map_err(err)?;
    let decades_y = (y.1 - y.0).round() as usize;
    chart
        .configure_mesh()
        .x_labels((x.1 - x.0).round() as usize + 1)
        .y_labels(decades_y.min(12) + 1)
        .y_label_formatter(&|v| error_label(*v))
        .y_desc("max normwise relative error (log)")
        .x_max_light_lines(0)
        .y_max_light_lines(if decades_y > 12 { 1 } else { 0 })
        .light_line_style(BLACK.mix(0.05))
        .bold_line_style(BLACK.mix(0.12))
        .label_style(("sans-serif", 12))
        .axis_desc_style(("sans-serif", 13))
        .draw()
        .map_err(err)?;
    // The formats' epsilons.
    for (eps, name) in [
        (f64::EPSILON, "f64 epsilon 2.2e-16"),
        (f32::EPSILON as f64, "f32 epsilon 1.2e-7"),
    ] {
        let level = eps.log10();
        chart
            .draw_series(LineSeries::new(
                [(x.0, level), (x.1, level)],
                RGBColor(120, 120, 120).stroke_width(1),
            ))
            .map_err(err)?;
        chart
            .draw_series([Text::new(
                name.to_string(),
                (x.1, level),
                ("sans-serif", 11)
                    .into_font()
                    .color(&RGBColor(90, 90, 90))
                    .pos(Pos::new(HPos::Right, VPos::Bottom)),
            )])
            .map_err(err)?;
    }
    // The Pareto frontier of the typical points, as a staircase.
    let points: Vec<(f64, f64)> = plotted
        .iter()
        .map(|e| (e.time.log10(), e.typical.log10()))
        .collect();
    let front: Vec<(f64, f64)> = frontier(&points).into_iter().map(|i| points[i]).collect();
    let mut stairs = Vec::new();
    for (k, &p) in front.iter().enumerate() {
        if k > 0 {
            stairs.push((p.0, front[k - 1].1));
        }
        stairs.push(p);
    }
    chart
        .draw_series(LineSeries::new(
            stairs,
            RGBColor(200, 0, 0).mix(0.55).stroke_width(2),
        ))
        .map_err(err)?;
    // Worst regimes: a line from the typical point to a hollow marker (alone for a variant
    // whose typical error is zero: its typical mark is in the band).
    for e in zero.iter().filter(|e| e.worst.0 > 0.0) {
        mark(
            &mut chart,
            (e.time.log10(), e.worst.0.log10()),
            e.shape,
            e.colour,
            false,
        )?;
    }
    for e in plotted {
        let (t, lo, hi) = (e.time.log10(), e.typical.log10(), e.worst.0.log10());
        if hi > lo {
            chart
                .draw_series(LineSeries::new(
                    [(t, lo), (t, hi)],
                    e.colour.stroke_width(1),
                ))
                .map_err(err)?;
        }
        mark(&mut chart, (t, hi), e.shape, e.colour, false)?;
    }
    for e in plotted {
        mark(
            &mut chart,
            (e.time.log10(), e.typical.log10()),
            e.shape,
            e.colour,
            true,
        )?;
    }
    Ok(())
}

/// The band for variants with zero error, sharing the chart's x axis, with the axis labels.
pub(super) fn zero_band<'a>(
    area: &DrawingArea<SVGBackend<'a>, Shift>,
    zero: &[&Entry],
    x: (f64, f64),
) -> Result<()> {
    let mut band = ChartBuilder::on(area)
        .margin(MARGIN)
        .margin_top(6)
        .x_label_area_size(44)
        .y_label_area_size(Y_LABELS)
        .build_cartesian_2d(x.0..x.1, 0.0..1.0)
        .map_err(err)?;
    band.configure_mesh()
        .x_labels((x.1 - x.0).round() as usize + 1)
        .x_label_formatter(&|v| time_label(*v))
        .y_labels(0)
        .x_desc("median time per collision (log)")
        .light_line_style(WHITE.mix(0.0))
        .bold_line_style(BLACK.mix(0.12))
        .label_style(("sans-serif", 12))
        .axis_desc_style(("sans-serif", 13))
        .draw()
        .map_err(err)?;
    band.draw_series([Text::new(
        "zero error (exact): not on the log scale",
        (x.0 + 0.03 * (x.1 - x.0), 0.92),
        ("sans-serif", 11)
            .into_font()
            .color(&RGBColor(90, 90, 90))
            .pos(Pos::new(HPos::Left, VPos::Top)),
    )])
    .map_err(err)?;
    for e in zero {
        mark(&mut band, (e.time.log10(), 0.45), e.shape, e.colour, true)?;
    }
    Ok(())
}
