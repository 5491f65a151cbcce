//! The plots of the granular-gas observables beyond the temperatures ([`crate::granular_plot`]
//! draws those), as `noslip simulate --observables` writes them beside the rows
//! (docs/granular.md): the pressure, the cumulant `a_2` and the mean square displacements
//! against time, and the pair correlation `g(r)` against `r`. Each is one labelled chart
//! (plotters, SVG), its axes named with their units in the scene's mass `M`, length `L` and
//! time `T`, and a dashed reference line where the observable has a value to compare with
//! (`a_2 = 0` for a Maxwellian, `g = 1` for an uncorrelated gas). Points that are not finite
//! (the first row's pressure, the pressure of a box with walls, both `NaN`) are left out; a
//! chart with no finite point says so in its caption.

use crate::granular::Sampler;
use crate::pair_correlation::PairCorrelation;
use plotters::prelude::*;

fn io_err(e: impl std::fmt::Display) -> std::io::Error {
    std::io::Error::other(e.to_string())
}

/// A line of a chart: label, colour and its `(x, y)` points.
pub type Line = (String, RGBColor, Vec<(f64, f64)>);

/// One chart: `title` above, `x` and `y` the axes' descriptions (with units), `lines` drawn
/// solid with a legend, and a dashed horizontal line at `reference` if given (labelled
/// `reference.1`). The ranges cover every finite point (and the reference), with 5 % margins.
pub fn chart_svg(
    title: &str,
    x: &str,
    y: &str,
    lines: Vec<Line>,
    reference: Option<(f64, &str)>,
) -> std::io::Result<String> {
    let lines: Vec<Line> = lines
        .into_iter()
        .map(|(l, c, p)| {
            let p = p
                .into_iter()
                .filter(|q| q.0.is_finite() && q.1.is_finite())
                .collect();
            (l, c, p)
        })
        .collect();
    let points = lines.iter().flat_map(|l| l.2.iter());
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for &(a, b) in points {
        (x0, x1, y0, y1) = (x0.min(a), x1.max(a), y0.min(b), y1.max(b));
    }
    let empty = x0 > x1;
    if empty {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    if let Some((r, _)) = reference {
        (y0, y1) = (y0.min(r), y1.max(r));
    }
    let pad = |a: f64, b: f64| {
        let d = if b > a { 0.05 * (b - a) } else { 0.5 };
        (a - d, b + d)
    };
    let ((x0, x1), (y0, y1)) = (pad(x0, x1), pad(y0, y1));
    let caption = if empty {
        format!("{title} (no finite values)")
    } else {
        title.to_string()
    };
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (800, 480)).into_drawing_area();
        root.fill(&WHITE).map_err(io_err)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(caption, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(80)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(io_err)?;
        chart
            .configure_mesh()
            .x_desc(x)
            .y_desc(y)
            .draw()
            .map_err(io_err)?;
        if let Some((r, label)) = reference {
            chart
                .draw_series(DashedLineSeries::new(
                    [(x0, r), (x1, r)],
                    6,
                    4,
                    BLACK.stroke_width(1),
                ))
                .map_err(io_err)?
                .label(label)
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK));
        }
        for (label, colour, pts) in lines {
            chart
                .draw_series(LineSeries::new(pts, colour.stroke_width(2)))
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
        root.present().map_err(io_err)?;
    }
    Ok(svg)
}

/// The unit of column `name` of `sampler`'s rows ([`Sampler::columns`]).
fn unit(sampler: &Sampler, name: &str) -> String {
    sampler
        .columns()
        .into_iter()
        .find(|c| c.0 == name)
        .map_or_else(String::new, |c| c.1)
}

/// The rows' `(time, f(row))`.
fn against_time(sampler: &Sampler, f: impl Fn(&crate::granular::Row) -> f64) -> Vec<(f64, f64)> {
    sampler.rows().iter().map(|r| (r.time, f(r))).collect()
}

/// `observables-pressure.svg`: the pressure (kinetic part plus the collisional virial since
/// the previous row) against time.
pub fn pressure_svg(title: &str, sampler: &Sampler) -> std::io::Result<String> {
    chart_svg(
        &format!("{title}: pressure"),
        "time [T]",
        &format!("pressure [{}]", unit(sampler, "pressure")),
        vec![("P".into(), BLUE, against_time(sampler, |r| r.pressure))],
        None,
    )
}

/// `observables-a2.svg`: the velocity distribution's cumulant `a_2` against time, the
/// Maxwellian's 0 dashed.
pub fn a2_svg(title: &str, sampler: &Sampler) -> std::io::Result<String> {
    chart_svg(
        &format!("{title}: velocity cumulant a_2"),
        "time [T]",
        "a_2 [1]",
        vec![("a_2".into(), BLUE, against_time(sampler, |r| r.a2))],
        Some((0.0, "Maxwellian (0)")),
    )
}

/// `observables-msd.svg`: `msd` and `msd_cm` against time (in a periodic box `msd` also
/// carries the centre of mass's ballistic drift).
pub fn msd_svg(title: &str, sampler: &Sampler) -> std::io::Result<String> {
    chart_svg(
        &format!("{title}: mean square displacement"),
        "time [T]",
        "mean square displacement [L^2]",
        vec![
            ("msd".into(), BLUE, against_time(sampler, |r| r.msd)),
            (
                "msd_cm (about the centre of mass)".into(),
                RED,
                against_time(sampler, |r| r.msd_cm),
            ),
        ],
        None,
    )
}

/// `pair-correlation.svg`: `g(r)` at the bins' centres, the uncorrelated gas's 1 dashed.
pub fn pair_correlation_svg(title: &str, g: &PairCorrelation) -> std::io::Result<String> {
    let points = g.g().into_iter().map(|[r, g]| (r, g)).collect();
    chart_svg(
        &format!("{title}: pair correlation"),
        "r [L]",
        "g(r) [1]",
        vec![("g".into(), BLUE, points)],
        Some((1.0, "uncorrelated (1)")),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The axes carry their descriptions, the lines and the reference their labels, and a
    /// chart without finite points says so instead of failing.
    #[test]
    fn a_chart_names_its_axes_lines_and_reference() {
        let svg = chart_svg(
            "t",
            "time [T]",
            "a_2 [1]",
            vec![(
                "a".into(),
                BLUE,
                vec![(0.0, f64::NAN), (1.0, 2.0), (2.0, 3.0)],
            )],
            Some((0.0, "zero")),
        )
        .unwrap();
        // plotters writes each text on a line of its own.
        for text in ["\ntime [T]\n", "\na_2 [1]\n", "\na\n", "\nzero\n", "\nt\n"] {
            assert!(svg.contains(text), "{text}");
        }
        let empty = chart_svg(
            "e",
            "x",
            "y",
            vec![("a".into(), BLUE, vec![(f64::NAN, 1.0)])],
            None,
        )
        .unwrap();
        assert!(empty.contains("e (no finite values)"));
    }
}
