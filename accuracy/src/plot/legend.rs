//! The legend beside the chart: every variant by time with its marker, its time, its typical
//! and worst errors (and the worst regime) and its non-finite results; then the key to the
//! marks and lines.

use super::entry::Entry;
use super::error::{err, Result};
use super::marker::{outline, Shape};
use plotters::coord::Shift;
use plotters::prelude::*;

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

/// The legend: every variant with its figures, then the key to the marks.
pub(super) fn draw_legend(area: &DrawingArea<SVGBackend, Shift>, entries: &[Entry]) -> Result<()> {
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
