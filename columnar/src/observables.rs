//! The granular-gas observables (`noslip simulate --observables DT`) as a table: the CSV's
//! columns (`noslip_sim::granular::Sampler::columns`), `contacts` and a mixture's
//! `contacts_{a}-{b}` integers and the rest doubles, one row per sample.

use crate::{Cell, Column, Kind, Table};
use noslip_sim::granular::{Row, Sampler};
use noslip_sim::pair_losses::is_count;
use std::io::{self, Write};

/// The columns of `sampler`'s rows, with their units.
pub fn columns(sampler: &Sampler) -> Vec<Column> {
    sampler
        .columns()
        .into_iter()
        .map(|(name, unit)| {
            let kind = if is_count(&name) {
                Kind::Int
            } else {
                Kind::Float
            };
            Column::new(name, kind, false, &unit)
        })
        .collect()
}

/// The cells of `row` (see [`columns`]).
pub fn cells(row: &Row) -> Vec<Cell<'static>> {
    let mut cells: Vec<Cell<'static>> = row.values().into_iter().map(Cell::Float).collect();
    cells[1] = Cell::Int(row.contacts as i64);
    // The pairs' contact counts come last (`Row::values`).
    let first = cells.len() - row.pair_contacts.len();
    for (cell, &c) in cells[first..].iter_mut().zip(&row.pair_contacts) {
        *cell = Cell::Int(c as i64);
    }
    cells
}

/// `g(r)` of `g` in dimension `n` as a Parquet table into `out`: the columns `r` (unit `L`, the
/// bins' centres) and `g` (unit `1`) of `pair-correlation.csv`.
pub fn pair_correlation<W: Write + Send>(
    g: &noslip_sim::pair_correlation::PairCorrelation,
    n: usize,
    out: W,
) -> io::Result<W> {
    let mut t = Table::new(
        out,
        "noslip_pair_correlation",
        vec![
            Column::new("r", Kind::Float, false, "L"),
            Column::new("g", Kind::Float, false, "1"),
        ],
        "one row per bin of the pair correlation g(r), averaged over the observables' rows \
         (docs/granular.md)",
        n,
    )?;
    for [r, value] in g.g() {
        t.push(&[Cell::Float(r), Cell::Float(value)])?;
    }
    t.finish()
}

/// The whole table of `sampler`'s rows in dimension `n`, as the bytes of a Parquet file.
pub fn parquet<W: Write + Send>(sampler: &Sampler, n: usize, out: W) -> io::Result<W> {
    let mut t = Table::new(
        out,
        "noslip_observables",
        columns(sampler),
        "one row per sample of the granular-gas observables: at the start and at the first \
         contact at or after each multiple of the interval, the state just after it \
         (docs/granular.md)",
        n,
    )?;
    for r in sampler.rows() {
        t.push(&cells(r))?;
    }
    t.finish()
}
