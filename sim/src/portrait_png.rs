//! The PNG of a boundary's phase portraits ([`crate::portrait`]): the same two panels as the
//! SVG, with a title, a legend, axes with ticks, tick labels and axis labels, drawn in the
//! public-domain 8 x 8 bitmap font of the `font8x8` crate (Basic Latin and Greek): no font
//! stack, no image crate; the PNG is written by `sim/src/png.rs`.

use crate::png::Raster;
use crate::portrait::{density, ranges, tick_label, Axes, Portrait, SHADES};

/// The side of a panel's plotting area, pixels.
const PANEL: usize = 400;
/// Left of each panel: the vertical axis label and the tick labels.
const LEFT: usize = 96;
/// Right of each panel.
const RIGHT: usize = 24;
/// Above the panels: the title and the legend.
const TOP: usize = 56;
/// Below the panels: the tick labels and the horizontal axis label.
const BOTTOM: usize = 48;
/// The ink's palette index (0 is the background; the density shades follow from 2).
const INK: u8 = 1;
/// The legend's swatch: the third shade.
const SWATCH: u8 = 4;

/// The glyph of `c` (rows top down, bit 0 the leftmost pixel), `None` outside the font.
fn glyph(c: char) -> Option<[u8; 8]> {
    let u = c as usize;
    match u {
        0x20..=0x7E => Some(font8x8::legacy::BASIC_LEGACY[u]),
        0x390..=0x3C9 => Some(font8x8::legacy::GREEK_LEGACY[u - 0x390]),
        _ => None,
    }
}

/// `text` in the font's characters: `√` spelled `sqrt`, anything else outside it `?`.
fn in_font(text: &str) -> Vec<char> {
    text.replace('√', "sqrt")
        .chars()
        .map(|c| if glyph(c).is_some() { c } else { '?' })
        .collect()
}

/// Draw `text` with its top left at `(x, y)`, or (`up`) rotated a quarter turn
/// counterclockwise with its bottom left at `(x, y)`, reading upwards.
fn text(raster: &mut Raster, x: i64, y: i64, text: &[char], up: bool) {
    for (i, &c) in text.iter().enumerate() {
        let rows = glyph(c).expect("in_font keeps only the font's characters");
        for (gy, row) in rows.iter().enumerate() {
            for gx in 0..8 {
                if row >> gx & 1 == 1 {
                    let (gx, gy, i) = (gx as i64, gy as i64, i as i64);
                    if up {
                        raster.set(x + gy, y - 8 * i - gx - 1, INK);
                    } else {
                        raster.set(x + 8 * i + gx, y + gy, INK);
                    }
                }
            }
        }
    }
}

/// About `target` round ticks (steps of 1, 2 or 5 times a power of 10) inside `[lo, hi]`.
pub(crate) fn ticks(lo: f64, hi: f64, target: usize) -> Vec<f64> {
    let raw = (hi - lo) / target as f64;
    if !(raw.is_finite() && raw > 0.0) {
        return vec![];
    }
    let magnitude = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|f| f * magnitude)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * magnitude);
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last).map(|k| k as f64 * step).collect()
}

/// The PNG of both portraits of one boundary: `title` and `legend` above two 400 x 400
/// panels with their axes (see [`Axes::labels`]); each pixel's shade counts the contacts in it.
pub(crate) fn portrait_png(title: &str, legend: &str, points: &[[f64; 4]], axes: &Axes) -> Vec<u8> {
    let width = 2 * (LEFT + PANEL + RIGHT);
    let height = TOP + PANEL + BOTTOM;
    let mut palette = vec![[255, 255, 255], [0, 0, 0]];
    palette.extend(SHADES);
    let mut raster = Raster::new(width, height, palette);
    let r = ranges(points, axes);
    let labels = axes.labels();
    text(&mut raster, 12, 10, &in_font(title), false);
    for dy in -3..=3 {
        for dx in -3..=3 {
            raster.set(16 + dx, 35 + dy, SWATCH);
        }
    }
    text(&mut raster, 26, 31, &in_font(legend), false);
    let side = PANEL as i64;
    for k in 0..2 {
        let x_off = (LEFT + k * (LEFT + PANEL + RIGHT)) as i64;
        let y_off = TOP as i64;
        let [(x0, x1), (y0, y1)] = r[k];
        let scatter = density(points, k, PANEL, PANEL, |x, y| {
            let px = ((x - x0) / (x1 - x0) * PANEL as f64).floor();
            let py = ((y1 - y) / (y1 - y0) * PANEL as f64).floor();
            (px >= 0.0 && py >= 0.0).then_some((px as usize, py as usize))
        });
        for (i, &c) in scatter.pixels.iter().enumerate() {
            if c != 0 {
                let (px, py) = ((i % PANEL) as i64, (i / PANEL) as i64);
                raster.set(x_off + px, y_off + py, c + 1);
            }
        }
        // The frame, one pixel outside the plotting area.
        for s in -1..=side {
            for (x, y) in [(s, -1), (s, side), (-1, s), (side, s)] {
                raster.set(x_off + x, y_off + y, INK);
            }
        }
        for t in ticks(x0, x1, 6) {
            let px = x_off + ((t - x0) / (x1 - x0) * PANEL as f64).floor() as i64;
            for d in 1..=5 {
                raster.set(px, y_off + side + d, INK);
            }
            let label = in_font(&tick_label(t));
            let w = 8 * label.len() as i64;
            text(&mut raster, px - w / 2, y_off + side + 9, &label, false);
        }
        for t in ticks(y0, y1, 6) {
            let py = y_off + ((y1 - t) / (y1 - y0) * PANEL as f64).floor() as i64;
            for d in 2..=6 {
                raster.set(x_off - d, py, INK);
            }
            let label = in_font(&tick_label(t));
            let w = 8 * label.len() as i64;
            text(&mut raster, x_off - 10 - w, py - 4, &label, false);
        }
        let [xl, yl] = labels[k].map(in_font);
        let xw = 8 * xl.len() as i64;
        text(
            &mut raster,
            x_off + (side - xw) / 2,
            y_off + side + 26,
            &xl,
            false,
        );
        let yw = 8 * yl.len() as i64;
        text(
            &mut raster,
            x_off - LEFT as i64 + 8,
            y_off + (side + yw) / 2,
            &yl,
            true,
        );
    }
    raster.png()
}

impl Portrait {
    /// The PNG for a run of `scene`: the two panels with title, legend, axes and labels.
    pub fn png(&self, scene: &str) -> Vec<u8> {
        let legend = Axes::legend(self.body, self.count, self.points.len());
        portrait_png(&self.title(scene), &legend, &self.points, &self.axes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_round_and_inside() {
        assert_eq!(ticks(-1.04, 1.04, 6), [-1.0, -0.5, 0.0, 0.5, 1.0]);
        let labels: Vec<String> = ticks(0.05, 1.0, 6).into_iter().map(tick_label).collect();
        assert_eq!(labels, ["0.2", "0.4", "0.6", "0.8", "1"]);
        let t = ticks(0.0, 7.3, 6);
        assert_eq!(t, [0.0, 2.0, 4.0, 6.0]);
        assert!(ticks(1.0, 1.0, 6).is_empty());
    }

    #[test]
    fn every_label_character_is_in_the_font() {
        for two_d in [false, true] {
            for angular in [false, true] {
                for label in (Axes { two_d, angular }).labels().concat() {
                    assert!(!in_font(label).contains(&'?'), "{label}");
                }
            }
        }
    }
}
