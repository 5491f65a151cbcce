//! # noslip-columnar
//!
//! Columnar outputs of `noslip simulate`: a table written as Apache Parquet, streamed in row
//! groups, with typed columns and the unit of each column in the file's key-value metadata.
//! The events log (`--log FILE.parquet`, [`events`]), the boundary map (`--boundary-map
//! FILE.parquet`, [`boundary_map`]) and the granular observables (`--observables DT`'s
//! `observables.parquet`, [`observables`]) are written through [`Table`].
//!
//! Memory is bounded: rows are buffered per column until [`ROW_GROUP`] rows, then written as
//! one row group (about `8 * ROW_GROUP` bytes per column). Floating-point columns are plain
//! encoded (their values are mostly distinct), integer and text columns dictionary encoded;
//! every page is Snappy compressed. Metadata keys: `noslip.units` (a JSON object, column name
//! to unit: `L` the scene's length unit, `T` its time unit, `1` none), `noslip.table` (what a
//! row is), `noslip.dim`. Any Parquet reader (pyarrow, pandas, polars, DuckDB, Dask) reads the
//! files; noslip is not needed.

#![warn(missing_docs, unreachable_pub)]

pub mod boundary_map;
pub mod events;
pub mod observables;

use parquet::basic::{Compression, ConvertedType, Repetition, Type as Physical};
use parquet::data_type::{ByteArray, ByteArrayType, DoubleType, Int64Type};
use parquet::file::metadata::KeyValue;
use parquet::file::properties::WriterProperties;
use parquet::file::writer::SerializedFileWriter;
use parquet::schema::types::{ColumnPath, Type};
use std::io::{self, Write};
use std::sync::Arc;

/// Rows per row group.
pub const ROW_GROUP: usize = 1 << 16;

/// A column's physical type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A signed 64-bit integer.
    Int,
    /// An IEEE double.
    Float,
    /// UTF-8 text.
    Text,
}

/// A column: its name, type, whether it may be null, and its unit.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Column {
    /// The name.
    pub name: String,
    /// The type.
    pub kind: Kind,
    /// Whether a row may leave it null.
    pub optional: bool,
    /// The unit (`L`, `T`, `L/T`, `1/T`, `1`, `rad`, or a description).
    pub unit: String,
}

impl Column {
    /// A column.
    pub fn new(name: impl Into<String>, kind: Kind, optional: bool, unit: &str) -> Self {
        Column {
            name: name.into(),
            kind,
            optional,
            unit: unit.into(),
        }
    }
}

/// One value of a row.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Cell<'a> {
    /// An integer.
    Int(i64),
    /// A double.
    Float(f64),
    /// Text.
    Text(&'a str),
    /// Null (an optional column only).
    Null,
}

/// One column's buffered values of the current row group.
enum Buffer {
    Int(Vec<i64>),
    Float(Vec<f64>),
    Text(Vec<ByteArray>),
}

fn parquet_err(e: parquet::errors::ParquetError) -> io::Error {
    io::Error::other(e.to_string())
}

/// A Parquet file being written row by row (see the module docs).
pub struct Table<W: Write + Send> {
    writer: SerializedFileWriter<W>,
    columns: Vec<Column>,
    buffers: Vec<(Buffer, Vec<i16>)>,
    rows: usize,
}

