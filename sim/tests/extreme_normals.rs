//! Issue 26, item 6: walls whose normals are written at magnitudes where `|n|^2` underflows
//! or overflows in f64 (`1e-300`, `1e200`) or whose components are beyond f64 (`1e-400`) ran
//! with a NaN normal: energy NaN, "every ball at rest", exit 0. They are the same walls as
//! with unit normals, and the run is the same, bit for bit.

use collision_core::Ball;
use noslip_scene::Scene;
use noslip_sim::run::{run, Limits, Summary};
use noslip_sim::setup::setup;
use noslip_sim::{GenericKernels, Simulation};

/// A 10 x 10 square of four walls with the given normals (left, right, bottom, top), a rough
/// disk inside, 200 contacts.
fn square(normals: [&str; 4]) -> Summary {
    let toml = format!(
        "dim = 2\n\
         [[wall]]\npoint = [0, 0]\nnormal = {}\n\
         [[wall]]\npoint = [10, 0]\nnormal = {}\n\
         [[wall]]\npoint = [0, 0]\nnormal = {}\n\
         [[wall]]\npoint = [0, 10]\nnormal = {}\n\
         [[species]]\nmass = 1\nradius = \"1/2\"\n\
         [[ball]]\nspecies = 0\nposition = [\"10/3\", \"20/7\"]\nvelocity = [\"3/5\", \"4/5\"]\n\
         angular_velocity = 1\n",
        normals[0], normals[1], normals[2], normals[3]
    );
    let scene = Scene::from_toml(&toml, "t.toml").unwrap_or_else(|e| panic!("{e}"));
    let s = setup::<2, 1>(&scene).unwrap_or_else(|e| panic!("{e}"));
    let species: Vec<Ball<f64>> = s.species.clone();
    let kernels = GenericKernels {
        species: species.clone(),
    };
    let mut sim = Simulation::new(s, kernels).unwrap();
    let limits = Limits {
        events: Some(200),
        time: None,
        samples: 10,
        traced: 0,
        contact_points: 0,
    };
    run(&mut sim, &species, &limits, None, &mut |_| {})
        .unwrap()
        .0
}

#[test]
fn walls_with_tiny_or_huge_normals_are_the_unit_walls() {
    let unit = square(["[1, 0]", "[-1, 0]", "[0, 1]", "[0, -1]"]);
    assert_eq!(unit.events, 200);
    assert!(unit.energy_drift < 1e-12, "{}", unit.energy_drift);
    for normals in [
        [
            "[\"1e-300\", 0]",
            "[\"-1e-300\", 0]",
            "[0, \"1e-200\"]",
            "[0, \"-1e-200\"]",
        ],
        [
            "[\"1e200\", 0]",
            "[\"-1e300\", 0]",
            "[0, \"1e-400\"]",
            "[0, \"-3e300\"]",
        ],
    ] {
        let got = square(normals);
        assert_eq!(got.events, 200, "{normals:?}");
        assert_eq!(got.stopped, None, "{normals:?}");
        assert_eq!(
            (got.time.to_bits(), got.energy_end.to_bits()),
            (unit.time.to_bits(), unit.energy_end.to_bits()),
            "{normals:?}"
        );
    }
}
