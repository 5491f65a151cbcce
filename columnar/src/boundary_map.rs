//! The boundary map as a table: the CSV's columns (`noslip_sim::boundary_map::header`),
//! typed, one row per contact of a ball with an immovable body.

use crate::{Cell, Column, Kind, Table};
use noslip_sim::boundary_map::Row;
use std::io::{self, Write};

/// The columns in dimension `n`: `event`, `ball`, `id` integers, `kind` text, the rest
/// doubles, named as in the CSV, with their units.
pub fn columns(n: usize) -> Vec<Column> {
    let col = |name: &str, kind: Kind, unit: &str| Column::new(name, kind, false, unit);
    let mut c = vec![
        col(
            "event",
            Kind::Int,
            "1 (index of the contact in the run, from 1)",
        ),
        col("time", Kind::Float, "T"),
        col("ball", Kind::Int, "1 (ball index)"),
        col("kind", Kind::Text, "boundary, box-wall or obstacle"),
        col(
            "id",
            Kind::Int,
            "1 (boundary id; box wall 2 axis + upper; obstacle index)",
        ),
    ];
    c.extend((0..n).map(|k| col(&format!("q{k}"), Kind::Float, "L")));
    c.push(col(
        "coordinate",
        Kind::Float,
        "L along a wall, edge or vertex; rad on a circle or sphere (see kind, id)",
    ));
    for name in ["incidence", "reflection"] {
        c.push(col(name, Kind::Float, "rad"));
    }
    for name in [
        "normal_velocity",
        "tangential_velocity",
        "tangential_velocity_post",
    ] {
        c.push(col(name, Kind::Float, "L/T"));
    }
    for name in ["spin", "spin_post"] {
        c.push(col(name, Kind::Float, "1/T"));
    }
    for name in ["scaled_spin", "scaled_spin_post"] {
        c.push(col(name, Kind::Float, "L/T"));
    }
    c
}

/// The boundary-map table for dimension `n` into `out`.
pub fn table<W: Write + Send>(out: W, n: usize) -> io::Result<Table<W>> {
    Table::new(
        out,
        "noslip_boundary_map",
        columns(n),
        "one row per contact of a ball with an immovable body, as a CSV row of the boundary \
         map (docs/tables.md)",
        n,
    )
}

/// The cells of `row` (see [`columns`]).
pub fn cells(row: &Row) -> Vec<Cell<'static>> {
    let (kind, id) = row.body.kind_id();
    let mut cells = vec![
        Cell::Int(row.event as i64),
        Cell::Float(row.time),
        Cell::Int(row.ball as i64),
        Cell::Text(kind),
        Cell::Int(id as i64),
    ];
    cells.extend(row.point.iter().map(|x| Cell::Float(*x)));
    cells.extend(
        [
            row.coordinate,
            row.incidence,
            row.reflection,
            row.normal_velocity,
            row.tangential[0],
            row.tangential[1],
            row.spin[0],
            row.spin[1],
            row.scaled_spin[0],
            row.scaled_spin[1],
        ]
        .map(Cell::Float),
    );
    cells
}