impl<W: Write + Send> Table<W> {
    /// Start a table named `name` with `columns` into `out`; `about` (what a row is) and
    /// `dim` go into the metadata beside the units.
    pub fn new(
        out: W,
        name: &str,
        columns: Vec<Column>,
        about: &str,
        dim: usize,
    ) -> io::Result<Self> {
        let fields = columns
            .iter()
            .map(|c| {
                let (physical, converted) = match c.kind {
                    Kind::Int => (Physical::INT64, ConvertedType::NONE),
                    Kind::Float => (Physical::DOUBLE, ConvertedType::NONE),
                    Kind::Text => (Physical::BYTE_ARRAY, ConvertedType::UTF8),
                };
                let repetition = if c.optional {
                    Repetition::OPTIONAL
                } else {
                    Repetition::REQUIRED
                };
                Type::primitive_type_builder(&c.name, physical)
                    .with_repetition(repetition)
                    .with_converted_type(converted)
                    .build()
                    .map(Arc::new)
            })
            .collect::<Result<Vec<_>, _>>()
            .map_err(parquet_err)?;
        let schema = Type::group_type_builder(name)
            .with_fields(fields)
            .build()
            .map_err(parquet_err)?;
        let units: serde_json::Map<String, serde_json::Value> = columns
            .iter()
            .map(|c| (c.name.clone(), c.unit.clone().into()))
            .collect();
        let mut props = WriterProperties::builder()
            .set_compression(Compression::SNAPPY)
            .set_dictionary_enabled(false)
            .set_max_row_group_row_count(Some(ROW_GROUP))
            .set_created_by(format!("noslip {}", env!("CARGO_PKG_VERSION")))
            .set_key_value_metadata(Some(vec![
                KeyValue::new(
                    "noslip.units".into(),
                    serde_json::Value::Object(units).to_string(),
                ),
                KeyValue::new("noslip.table".into(), about.to_string()),
                KeyValue::new("noslip.dim".into(), dim.to_string()),
            ]));
        for c in columns.iter().filter(|c| c.kind != Kind::Float) {
            props = props.set_column_dictionary_enabled(ColumnPath::from(c.name.as_str()), true);
        }
        let writer = SerializedFileWriter::new(out, Arc::new(schema), Arc::new(props.build()))
            .map_err(parquet_err)?;
        let buffers = columns
            .iter()
            .map(|c| {
                let b = match c.kind {
                    Kind::Int => Buffer::Int(Vec::new()),
                    Kind::Float => Buffer::Float(Vec::new()),
                    Kind::Text => Buffer::Text(Vec::new()),
                };
                (b, Vec::new())
            })
            .collect();
        Ok(Table {
            writer,
            columns,
            buffers,
            rows: 0,
        })
    }

    /// The columns.
    pub fn columns(&self) -> &[Column] {
        &self.columns
    }

