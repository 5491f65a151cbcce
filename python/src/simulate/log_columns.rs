//! The events log of `noslip.simulate` in columns: the simulator's JSON-lines log
//! (`noslip_sim::run::event_json`, and `run::kick_json` for a thermostat's kicks) read line
//! by line as it comes into one vector per field, then handed to Python as NumPy arrays:
//! the same numbers, bit for bit (the log's shortest round-trip text).

use super::array;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use serde_json::Value;

/// The events log as the simulator writes it (JSON lines), read into [`Columns`] line by
/// line as it comes: the log's text is never held whole (it was, about 0.5 kB a contact,
/// then read into the columns: 0.9 kB a contact at the peak).
pub(super) struct LogColumns {
    line: Vec<u8>,
    columns: Columns,
    n: usize,
    s: usize,
}

impl std::io::Write for LogColumns {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        for part in buf.split_inclusive(|&b| b == b'\n') {
            self.line.extend_from_slice(part);
            if self.line.last() == Some(&b'\n') {
                let e: Value = serde_json::from_slice(&self.line)
                    .map_err(|e| std::io::Error::other(format!("a log line: {e}")))?;
                // A thermostat's kick (`run::kick_json`) is no contact: its own arrays.
                if e.get("kick").is_none() {
                    self.columns.push(&e, self.n, self.s);
                } else {
                    self.columns.push_kick(&e);
                }
                self.line.clear();
            }
        }
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// Bytes one contact's row of the events log's columns holds, in dimension `n` (`s` spin
/// entries): 57 + 56 n + 32 s (201 in 2D, 321 in 3D).
pub(super) fn log_bytes(n: usize) -> u64 {
    let s = n * (n - 1) / 2;
    (57 + 56 * n + 32 * s) as u64
}

/// The columns of the events log.
#[derive(Default)]
pub(super) struct Columns {
    time: Vec<f64>,
    kind: Vec<i64>,
    balls: Vec<i64>,
    wall_axis: Vec<i64>,
    wall_upper: Vec<bool>,
    obstacle: Vec<i64>,
    boundary: Vec<i64>,
    nu: Vec<f64>,
    positions: Vec<f64>,
    pre_spin: Vec<f64>,
    pre_velocity: Vec<f64>,
    post_spin: Vec<f64>,
    post_velocity: Vec<f64>,
    /// The thermostat's kicks: number, time, every ball's velocity after it (ball order),
    /// energy injected.
    kick: Vec<i64>,
    kick_time: Vec<f64>,
    kick_velocities: Vec<f64>,
    kick_energy_injected: Vec<f64>,
}

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .map(|a| a.iter().map(|x| x.as_f64().unwrap_or(f64::NAN)).collect())
        .unwrap_or_default()
}

impl Columns {
    /// Append one kick's log line (`run::kick_json`).
    fn push_kick(&mut self, e: &Value) {
        self.kick.push(e["kick"].as_i64().unwrap_or(-1));
        self.kick_time.push(e["time"].as_f64().unwrap_or(f64::NAN));
        if let Some(v) = e["velocities"].as_array() {
            for u in v {
                self.kick_velocities.extend(numbers(u));
            }
        }
        self.kick_energy_injected
            .push(e["energy_injected"].as_f64().unwrap_or(f64::NAN));
    }

