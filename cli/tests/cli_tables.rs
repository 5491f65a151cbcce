//! Tables from the outside: bad table scenes exit 2 with one line naming the place, the
//! boundary map's CSV and portraits, and `noslip gen --check` on the shipped table scenes.

use crate::support;
use std::path::Path;
use support::noslip;

/// A fresh scratch directory for one test ([`support::scratch`]).
fn scratch(name: &str) -> support::Scratch {
    support::scratch(&format!("tables-{name}"))
}

const DISK: &str = "dim = 2\n[[species]]\nmass = 1\nradius = \"1/10\"\n[[ball]]\nspecies = 0\nposition = [\"1/2\", \"1/2\"]\nvelocity = [1, 0]\n";

#[test]
fn bad_tables_exit_2_with_one_line_naming_the_place() {
    let dir = scratch("bad");
    let cases = [
        (
            "[[wall]]\npoint = [0, 0]\nnormal = [0, 0]\n",
            "wall[0].normal: must be a nonzero vector",
        ),
        (
            "[[wall]]\npoint = [0, 1]\nnormal = [0, 1]\n",
            "ball[0].position: outside the table: behind wall[0]",
        ),
        (
            "[[wall]]\npoint = [0, \"0.45\"]\nnormal = [0, 1]\n",
            "ball[0].position: cut by wall[0]",
        ),
        (
            "[[container]]\ncentre = [0, 0]\nradius = \"1/20\"\n",
            "ball[0].position: container[0] is too small",
        ),
        (
            "[table]\npolygon = [[0, 0], [1, 0], [1, 1], [\"0.9\", \"0.1\"]]\n",
            "table.polygon: not strictly convex",
        ),
        (
            "[[wall]]\npoint = [0, nan]\nnormal = [0, 1]\n",
            "must be finite",
        ),
        (
            "[[wall]]\npoint = [0, 0]\nnormal = [0, inf]\n",
            "must be finite",
        ),
    ];
    for (k, (table, want)) in cases.iter().enumerate() {
        let file = dir.join(format!("bad{k}.toml"));
        std::fs::write(&file, format!("{DISK}{table}")).unwrap();
        for sub in [
            vec!["simulate", file.to_str().unwrap(), "--quiet", "--out"],
            vec!["gen", "--scene", file.to_str().unwrap()],
        ] {
            let mut cmd = noslip();
            cmd.args(&sub);
            if sub[0] == "simulate" {
                cmd.arg(dir.join(format!("out{k}")));
            }
            let out = cmd.output().unwrap();
            let err = String::from_utf8(out.stderr).unwrap();
            assert_eq!(out.status.code(), Some(2), "{table}: {err}");
            assert_eq!(err.lines().count(), 1, "{err}");
            assert!(err.contains(want), "{table}: {err}");
        }
    }
}

#[test]
fn the_boundary_map_has_a_row_per_boundary_contact_and_a_portrait_per_boundary() {
    let dir = scratch("map");
    let csv = dir.join("map.csv");
    let out = dir.join("out");
    let run = noslip()
        .args([
            "simulate",
            "scenes/sinai_square.toml",
            "--events",
            "500",
            "--quiet",
            "--out",
        ])
        .arg(&out)
        .arg("--boundary-map")
        .arg(&csv)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(
        header[..7],
        ["event", "time", "ball", "kind", "id", "q0", "q1"]
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    // One ball: every contact is with an immovable body, one row each, in order.
    assert_eq!(rows.len(), 500);
    for (k, row) in rows.iter().enumerate() {
        assert_eq!(row.len(), header.len());
        assert_eq!(row[0], (k + 1).to_string());
        assert!(["boundary", "obstacle"].contains(&row[3]), "{row:?}");
        // The normal velocity before is towards the body; the angles are within +-pi/2.
        let get = |name: &str| -> f64 {
            row[header.iter().position(|h| *h == name).unwrap()]
                .parse()
                .unwrap()
        };
        assert!(get("normal_velocity") < 0.0);
        assert!(get("incidence").abs() <= std::f64::consts::FRAC_PI_2);
    }
    // The four walls of the square and the obstacle each get both pictures.
    for name in [
        "boundary-0",
        "boundary-1",
        "boundary-2",
        "boundary-3",
        "obstacle-0",
    ] {
        let svg = std::fs::read_to_string(out.join(format!("portrait-{name}.svg"))).unwrap();
        assert!(svg.starts_with("<svg"), "{name}");
        let png = std::fs::read(out.join(format!("portrait-{name}.png"))).unwrap();
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    }
}

#[test]
fn gen_checks_the_shipped_table_scenes() {
    for name in [
        "strip",
        "wedge",
        "sector",
        "triangle",
        "circle",
        "sinai_square",
        "cube3d",
        "sphere3d",
    ] {
        let path = Path::new("scenes").join(format!("{name}.toml"));
        let out = noslip()
            .args(["gen", "--scene"])
            .arg(&path)
            .args(["--check", "8"])
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{name}: {}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
    }
}
