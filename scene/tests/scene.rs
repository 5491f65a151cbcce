//! Scene files: the shipped ones are valid; bad ones are refused with the place named.

use noslip_scene::{Boundary, ContactKind, Placement, Scene, WallSide, MAX_BALLS};
use std::path::Path;

const BASE: &str = r#"
dim = 2
[box]
size = [10, 10]
boundary = ["wall", "periodic"]
[[species]]
mass = 1
radius = "1/2"
"#;

fn error(extra: &str) -> String {
    Scene::from_toml(&format!("{BASE}{extra}"), "t.toml")
        .expect_err("a bad scene")
        .to_string()
}

#[test]
fn shipped_scenes_are_valid() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    let mut names = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let scene = Scene::from_file(&path).unwrap_or_else(|e| panic!("{e}"));
        assert!(scene.ball_count() > 0);
        names.push(scene.pairs().name);
    }
    names.sort();
    assert_eq!(
        names,
        [
            "circle",
            "cube3d",
            "disk_between_walls",
            "driven3d",
            "gas2d",
            "gas3d",
            "gas4d",
            "gas5d",
            "gas6d",
            "granular3d",
            "mixture2d",
            "sector",
            "sinai",
            "sinai_square",
            "sphere3d",
            "strip",
            "triangle",
            "wedge"
        ]
    );
}

#[test]
fn pairs_follow_the_scene() {
    let s = Scene::from_toml(
        &format!("{BASE}[[ball]]\nspecies = 0\nposition = [1, 1]\n"),
        "one.toml",
    )
    .unwrap();
    let p = s.pairs();
    assert_eq!(s.boundary, [Boundary::Wall, Boundary::Periodic]);
    // One ball: no ball-ball; walls on axis 0 only; no obstacles.
    assert!(p.ball_ball.is_empty());
    assert_eq!(
        p.ball_wall,
        [(0, 0, WallSide::Lower), (0, 0, WallSide::Upper)]
    );
    assert!(p.ball_obstacle.is_empty());
}

#[test]
fn bad_scenes_name_the_place() {
    let cases = [
        ("[[ball]]\nspecies = 0\nposition = [1, 1]\nradius = 2\n", "t.toml: line 12, column 1: ball[0].radius: unknown field `radius`"),
        ("[[ball]]\nspecies = 0\nposition = [1, 1]\n[[ball]]\nspecies = 0\nposition = [1.5, 1]\n", "t.toml: ball[1].position: overlaps ball[0]"),
        ("[[ball]]\nspecies = 0\nposition = [0.25, 1]\n", "t.toml: ball[0].position[0]: the ball is outside the box"),
        ("[[ball]]\nspecies = 0\nposition = [1, 10]\n", "t.toml: ball[0].position[1]: the ball is outside the box"),
        ("[[ball]]\nspecies = 0\nposition = [1, 1, 1]\n", "t.toml: ball[0].position: has 3 components, expected dim = 2"),
        ("[[ball]]\nspecies = 0\nposition = [1, 1]\nvelocity = [1]\n", "t.toml: ball[0].velocity: has 1 components"),
        ("[[ball]]\nspecies = 3\nposition = [1, 1]\n", "t.toml: ball[0].species: no species 3"),
        ("[[ball]]\nspecies = 0\nposition = [1, 1]\nangular_velocity = [[0, 1], [1, 0]]\n", "t.toml: ball[0].angular_velocity: not skew"),
        ("[[species]]\nmass = 1\nradius = 1\nlambda = \"0.6\"\ncount = 1\n", "t.toml: species[1].lambda: must be in [0, R^2/n] = [0, 1/2], got 3/5"),
        ("[[species]]\nmass = 0\nradius = 1\n", "t.toml: species[1].mass: must be positive"),
        ("[[species]]\nmass = 1\nradius = 6\n", "t.toml: species[1].radius: a ball of radius 6 does not fit"),
        ("[[obstacle]]\nposition = [5, 5]\nradius = 2\n[[ball]]\nspecies = 0\nposition = [5, 7]\n", "t.toml: ball[0].position: overlaps obstacle[0]"),
        ("[random]\nspeed = -1\n", "t.toml: random.speed: must be >= 0"),
        ("[random]\nplacement = \"grid\"\n", "t.toml: random.placement: must be \"random\" or \"lattice\", got \"grid\""),
        ("[random]\nplacement = 1\n", "t.toml: line 10, column 13: random.placement: invalid type: integer `1`, expected a string"),
        ("[[ball]]\nspecies = 0\nposition = [\"1/0\", 1]\n", "zero denominator"),
    ];
    for (extra, want) in cases {
        let got = error(extra);
        assert!(
            got.starts_with(want) || got.contains(want),
            "for {extra:?}:\n got  {got}\n want {want}"
        );
    }
    // lambda = R^2/n (a shell) is in range.
    Scene::from_toml(
        &format!("{BASE}[[species]]\nmass = 1\nradius = 1\nlambda = \"1/2\"\ncount = 1\n"),
        "t.toml",
    )
    .unwrap();
    // Periodic minimum image: balls near opposite faces of the periodic axis overlap.
    let wrap = error(
        "[[ball]]\nspecies = 0\nposition = [5, 0.2]\n[[ball]]\nspecies = 0\nposition = [5, 9.6]\n",
    );
    assert!(
        wrap.contains("ball[1].position: overlaps ball[0]"),
        "{wrap}"
    );
    let dims = Scene::from_toml(
        "dim = 7\n[box]\nsize=[1]\nboundary=[\"wall\"]\n[[species]]\nmass=1\nradius=1\n",
        "d.toml",
    );
    assert_eq!(
        dims.unwrap_err().to_string(),
        "d.toml: dim: must be in 2..=6, got 7"
    );
}