    /// Append one log line; a one-ball contact's second slot is NaN (ball index -1).
    fn push(&mut self, e: &Value, n: usize, s: usize) {
        self.time.push(e["time"].as_f64().unwrap_or(f64::NAN));
        let kind = match e["kind"].as_str() {
            Some("ball-ball") => 0,
            Some("ball-wall") => 1,
            Some("ball-obstacle") => 2,
            _ => 3,
        };
        self.kind.push(kind);
        let balls: Vec<i64> = e["balls"]
            .as_array()
            .map(|a| a.iter().filter_map(Value::as_i64).collect())
            .unwrap_or_default();
        self.balls.extend([
            balls.first().copied().unwrap_or(-1),
            balls.get(1).copied().unwrap_or(-1),
        ]);
        self.wall_axis.push(e["axis"].as_i64().unwrap_or(-1));
        self.wall_upper.push(e["side"].as_str() == Some("upper"));
        self.obstacle.push(e["obstacle"].as_i64().unwrap_or(-1));
        self.boundary.push(e["boundary"].as_i64().unwrap_or(-1));
        self.nu.extend(numbers(&e["nu"]));
        for slot in 0..2 {
            let fill = |out: &mut Vec<f64>, v: Option<&Value>, len: usize| match v {
                Some(v) => out.extend(numbers(v)),
                None => out.extend(std::iter::repeat_n(f64::NAN, len)),
            };
            fill(&mut self.positions, e["positions"].get(slot), n);
            fill(
                &mut self.pre_spin,
                e["pre"].get(slot).map(|p| &p["spin"]),
                s,
            );
            fill(
                &mut self.pre_velocity,
                e["pre"].get(slot).map(|p| &p["velocity"]),
                n,
            );
            fill(
                &mut self.post_spin,
                e["post"].get(slot).map(|p| &p["spin"]),
                s,
            );
            fill(
                &mut self.post_velocity,
                e["post"].get(slot).map(|p| &p["velocity"]),
                n,
            );
        }
    }
}

impl LogColumns {
    /// An empty reader for a run in dimension `n` with `s` spin entries.
    pub(super) fn new(n: usize, s: usize) -> Self {
        LogColumns {
            line: Vec::new(),
            columns: Columns::default(),
            n,
            s,
        }
    }

    /// The columns read so far.
    pub(super) fn into_columns(self) -> Columns {
        self.columns
    }
}

impl Columns {
    /// The columns as the `events` dict of `simulate`'s result: a contact's arrays with
    /// `count` rows (`balls` `(count, 2)`, `nu` `(count, n)`, the two slots' states `(count, 2,
    /// n)` and `(count, 2, s)`), the kicks' with `kicks` rows (`kick_velocities` `(kicks,
    /// balls, n)`).
    pub(super) fn into_dict<'py>(
        self,
        py: Python<'py>,
        n: usize,
        balls: usize,
    ) -> PyResult<Bound<'py, PyDict>> {
        let s = n * (n - 1) / 2;
        let cols = self;
        let count = cols.time.len();
        let ev = PyDict::new(py);
        ev.set_item("time", array(py, cols.time, &[count])?)?;
        ev.set_item("kind", array(py, cols.kind, &[count])?)?;
        ev.set_item("balls", array(py, cols.balls, &[count, 2])?)?;
        ev.set_item("wall_axis", array(py, cols.wall_axis, &[count])?)?;
        ev.set_item("wall_upper", array(py, cols.wall_upper, &[count])?)?;
        ev.set_item("obstacle", array(py, cols.obstacle, &[count])?)?;
        ev.set_item("boundary", array(py, cols.boundary, &[count])?)?;
        ev.set_item("nu", array(py, cols.nu, &[count, n])?)?;
        ev.set_item("positions", array(py, cols.positions, &[count, 2, n])?)?;
        ev.set_item("pre_spin", array(py, cols.pre_spin, &[count, 2, s])?)?;
        ev.set_item(
            "pre_velocity",
            array(py, cols.pre_velocity, &[count, 2, n])?,
        )?;
        ev.set_item("post_spin", array(py, cols.post_spin, &[count, 2, s])?)?;
        ev.set_item(
            "post_velocity",
            array(py, cols.post_velocity, &[count, 2, n])?,
        )?;
        let kicks = cols.kick.len();
        ev.set_item("kick", array(py, cols.kick, &[kicks])?)?;
        ev.set_item("kick_time", array(py, cols.kick_time, &[kicks])?)?;
        ev.set_item(
            "kick_velocities",
            array(py, cols.kick_velocities, &[kicks, balls, n])?,
        )?;
        ev.set_item(
            "kick_energy_injected",
            array(py, cols.kick_energy_injected, &[kicks])?,
        )?;
        Ok(ev)
    }
}
