//! The events log as a table: the JSON lines log's fields (`noslip_sim::run::event_json`),
//! flattened into typed columns, one row per contact; a thermostat's kick
//! (`noslip_sim::run::kick_json`) is one row per ball, in time order among the contacts'
//! ([`kick_rows`]).

use crate::{Cell, Column, Kind, Table};
use noslip_sim::thermostat::Kick;
use noslip_sim::{Contact, Event};
use std::io::{self, Write};

/// The events log's columns in dimension `n` (`s = n(n-1)/2` spin entries): the JSON lines
/// log's fields, flattened (`positions[b][k]` is `position_b_k`, `pre[b].spin[j]` is
/// `pre_b_spin_j`, ...; `b = 1` columns are null unless the contact is ball-ball, as are
/// `axis`/`side` except for a box wall, `obstacle` and `boundary` except for those). A kick's
/// rows ([`kick_rows`]) have `kind` "kick", the ball in `ball_0`, its velocity before and after
/// in `pre_0_velocity_k` and `post_0_velocity_k`, the kick's number in `kick` and its energy
/// in `energy_injected` (on its first row); their other columns are null, as `kick` and
/// `energy_injected` are on a contact's row.
pub fn event_columns(n: usize) -> Vec<Column> {
    let s = n * (n - 1) / 2;
    let mut c = vec![
        Column::new(
            "event",
            Kind::Int,
            true,
            "1 (index of the contact in the run, from 1; null on a kick's rows)",
        ),
        Column::new("time", Kind::Float, false, "T"),
        Column::new(
            "kind",
            Kind::Text,
            false,
            "ball-ball, ball-wall, ball-obstacle, ball-boundary or kick",
        ),
        Column::new("ball_0", Kind::Int, false, "1 (ball index)"),
        Column::new("ball_1", Kind::Int, true, "1 (ball index)"),
        Column::new("axis", Kind::Int, true, "1 (box axis)"),
        Column::new("side", Kind::Text, true, "lower or upper"),
        Column::new("obstacle", Kind::Int, true, "1 (obstacle index)"),
        Column::new("boundary", Kind::Int, true, "1 (boundary id)"),
    ];
    c.extend((0..n).map(|k| Column::new(format!("nu_{k}"), Kind::Float, true, "1")));
    for b in 0..2 {
        c.extend((0..n).map(|k| Column::new(format!("position_{b}_{k}"), Kind::Float, true, "L")));
    }
    for when in ["pre", "post"] {
        for b in 0..2 {
            c.extend(
                (0..s)
                    .map(|j| Column::new(format!("{when}_{b}_spin_{j}"), Kind::Float, true, "1/T")),
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
    c.push(Column::new(
        "kick",
        Kind::Int,
        true,
        "1 (the thermostat's kick number, from 1; null on a contact's row)",
    ));
    c.push(Column::new(
        "energy_injected",
        Kind::Float,
        true,
        "M L^2 T^-2",
    ));
    c
}

/// The events table (see [`event_columns`]) for dimension `n` into `out`.
pub fn events_table<W: Write + Send>(out: W, n: usize) -> io::Result<Table<W>> {
    Table::new(
        out,
        "noslip_events",
        event_columns(n),
        "one row per contact, as a line of the JSON events log, and one per ball of each \
         thermostat kick (docs/scenes.md)",
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
    row.extend([Cell::Null, Cell::Null]);
    row
}

/// The rows of kick `k` in dimension `N` with `s` spin entries (the columns of
/// [`event_columns`]): one per ball `i`, in ball order, with `time` `t_k`, `kind` "kick",
/// `ball_0` `i`, `pre_0_velocity_k` and `post_0_velocity_k` its velocity before and after
/// (`Kick::before`, `Kick::after`: the JSON line's `velocities` are the latter), `kick` the
/// kick's number and `energy_injected` the kick's energy on ball 0's row (null on the others,
/// so that the column adds up to the kicks' energy), every other column null (spins are not
/// kicked).
pub fn kick_rows<const N: usize>(k: &Kick<N>, s: usize) -> Vec<Vec<Cell<'static>>> {
    let nulls = |count: usize| std::iter::repeat_n(Cell::Null, count);
    k.before
        .iter()
        .zip(&k.after)
        .enumerate()
        .map(|(i, (before, after))| {
            let mut row = vec![
                Cell::Null,
                Cell::Float(k.time),
                Cell::Text("kick"),
                Cell::Int(i as i64),
            ];
            // ball_1, axis, side, obstacle, boundary; nu; both positions.
            row.extend(nulls(5 + N + 2 * N));
            for u in [before, after] {
                row.extend(nulls(s));
                row.extend(u.iter().map(|x| Cell::Float(*x)));
                row.extend(nulls(s + N));
            }
            row.push(Cell::Int(k.index as i64));
            row.push(if i == 0 {
                Cell::Float(k.injected)
            } else {
                Cell::Null
            });
            row
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A kick's rows fill the columns of [`event_columns`] by name: the ball, its velocities
    /// before and after, the kick's number, its energy on the first row only; the rest null.
    #[test]
    fn a_kicks_rows_fill_their_columns_by_name() {
        let k = Kick::<2> {
            index: 7,
            time: 3.5,
            before: vec![[1.0, 2.0], [3.0, 4.0]],
            after: vec![[5.0, 6.0], [7.0, 8.0]],
            injected: 0.25,
        };
        let columns = event_columns(2);
        let rows = kick_rows(&k, 1);
        assert_eq!(rows.len(), 2);
        for (i, row) in rows.iter().enumerate() {
            assert_eq!(row.len(), columns.len());
            let cell = |name: &str| {
                let at = columns.iter().position(|c| c.name == name).unwrap();
                row[at]
            };
            assert_eq!(cell("time"), Cell::Float(3.5));
            assert_eq!(cell("kind"), Cell::Text("kick"));
            assert_eq!(cell("ball_0"), Cell::Int(i as i64));
            assert_eq!(cell("kick"), Cell::Int(7));
            for c in 0..2 {
                let f = |x: f64| Cell::Float(x);
                assert_eq!(cell(&format!("pre_0_velocity_{c}")), f(k.before[i][c]));
                assert_eq!(cell(&format!("post_0_velocity_{c}")), f(k.after[i][c]));
                assert_eq!(cell(&format!("nu_{c}")), Cell::Null);
                assert_eq!(cell(&format!("position_0_{c}")), Cell::Null);
            }
            for name in ["event", "ball_1", "pre_0_spin_0", "post_1_velocity_0"] {
                assert_eq!(cell(name), Cell::Null, "{name}");
            }
            let energy = if i == 0 {
                Cell::Float(0.25)
            } else {
                Cell::Null
            };
            assert_eq!(cell("energy_injected"), energy);
        }
    }
}
