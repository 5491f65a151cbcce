//! Polygons of many vertices: validation, setup and a run cost time linear in the vertices
//! (issue 26, item 8: 1000 vertices took 25 s before the first contact, the convexity check,
//! the placement check and the boundary coordinates' arc lengths being quadratic), and a
//! table without a box is not refused for its balls' "volume".

use collision_core::{Ball, Generated, Kernel};
use noslip_scene::Scene;
use noslip_sim::run::{run, Limits, Summary};
use noslip_sim::setup::setup;
use noslip_sim::{GenericKernels, Simulation};

/// `m` vertices `(k, k^2)`, `k = 0 .. m - 1`, an arc of a parabola closed by its chord:
/// strictly convex, integer, exact.
fn parabola(m: usize) -> String {
    let v: Vec<String> = (0..m as u64).map(|k| format!("[{k}, {}]", k * k)).collect();
    v.join(", ")
}

fn run_scene<const N: usize, const S: usize>(scene: &Scene, events: u64) -> Summary
where
    Generated: Kernel<f64, N, S>,
{
    let s = setup::<N, S>(scene).unwrap_or_else(|e| panic!("{e}"));
    let species: Vec<Ball<f64>> = s.species.clone();
    let kernels = GenericKernels {
        species: species.clone(),
    };
    let mut sim = Simulation::new(s, kernels).unwrap();
    let limits = Limits {
        events: Some(events),
        time: None,
        samples: 10,
        traced: 0,
        contact_points: 0,
    };
    run(&mut sim, &species, &limits, None, &mut |_| {})
        .unwrap()
        .0
}

/// A polygon table of 20 000 vertices: validated, set up and run for 200 contacts in well
/// under a second in release (the quadratic checks took hours at this size).
#[test]
fn a_polygon_table_of_many_vertices_is_linear_to_set_up() {
    let m = 20_000u64;
    let (x, y) = (m / 2, 3 * m * m / 8);
    let toml = format!(
        "dim = 2\n[table]\npolygon = [{}]\n[[species]]\nmass = 1\nradius = 10\n\
         [[ball]]\nspecies = 0\nposition = [{x}, {y}]\nvelocity = [\"3/5\", \"4/5\"]\n",
        parabola(m as usize)
    );
    let scene = Scene::from_toml(&toml, "t.toml").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.boundaries.len(), m as usize);
    let summary = run_scene::<2, 1>(&scene, 200);
    assert_eq!(summary.events, 200);
    assert_eq!(summary.stopped, None);
}

/// A polygon obstacle of 20 000 vertices in a box, a ball beside it: the same.
#[test]
fn a_polygon_obstacle_of_many_vertices_is_linear_to_set_up() {
    let m = 20_000u64;
    let side = 2 * m * m;
    let toml = format!(
        "dim = 2\n[box]\nsize = [{side}, {side}]\nboundary = [\"wall\", \"wall\"]\n\
         [[polygon]]\nvertices = [{}]\n[[species]]\nmass = 1\nradius = 100\n\
         [[ball]]\nspecies = 0\nposition = [{}, 1000]\nvelocity = [\"-3/5\", \"4/5\"]\n",
        parabola(m as usize),
        3 * m,
    );
    let scene = Scene::from_toml(&toml, "t.toml").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.boundaries.len(), 2 * m as usize);
    let summary = run_scene::<2, 1>(&scene, 20);
    assert_eq!(summary.events, 20);
}
