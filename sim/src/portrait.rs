//! Phase portraits of the boundary map, per boundary: the Birkhoff coordinates `(s, sin phi)`
//! (the boundary coordinate against the sine of the angle of reflection) and the tangential
//! velocity against the scaled spin `gamma R c`, after each contact
//! ([`crate::boundary_map`]).
//!
//! Both files carry a title, axes with ticks, axis labels with units and a legend. The SVG
//! (plotters) keeps its text and axes as vectors and rasterises the scatter into one embedded
//! PNG image per panel (one pixel of the plotting area per image pixel, darker where more
//! contacts fall), so its size is bounded by the panel's area, not by the number of contacts:
//! under 1 MB at any count (`sim/tests/portraits.rs`). The PNG is the same picture drawn in
//! an 8 x 8 bitmap font (`sim/src/portrait_png.rs`).

use crate::immovable::Body;
use crate::png::Raster;
use crate::table::{Shape, Table};
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

/// What the axes of one body's portraits show: the dimension's conventions (2D signed
/// quantities, nD sizes) and whether the boundary coordinate is an arc length (a distance, in
/// the scene's length unit) or an angle about a centre (radians).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Axes {
    /// Two dimensions: signed angle, tangential velocity and spin.
    pub two_d: bool,
    /// The coordinate is an angle (a circle or sphere: container, obstacle, round boundary).
    pub angular: bool,
}

impl Axes {
    /// The axes of `body`'s portraits in `table` (the coordinate's kind as in
    /// [`crate::boundary_map`]: a wall, an edge or a vertex by length, a circle by angle).
    pub fn of<const N: usize>(table: &Table<N>, body: Body) -> Axes {
        let angular = match body {
            Body::BoxWall(..) => false,
            Body::Obstacle(_) => true,
            Body::Boundary(b) => match &table.boundaries[b].shape {
                Shape::Wall { .. } | Shape::Edge { .. } => false,
                Shape::Sphere { radius, .. } => *radius != 0.0,
                Shape::Container { .. } => true,
            },
        };
        Axes {
            two_d: N == 2,
            angular,
        }
    }

    /// The axis labels, `[[x, y] of the Birkhoff panel, [x, y] of the velocity panel]`, with
    /// their units (`L` the scene's length unit, `T` its time unit).
    pub fn labels(&self) -> [[&'static str; 2]; 2] {
        let s = match (self.two_d, self.angular) {
            (true, false) => "s: arc length along the boundary [L]",
            (true, true) => "θ: angle of Q about the centre [rad]",
            (false, false) => "s: distance of Q from the wall's point [L]",
            (false, true) => "θ: angle of Q - c from e_0 [rad]",
        };
        if self.two_d {
            [
                [s, "sin φ [1] (φ: signed angle of reflection)"],
                [
                    "u_t: tangential velocity [L/T]",
                    "γRc: scaled spin, γR = √(2λ) [L/T]",
                ],
            ]
        } else {
            [
                [s, "sin φ [1] (φ: angle of reflection)"],
                [
                    "|u_t|: tangential speed [L/T]",
                    "γR|U|: scaled spin norm [L/T]",
                ],
            ]
        }
    }

    /// The legend's text for `count` contacts with `body`, of which `kept` are drawn.
    pub fn legend(body: Body, count: u64, kept: usize) -> String {
        let (kind, id) = body.kind_id();
        let drawn = if (kept as u64) < count {
            format!(" (first {kept} drawn)")
        } else {
            String::new()
        };
        format!(
            "state after each of {count} contacts with {kind} {id}{drawn}; darker: more per pixel"
        )
    }
}

/// One body's portraits: what [`crate::boundary_map::BoundaryMap::portraits`] gives.
#[derive(Clone, Debug, PartialEq)]
pub struct Portrait {
    /// The body.
    pub body: Body,
    /// Its axes.
    pub axes: Axes,
    /// Its contacts in the run.
    pub count: u64,
    /// The points drawn, `[coordinate, angle of reflection, tangential, scaled spin]` after
    /// each of the first contacts.
    pub points: Vec<[f64; 4]>,
}

impl Portrait {
    /// The title of the pictures of a run of `scene` (a file name).
    pub fn title(&self, scene: &str) -> String {
        let (kind, id) = self.body.kind_id();
        let scene = if scene.is_empty() {
            String::new()
        } else {
            format!("{scene}: ")
        };
        format!("{scene}boundary map of {kind} {id}, Birkhoff coordinates and velocity-spin plane")
    }

