//! `noslip simulate --observables DT` on the shipped granular gas: the CSV's header with its
//! units, one row per interval, the gas cooling, the mean square displacement, g(r) with
//! --pair-correlation, the Parquet table equal to the CSV, the plots with their axes' units,
//! the self-diffusion blocks, a mixture's losses and contacts per pair of species, and bad
//! intervals, radii, blocks and laws
//! refused (exit 2, the option or the field named).

use crate::support;
use parquet::file::reader::{FileReader, SerializedFileReader};
use parquet::record::Field;
use support::{noslip, run_ok, temp};

/// The rows of the Parquet file `path`, each a list of its fields.
fn parquet_rows(path: &std::path::Path) -> Vec<Vec<Field>> {
    let reader = SerializedFileReader::new(std::fs::File::open(path).unwrap()).unwrap();
    reader
        .get_row_iter(None)
        .unwrap()
        .map(|r| {
            r.unwrap()
                .get_column_iter()
                .map(|(_, f)| f.clone())
                .collect()
        })
        .collect()
}

#[test]
fn the_granular_gas_writes_its_observables() {
    let dir = temp("granular");
    run_ok(
        noslip()
            .args([
                "simulate",
                "scenes/granular3d.toml",
                "--time",
                "5",
                "--observables",
                "1",
                "--pair-correlation",
                "3",
                "--pair-bins",
                "30",
                "--quiet",
                "--out",
            ])
            .arg(&dir),
    );
    let csv = std::fs::read_to_string(dir.join("observables.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        "time [T],contacts [1],T_tr [M L^2 T^-2],T_rot [M L^2 T^-2],energy [M L^2 T^-2],\
         collision_frequency [T^-1],lost_ball_ball [M L^2 T^-2],lost_ball_wall [M L^2 T^-2],\
         lost_ball_obstacle [M L^2 T^-2],lost_ball_boundary [M L^2 T^-2],\
         injected [M L^2 T^-2],pressure [M L^-1 T^-2],a2 [1],msd [L^2],msd_cm [L^2]"
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    // A row at the start and at the first contact after each of t = 1, 2, 3, 4.
    assert_eq!(rows.len(), 5, "{csv}");
    let (first, last) = (&rows[0], &rows[4]);
    // The Maxwellian start at temperature 1, 500 balls: within a few standard errors
    // (sqrt(2 / (3 * 499)) = 3.7 % for T_tr, sqrt(2 / 1500) for T_rot).
    assert!(
        (first[2] - 1.0).abs() < 0.15 && (first[3] - 1.0).abs() < 0.15,
        "{first:?}"
    );
    // It cools, and the ball-ball contacts took what it lost, to rounding: the bound of
    // sim/tests/granular.rs, (64 C + 40 N_b) eps E_0 for C contacts (the CSV's shortest
    // round-trip decimals are the f64 values).
    assert!(last[4] < first[4] && last[6] > 0.0, "{last:?}");
    let bound = (64.0 * last[1] + 40.0 * 500.0) * f64::EPSILON * first[4];
    assert!(((first[4] - last[4]) - last[6]).abs() <= bound, "{last:?}");
    // No displacement at the start; then msd_cm <= msd (equal masses: msd - msd_cm is the
    // centre of mass's |D|^2).
    assert_eq!((first[13], first[14]), (0.0, 0.0));
    assert!(last[14] > 0.0 && last[14] <= last[13], "{last:?}");
    // No thermostat: nothing injected.
    assert!(rows.iter().all(|r| r[10] == 0.0), "{csv}");
    // pair-correlation.csv: 30 bins of width 0.1 up to 3, none below contact (the bin
    // [0.9, 1) may hold a pair touching at a row's contact), g near 1 far out.
    let pairs = std::fs::read_to_string(dir.join("pair-correlation.csv")).unwrap();
    let mut lines = pairs.lines();
    assert_eq!(lines.next().unwrap(), "r [L],g [1]");
    let g: Vec<[f64; 2]> = lines
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            [v[0], v[1]]
        })
        .collect();
    assert_eq!(g.len(), 30, "{pairs}");
    assert!((g[0][0] - 0.05).abs() < 1e-12 && (g[29][0] - 2.95).abs() < 1e-12);
    assert!(g[..9].iter().all(|&[_, g]| g == 0.0), "{pairs}");
    assert!(
        g[20..].iter().all(|&[_, g]| (g - 1.0).abs() < 0.2),
        "{pairs}"
    );
    // pair-correlation.parquet: the same numbers, bit for bit.
    let table = parquet_rows(&dir.join("pair-correlation.parquet"));
    assert_eq!(table.len(), g.len());
    for (got, want) in table.iter().zip(&g) {
        for (x, w) in got.iter().zip(want) {
            let Field::Double(x) = x else { panic!("{x:?}") };
            assert_eq!(x.to_bits(), w.to_bits());
        }
    }
    // observables.parquet holds the same numbers, bit for bit (the CSV's shortest
    // round-trip decimals parse back to the f64 values), `contacts` an integer.
    let table = parquet_rows(&dir.join("observables.parquet"));
    assert_eq!(table.len(), rows.len());
    for (got, want) in table.iter().zip(&rows) {
        assert_eq!(got.len(), want.len());
        for (k, (g, w)) in got.iter().zip(want).enumerate() {
            match g {
                Field::Long(c) if k == 1 => assert_eq!(*c as f64, *w),
                Field::Double(x) => assert_eq!(x.to_bits(), w.to_bits(), "column {k}"),
                other => panic!("column {k}: {other:?}"),
            }
        }
    }
    // observables.svg: the temperatures against time, titled with the scene.
    let svg = std::fs::read_to_string(dir.join("observables.svg")).unwrap();
    assert!(svg.contains("granular3d.toml: granular temperatures"));
    // The other observables' plots, each titled and its axes named with units (the pressure
    // of a 3D box in M L^-1 T^-2).
    for (file, texts) in [
        (
            "observables-pressure.svg",
            &[
                "granular3d.toml: pressure",
                "time [T]",
                "pressure [M L^-1 T^-2]",
            ][..],
        ),
        (
            "observables-a2.svg",
            &["velocity cumulant a_2", "a_2 [1]", "Maxwellian (0)"][..],
        ),
        (
            "observables-msd.svg",
            &[
                "mean square displacement [L^2]",
                "msd_cm (about the centre of mass)",
            ][..],
        ),
        (
            "pair-correlation.svg",
            &[
                "granular3d.toml: pair correlation",
                "r [L]",
                "g(r) [1]",
                "uncorrelated (1)",
            ][..],
        ),
    ] {
        let svg = std::fs::read_to_string(dir.join(file)).unwrap();
        for text in texts {
            assert!(svg.contains(text), "{file}: {text}");
        }
        assert!(!svg.contains("no finite values"), "{file}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A mixture's observables end with the energy lost and the contacts per pair of species,
/// named by the species (`scenes/mixture2d.toml`: grain and tracer): in the CSV with units,
/// in the Parquet table the same numbers bit for bit with the counts as integers; each row's
/// pairs' contacts add up to its ball-ball contacts (the box is periodic: `contacts`), and
/// its pairs' losses to `lost_ball_ball` within two summation orders' rounding, `(C + 2) eps
/// E_0` (the losses are nonnegative and add up to at most `E_0`; `sim/tests/pair_laws.rs`).
#[test]
fn a_mixture_writes_the_losses_and_contacts_per_pair_of_species() {
    let dir = temp("mixture-observables");
    run_ok(
        noslip()
            .args([
                "simulate",
                "scenes/mixture2d.toml",
                "--time",
                "3",
                "--observables",
                "0.5",
                "--quiet",
                "--out",
            ])
            .arg(&dir),
    );
    let csv = std::fs::read_to_string(dir.join("observables.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(
        header[header.len() - 8..],
        [
            "msd_cm_0 [L^2]",
            "msd_cm_1 [L^2]",
            "lost_ball_ball_grain-grain [M L^2 T^-2]",
            "lost_ball_ball_grain-tracer [M L^2 T^-2]",
            "lost_ball_ball_tracer-tracer [M L^2 T^-2]",
            "contacts_grain-grain [1]",
            "contacts_grain-tracer [1]",
            "contacts_tracer-tracer [1]",
        ]
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 6, "{csv}");
    let w = header.len();
    let e0 = rows[0][4];
    for r in &rows {
        let (losses, counts) = (&r[w - 6..w - 3], &r[w - 3..]);
        assert_eq!(counts.iter().sum::<f64>(), r[1], "{r:?}");
        let bound = (r[1] + 2.0) * f64::EPSILON * e0;
        assert!((losses.iter().sum::<f64>() - r[6]).abs() <= bound, "{r:?}");
    }
    let last = rows.last().unwrap();
    assert!(
        last[w - 6..].iter().all(|&x| x > 0.0),
        "every pair met: {last:?}"
    );
    let table = parquet_rows(&dir.join("observables.parquet"));
    assert_eq!(table.len(), rows.len());
    for (got, want) in table.iter().zip(&rows) {
        assert_eq!(got.len(), w);
        for (k, (g, x)) in got.iter().zip(want).enumerate() {
            match g {
                Field::Long(c) if k == 1 || k >= w - 3 => assert_eq!(*c as f64, *x),
                Field::Double(v) if k != 1 && k < w - 3 => {
                    assert_eq!(v.to_bits(), x.to_bits(), "column {k}")
                }
                other => panic!("column {k}: {other:?}"),
            }
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `--self-diffusion BLOCK`: blocks from the start's row on the grid of BLOCK, each ending at
/// the first row at or after its nominal end and starting the next, written to
/// self-diffusion.csv with units; the estimate on stdout is the blocks' mean.
#[test]
fn the_self_diffusion_blocks_are_written_with_units() {
    let dir = temp("granular-diffusion");
    let out = noslip()
        .args([
            "simulate",
            "scenes/driven3d.toml",
            "--time",
            "12.5",
            "--observables",
            "0.25",
            "--self-diffusion",
            "3",
            "--quiet",
            "--out",
        ])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(out.status.success(), "{out:?}");
    let stdout = String::from_utf8(out.stdout).unwrap();
    let csv = std::fs::read_to_string(dir.join("self-diffusion.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        "block [1],start [T],end [T],D [L^2 T^-1]"
    );
    let blocks: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    // From t = 0: blocks ending at the first row at or after 3, 6, 9, 12 (rows at the first
    // contact at or after each multiple of 0.25; the grid does not drift).
    assert_eq!(blocks.len(), 4, "{csv}");
    assert_eq!(blocks[0][1], 0.0, "{csv}");
    for (k, b) in blocks.iter().enumerate() {
        assert_eq!(b[0], k as f64);
        let nominal = 3.0 * (k + 1) as f64;
        assert!(b[2] >= nominal && b[2] < nominal + 0.25, "{csv}");
        assert!(b[3] > 0.0, "{csv}");
        if k > 0 {
            assert_eq!(b[1], blocks[k - 1][2], "{csv}");
        }
    }
    let mean = blocks.iter().map(|b| b[3]).sum::<f64>() / 4.0;
    let line = stdout
        .lines()
        .find(|l| l.starts_with("self-diffusion: D = "))
        .unwrap_or_else(|| panic!("{stdout}"));
    let printed: f64 = line["self-diffusion: D = ".len()..]
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!((printed - mean).abs() <= 1e-6 * mean, "{line} {mean}");
    assert!(line.contains("[L^2 T^-1] (4 blocks of 3 from 0"), "{line}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `noslip args`: it must exit 2 with `says` in its stderr.
fn refused(args: &[&str], says: &str) {
    let out = noslip().args(args).output().unwrap();
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains(says), "{err}");
}

#[test]
fn bad_intervals_and_laws_exit_2_naming_them() {
    let gas = "scenes/granular3d.toml";
    refused(
        &["simulate", gas, "--observables", "0", "--quiet"],
        "--observables: the interval must be positive",
    );
    // g(r) beyond half the box's side (14) is refused.
    refused(
        &[
            "simulate",
            gas,
            "--observables",
            "1",
            "--pair-correlation",
            "8",
            "--quiet",
        ],
        "--pair-correlation: the pair correlation's r_max = 8 must be in (0, 7]",
    );
    refused(
        &[
            "simulate",
            gas,
            "--observables",
            "1",
            "--self-diffusion",
            "3",
            "--quiet",
        ],
        "--self-diffusion: the block (3) must be at least 4 sampling intervals (4): its last four \
         fifths are fitted",
    );
    refused(
        &[
            "simulate",
            gas,
            "--observables",
            "1",
            "--self-diffusion",
            "8",
            "--self-diffusion-from",
            "-1",
            "--quiet",
        ],
        "--self-diffusion: the start must be at least 0 and finite, got -1",
    );
    // The bins are bounded (2^30 asked for 8 GiB; 0 for none).
    for bins in ["0", "1048577", "1073741824"] {
        refused(
            &[
                "simulate",
                gas,
                "--observables",
                "1",
                "--pair-correlation",
                "2",
                "--pair-bins",
                bins,
                "--quiet",
            ],
            &format!(
                "--pair-correlation: the pair correlation's bins must be in 1..=1048576, got {bins}"
            ),
        );
    }
    // One ball is its own centre of mass: its displacement about it is always 0.
    refused(
        &[
            "simulate",
            "scenes/sinai.toml",
            "--observables",
            "1",
            "--self-diffusion",
            "8",
            "--quiet",
        ],
        "--self-diffusion: needs at least two balls: the displacements are measured about the \
         centre of mass, which one ball is, so its D would be 0 by construction",
    );
    let dir = temp("granular-bad");
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.toml");
    let scene = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/granular3d.toml"),
    )
    .unwrap()
    .replace("e = \"0.9\"", "e = \"1.2\"");
    std::fs::write(&bad, scene).unwrap();
    refused(
        &["simulate", bad.to_str().unwrap(), "--quiet"],
        "bad.toml: contact.balls.e: must be in [0, 1], got 6/5",
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A disk that collapses against the circle's wall (`e = 1/2`, no TC model) leaves along it
/// after 33 contacts: `simulate` exits 2 naming the ball and the container, after writing
/// the run up to it (the log's 33 lines, the summary with `left_table`); at `e = 0` the
/// scene is refused naming `e`.
#[test]
fn a_ball_leaving_its_container_exits_2_naming_it_and_keeps_the_run() {
    let dir = temp("granular-left");
    std::fs::create_dir_all(&dir).unwrap();
    let shipped = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/circle.toml"),
    )
    .unwrap();
    let with =
        |law: &str| shipped.replacen("radius = 1\n", &format!("radius = 1\ncontact = {law}\n"), 1);
    let scene = dir.join("collapse.toml");
    std::fs::write(&scene, with("{ e = \"0.5\", beta = \"-1\" }")).unwrap();
    let out = dir.join("out");
    let log = out.join("events.jsonl");
    refused(
        &[
            "simulate",
            scene.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--log",
            log.to_str().unwrap(),
            "--quiet",
        ],
        "collapse.toml: ball 0 left the table through container[0] after its contact at t = ",
    );
    assert_eq!(std::fs::read_to_string(&log).unwrap().lines().count(), 33);
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["left_table"]["ball"], 0);
    assert_eq!(summary["left_table"]["boundary"], 0);
    assert!(summary["stopped"]
        .as_str()
        .unwrap()
        .contains("container[0]"));
    // Contacts at one instant without end (the wedge's walls at e = 0 drive the disk into
    // the apex): exit 2 naming the ball, where a run with --time and no event limit used to
    // never return.
    let wedge = dir.join("apex.toml");
    let apex = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/wedge.toml"),
    )
    .unwrap()
    .replace(
        "[table.wedge]",
        "[table]\ncontact = { e = 0, beta = -1 }\n[table.wedge]",
    )
    .replace("events = 100_000", "");
    std::fs::write(&wedge, apex).unwrap();
    refused(
        &[
            "simulate",
            wedge.to_str().unwrap(),
            "--time",
            "10",
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ],
        "apex.toml: inelastic collapse at t = 2.57845",
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["collapse"]["balls"], serde_json::json!([0]));
    let zero = dir.join("zero.toml");
    std::fs::write(&zero, with("{ e = 0, beta = \"0.5\" }")).unwrap();
    refused(
        &["simulate", zero.to_str().unwrap(), "--quiet"],
        "zero.toml: container[0].contact.e: must be > 0 on a container",
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The tangent maps of `lyapunov` and the exact return maps of `orbits` are those of the
/// elastic laws: a scene with a rough law is refused (exit 2, the place named), not run with
/// a wrong map.
#[test]
fn lyapunov_and_orbits_refuse_rough_laws() {
    let dir = temp("granular-dynamics");
    std::fs::create_dir_all(&dir).unwrap();
    let triangle = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/triangle.toml"),
    )
    .unwrap()
    .replace(
        "[table]\n",
        "[table]\ncontact = { e = \"0.9\", beta = \"0.5\" }\n",
    );
    let scene = dir.join("rough.toml");
    std::fs::write(&scene, triangle).unwrap();
    let path = scene.to_str().unwrap();
    for (args, says) in [
        (
            vec!["orbits", path, "--period", "3", "--grid", "1"],
            "rough.toml: table.polygon[0].contact: a rough law",
        ),
        (
            vec!["lyapunov", path, "--events", "100"],
            "a contact follows a rough law",
        ),
    ] {
        let out = noslip()
            .args(&args)
            .arg("--out")
            .arg(dir.join("out"))
            .output()
            .unwrap();
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
