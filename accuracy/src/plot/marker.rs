//! The markers: a colour (Tableau 10) and a shape per variant in report order, the shape's
//! outline in pixels, drawn filled (the typical regime) or as a ring (the worst regime) at a
//! point of a chart.

use super::error::{err, Result};
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

/// Colours (Tableau 10) and shapes, one per variant in report order.
pub(super) const COLOURS: [RGBColor; 8] = [
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
pub(super) enum Shape {
    Circle,
    Square,
    TriangleUp,
    Diamond,
    TriangleDown,
    Hexagon,
    Pentagon,
    Star,
}

pub(super) const SHAPES: [Shape; 8] = [
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
pub(super) fn outline(shape: Shape, r: f64) -> Vec<(i32, i32)> {
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
pub(super) fn mark(
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
