//! The recorder against the engine itself: frames equal the engine's positions and
//! orientations at the frame times (a second run stopped at each), the caps hold, the
//! portrait's contact in effect is the last one before each frame; and the page's structure.

use super::*;
use crate::animation_page::{base64, data, html};
use crate::run::{run_observed, Limits};
use crate::setup::setup;
use crate::{GenericKernels, Setup, Step};
use collision_core::{Generated, Kernel};
use noslip_scene::Scene;

fn scene_setup<const N: usize, const S: usize>(name: &str) -> Setup<N, S> {
    let path = format!("{}/../scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    let scene = Scene::from_file(std::path::Path::new(&path)).expect("shipped scene");
    setup::<N, S>(&scene).expect("valid setup")
}

type Sim<const N: usize, const S: usize> = Simulation<N, S, GenericKernels<f64>>;

fn sim<const N: usize, const S: usize>(setup: Setup<N, S>) -> Sim<N, S>
where
    Generated: Kernel<f64, N, S>,
{
    let species = setup.species.clone();
    Simulation::new(setup, GenericKernels { species }).expect("valid")
}

/// Record `events` contacts of `name`, returning the animation and every boundary row.
fn record<const N: usize, const S: usize>(
    name: &str,
    events: u64,
) -> (Animation, Vec<boundary_map::Row>)
where
    Generated: Kernel<f64, N, S>,
{
    let setup = scene_setup::<N, S>(name);
    let species = setup.species.clone();
    let mut s = sim(setup);
    let mut rec = Recorder::new(&s, &species, name);
    let mut rows = Vec::new();
    let limits = Limits {
        events: Some(events),
        time: None,
        samples: 1,
        traced: 0,
        contact_points: 0,
    };
    run_observed(
        &mut s,
        &species,
        &limits,
        None,
        &mut |_| {},
        &mut |i, e, sim| {
            rec.observe(i, e, sim, &species);
            rows.extend(boundary_map::row(i, e, sim, &species));
            Ok(())
        },
    )
    .expect("no writer to fail");
    (rec.finish(&s), rows)
}

#[test]
fn frames_are_the_engines_positions_and_orientations_at_the_frame_times() {
    let (a, _) = record::<2, 1>("sinai", 3000);
    // A second run of the same scene, stopped at each frame time (2D: no projection).
    let mut s = sim(scene_setup::<2, 1>("sinai"));
    assert!(a.frames.len() > 10, "{} frames", a.frames.len());
    for (k, frame) in a.frames.iter().enumerate() {
        let t = a.t0 + k as f64 * a.dt;
        while let Step::Contact(_) | Step::Quiet { .. } = s.step(t) {}
        let x = s.position(0).map(|v| v.rem_euclid(1.0));
        let axis = s.orientation(0).expect("sinai tracks orientation");
        let got = frame[0];
        for (g, w) in [got[0], got[1], got[3], got[4]]
            .iter()
            .zip([x[0], x[1], axis[0][0], axis[1][0]])
        {
            assert!(
                (g - w).abs() < 1e-9,
                "frame {k} at t = {t}: {got:?} vs {x:?}, {axis:?}"
            );
        }
    }
}

#[test]
fn a_short_run_is_kept_whole_a_long_one_its_beginning() {
    // Sinai: speed 1, side 1, so dt starts at 1/64 and grows to 1/4 at most. 40 contacts
    // take about 44 time units: kept whole (352 frames at dt = 1/8).
    let (a, rows) = record::<2, 1>("sinai", 40);
    let end = rows.last().expect("contacts").time;
    assert!(a.frames.len() <= MAX_FRAMES && a.frames.len() > MAX_FRAMES / 2);
    let last = a.t0 + (a.frames.len() - 1) as f64 * a.dt;
    assert!(last <= end && end - last < a.dt, "{last} {end} {}", a.dt);
    assert_eq!(a.end, (end, 40));
    // 20 000 contacts: full frames at the largest dt, the beginning of the run only.
    let (a, rows) = record::<2, 1>("sinai", 20_000);
    assert_eq!(a.frames.len(), MAX_FRAMES);
    assert_eq!(a.dt, MAX_SLOWDOWN / 64.0);
    assert!(a.contacts.last().copied() < Some(20_000));
    assert_eq!(a.end, (rows.last().expect("contacts").time, 20_000));
    assert_eq!(a.contacts.len(), a.frames.len());
    assert!(a.contacts.windows(2).all(|w| w[0] <= w[1]));
    assert!(a.trails.iter().flatten().all(|t| t.len() <= TRAIL_POINTS));
    assert!(a.trails.iter().flatten().any(|t| !t.is_empty()));
    // The portrait's cloud takes the whole run, thinned.
    assert!(a.cloud.len() <= CLOUD_POINTS && a.cloud.len() > CLOUD_POINTS / 2);
    assert!(a.cloud.last().expect("cloud").0 > a.t0 + MAX_FRAMES as f64 * a.dt);
}

#[test]
fn the_portraits_contact_in_effect_is_the_last_one_before_each_frame() {
    let (a, rows) = record::<2, 1>("sinai", 5000);
    assert_eq!(a.current.len(), a.frames.len());
    let mut seen = 0;
    for (k, cur) in a.current.iter().enumerate() {
        let t = a.t0 + k as f64 * a.dt;
        let last = rows.iter().rev().find(|r| r.time < t);
        match (cur, last) {
            (None, None) => {}
            (Some((body, s, y)), Some(r)) => {
                assert_eq!(a.bodies[*body].0, r.body);
                assert_eq!((*s, *y), (r.coordinate, r.reflection.sin()));
                seen += 1;
            }
            other => panic!("frame {k}: {other:?}"),
        }
    }
    assert!(seen > a.frames.len() / 2);
    // Every cloud point is a contact of the run.
    for &(t, body, s, _) in &a.cloud {
        assert!(rows
            .iter()
            .any(|r| r.time == t && r.coordinate == s && r.body == a.bodies[body].0));
    }
}

#[test]
fn a_gas_has_no_portrait_and_3d_is_projected_with_depth() {
    let (a, _) = record::<3, 3>("gas3d", 2000);
    assert!(a.bodies.is_empty() && a.cloud.is_empty());
    assert_eq!(a.radius.len(), a.balls.min(MAX_BALLS));
    assert!(a.frames.len() * a.radius.len() <= BALL_FRAMES + a.radius.len());
    for frame in &a.frames {
        for b in frame {
            assert!(
                b[0] >= a.view[0] && b[0] <= a.view[2] && b[1] >= a.view[1] && b[1] <= a.view[3]
            );
            assert!(b[2] >= a.depth[0] && b[2] <= a.depth[1]);
            // The mark is a projected unit vector: at most 1 long.
            assert!(b[3].hypot(b[4]) <= 1.0 + 1e-12);
        }
    }
    // 12 box edges.
    assert_eq!(a.segments.len(), 12);
}

#[test]
fn base64_matches_rfc_4648() {
    for (text, code) in [
        ("", ""),
        ("f", "Zg=="),
        ("fo", "Zm8="),
        ("foo", "Zm9v"),
        ("foob", "Zm9vYg=="),
        ("fooba", "Zm9vYmE="),
        ("foobar", "Zm9vYmFy"),
    ] {
        assert_eq!(base64(text.as_bytes()), code);
    }
}

#[test]
fn the_page_is_self_contained_and_carries_every_frame() {
    let (mut a, _) = record::<2, 1>("sinai", 2000);
    a.title = "a <b>&</script> title".into();
    let page = html(&a);
    for outside in ["http:", "https:", "src=", "<link", "url(", "import "] {
        assert!(!page.contains(outside), "the page names {outside}");
    }
    assert_eq!(page.matches("</script>").count(), 2);
    assert!(page.contains("<h1>a &lt;b&gt;&amp;&lt;/script&gt; title</h1>"));
    // The data element parses back, with every frame's values.
    let start = page.find("application/json\">").expect("data") + "application/json\">".len();
    let end = start + page[start..].find("</script>").expect("end");
    let d: serde_json::Value = serde_json::from_str(&page[start..end]).expect("json");
    assert_eq!(d, data(&a));
    let pos = d["pos"].as_str().expect("frames");
    assert_eq!(
        pos.len(),
        (a.frames.len() * a.radius.len() * 4 * 2).div_ceil(3) * 4
    );
    assert_eq!(d["frames"], a.frames.len());
    assert!(page.contains("id=\"portrait\""));
}

/// A 3D cube with the wall `x + y + z = 3/2` (through its centre, normal `(1, 1, 1)`): the
/// section is the regular hexagon through the midpoints of the six edges the plane crosses,
/// drawn as six segments beside the box's twelve edges, each the projection of two of those
/// midpoints. In 4D, the same wall seen in the slice `x_3 = size_3 / 2`.
#[test]
fn an_oblique_wall_in_3d_is_drawn_as_its_section_by_the_box() {
    let text = "dim = 3\n[box]\nsize = [1, 1, 1]\nboundary = [\"wall\", \"wall\", \"wall\"]\n\
                [[wall]]\npoint = [\"1/2\", \"1/2\", \"1/2\"]\nnormal = [-1, -1, -1]\n\
                [[species]]\nmass = 1\nradius = \"1/20\"\n\
                [[ball]]\nspecies = 0\nposition = [\"1/5\", \"1/5\", \"1/5\"]\nvelocity = [1, \"1/3\", \"1/7\"]\n";
    let scene = Scene::from_toml(text, "hexagon.toml").unwrap();
    let setup = setup::<3, 3>(&scene).unwrap();
    let species = setup.species.clone();
    let s = sim(setup);
    let rec = Recorder::new(&s, &species, "hexagon");
    let (segments, ..) = rec.table_lines(&s);
    assert_eq!(segments.len(), 12 + 6, "{segments:?}");
    // The hexagon's vertices: the midpoints of the edges from (1,0,0)-like to (1,1,0)-like
    // corners, every permutation of (1, 1/2, 0), in the recorder's local frame.
    let mut want: Vec<[f64; 2]> = Vec::new();
    for perm in [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ] {
        let mut x = [0.0; 3];
        x[perm[0]] = 1.0;
        x[perm[1]] = 0.5;
        let p = apply(&rec.project, &x);
        want.push([p[0], p[1]]);
    }
    let close = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]) < 1e-12;
    for seg in &segments[12..] {
        for end in [[seg[0], seg[1]], [seg[2], seg[3]]] {
            assert!(want.iter().any(|&w| close(w, end)), "{end:?} not a vertex");
        }
    }
    // Each vertex ends two of the six segments: a closed hexagon.
    for w in &want {
        let ends = segments[12..]
            .iter()
            .flat_map(|s| [[s[0], s[1]], [s[2], s[3]]])
            .filter(|&e| close(*w, e))
            .count();
        assert_eq!(ends, 2, "{w:?}");
    }
    // The plane of a face (x = 0, the box's own wall) adds nothing; through one corner only,
    // nothing; x = y, the diagonal of the faces z = 0 and z = 1 (its two box edges are drawn
    // already). In 4D, the wall x_0 + x_3 = 1 seen at x_3 = 1/2 is the square x_0 = 1/2.
    let size = [1.0; 3];
    assert!(table::wall_section(&[0.0; 3], &[1.0, 0.0, 0.0], &size).is_empty());
    assert!(table::wall_section(&[0.0; 3], &[1.0, 1.0, 1.0], &size).is_empty());
    let diagonal = table::wall_section(&[0.0; 3], &[1.0, -1.0, 0.0], &size);
    assert_eq!(diagonal.len(), 2, "{diagonal:?}");
    for [a, b] in diagonal {
        assert_eq!((a[0], a[1], b[0], b[1], a[2]), (0.0, 0.0, 1.0, 1.0, b[2]));
    }
    let slice = table::wall_section(&[1.0, 0.0, 0.0, 0.0], &[1.0, 0.0, 0.0, 1.0], &[1.0; 4]);
    assert_eq!(slice.len(), 4, "{slice:?}");
    for [a, b] in slice {
        assert_eq!((a[0], b[0], a[3], b[3]), (0.5, 0.5, 0.5, 0.5));
    }
}
