//! `noslip simulate --log FILE.parquet --boundary-map FILE.parquet`: the Parquet files hold,
//! value for value (doubles bit for bit), what the JSON lines log and the CSV boundary map of
//! the same run hold; their columns are typed and carry units in the metadata.

use crate::support;

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

/// The log of a driven run, as JSON lines and as Parquet: each contact's line is its row (as
/// [`compare_log`] checks), each kick's line `{"kick", "time", "velocities",
/// "energy_injected"}` is `balls` rows in ball order, kind "kick", `ball_0` the ball, its
/// velocity after the kick in `post_0_velocity_k` bit for bit, the kick's number in `kick`
/// and its energy in `energy_injected` on the first row (null on the others), `event` null.
/// Returns (contacts, kicks).
fn compare_driven_log(lines: &str, parquet: &Path, balls: usize) -> (usize, usize) {
    let (rows, meta) = read(parquet);
    let units: Value = serde_json::from_str(&meta["noslip.units"]).unwrap();
    assert_eq!(
        units["kick"],
        "1 (the thermostat's kick number, from 1; null on a contact's row)"
    );
    assert_eq!(units["energy_injected"], "M L^2 T^-2");
    let field = |row: &Row, name: &str| row.iter().find(|c| c.0 == name).unwrap().1.clone();
    let (mut at, mut contacts, mut kicks) = (0, 0, 0);
    let (mut contact_lines, mut contact_rows) = (String::new(), Vec::new());
    for line in lines.lines() {
        let v: Value = serde_json::from_str(line).unwrap();
        if v.get("kick").is_none() {
            contact_lines.push_str(line);
            contact_lines.push('\n');
            contact_rows.push(rows[at].clone());
            assert_eq!(field(&rows[at], "kick"), Field::Null);
            assert_eq!(field(&rows[at], "energy_injected"), Field::Null);
            at += 1;
            contacts += 1;
            continue;
        }
        kicks += 1;
        let velocities = v["velocities"].as_array().unwrap();
        assert_eq!(velocities.len(), balls);
        for (i, u) in velocities.iter().enumerate() {
            let row = &rows[at + i];
            assert_eq!(field(row, "kind"), Field::Str("kick".into()));
            assert_eq!(field(row, "event"), Field::Null);
            assert_eq!(field(row, "ball_0"), Field::Long(i as i64));
            assert_eq!(field(row, "kick"), Field::Long(v["kick"].as_i64().unwrap()));
            let Field::Double(t) = field(row, "time") else {
                panic!()
            };
            assert_eq!(t.to_bits(), float(&v["time"]).to_bits());
            for (k, x) in u.as_array().unwrap().iter().enumerate() {
                let Field::Double(y) = field(row, &format!("post_0_velocity_{k}")) else {
                    panic!("{row:?}")
                };
                assert_eq!(y.to_bits(), float(x).to_bits(), "kick {kicks}, ball {i}");
                assert!(matches!(
                    field(row, &format!("pre_0_velocity_{k}")),
                    Field::Double(_)
                ));
                assert_eq!(field(row, &format!("nu_{k}")), Field::Null);
            }
            let energy = field(row, "energy_injected");
            match (i, energy) {
                (0, Field::Double(e)) => {
                    assert_eq!(e.to_bits(), float(&v["energy_injected"]).to_bits())
                }
                (0, other) => panic!("{other:?}"),
                (_, other) => assert_eq!(other, Field::Null),
            }
        }
        at += balls;
    }
    assert_eq!(at, rows.len());
    // The contacts' rows equal their lines as for an undriven run.
    for (row, line) in contact_rows.iter().zip(contact_lines.lines()) {
        let line: Value = serde_json::from_str(line).unwrap();
        for (name, f) in row {
            if let (Field::Double(x), Some(v)) = (f, json_field(&line, name)) {
                assert_eq!(x.to_bits(), float(&v).to_bits(), "{name} in {line}");
            }
        }
    }
    (contacts, kicks)
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

/// A driven run's Parquet log holds its kicks as the JSON lines log does, velocity for
/// velocity (`compare_driven_log`): with the start, the contacts' `post` velocities and the
/// kicks' rows replay every ball's velocity, as the JSON log does
/// (`sim/tests/driven_observables.rs`, `a_driven_log_replays_every_velocity`).
#[test]
fn parquet_log_holds_the_kicks_as_the_json_log_does() {
    let dir = temp("parquet-kicks");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for (out, log) in [("text", "e.jsonl"), ("columns", "e.parquet")] {
        run_ok(
            noslip()
                .args(["simulate", "scenes/driven3d.toml", "--quiet", "--time", "2"])
                .arg("--out")
                .arg(dir.join(out))
                .arg("--log")
                .arg(dir.join(log)),
        );
    }
    let text = std::fs::read_to_string(dir.join("e.jsonl")).unwrap();
    let (contacts, kicks) = compare_driven_log(&text, &dir.join("e.parquet"), 500);
    // Kicks every 0.43 up to t = 2: at 0.43, 0.86, 1.29, 1.72.
    assert_eq!(kicks, 4);
    assert!(contacts > 100, "{contacts}");
    std::fs::remove_dir_all(&dir).unwrap();
}
