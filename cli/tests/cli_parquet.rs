//! `noslip simulate --log FILE.parquet --boundary-map FILE.parquet`: the Parquet files hold,
//! value for value (doubles bit for bit), what the JSON lines log and the CSV boundary map of
//! the same run hold; their columns are typed and carry units in the metadata.

mod support;

use parquet::file::reader::{FileReader, SerializedFileReader};
use parquet::record::Field;
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::Path;
use support::{noslip, run_ok, temp};

/// Run `scene` for `events` contacts with the log and the map in `log` and `map`.
fn simulate(scene: &str, events: u64, dir: &Path, out: &str, log: &str, map: &str) {
    run_ok(
        noslip()
            .args([
                "simulate",
                scene,
                "--quiet",
                "--events",
                &events.to_string(),
            ])
            .arg("--out")
            .arg(dir.join(out))
            .arg("--log")
            .arg(dir.join(log))
            .arg("--boundary-map")
            .arg(dir.join(map)),
    );
}

/// A row: (column name, value) in column order.
type Row = Vec<(String, Field)>;

/// The rows of a Parquet file, and its key-value metadata.
fn read(path: &Path) -> (Vec<Row>, BTreeMap<String, String>) {
    let reader = SerializedFileReader::new(std::fs::File::open(path).unwrap()).unwrap();
    let meta = reader
        .metadata()
        .file_metadata()
        .key_value_metadata()
        .map(|kv| {
            kv.iter()
                .map(|k| (k.key.clone(), k.value.clone().unwrap_or_default()))
                .collect()
        })
        .unwrap_or_default();
    let rows = reader
        .get_row_iter(None)
        .unwrap()
        .map(|r| {
            r.unwrap()
                .get_column_iter()
                .map(|(name, field)| (name.clone(), field.clone()))
                .collect()
        })
        .collect();
    (rows, meta)
}

fn float(x: &Value) -> f64 {
    x.as_f64().unwrap_or_else(|| panic!("not a number: {x}"))
}

/// The JSON log line's value for column `name` (`None`: null).
fn json_field(line: &Value, name: &str) -> Option<Value> {
    let parts: Vec<&str> = name.split('_').collect();
    let at = |v: &Value, i: &str| v.get(i.parse::<usize>().unwrap()).cloned();
    match parts[..] {
        ["ball", b] => at(&line["balls"], b),
        ["nu", k] => at(&line["nu"], k),
        ["position", b, k] => at(&line["positions"], b).and_then(|p| at(&p, k)),
        [when, b, what, k] => at(&line[when], b).and_then(|s| at(&s[what], k)),
        _ => line.get(name).cloned(),
    }
}

/// The log of one scene, as JSON lines and as Parquet, agree in every column of every row.
fn compare_log(lines: &str, parquet: &Path) -> usize {
    let (rows, meta) = read(parquet);
    let lines: Vec<Value> = lines
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(rows.len(), lines.len());
    let units: Value = serde_json::from_str(&meta["noslip.units"]).unwrap();
    for (row, line) in rows.iter().zip(&lines) {
        for (name, field) in row {
            assert!(units.get(name).is_some(), "no unit for {name}");
            let expected = json_field(line, name);
            match (field, &expected) {
                (Field::Null, None) => {}
                (Field::Double(x), Some(v)) => {
                    assert_eq!(x.to_bits(), float(v).to_bits(), "{name} in {line}")
                }
                (Field::Long(x), Some(v)) => assert_eq!(Some(*x), v.as_i64(), "{name} in {line}"),
                (Field::Str(s), Some(v)) => assert_eq!(Some(s.as_str()), v.as_str(), "{name}"),
                (f, e) => panic!("{name}: parquet {f:?}, JSON {e:?} in {line}"),
            }
        }
        // Every field of the JSON line is in the row (as columns of its flattening).
        for key in line.as_object().unwrap().keys() {
            let prefix = match key.as_str() {
                "balls" => "ball_",
                "positions" => "position_",
                k => k,
            };
            assert!(
                row.iter()
                    .any(|(n, f)| n.starts_with(prefix) && *f != Field::Null),
                "{key} of {line} is in no column"
            );
        }
    }
    assert_eq!(units["time"], "T");
    assert_eq!(units["pre_0_velocity_0"], "L/T");
    lines.len()
}

/// The boundary map as CSV and as Parquet agree in every column of every row.
fn compare_map(csv: &str, parquet: &Path) -> usize {
    let (rows, meta) = read(parquet);
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let lines: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), lines.len());
    for (row, line) in rows.iter().zip(&lines) {
        let names: Vec<&str> = row.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, header);
        for ((name, field), text) in row.iter().zip(line) {
            match field {
                Field::Double(x) => {
                    assert_eq!(
                        x.to_bits(),
                        text.parse::<f64>().unwrap().to_bits(),
                        "{name}"
                    )
                }
                Field::Long(x) => assert_eq!(x.to_string(), *text, "{name}"),
                Field::Str(s) => assert_eq!(s, text, "{name}"),
                f => panic!("{name}: {f:?}"),
            }
        }
    }
    let units: Value = serde_json::from_str(&meta["noslip.units"]).unwrap();
    assert_eq!(units["incidence"], "rad");
    assert_eq!(
        meta["noslip.dim"].parse::<usize>().unwrap(),
        header.len() - 15
    );
    lines.len()
}

#[test]
fn parquet_log_and_map_equal_the_text_ones_value_for_value() {
    let dir = temp("parquet");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    // Ball-ball and box walls (2D), an obstacle and polygon boundaries, 3D spins in a
    // periodic gas (no boundary: an empty map) and in a cube.
    for (scene, events, walls) in [
        ("scenes/gas2d.toml", 4000, true),
        ("scenes/sinai_square.toml", 2000, true),
        ("scenes/gas3d.toml", 2000, false),
        ("scenes/cube3d.toml", 1000, true),
    ] {
        simulate(scene, events, &dir, "text", "e.jsonl", "m.csv");
        simulate(scene, events, &dir, "columns", "e.parquet", "m.parquet");
        let text = |name: &str| std::fs::read_to_string(dir.join(name)).unwrap();
        let rows = compare_log(&text("e.jsonl"), &dir.join("e.parquet"));
        assert_eq!(rows, events as usize, "{scene}");
        let map_rows = compare_map(&text("m.csv"), &dir.join("m.parquet"));
        assert_eq!(map_rows > 0, walls, "{scene}: {map_rows} boundary contacts");
        // Outside --out, each file links to its member of the published set, named by format.
        for member in ["events.parquet", "boundary-map.parquet"] {
            assert!(dir.join("columns").join(member).is_file(), "{member}");
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