    /// The SVG ([`portrait_svg`]) for a run of `scene`.
    pub fn svg(&self, scene: &str) -> std::io::Result<String> {
        let legend = Axes::legend(self.body, self.count, self.points.len());
        portrait_svg(&self.title(scene), &legend, &self.points, &self.axes)
    }
}

/// The picture's two panels' ranges: `[(x0, x1), (y0, y1)]` each.
pub(crate) type Ranges = [[(f64, f64); 2]; 2];

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

/// Point `p` (`[coordinate, angle of reflection, tangential, scaled spin]`) in panel `k`:
/// `(s, sin phi)` or `(u_t, gamma R c)`.
pub(crate) fn panel_point(p: &[f64; 4], k: usize) -> (f64, f64) {
    if k == 0 {
        (p[0], p[1].sin())
    } else {
        (p[2], p[3])
    }
}

/// The ranges of the portraits of `points`: the coordinate's own, `sin phi`'s full range
/// (`[-1, 1]` in 2D, `[0, 1]` in nD, padded), and one square for velocity and spin (2D
/// symmetric about 0; nD from 0, as both are sizes).
pub(crate) fn ranges(points: &[[f64; 4]], axes: &Axes) -> Ranges {
    let sine = if axes.two_d {
        (-1.04, 1.04)
    } else {
        (-0.02, 1.02)
    };
    let (lo, hi) = span(points.iter().flat_map(|p| [p[2], p[3]]));
    let m = lo.abs().max(hi.abs());
    // nD: speed and spin norm are sizes, `>= 0`.
    let square = if axes.two_d { (-m, m) } else { (-0.02 * m, m) };
    [[span(points.iter().map(|p| p[0])), sine], [square, square]]
}

/// The palette of a density raster: transparent, then [`SHADES`] blues from light (one
/// contact in the pixel) to dark (many).
pub(crate) const SHADES: [[u8; 3]; 4] = [
    [140, 170, 235],
    [70, 110, 220],
    [30, 60, 190],
    [10, 25, 110],
];

/// The shade (palette index 1..=4) of a pixel hit `count > 0` times: 1, 2-3, 4-15, 16+.
pub(crate) fn shade(count: u32) -> u8 {
    match count {
        0 => 0,
        1 => 1,
        2..=3 => 2,
        4..=15 => 3,
        _ => 4,
    }
}

/// Panel `k`'s points as a `width x height` density raster (colour 0 transparent, then the
/// [`SHADES`]), `pixel` mapping a point to its raster pixel (`None` outside).
pub(crate) fn density(
    points: &[[f64; 4]],
    k: usize,
    width: usize,
    height: usize,
    pixel: impl Fn(f64, f64) -> Option<(usize, usize)>,
) -> Raster {
    let mut counts = vec![0u32; width * height];
    for p in points {
        let (x, y) = panel_point(p, k);
        if !(x.is_finite() && y.is_finite()) {
            continue;
        }
        if let Some((px, py)) = pixel(x, y).filter(|&(px, py)| px < width && py < height) {
            counts[py * width + px] = counts[py * width + px].saturating_add(1);
        }
    }
    let mut palette = vec![[255, 255, 255]];
    palette.extend(SHADES);
    let mut raster = Raster::new(width, height, palette);
    raster.transparent = true;
    for (pixel, count) in raster.pixels.iter_mut().zip(counts) {
        *pixel = shade(count);
    }
    raster
}

/// Standard base64 (RFC 4648, with padding) of `data`.
pub(crate) fn base64(data: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(data.len().div_ceil(3) * 4);
    for chunk in data.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let v = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for j in 0..4 {
            if j <= chunk.len() {
                out.push(ALPHABET[(v >> (18 - 6 * j)) as usize & 63] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// The SVG of both portraits of one boundary: `title` above, the axes of `axes`, and `legend`
/// (see [`Axes::legend`]) below the title. Each panel's scatter is an embedded PNG
/// (`<image href="data:image/png;base64,...">`) over its plotting area.
pub fn portrait_svg(
    title: &str,
    legend: &str,
    points: &[[f64; 4]],
    axes: &Axes,
) -> std::io::Result<String> {
    let r = ranges(points, axes);
    let labels = axes.labels();
    let mut svg = String::new();
    let mut images = Vec::new();
    {
        let root = SVGBackend::with_string(&mut svg, (1000, 560)).into_drawing_area();
        root.fill(&WHITE).map_err(io_err)?;
        let root = root.titled(title, ("sans-serif", 18)).map_err(io_err)?;
        let (key, body) = root.split_vertically(26);
        let swatch = EmptyElement::at((24, 12))
            + Rectangle::new(
                [(-5, -5), (5, 5)],
                ShapeStyle::from(&RGBColor(30, 60, 190)).filled(),
            )
            + Text::new(legend.to_string(), (12, -7), ("sans-serif", 13));
        key.draw(&swatch).map_err(io_err)?;
        let panels = body.split_evenly((1, 2));
        for (k, area) in panels.iter().enumerate() {
            let [(x0, x1), (y0, y1)] = r[k];
            let mut chart = ChartBuilder::on(area)
                .margin(14)
                .x_label_area_size(44)
                .y_label_area_size(64)
                .build_cartesian_2d(x0..x1, y0..y1)
                .map_err(io_err)?;
            chart
                .configure_mesh()
                .disable_mesh()
                .x_desc(labels[k][0])
                .y_desc(labels[k][1])
                .axis_desc_style(("sans-serif", 14))
                .x_labels(7)
                .y_labels(7)
                .x_label_formatter(&|x| tick_label(*x))
                .y_label_formatter(&|y| tick_label(*y))
                .draw()
                .map_err(io_err)?;
            let (xs, ys) = chart.plotting_area().get_pixel_range();
            let (w, h) = ((xs.end - xs.start) as usize, (ys.end - ys.start) as usize);
            let raster = density(points, k, w, h, |x, y| {
                let (px, py) = chart.backend_coord(&(x, y));
                let (px, py) = (px - xs.start, py - ys.start);
                (px >= 0 && py >= 0).then_some((px as usize, py as usize))
            });
            images.push(format!(
                r#"<image x="{}" y="{}" width="{w}" height="{h}" preserveAspectRatio="none" style="image-rendering:pixelated" href="data:image/png;base64,{}"/>"#,
                xs.start,
                ys.start,
                base64(&raster.png())
            ));
        }
        root.present().map_err(io_err)?;
    }
    let end = svg
        .rfind("</svg>")
        .ok_or_else(|| io_err("plotters wrote no </svg>"))?;
    svg.insert_str(end, &(images.join("\n") + "\n"));
    Ok(svg)
}

/// A tick's label: up to 4 significant digits, in exponent form outside `[1e-3, 1e5)`.
pub(crate) fn tick_label(x: f64) -> String {
    let a = x.abs();
    if a != 0.0 && !(1e-3..1e5).contains(&a) {
        return format!("{x:.2e}");
    }
    let s = format!("{x:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_of_the_rfc_4648_vectors() {
        for (input, expected) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(input.as_bytes()), expected);
        }
    }

    #[test]
    fn tick_labels_are_short() {
        assert_eq!(tick_label(0.5), "0.5");
        assert_eq!(tick_label(-0.0), "0");
        assert_eq!(tick_label(3.0), "3");
        assert_eq!(tick_label(1e-7), "1.00e-7");
        assert_eq!(tick_label(-1.25), "-1.25");
    }

    #[test]
    fn shades_grow_with_the_count() {
        let s: Vec<u8> = [0, 1, 2, 3, 4, 15, 16, 1000].map(shade).to_vec();
        assert_eq!(s, [0, 1, 2, 2, 3, 3, 4, 4]);
    }
}
