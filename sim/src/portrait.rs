//! Phase portraits of the boundary map, per boundary: the boundary coordinate against the
//! angle of reflection, and the tangential velocity against the scaled spin `gamma R c` after
//! each contact ([`crate::boundary_map`]). SVG (plotters, with axes and labels) and PNG (the
//! same two panels as dots in frames, no text: `sim/src/png.rs`).

use crate::png::Raster;
use plotters::prelude::*;

/// The shipped tables whose portraits docs/tables.md shows (`scenes/NAME.toml`), written by
/// `examples/table_portraits.rs` to `docs/tables/NAME-KIND-ID.png`.
pub const DOCS_TABLES: [&str; 9] = [
    "strip",
    "wedge",
    "sector",
    "triangle",
    "circle",
    "sinai_square",
    "sinai",
    "cube3d",
    "sphere3d",
];

/// The contacts of each of those pictures.
pub const DOCS_EVENTS: u64 = 20_000;

/// The picture's two panels' ranges: `[(x0, x1), (y0, y1)]` each.
type Ranges = [[(f64, f64); 2]; 2];

fn io_err(e: impl std::fmt::Display) -> std::io::Error {
    std::io::Error::other(e.to_string())
}

/// `(lo, hi)` of the values, widened to a nonzero span.
fn span(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|x| x.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(x), b.max(x))
        });
    if lo > hi {
        return (-1.0, 1.0); // no finite value
    }
    let pad = 0.02 * (hi - lo).max(1e-12 * hi.abs().max(1.0));
    (lo - pad, hi + pad)
}

/// The ranges of the portraits of `points` (`[coordinate, angle, tangential, scaled spin]`):
/// the coordinate's own, the angle's full range (`[-pi/2, pi/2]` in 2D, `[0, pi/2]` in nD),
/// and one symmetric square for velocity and spin.
fn ranges(points: &[[f64; 4]], two_d: bool) -> Ranges {
    let half = std::f64::consts::FRAC_PI_2;
    let angle = if two_d { (-half, half) } else { (0.0, half) };
    let (lo, hi) = span(points.iter().flat_map(|p| [p[2], p[3]]));
    let m = lo.abs().max(hi.abs());
    [
        [span(points.iter().map(|p| p[0])), angle],
        [(-m, m), (-m, m)],
    ]
}

/// The points of panel `k` thinned to one per cell of a `THIN x THIN` grid over its ranges
/// (the first in each), so that the SVG stays small however many contacts there were.
fn thinned(points: &[[f64; 4]], k: usize, r: &[(f64, f64); 2]) -> Vec<(f64, f64)> {
    const THIN: f64 = 300.0;
    let mut seen = std::collections::HashSet::new();
    points
        .iter()
        .map(|p| (p[2 * k], p[2 * k + 1]))
        .filter(|(x, y)| x.is_finite() && y.is_finite())
        .filter(|(x, y)| {
            let cell = |v: f64, (lo, hi): (f64, f64)| ((v - lo) / (hi - lo) * THIN).floor() as i64;
            seen.insert((cell(*x, r[0]), cell(*y, r[1])))
        })
        .collect()
}

/// The SVG of both portraits of one boundary.
pub fn portrait_svg(title: &str, points: &[[f64; 4]], two_d: bool) -> std::io::Result<String> {
    let r = ranges(points, two_d);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (960, 500)).into_drawing_area();
        root.fill(&WHITE).map_err(io_err)?;
        let root = root.titled(title, ("sans-serif", 18)).map_err(io_err)?;
        let panels = root.split_evenly((1, 2));
        let labels = [
            ["boundary coordinate", "angle of reflection (rad)"],
            ["tangential velocity u_t", "scaled spin gamma R c"],
        ];
        for (k, area) in panels.iter().enumerate() {
            let [(x0, x1), (y0, y1)] = r[k];
            let mut chart = ChartBuilder::on(area)
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(60)
                .build_cartesian_2d(x0..x1, y0..y1)
                .map_err(io_err)?;
            chart
                .configure_mesh()
                .disable_mesh()
                .x_desc(labels[k][0])
                .y_desc(labels[k][1])
                .x_label_formatter(&|x| format!("{x:.3}"))
                .y_label_formatter(&|y| format!("{y:.3}"))
                .draw()
                .map_err(io_err)?;
            chart
                .draw_series(
                    thinned(points, k, &r[k])
                        .into_iter()
                        .map(|p| Pixel::new(p, BLUE)),
                )
                .map_err(io_err)?;
        }
        root.present().map_err(io_err)?;
    }
    Ok(svg)
}

/// The PNG of both portraits: two 400 x 400 panels side by side, each point one pixel.
pub fn portrait_png(points: &[[f64; 4]], two_d: bool) -> Vec<u8> {
    const SIDE: usize = 400;
    const GAP: usize = 20;
    let r = ranges(points, two_d);
    let mut raster = Raster::new(
        2 * SIDE + 3 * GAP,
        SIDE + 2 * GAP,
        vec![[255, 255, 255], [0, 0, 0], [30, 60, 200]],
    );
    for k in 0..2 {
        let x_off = (GAP + k * (SIDE + GAP)) as i64;
        let y_off = GAP as i64;
        let side = SIDE as i64;
        for s in -1..=side {
            for (x, y) in [(s, -1), (s, side), (-1, s), (side, s)] {
                raster.set(x_off + x, y_off + y, 1);
            }
        }
        let [(x0, x1), (y0, y1)] = r[k];
        for p in points {
            let (x, y) = (p[2 * k], p[2 * k + 1]);
            if !(x.is_finite() && y.is_finite()) {
                continue;
            }
            let px = ((x - x0) / (x1 - x0) * (SIDE - 1) as f64).round() as i64;
            let py = ((y1 - y) / (y1 - y0) * (SIDE - 1) as f64).round() as i64;
            if (0..side).contains(&px) && (0..side).contains(&py) {
                raster.set(x_off + px, y_off + py, 2);
                raster.set(x_off + (px + 1).min(side - 1), y_off + py, 2);
            }
        }
    }
    raster.png()
}
