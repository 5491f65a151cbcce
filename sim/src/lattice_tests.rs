//! The lattice start from a scene (`[random] placement = "lattice"`): no two balls overlap
//! and none overlaps an obstacle (distances checked against the exact radius sums), every
//! ball is inside the box, the start is a function of the seed, the lattice holds as many
//! balls as its construction says and no more, and packings it cannot hold are refused.

use crate::setup::setup;
use crate::Setup;
use noslip_scene::{Boundary, Scene};
use num_rational::BigRational;
use num_traits::Signed;

fn exact(x: f64) -> BigRational {
    BigRational::from_float(x).expect("a finite coordinate")
}

/// Whether balls at `a` and `b` of radius sum `s` (exact, from the scene) are at least `s`
/// apart (minimum image on periodic axes). The f64 sum of `n <= 6` squares has a relative
/// error below `8 * 2^-53` (each difference of two coordinates below `L` is exact up to one
/// rounding, each square and sum one more), so an f64 value above `s^2 (1 + 1e-9)` decides;
/// the rest are checked in exact rationals.
fn apart<const N: usize>(a: &[f64; N], b: &[f64; N], s: &BigRational, scene: &Scene) -> bool {
    let periodic = |k: usize| scene.boundary[k] == Boundary::Periodic;
    let sf = crate::setup::f(s);
    let d2: f64 = (0..N)
        .map(|k| {
            let mut d = (a[k] - b[k]).abs();
            if periodic(k) {
                d = d.min(crate::setup::f(&scene.size[k]) - d);
            }
            d * d
        })
        .sum();
    if d2 > sf * sf * (1.0 + 1e-9) {
        return true;
    }
    let d2: BigRational = (0..N)
        .map(|k| {
            let mut d = (exact(a[k]) - exact(b[k])).abs();
            if periodic(k) {
                let other = &scene.size[k] - &d;
                if other < d {
                    d = other;
                }
            }
            &d * &d
        })
        .sum();
    d2 >= s * s
}

/// The scene's setup, checked: no overlaps among the balls and with the obstacles (all
/// pairs), every centre inside the box (exactly: `R <= x <= L - R` between walls, `0 <= x <
/// L` on periodic axes), speeds within `speed`.
fn checked<const N: usize, const S: usize>(text: &str) -> (Scene, Setup<N, S>) {
    let scene = Scene::from_toml(text, "t.toml").unwrap();
    let start = setup::<N, S>(&scene).unwrap_or_else(|e| panic!("{e}\n{text}"));
    assert_eq!(start.bodies.len(), scene.ball_count());
    let radius = |k: usize| &scene.species[k].radius;
    for (i, a) in start.bodies.iter().enumerate() {
        for k in 0..N {
            let x = exact(a.position[k]);
            let inside = match scene.boundary[k] {
                Boundary::Wall => {
                    radius(a.species) <= &x && x <= &scene.size[k] - radius(a.species)
                }
                Boundary::Periodic => !x.is_negative() && x < scene.size[k],
            };
            assert!(inside, "ball {i} outside on axis {k}: {:?}", a.position);
        }
        for (j, b) in start.bodies[..i].iter().enumerate() {
            let s = radius(a.species) + radius(b.species);
            assert!(
                apart(&a.position, &b.position, &s, &scene),
                "balls {i} and {j} overlap"
            );
        }
        for (j, o) in scene.obstacles.iter().enumerate() {
            let s = radius(a.species) + &o.radius;
            let p = std::array::from_fn(|k| crate::setup::f(&o.position[k]));
            assert!(apart(&a.position, &p, &s, &scene), "ball {i}, obstacle {j}");
        }
        let speed = crate::setup::f(&scene.random.speed);
        assert!(a.state.velocity.iter().all(|v| v.abs() <= speed));
    }
    (scene, start)
}

fn lattice(text: &str) -> String {
    format!("{text}[random]\nplacement = \"lattice\"\nseed = 5\nspin = 1\n")
}

#[test]
fn lattice_starts_do_not_overlap_and_stay_in_the_box() {
    // 2D, a walled and a periodic axis, two species, an obstacle and an explicit ball, at a
    // packing (0.58 of the box) beyond random placement (saturation near 0.54).
    checked::<2, 1>(&lattice(
        "dim = 2\n[box]\nsize = [20, 16]\nboundary = [\"wall\", \"periodic\"]\n\
         [[species]]\nmass = 2\nradius = \"1/2\"\ncount = 220\n\
         [[species]]\nmass = 1\nradius = \"0.3\"\ncount = 40\n\
         [[obstacle]]\nposition = [10, 0]\nradius = 2\n\
         [[ball]]\nspecies = 0\nposition = [\"0.5\", \"0.5\"]\n",
    ));
    // 3D periodic at 0.52 (random placement saturates near 0.39).
    checked::<3, 3>(&lattice(
        "dim = 3\n[box]\nsize = [6, 6, 6]\nboundary = [\"periodic\", \"periodic\", \"periodic\"]\n\
         [[species]]\nmass = 1\nradius = \"1/2\"\ncount = 216\n",
    ));
    // 3D walls on every axis, sides that are not multiples of the spacing.
    checked::<3, 3>(&lattice(
        "dim = 3\n[box]\nsize = [\"5.3\", \"4.1\", 7]\nboundary = [\"wall\", \"wall\", \"wall\"]\n\
         [[species]]\nmass = 1\nradius = \"1/2\"\ncount = 60\n\
         [[species]]\nmass = 1\nradius = \"1/4\"\ncount = 20\n",
    ));
    // 6D, one walled axis, 1000 balls of volume (pi^3/6) / 64 in 729: 0.11 of the box
    // (random placement saturates near 0.09).
    checked::<6, 15>(&lattice(
        "dim = 6\n[box]\nsize = [3, 3, 3, 3, 3, 3]\nboundary = [\"periodic\", \"periodic\", \"periodic\", \"periodic\", \"periodic\", \"wall\"]\n\
         [[species]]\nmass = 1\nradius = \"1/2\"\ncount = 1000\n",
    ));
    // A table with a container: sites outside it are skipped.
    checked::<2, 1>(&lattice(
        "dim = 2\n[box]\nsize = [10, 10]\nboundary = [\"wall\", \"wall\"]\n\
         [[container]]\ncentre = [5, 5]\nradius = 4\n\
         [[species]]\nmass = 1\nradius = \"1/2\"\ncount = 30\n",
    ));
}