#[test]
fn placement_is_random_unless_lattice_is_asked() {
    let with = |extra: &str| {
        Scene::from_toml(&format!("{BASE}count = 3\n{extra}"), "t.toml")
            .unwrap()
            .random
            .placement
    };
    assert_eq!(with(""), Placement::Random);
    assert_eq!(with("[random]\nseed = 3\n"), Placement::Random);
    assert_eq!(
        with("[random]\nplacement = \"random\"\n"),
        Placement::Random
    );
    assert_eq!(
        with("[random]\nplacement = \"lattice\"\n"),
        Placement::Lattice
    );
}

#[test]
fn duplicate_keys_are_refused() {
    let cases = [
        (
            "mass = 2\n",
            "t.toml: line 9, column 1: species[0].mass: duplicate key `mass`",
        ),
        (
            "[[ball]]\nspecies = 0\nspecies = 0\nposition = [1, 1]\n",
            "t.toml: line 11, column 1: ball[0].species: duplicate key `species`",
        ),
        (
            "[random]\nseed = 1\n[random]\nseed = 2\n",
            "t.toml: line 11, column 1: invalid table header duplicate key `random`",
        ),
    ];
    for (extra, want) in cases {
        let got = error(extra);
        assert!(
            got.starts_with(want),
            "for {extra:?}:\n got  {got}\n want {want}"
        );
    }
}

#[test]
fn ball_counts_are_summed_without_overflow_and_limited() {
    // Four species of 2^62 balls: the total 2^64 used to wrap to 0 ("the scene has no balls").
    let big = "[[species]]\nmass = 1\nradius = \"1/2\"\ncount = 4611686018427387904\n".repeat(4);
    let got = error(&big);
    assert!(
        got.starts_with("t.toml: species[1].count: 4611686018427387904 balls"),
        "{got}"
    );
    // The limit itself is accepted, one more is not.
    let at = |n: usize| format!("[[species]]\nmass = 1\nradius = \"1/2\"\ncount = {n}\n");
    Scene::from_toml(&format!("{BASE}{}", at(MAX_BALLS)), "t.toml").unwrap();
    let over = error(&format!(
        "{}[[ball]]\nspecies = 0\nposition = [1, 1]\n",
        at(MAX_BALLS)
    ));
    assert!(
        over.starts_with(&format!(
            "t.toml: species[1].count: {} balls",
            MAX_BALLS + 1
        )),
        "{over}"
    );
}

