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

use crate::report::{DimResult, MethodResult};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

const WIDTH: u32 = 1040;
const HEIGHT: u32 = 600;
/// The legend panel on the right.
const LEGEND: u32 = 360;
/// The zero-error band under the chart (with the x axis labels).
const BAND: u32 = 96;
/// Left and right margins of both charts, so their x axes line up.
const MARGIN: u32 = 14;
const Y_LABELS: u32 = 62;

/// Colours (Tableau 10) and shapes, one per variant in report order.
const COLOURS: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(214, 39, 40),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
];

#[derive(Clone, Copy)]
enum Shape {
    Circle,
    Square,
    TriangleUp,
    Diamond,
    TriangleDown,
    Hexagon,
    Pentagon,
    Star,
}

const SHAPES: [Shape; 8] = [
    Shape::Circle,
    Shape::Square,
    Shape::TriangleUp,
    Shape::Diamond,
    Shape::TriangleDown,
    Shape::Hexagon,
    Shape::Pentagon,
    Shape::Star,
];

/// The outline of `shape` around the origin, in pixels (radius about `r`).
fn outline(shape: Shape, r: f64) -> Vec<(i32, i32)> {
    let polygon = |n: usize, start: f64, radius: &dyn Fn(usize) -> f64| -> Vec<(i32, i32)> {
        (0..n)
            .map(|k| {
                let a = start + std::f64::consts::TAU * k as f64 / n as f64;
                let rr = radius(k);
                (
                    (rr * a.cos()).round() as i32,
                    (-rr * a.sin()).round() as i32,
                )
            })
            .collect()
    };
    let flat = |_: usize| r;
    use std::f64::consts::FRAC_PI_2 as UP;
    match shape {
        Shape::Circle => polygon(16, 0.0, &flat),
        Shape::Square => polygon(4, UP / 2.0, &|_| r * 1.15),
        Shape::TriangleUp => polygon(3, UP, &|_| r * 1.3),
        Shape::Diamond => polygon(4, UP, &|_| r * 1.3),
        Shape::TriangleDown => polygon(3, -UP, &|_| r * 1.3),
        Shape::Hexagon => polygon(6, 0.0, &|_| r * 1.1),
        Shape::Pentagon => polygon(5, UP, &|_| r * 1.15),
        Shape::Star => polygon(10, UP, &|k| if k % 2 == 0 { r * 1.45 } else { r * 0.6 }),
    }
}

type Chart<'c, 'a> = ChartContext<'c, SVGBackend<'a>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Draw a marker at `at` (chart coordinates): filled, or hollow (the ring of the outline).
fn mark(
    chart: &mut Chart,
    at: (f64, f64),
    shape: Shape,
    colour: RGBColor,
    filled: bool,
) -> Result<()> {
    let points = outline(shape, 5.0);
    if filled {
        chart
            .draw_series([EmptyElement::at(at) + Polygon::new(points, colour.filled())])
            .map_err(err)?;
    } else {
        let mut ring = points;
        ring.push(ring[0]);
        chart
            .draw_series([EmptyElement::at(at) + PathElement::new(ring, colour.stroke_width(2))])
            .map_err(err)?;
    }
    Ok(())
}

/// A variant's place in the plot.
struct Entry {
    name: String,
    colour: RGBColor,
    shape: Shape,
    /// Median ns per collision.
    time: f64,
    /// Max normwise relative error, typical regime (0 for the exact kernel).
    typical: f64,
    /// The largest over all regimes, and that regime's name.
    worst: (f64, String),
    /// Cases with a NaN or infinite result over all regimes, and those regimes.
    non_finite: (usize, Vec<String>),
}

/// Max normwise relative error of a variant's run (normwise eps times the format's eps).
fn error(v: &MethodResult) -> Option<f64> {
    (v.evaluated > 0).then(|| v.normwise_eps.max * v.variant.epsilon())
}