#[test]
fn the_lattice_holds_what_its_construction_says_and_no_more() {
    // A periodic cube of side 10, R = 1/2: steps of at least sqrt(2)/2 (1 + 2^-30) give 14
    // points per axis (the largest even number <= 10 / 0.7071 = 14.14) and 14^3 / 2 = 1372
    // sites, a packing of 1372 (pi/6) / 1000 = 0.718.
    let cube = |count: usize| {
        lattice(&format!(
            "dim = 3\n[box]\nsize = [10, 10, 10]\nboundary = [\"periodic\", \"periodic\", \"periodic\"]\n\
             [[species]]\nmass = 1\nradius = \"1/2\"\ncount = {count}\n"
        ))
    };
    checked::<3, 3>(&cube(1372));
    let scene = Scene::from_toml(&cube(1373), "t.toml").unwrap();
    let err = setup::<3, 3>(&scene).unwrap_err();
    assert!(
        err.starts_with("species[0].count: the lattice start holds 1372 balls with centres at least 2 R_max = 1 apart"),
        "{err}"
    );
    // Fewer balls spread out on the widest lattice with enough sites: for 300, 8 points per
    // axis give 256 sites, 10 give 500, so the steps are 10 / 10 = 1.
    let (_, start) = checked::<3, 3>(&cube(300));
    for b in &start.bodies {
        for x in b.position {
            assert_eq!(x.fract(), 0.5, "{:?}", b.position);
        }
    }
}

#[test]
fn the_lattice_start_is_a_function_of_the_seed() {
    let text = |seed: u64| {
        format!(
            "dim = 2\n[box]\nsize = [12, 12]\nboundary = [\"wall\", \"periodic\"]\n\
             [[species]]\nmass = 1\nradius = \"1/2\"\ncount = 50\n\
             [[species]]\nmass = 3\nradius = \"1/3\"\ncount = 50\n\
             [random]\nplacement = \"lattice\"\nseed = {seed}\nspin = 2\n"
        )
    };
    let bits = |seed: u64| {
        let scene = Scene::from_toml(&text(seed), "t.toml").unwrap();
        setup::<2, 1>(&scene)
            .unwrap()
            .bodies
            .iter()
            .map(|b| {
                let mut v: Vec<u64> = b.position.iter().map(|x| x.to_bits()).collect();
                v.extend(b.state.velocity.iter().map(|x| x.to_bits()));
                v.extend(b.state.spin.iter().map(|x| x.to_bits()));
                v.push(b.species as u64);
                v
            })
            .collect::<Vec<_>>()
    };
    assert_eq!(bits(7), bits(7));
    assert_ne!(bits(7), bits(8));
    // The species are mixed over the sites, not one block each: both species appear in
    // the lower and the upper half of the walled axis.
    let scene = Scene::from_toml(&text(7), "t.toml").unwrap();
    let start = setup::<2, 1>(&scene).unwrap();
    for k in 0..2 {
        let low = start
            .bodies
            .iter()
            .filter(|b| b.species == k && b.position[0] < 6.0);
        let high = start
            .bodies
            .iter()
            .filter(|b| b.species == k && b.position[0] > 6.0);
        assert!(low.count() > 0 && high.count() > 0, "species {k}");
    }
}

#[test]
fn packings_the_lattice_cannot_hold_are_refused_naming_the_count() {
    let refused = |text: &str| {
        let scene = Scene::from_toml(text, "t.toml").unwrap();
        setup::<2, 1>(&scene).unwrap_err()
    };
    // 2D periodic square of side 10, R = 1/2: 14 x 14 / 2 = 98 sites (0.77 of the box).
    let square = |count: usize, extra: &str| {
        lattice(&format!(
            "dim = 2\n[box]\nsize = [10, 10]\nboundary = [\"periodic\", \"periodic\"]\n\
             [[species]]\nmass = 1\nradius = \"1/2\"\ncount = {count}\n{extra}"
        ))
    };
    checked::<2, 1>(&square(98, ""));
    let err = refused(&square(99, ""));
    assert!(
        err.starts_with("species[0].count: the lattice start holds 98 balls"),
        "{err}"
    );
    // An obstacle takes sites: fewer are clear, and the message says so.
    let err = refused(&square(98, "[[obstacle]]\nposition = [5, 5]\nradius = 2\n"));
    assert!(
        err.starts_with("species[0].count: the lattice start holds ")
            && err.contains("clear of the table's boundaries, obstacles and explicit balls"),
        "{err}"
    );
    // The last species with balls is named.
    let err = refused(&lattice(
        "dim = 2\n[box]\nsize = [10, 10]\nboundary = [\"periodic\", \"periodic\"]\n\
         [[species]]\nmass = 1\nradius = \"1/2\"\ncount = 60\n\
         [[species]]\nmass = 1\nradius = \"1/2\"\ncount = 60\n\
         [[species]]\nmass = 1\nradius = \"1/2\"\n",
    ));
    assert!(
        err.starts_with("species[1].count: the lattice start holds 98"),
        "{err}"
    );
}