#[test]
fn a_run_of_no_events_is_refused() {
    let got = error("[simulation]\nevents = 0\n");
    assert!(
        got.starts_with("t.toml: simulation.events: must be at least 1"),
        "{got}"
    );
}

const NO_BOX: &str = r#"
dim = 2
[[species]]
mass = 1
radius = "1/10"
"#;

fn table_error(extra: &str) -> String {
    Scene::from_toml(&format!("{NO_BOX}{extra}"), "t.toml")
        .expect_err("a bad scene")
        .to_string()
}

const BALL: &str = "[[ball]]\nspecies = 0\nposition = [\"1/2\", \"1/2\"]\nvelocity = [1, 0]\n";

#[test]
fn bad_tables_name_the_place() {
    let cases = [
        (format!("[[wall]]\npoint = [0, 0]\nnormal = [0, 0]\n{BALL}"), "t.toml: wall[0].normal: must be a nonzero vector"),
        (format!("[[wall]]\npoint = [0, 0]\nnormal = [0, 1, 0]\n{BALL}"), "t.toml: wall[0].normal: has 3 components"),
        (format!("[[wall]]\npoint = [0, 1]\nnormal = [0, 1]\n{BALL}"), "t.toml: ball[0].position: outside the table: behind wall[0]"),
        (format!("[[wall]]\npoint = [0, \"0.55\"]\nnormal = [0, -3]\n{BALL}"), "t.toml: ball[0].position: cut by wall[0]"),
        (format!("[[container]]\ncentre = [0, 0]\nradius = \"1/20\"\n{BALL}"), "t.toml: ball[0].position: container[0] is too small"),
        (format!("[[container]]\ncentre = [0, 0]\nradius = \"1/2\"\n{BALL}"), "t.toml: ball[0].position: outside the table or cut by container[0]"),
        (format!("[[container]]\ncentre = [0, 0]\nradius = 0\n{BALL}"), "t.toml: container[0].radius: must be positive"),
        (format!("[table]\npolygon = [[0, 0], [1, 0], [1, 1], [\"0.9\", \"0.1\"]]\n{BALL}"), "t.toml: table.polygon: not strictly convex"),
        (format!("[table]\npolygon = [[0, 0], [1, 0], [2, 0]]\n{BALL}"), "t.toml: table.polygon: the polygon has no area"),
        (format!("[table]\npolygon = [[0, 0], [1, 0]]\n{BALL}"), "t.toml: table.polygon: a polygon needs at least 3 vertices"),
        // A pentagram: every turn the same way, but it winds twice.
        (format!("[table]\npolygon = [[0, 0], [2, 1], [-1, 1], [1, 0], [0, 2]]\n{BALL}"), "t.toml: table.polygon: not strictly convex"),
        (format!("[table]\npolygon = [[0, 0], [1, 0], [0, 1]]\n[table.wedge]\ncorner = [0, 0]\nangle_degrees = 30\n{BALL}"), "t.toml: table: give exactly one of polygon and [table.wedge]"),
        (format!("[table.wedge]\ncorner = [0, 0]\nangle_degrees = 180\n{BALL}"), "t.toml: table.wedge.angle_degrees: must be in (0, 180)"),
        (format!("[table.wedge]\ncorner = [0, 0]\ndirections = [[0, 1], [1, 0]]\n{BALL}"), "t.toml: table.wedge.directions: the second direction must be strictly counterclockwise"),
        (format!("[[polygon]]\nvertices = [[0, 0], [3, 0], [0, 3]]\n{BALL}"), "t.toml: ball[0].position: inside the polygon obstacle"),
        (format!("[[polygon]]\nvertices = [[\"0.55\", \"0.5\"], [2, 0], [2, 2]]\n{BALL}"), "t.toml: ball[0].position: overlaps the polygon edge polygon[0].vertices[0]"),
        (format!("[[wall]]\npoint = [0, nan]\nnormal = [0, 1]\n{BALL}"), "must be finite"),
        (format!("[[wall]]\npoint = [0, 0]\nnormal = [inf, 1]\n{BALL}"), "must be finite"),
        ("[[container]]\ncentre = [0, 0]\nradius = \"0.6\"\n[[ball]]\nspecies = 0\nposition = [\"1/2\", 0]\nvelocity = [0, 1]\n".to_string(), "t.toml: ball[0].velocity: the ball touches container[0] from inside moving along it"),
        ("[[species]]\nmass = 1\nradius = 1\ncount = 3\n[[wall]]\npoint = [0, 0]\nnormal = [0, 1]\n".to_string(), "t.toml: species[1].count: random placement needs a [box]"),
    ];
    for (extra, want) in &cases {
        let got = table_error(extra);
        assert!(
            got.starts_with(want) || got.contains(want),
            "for {extra:?}:\n got  {got}\n want {want}"
        );
        assert!(!got.contains('\n'), "one line: {got}");
    }
    // 3D: a polygon is 2D; with a periodic box, no walls.
    let e = Scene::from_toml(
        "dim = 3\n[[species]]\nmass = 1\nradius = 1\n[table]\npolygon = [[0, 0], [1, 0], [0, 1]]\n",
        "t.toml",
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.starts_with("t.toml: table: a polygon or wedge table is 2D"),
        "{e}"
    );
    let e = error("[[wall]]\npoint = [0, 0]\nnormal = [1, 0]\n");
    assert!(e.starts_with("t.toml: wall[0]: walls, containers, polygons and [table] need a box without periodic axes"), "{e}");
}

