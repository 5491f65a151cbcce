//! The granular-gas observables (`noslip simulate --observables DT`) as a table: the CSV's
//! columns (`noslip_sim::granular::COLUMNS`), `contacts` an integer and the rest doubles,
//! one row per sample.

use crate::{Cell, Column, Kind, Table};
use noslip_sim::granular::{Row, COLUMNS};
use std::io::{self, Write};

/// The columns: the names and units of [`COLUMNS`].
pub fn columns() -> Vec<Column> {
    COLUMNS
        .iter()
        .map(|&(name, unit)| {
            let kind = if name == "contacts" {
                Kind::Int
            } else {
                Kind::Float
            };
            Column::new(name, kind, false, unit)
        })
        .collect()
}

/// The observables' table for dimension `n` into `out`.
pub fn table<W: Write + Send>(out: W, n: usize) -> io::Result<Table<W>> {
    Table::new(
        out,
        "noslip_observables",
        columns(),
        "one row per sample of the granular-gas observables: at the start and at the first \
         contact at or after each multiple of the interval, the state just after it \
         (docs/granular.md)",
        n,
    )
}

/// The cells of `row` (see [`columns`]).
pub fn cells(row: &Row) -> Vec<Cell<'static>> {
    let mut cells: Vec<Cell<'static>> = row.values().map(Cell::Float).to_vec();
    cells[1] = Cell::Int(row.contacts as i64);
    cells
}

/// The whole table of `rows` in dimension `n`, as the bytes of a Parquet file.
pub fn parquet(rows: &[Row], n: usize) -> io::Result<Vec<u8>> {
    let mut t = table(Vec::new(), n)?;
    for r in rows {
        t.push(&cells(r))?;
    }
    t.finish()
}

#[cfg(test)]
mod tests {
    use super::*;
    use parquet::file::reader::{FileReader, SerializedFileReader};
    use parquet::record::Field;

    #[test]
    fn rows_read_back_as_written_with_the_units_of_the_csv_header() {
        let rows: Vec<Row> = (0..5)
            .map(|k| Row {
                time: k as f64 / 3.0,
                contacts: 1000 * k,
                t_tr: 1.0 / (1.0 + k as f64),
                t_rot: 0.7 / (1.0 + k as f64),
                energy: 2.5 - k as f64 * 0.1,
                frequency: if k == 0 { f64::NAN } else { 0.1 * k as f64 },
                lost: [0.01 * k as f64, 0.0, -0.0, 1e-300],
            })
            .collect();
        let path =
            std::env::temp_dir().join(format!("noslip-observables-{}.parquet", std::process::id()));
        std::fs::write(&path, parquet(&rows, 3).unwrap()).unwrap();
        let reader = SerializedFileReader::new(std::fs::File::open(&path).unwrap()).unwrap();
        let meta = reader.metadata().file_metadata();
        let kv = meta.key_value_metadata().unwrap();
        let get = |k: &str| kv.iter().find(|x| x.key == k).unwrap().value.clone();
        let units: serde_json::Value = serde_json::from_str(&get("noslip.units").unwrap()).unwrap();
        for (name, unit) in COLUMNS {
            assert_eq!(units[name], unit, "{name}");
        }
        assert_eq!(get("noslip.dim").as_deref(), Some("3"));
        let read: Vec<Vec<Field>> = reader
            .get_row_iter(None)
            .unwrap()
            .map(|r| {
                r.unwrap()
                    .get_column_iter()
                    .map(|(_, f)| f.clone())
                    .collect()
            })
            .collect();
        assert_eq!(read.len(), rows.len());
        for (got, row) in read.iter().zip(&rows) {
            assert_eq!(got[1], Field::Long(row.contacts as i64));
            for (k, want) in row.values().iter().enumerate().filter(|(k, _)| *k != 1) {
                let Field::Double(x) = got[k] else {
                    panic!("column {k} is not a double: {:?}", got[k])
                };
                assert_eq!(x.to_bits(), want.to_bits(), "column {}", COLUMNS[k].0);
            }
        }
        std::fs::remove_file(path).unwrap();
    }
}
