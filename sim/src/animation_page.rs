//! The animation's page: one self-contained HTML file (inline CSS and JavaScript, the data
//! embedded, nothing fetched), which plays an [`Animation`] in any current browser.
//!
//! **The data** is one JSON object in a `<script type="application/json">` element. The
//! frames, the bulk of it, are quantised to 16 bits per value (positions over the view,
//! depth over the box's depth range, the spin mark's components over `[-1, 1]`: a position
//! error of at most `1/131070` of the view, far below a pixel) and stored little-endian in
//! base64: `frames x balls x channels` values, 4 channels in 2D (`x, y, mark_x, mark_y`) and 5
//! beyond (depth after `y`). With the caps of [`crate::animation`] the page stays under about
//! 2 MB whatever the run. Trails are quantised the same way; the table and the phase
//! portrait are plain numbers, rounded to 6 significant digits.
//!
//! **The page** (`animation.js`) shows the balls with their spin marks and trails, the time
//! and the contacts so far, play/pause and a slider, and for a one-ball table the phase
//! portrait beside it, with the contact in effect highlighted. Its current frame is the text
//! of the element `#frame` (what the browser test reads); `#frame=K&pause` in the URL starts
//! it at frame `K`, paused. A script error is shown in `#errors`.

use crate::animation::Animation;
use serde_json::{json, Value};

/// The page's script.
const SCRIPT: &str = include_str!("animation.js");

/// The page's style.
const STYLE: &str = "body{font:14px sans-serif;margin:12px;color:#222}\
#stage{display:flex;flex-wrap:wrap;gap:12px;align-items:flex-start}\
canvas{border:1px solid #ccc;background:#fff}\
#controls{margin:8px 0;display:flex;gap:12px;align-items:center}\
#slider{width:420px}#errors{color:#b00}.note{max-width:1040px;color:#555}";

/// `x` rounded to 6 significant digits (what the page draws needs no more).
fn round6(x: f64) -> Value {
    if !x.is_finite() {
        return Value::Null;
    }
    let r: f64 = format!("{x:.5e}").parse().unwrap_or(x);
    json!(r)
}

/// `v` in `[lo, hi]` as a 16-bit fraction of the range (clamped; 0 for an empty range).
fn quantise(v: f64, lo: f64, hi: f64) -> u16 {
    if hi <= lo || !v.is_finite() {
        return 0;
    }
    ((v - lo) / (hi - lo) * 65535.0).round().clamp(0.0, 65535.0) as u16
}

/// Standard base64 (RFC 4648, with padding) of `bytes`.
pub fn base64(bytes: &[u8]) -> String {
    const ABC: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = u32::from(b[0]) << 16 | u32::from(b[1]) << 8 | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(char::from(ABC[(n >> (18 - 6 * k) & 63) as usize]));
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// The page's data object (see the module docs).
pub fn data(a: &Animation) -> Value {
    let [x0, y0, x1, y1] = a.view;
    let channels = if a.dim == 2 { 4 } else { 5 };
    let mut bytes = Vec::with_capacity(a.frames.len() * a.radius.len() * channels * 2);
    for frame in &a.frames {
        for b in frame {
            let mut vals = vec![quantise(b[0], x0, x1), quantise(b[1], y0, y1)];
            if channels == 5 {
                vals.push(quantise(b[2], a.depth[0], a.depth[1]));
            }
            vals.push(quantise(b[3], -1.0, 1.0));
            vals.push(quantise(b[4], -1.0, 1.0));
            for v in vals {
                bytes.extend_from_slice(&v.to_le_bytes());
            }
        }
    }
    let trails: Vec<Vec<Vec<u16>>> = a
        .trails
        .iter()
        .map(|per_ball| {
            per_ball
                .iter()
                .map(|pts| {
                    pts.iter()
                        .flat_map(|p| [quantise(p[0], x0, x1), quantise(p[1], y0, y1)])
                        .collect()
                })
                .collect()
        })
        .collect();
    let bodies: Vec<Value> = a
        .bodies
        .iter()
        .map(|(body, labels)| {
            let (kind, id) = body.kind_id();
            json!({"name": format!("{kind} {id}"), "x": labels[0], "y": labels[1]})
        })
        .collect();
    let cloud: Vec<Value> = a
        .cloud
        .iter()
        .flat_map(|&(t, body, s, y)| [round6(t), json!(body), round6(s), round6(y)])
        .collect();
    let current: Vec<Value> = a
        .current
        .iter()
        .map(|c| c.map_or(Value::Null, |(b, s, y)| json!([b, round6(s), round6(y)])))
        .collect();
    json!({
        "title": a.title,
        "dim": a.dim,
        "balls": a.balls,
        "shown": a.radius.len(),
        "frames": a.frames.len(),
        "t0": a.t0,
        "dt": a.dt,
        "channels": channels,
        "view": a.view.map(round6),
        "depth": a.depth.map(round6),
        "radius": a.radius.iter().map(|&r| round6(r)).collect::<Vec<_>>(),
        "species": a.species,
        "contacts": a.contacts,
        "end": [a.end.0, a.end.1],
        "pos": base64(&bytes),
        "trails": trails,
        "segments": a.segments.iter().map(|s| s.map(round6)).collect::<Vec<_>>(),
        "circles": a.circles.iter().map(|c| c.map(round6)).collect::<Vec<_>>(),
        "bodies": bodies,
        "cloud": cloud,
        "current": current,
        "rules": {
            "max_balls": crate::animation::MAX_BALLS,
            "max_frames": crate::animation::MAX_FRAMES,
            "ball_frames": crate::animation::BALL_FRAMES,
            "trail_points": crate::animation::TRAIL_POINTS,
            "cloud_points": crate::animation::CLOUD_POINTS,
        },
    })
}

/// Text safe inside an HTML element: `<`, `>` and `&` escaped.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// The whole page.
pub fn html(a: &Animation) -> String {
    // `<` never appears raw inside the data element, so no `</script>` can end it early.
    let data = data(a).to_string().replace('<', "\\u003c");
    let title = escape(&a.title);
    let portrait = if a.bodies.is_empty() {
        ""
    } else {
        "<canvas id=\"portrait\" width=\"440\" height=\"440\"></canvas>"
    };
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
<title>{title}: noslip animation</title>\n<style>{STYLE}</style>\n</head>\n<body>\n\
<h1>{title}</h1>\n\
<div id=\"controls\"><button id=\"play\" type=\"button\">pause</button>\
<input id=\"slider\" type=\"range\" min=\"0\" max=\"{last}\" value=\"0\">\
<span id=\"time\"></span><span>frame <span id=\"frame\">0</span> of {count}</span>\
<span id=\"contacts\"></span></div>\n\
<div id=\"stage\"><canvas id=\"balls\" width=\"600\" height=\"600\"></canvas>{portrait}</div>\n\
<p class=\"note\" id=\"note\"></p>\n<pre id=\"errors\" hidden></pre>\n\
<script id=\"noslip-data\" type=\"application/json\">{data}</script>\n\
<script>\n{SCRIPT}</script>\n</body>\n</html>\n",
        last = a.frames.len().saturating_sub(1),
        count = a.frames.len(),
    )
}