#[test]
fn tables_number_their_boundaries_and_orient_polygons() {
    // A clockwise triangle table, a wall, a container and a polygon obstacle.
    let s = Scene::from_toml(
        &format!(
            "{NO_BOX}[[wall]]\npoint = [0, -1]\nnormal = [0, 2]\n[table]\npolygon = [[0, 0], [0, 4], [4, 0]]\ncontact = \"smooth\"\n\
             [[container]]\ncentre = [1, 1]\nradius = 5\n[[polygon]]\nvertices = [[2, \"1/2\"], [3, \"1/2\"], [2, \"3/2\"]]\n\
             [contact]\nballs = \"smooth\"\n{BALL}"
        ),
        "t.toml",
    )
    .unwrap();
    let places: Vec<&str> = s.boundaries.iter().map(|b| b.place.as_str()).collect();
    assert_eq!(
        places,
        [
            "wall[0]",
            "table.polygon[0]",
            "table.polygon[1]",
            "table.polygon[2]",
            "container[0]",
            "polygon[0].vertices[0]",
            "polygon[0].vertices[1]",
            "polygon[0].vertices[2]",
            "polygon[0].vertices[0]",
            "polygon[0].vertices[1]",
            "polygon[0].vertices[2]",
        ]
    );
    // The table's polygon is turned counterclockwise; its walls' normals point inside.
    assert_eq!(
        s.polygons[0][1],
        [4.into(), 0.into()]
            .map(num_rational::BigRational::from_integer)
            .to_vec()
    );
    assert!(s.boundaries[1..4]
        .iter()
        .all(|b| b.contact == ContactKind::Smooth));
    assert_eq!(s.ball_contact, ContactKind::Smooth);
    // Balls meet only boundaries with no-slip: the ball-obstacle kernel; smooth ball pairs need none.
    let p = s.pairs();
    assert_eq!(p.ball_obstacle, [0]);
    assert!(p.ball_wall.is_empty() && p.ball_ball.is_empty());
}