fn entries(dim: &DimResult) -> Vec<Entry> {
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

/// The decades `[floor(log10 lo), ceil(log10 hi)]`, at least one wide.
fn decades(lo: f64, hi: f64) -> (f64, f64) {
    let (a, b) = (lo.log10().floor(), hi.log10().ceil());
    (a, b.max(a + 1.0))
}

/// A time in ns at a decade, as people write it.
fn time_label(log_ns: f64) -> String {
    if (log_ns - log_ns.round()).abs() > 1e-9 {
        return String::new();
    }
    match log_ns.round() as i32 {
        k @ 0..=2 => format!("{} ns", 10i64.pow(k as u32)),
        k @ 3..=5 => format!("{} us", 10i64.pow(k as u32 - 3)),
        k @ 6..=8 => format!("{} ms", 10i64.pow(k as u32 - 6)),
        k => format!("1e{k} ns"),
    }
}

fn error_label(log_err: f64) -> String {
    if (log_err - log_err.round()).abs() > 1e-9 {
        return String::new();
    }
    format!("1e{}", log_err.round() as i32)
}

/// A short number for the legend: `3.1e-16`, `1.94 ns`.
fn short(x: f64) -> String {
    format!("{x:.1e}")
}

fn short_time(ns: f64) -> String {
    if ns >= 1e6 {
        format!("{:.1} ms", ns / 1e6)
    } else if ns >= 1e3 {
        format!("{:.1} us", ns / 1e3)
    } else {
        format!("{ns:.2} ns")
    }
}

type Result<T> = std::result::Result<T, String>;

fn err(e: impl std::fmt::Display) -> String {
    e.to_string()
}

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

/// The main chart: log10 time against log10 error.
fn chart<'a>(
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
fn zero_band<'a>(
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

/// The legend: every variant with its figures, then the key to the marks.
fn draw_legend(area: &DrawingArea<SVGBackend, Shift>, entries: &[Entry]) -> Result<()> {
    let name_font = ("sans-serif", 13).into_font();
    let grey = RGBColor(80, 80, 80);
    let detail_font = ("sans-serif", 11).into_font().color(&grey);
    let left = |dy: i32, x: i32| (x, dy);
    let mut y = 40;
    area.draw(&Text::new(
        "variant: median time; max normwise relative error",
        left(y, 8),
        ("sans-serif", 12).into_font().color(&grey),
    ))
    .map_err(err)?;
    y += 24;
    let mut order: Vec<&Entry> = entries.iter().collect();
    order.sort_by(|a, b| a.time.total_cmp(&b.time));
    for e in order {
        let glyph: Vec<(i32, i32)> = outline(e.shape, 5.0)
            .iter()
            .map(|p| (p.0 + 16, p.1 + y + 8))
            .collect();
        area.draw(&Polygon::new(glyph, e.colour.filled()))
            .map_err(err)?;
        area.draw(&Text::new(
            format!("{}: {}", e.name, short_time(e.time)),
            left(y, 30),
            name_font.clone(),
        ))
        .map_err(err)?;
        y += 17;
        let detail = if e.worst.0 == 0.0 {
            "zero error in every regime (the band below the chart)".to_string()
        } else if e.typical == 0.0 {
            format!(
                "typical 0 (the band); worst {} ({})",
                short(e.worst.0),
                e.worst.1
            )
        } else if e.worst.1 == "typical" {
            format!("typical {}, also its worst regime", short(e.typical))
        } else {
            format!(
                "typical {}; worst {} ({})",
                short(e.typical),
                short(e.worst.0),
                e.worst.1
            )
        };
        area.draw(&Text::new(detail, left(y, 30), detail_font.clone()))
            .map_err(err)?;
        if e.non_finite.0 > 0 {
            y += 14;
            area.draw(&Text::new(
                format!(
                    "NaN or infinity in {} case{} ({})",
                    e.non_finite.0,
                    if e.non_finite.0 == 1 { "" } else { "s" },
                    e.non_finite.1.join(", ")
                ),
                left(y, 30),
                ("sans-serif", 11).into_font().color(&RED),
            ))
            .map_err(err)?;
        }
        y += 24;
    }
    y += 6;
    let key_font = ("sans-serif", 11).into_font().color(&grey);
    let key = [
        "filled: the typical regime",
        "hollow, joined by a line: the variant's worst regime",
        "red steps: Pareto frontier of the typical points",
        "grey lines: the f64 and f32 epsilons",
    ];
    for (k, text) in key.iter().enumerate() {
        let centre = (16, y + 6);
        match k {
            0 => area
                .draw(&Polygon::new(
                    outline(Shape::Circle, 5.0)
                        .into_iter()
                        .map(|p| (p.0 + centre.0, p.1 + centre.1))
                        .collect::<Vec<_>>(),
                    grey.filled(),
                ))
                .map_err(err)?,
            1 => {
                let mut ring: Vec<(i32, i32)> = outline(Shape::Circle, 5.0)
                    .into_iter()
                    .map(|p| (p.0 + centre.0, p.1 + centre.1))
                    .collect();
                ring.push(ring[0]);
                area.draw(&PathElement::new(ring, grey.stroke_width(2)))
                    .map_err(err)?
            }
            2 => area
                .draw(&PathElement::new(
                    vec![(8, y + 10), (16, y + 10), (16, y + 2), (24, y + 2)],
                    RGBColor(200, 0, 0).mix(0.55).stroke_width(2),
                ))
                .map_err(err)?,
            _ => area
                .draw(&PathElement::new(
                    vec![(8, y + 6), (24, y + 6)],
                    RGBColor(120, 120, 120).stroke_width(1),
                ))
                .map_err(err)?,
        }
        area.draw(&Text::new(text.to_string(), left(y, 30), key_font.clone()))
            .map_err(err)?;
        y += 18;
    }
    Ok(())
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

    #[test]
    fn axes_cover_whole_decades_with_readable_labels() {
        assert_eq!(decades(2.3e-16, 0.4), (-16.0, 0.0));
        assert_eq!(decades(5.0, 5.0), (0.0, 1.0));
        assert_eq!(time_label(0.0), "1 ns");
        assert_eq!(time_label(4.0), "10 us");
        assert_eq!(time_label(6.0), "1 ms");
        assert_eq!(time_label(0.5), "");
        assert_eq!(error_label(-16.0), "1e-16");
        assert_eq!(error_label(-15.5), "");
    }
}
