//! The events log as a table: the JSON lines log's fields (`noslip_sim::run::event_json`),
//! flattened into typed columns, one row per contact.

use crate::{Cell, Column, Kind, Table};
use noslip_sim::{Contact, Event};
use std::io::{self, Write};

/// The events log's columns in dimension `n` (`s = n(n-1)/2` spin entries): the JSON lines
/// log's fields, flattened (`positions[b][k]` is `position_b_k`, `pre[b].spin[j]` is
/// `pre_b_spin_j`, ...; `b = 1` columns are null unless the contact is ball-ball, as are
/// `axis`/`side` except for a box wall, `obstacle` and `boundary` except for those).
pub fn event_columns(n: usize) -> Vec<Column> {
    let s = n * (n - 1) / 2;
    let mut c = vec![
        Column::new(
            "event",
            Kind::Int,
            false,
            "1 (index of the contact in the run, from 1)",
        ),
        Column::new("time", Kind::Float, false, "T"),
        Column::new(
            "kind",
            Kind::Text,
            false,
            "ball-ball, ball-wall, ball-obstacle or ball-boundary",
        ),
        Column::new("ball_0", Kind::Int, false, "1 (ball index)"),
        Column::new("ball_1", Kind::Int, true, "1 (ball index)"),
        Column::new("axis", Kind::Int, true, "1 (box axis)"),
        Column::new("side", Kind::Text, true, "lower or upper"),
        Column::new("obstacle", Kind::Int, true, "1 (obstacle index)"),
        Column::new("boundary", Kind::Int, true, "1 (boundary id)"),
    ];
    c.extend((0..n).map(|k| Column::new(format!("nu_{k}"), Kind::Float, false, "1")));
    for b in 0..2 {
        c.extend(
            (0..n).map(|k| Column::new(format!("position_{b}_{k}"), Kind::Float, b == 1, "L")),
        );
    }
    for when in ["pre", "post"] {
        for b in 0..2 {
            c.extend(
                (0..s).map(|j| {
                    Column::new(format!("{when}_{b}_spin_{j}"), Kind::Float, b == 1, "1/T")
                }),
            );
            c.extend((0..n).map(|k| {
                Column::new(
                    format!("{when}_{b}_velocity_{k}"),
                    Kind::Float,
                    b == 1,
                    "L/T",
                )
            }));
        }
    }
    c
}

/// The events table (see [`event_columns`]) for dimension `n` into `out`.
pub fn events_table<W: Write + Send>(out: W, n: usize) -> io::Result<Table<W>> {
    Table::new(
        out,
        "noslip_events",
        event_columns(n),
        "one row per contact, as a line of the JSON events log (docs/scenes.md)",
        n,
    )
}

/// The row of contact `index` (the cells of [`event_columns`]).
pub fn event_row<const N: usize, const S: usize>(
    index: u64,
    e: &Event<N, S>,
) -> Vec<Cell<'static>> {
    let (kind, balls, axis, side, obstacle, boundary) = match e.contact {
        Contact::Ball { i, j } => ("ball-ball", [i, j].map(Some), None, None, None, None),
        Contact::Wall { i, axis, upper } => (
            "ball-wall",
            [Some(i), None],
            Some(axis),
            Some(if upper { "upper" } else { "lower" }),
            None,
            None,
        ),
        Contact::Obstacle { i, obstacle } => (
            "ball-obstacle",
            [Some(i), None],
            None,
            None,
            Some(obstacle),
            None,
        ),
        Contact::Boundary { i, boundary } => (
            "ball-boundary",
            [Some(i), None],
            None,
            None,
            None,
            Some(boundary),
        ),
    };
    let int = |x: Option<usize>| x.map_or(Cell::Null, |x| Cell::Int(x as i64));
    let mut row = vec![
        Cell::Int(index as i64),
        Cell::Float(e.time),
        Cell::Text(kind),
        int(balls[0]),
        int(balls[1]),
        int(axis),
        side.map_or(Cell::Null, Cell::Text),
        int(obstacle),
        int(boundary),
    ];
    row.extend(e.nu.iter().map(|x| Cell::Float(*x)));
    let two = balls[1].is_some();
    let body = |b: usize, xs: &[f64]| -> Vec<Cell<'static>> {
        xs.iter()
            .map(|x| {
                if b == 0 || two {
                    Cell::Float(*x)
                } else {
                    Cell::Null
                }
            })
            .collect()
    };
    for b in 0..2 {
        row.extend(body(b, &e.position[b]));
    }
    for states in [&e.pre, &e.post] {
        for (b, state) in states.iter().enumerate() {
            row.extend(body(b, &state.spin));
            row.extend(body(b, &state.velocity));
        }
    }
    row
}
