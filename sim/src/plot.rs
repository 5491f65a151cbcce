//! SVG pictures of a run (plotters; the caller publishes them with the run's other files): energy drift against events (any
//! dimension), and for 2D scenes the traced trajectories and the contact points.

use crate::run::Trace;
use crate::trace::PICTURE;
use crate::Setup;
use plotters::prelude::*;

fn io_err(e: impl std::fmt::Display) -> std::io::Error {
    std::io::Error::other(e.to_string())
}

/// `(E - E_0) / E_0` against the number of events.
pub fn energy_svg(title: &str, trace: &Trace) -> std::io::Result<String> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (800, 480)).into_drawing_area();
        root.fill(&WHITE).map_err(io_err)?;
        let last = trace.energy.last().map_or(1, |e| e.0).max(1);
        let big = trace
            .energy
            .iter()
            .fold(f64::MIN_POSITIVE, |m, e| m.max(e.1.abs()));
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(80)
            .build_cartesian_2d(0u64..last, -1.1 * big..1.1 * big)
            .map_err(io_err)?;
        chart
            .configure_mesh()
            .x_desc("events")
            .y_desc("(E - E0) / E0")
            .y_label_formatter(&|y| format!("{y:.1e}"))
            .draw()
            .map_err(io_err)?;
        chart
            .draw_series(LineSeries::new(trace.energy.iter().copied(), &BLUE))
            .map_err(io_err)?;
        root.present().map_err(io_err)?;
    }
    Ok(svg)
}

/// The part of the segment `s` inside the box `[0, size_0] x [0, size_1]` (Liang-Barsky).
fn clip_segment(s: &[[f64; 2]; 2], size: [f64; 2]) -> Option<Vec<(f64, f64)>> {
    let d = [s[1][0] - s[0][0], s[1][1] - s[0][1]];
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for k in 0..2 {
        for (p, q) in [(-d[k], s[0][k]), (d[k], size[k] - s[0][k])] {
            if p == 0.0 {
                if q < 0.0 {
                    return None;
                }
            } else {
                let r = q / p;
                if p < 0.0 {
                    t0 = t0.max(r);
                } else {
                    t1 = t1.min(r);
                }
            }
        }
    }
    (t0 < t1).then(|| {
        [t0, t1]
            .iter()
            .map(|&t| (s[0][0] + t * d[0], s[0][1] + t * d[1]))
            .collect()
    })
}

/// The most obstacles drawn (each a ring of up to 90 points, with its periodic images).
pub const OBSTACLES_DRAWN: usize = 200;

/// The runs of a closed ring of points that lie in the box `[0, size_0] x [0, size_1]`.
fn clip_ring(ring: &[(f64, f64)], size: [f64; 2]) -> Vec<Vec<(f64, f64)>> {
    let inside = |p: &(f64, f64)| (0.0..=size[0]).contains(&p.0) && (0.0..=size[1]).contains(&p.1);
    let mut runs = vec![Vec::new()];
    for p in ring {
        if inside(p) {
            runs.last_mut().expect("a run").push(*p);
        } else if !runs.last().expect("a run").is_empty() {
            runs.push(Vec::new());
        }
    }
    runs.retain(|r| r.len() > 1);
    runs
}

/// What the trajectory picture draws of a table: its first two sides, whether they are
/// periodic, each obstacle's centre (first two coordinates) and radius, and the other
/// boundaries; every point from the table's origin ([`crate::Table::origin`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Table2d {
    /// `[L_0, L_1]`.
    pub size: [f64; 2],
    /// Whether axes 0 and 1 are periodic.
    pub periodic: [bool; 2],
    /// `(centre, radius)` of each fixed obstacle (and container, and polygon vertex).
    pub obstacles: Vec<([f64; 2], f64)>,
    /// The segments drawn for walls (clipped to the picture) and polygon edges.
    pub segments: Vec<[[f64; 2]; 2]>,
    /// The origin added back to the axis labels.
    pub origin: [f64; 2],
}