    /// Append one row (one cell per column, in order); a full row group is written out.
    pub fn push(&mut self, row: &[Cell<'_>]) -> io::Result<()> {
        if row.len() != self.columns.len() {
            return Err(io::Error::other(format!(
                "a row of {} cells for {} columns",
                row.len(),
                self.columns.len()
            )));
        }
        for ((cell, (buffer, defs)), column) in row.iter().zip(&mut self.buffers).zip(&self.columns)
        {
            match (cell, buffer) {
                (Cell::Null, _) if column.optional => defs.push(0),
                (Cell::Int(x), Buffer::Int(v)) => {
                    v.push(*x);
                    defs.push(1);
                }
                (Cell::Float(x), Buffer::Float(v)) => {
                    v.push(*x);
                    defs.push(1);
                }
                (Cell::Text(s), Buffer::Text(v)) => {
                    v.push(ByteArray::from(*s));
                    defs.push(1);
                }
                (cell, _) => {
                    return Err(io::Error::other(format!(
                        "column {}: {cell:?} does not fit a {:?} column",
                        column.name, column.kind
                    )))
                }
            }
        }
        self.rows += 1;
        if self.rows == ROW_GROUP {
            self.flush_group()?;
        }
        Ok(())
    }

    /// Write the buffered rows as one row group.
    fn flush_group(&mut self) -> io::Result<()> {
        if self.rows == 0 {
            return Ok(());
        }
        let mut group = self.writer.next_row_group().map_err(parquet_err)?;
        for ((buffer, defs), column) in self.buffers.iter_mut().zip(&self.columns) {
            let mut writer = group
                .next_column()
                .map_err(parquet_err)?
                .ok_or_else(|| io::Error::other("fewer columns in the schema than buffered"))?;
            let defs_arg = column.optional.then_some(defs.as_slice());
            match buffer {
                Buffer::Int(v) => {
                    writer
                        .typed::<Int64Type>()
                        .write_batch(v, defs_arg, None)
                        .map_err(parquet_err)?;
                    v.clear();
                }
                Buffer::Float(v) => {
                    writer
                        .typed::<DoubleType>()
                        .write_batch(v, defs_arg, None)
                        .map_err(parquet_err)?;
                    v.clear();
                }
                Buffer::Text(v) => {
                    writer
                        .typed::<ByteArrayType>()
                        .write_batch(v, defs_arg, None)
                        .map_err(parquet_err)?;
                    v.clear();
                }
            }
            defs.clear();
            writer.close().map_err(parquet_err)?;
        }
        group.close().map_err(parquet_err)?;
        self.rows = 0;
        Ok(())
    }

    /// Write the last row group and the footer; the writer.
    pub fn finish(mut self) -> io::Result<W> {
        self.flush_group()?;
        self.writer.into_inner().map_err(parquet_err)
    }
}

/// Whether `path` names a Parquet file: its extension is `parquet` (any case).
pub fn is_parquet(path: &std::path::Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("parquet"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use parquet::file::reader::{FileReader, SerializedFileReader};
    use parquet::record::Field;

    #[test]
    fn rows_stream_in_row_groups_and_read_back_with_nulls() {
        let path =
            std::env::temp_dir().join(format!("noslip-columnar-{}.parquet", std::process::id()));
        let columns = vec![
            Column::new("i", Kind::Int, false, "1"),
            Column::new("x", Kind::Float, true, "L"),
            Column::new("s", Kind::Text, false, "1"),
        ];
        let mut table = Table::new(
            std::fs::File::create(&path).unwrap(),
            "t",
            columns,
            "test",
            2,
        )
        .unwrap();
        let rows = 2 * ROW_GROUP + 5;
        for i in 0..rows {
            let x = if i % 3 == 0 {
                Cell::Null
            } else {
                Cell::Float(i as f64 / 7.0)
            };
            let s = if i % 2 == 0 { "even" } else { "odd" };
            table
                .push(&[Cell::Int(i as i64), x, Cell::Text(s)])
                .unwrap();
        }
        // A cell of the wrong type, a null in a required column, a short row: errors.
        assert!(table
            .push(&[Cell::Float(1.0), Cell::Null, Cell::Text("a")])
            .is_err());
        assert!(table
            .push(&[Cell::Null, Cell::Null, Cell::Text("a")])
            .is_err());
        assert!(table.push(&[Cell::Int(1)]).is_err());
        table.finish().unwrap();
        let reader = SerializedFileReader::new(std::fs::File::open(&path).unwrap()).unwrap();
        assert_eq!(
            reader.metadata().num_row_groups(),
            3,
            "full groups of ROW_GROUP, then the rest"
        );
        let meta = reader
            .metadata()
            .file_metadata()
            .key_value_metadata()
            .unwrap();
        let units = meta.iter().find(|kv| kv.key == "noslip.units").unwrap();
        let units: serde_json::Value =
            serde_json::from_str(units.value.as_deref().unwrap()).unwrap();
        assert_eq!(units, serde_json::json!({"i": "1", "x": "L", "s": "1"}));
        let mut count = 0;
        for (i, row) in reader.get_row_iter(None).unwrap().enumerate() {
            let row = row.unwrap();
            let fields: Vec<Field> = row.get_column_iter().map(|(_, f)| f.clone()).collect();
            let x = if i % 3 == 0 {
                Field::Null
            } else {
                Field::Double(i as f64 / 7.0)
            };
            let s = if i % 2 == 0 { "even" } else { "odd" };
            assert_eq!(fields, [Field::Long(i as i64), x, Field::Str(s.into())]);
            count += 1;
        }
        assert_eq!(count, rows);
        std::fs::remove_file(path).unwrap();
    }
}