impl Table2d {
    /// The table of `setup` as the picture sees it (n >= 2).
    pub fn of<const N: usize, const S: usize>(setup: &Setup<N, S>) -> Table2d {
        use crate::table::Shape;
        let o = setup.table.origin;
        let at = |x: &[f64; N]| [x[0] - o[0], x[1] - o[1]];
        let size = [setup.size[0], setup.size[1]];
        let mut obstacles: Vec<([f64; 2], f64)> = setup
            .obstacles
            .iter()
            .map(|b| (at(&b.position), b.radius))
            .collect();
        let mut segments = Vec::new();
        for b in &setup.table.boundaries {
            match &b.shape {
                Shape::Container { centre, radius } | Shape::Sphere { centre, radius } => {
                    obstacles.push((at(centre), *radius))
                }
                Shape::Edge { from, to, .. } => segments.push([at(from), at(to)]),
                Shape::Wall { point, normal } => {
                    // The wall's line through the picture: long enough to cross it.
                    let p = at(point);
                    let t = [normal[1], -normal[0]];
                    let reach = 2.0 * (size[0] + size[1] + p[0].abs() + p[1].abs());
                    segments.push([
                        [p[0] - reach * t[0], p[1] - reach * t[1]],
                        [p[0] + reach * t[0], p[1] + reach * t[1]],
                    ]);
                }
            }
        }
        Table2d {
            size,
            periodic: [setup.periodic[0], setup.periodic[1]],
            obstacles,
            segments,
            origin: [o[0], o[1]],
        }
    }
}

/// The box, the obstacles (with their images on periodic axes), the traced balls' centre
/// paths (cut at periodic wraps, thinned; see [`crate::trace`]) and the contact points (2D).
pub fn trajectories_svg(title: &str, table: &Table2d, trace: &Trace) -> std::io::Result<String> {
    let Table2d {
        size,
        periodic,
        obstacles,
        segments,
        origin,
    } = table;
    let mut svg = String::new();
    {
        let scale = PICTURE / size[0].max(size[1]);
        let dims = (
            (size[0] * scale) as u32 + 100,
            (size[1] * scale) as u32 + 80,
        );
        let root = SVGBackend::with_string(&mut svg, dims).into_drawing_area();
        root.fill(&WHITE).map_err(io_err)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 16))
            .margin(10)
            .x_label_area_size(30)
            .y_label_area_size(40)
            .build_cartesian_2d(0.0..size[0], 0.0..size[1])
            .map_err(io_err)?;
        let (ox, oy) = (origin[0], origin[1]);
        let x_label = move |x: &f64| format!("{}", ((x + ox) * 1e6).round() / 1e6);
        let y_label = move |y: &f64| format!("{}", ((y + oy) * 1e6).round() / 1e6);
        chart
            .configure_mesh()
            .disable_mesh()
            .x_label_formatter(&x_label)
            .y_label_formatter(&y_label)
            .draw()
            .map_err(io_err)?;
        for s in segments {
            if let Some(run) = clip_segment(s, *size) {
                chart
                    .draw_series(LineSeries::new(run, &BLACK))
                    .map_err(io_err)?;
            }
        }
        let images = |k: usize| {
            if periodic[k] {
                vec![-1.0, 0.0, 1.0]
            } else {
                vec![0.0]
            }
        };
        for &(c, r) in obstacles.iter().take(OBSTACLES_DRAWN) {
            let segments = (std::f64::consts::TAU * r * scale / 6.0)
                .ceil()
                .clamp(12.0, 90.0) as usize;
            for sx in images(0) {
                for sy in images(1) {
                    let centre = (c[0] + sx * size[0], c[1] + sy * size[1]);
                    let ring: Vec<(f64, f64)> = (0..=segments)
                        .map(|k| {
                            let a = k as f64 * std::f64::consts::TAU / segments as f64;
                            (centre.0 + r * a.cos(), centre.1 + r * a.sin())
                        })
                        .collect();
                    for run in clip_ring(&ring, *size) {
                        chart
                            .draw_series(LineSeries::new(run, &BLACK))
                            .map_err(io_err)?;
                    }
                }
            }
        }
        for (b, pieces) in trace.paths.iter().enumerate() {
            let color = Palette99::pick(b).to_rgba();
            for piece in pieces.iter().filter(|p| p.len() > 1) {
                chart
                    .draw_series(LineSeries::new(piece.iter().map(|p| (p[0], p[1])), color))
                    .map_err(io_err)?;
            }
        }
        chart
            .draw_series(
                trace
                    .contacts
                    .iter()
                    .map(|p| Circle::new((p[0], p[1]), 1, RED.filled())),
            )
            .map_err(io_err)?;
        root.present().map_err(io_err)?;
    }
    Ok(svg)
}
