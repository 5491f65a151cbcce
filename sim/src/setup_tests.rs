//! The setup (`setup.rs`): the random placement against the all-pairs form of its rule (the
//! same centres, bit for bit), its centres uniform over a periodic box, and the walls' unit
//! normals (exact when given unit, and from normals of any magnitude).

use super::*;
use crate::place::distance2;
use crate::sequential::random_position;

/// The placement rule tested against every placed ball and obstacle (the `O(N^2)` form
/// the grid replaces), drawing from the same stream: the centres must be the same bits.
fn all_pairs<const N: usize>(scene: &Scene) -> Vec<[f64; N]> {
    let size: [f64; N] = array(&scene.size);
    let periodic: [bool; N] = std::array::from_fn(|k| scene.boundary[k] == Boundary::Periodic);
    let radius: Vec<f64> = scene.species.iter().map(|s| f(&s.radius)).collect();
    let obstacles: Vec<([f64; N], f64)> = scene
        .obstacles
        .iter()
        .map(|o| (array(&o.position), f(&o.radius)))
        .collect();
    let mut placed: Vec<([f64; N], f64)> = scene
        .balls
        .iter()
        .map(|b| (array(&b.position), radius[b.species]))
        .collect();
    // The polygon obstacles (their edges' gaps say nothing of a centre deep inside).
    let mut polygons: Vec<Vec<[f64; 2]>> = Vec::new();
    let mut seen = Vec::new();
    for b in &scene.boundaries {
        if let (noslip_scene::Shape::Edge { .. }, Some((g, _))) = (&b.shape, b.polygon) {
            if !seen.contains(&g) {
                seen.push(g);
                polygons.push(
                    scene.polygons[g]
                        .iter()
                        .map(|v| [f(&v[0]), f(&v[1])])
                        .collect(),
                );
            }
        }
    }
    let mut rng = Rng::new(scene.random.seed);
    for (k, sp) in scene.species.iter().enumerate() {
        let r = radius[k];
        for _ in 0..sp.count {
            let p = loop {
                let p = random_position(&mut rng, &size, &periodic, r);
                let clear = placed.iter().chain(&obstacles).all(|(q, rq)| {
                    let s = r + rq;
                    distance2(&p, q, &size, &periodic) >= s * s
                });
                if clear {
                    break p;
                }
            };
            for _ in 0..N + N * (N - 1) / 2 {
                rng.next_u64();
            }
            placed.push((p, r));
        }
    }
    placed.into_iter().map(|(p, _)| p).collect()
}

fn same_placement<const N: usize, const S: usize>(text: &str) {
    let scene = Scene::from_toml(text, "t.toml").unwrap();
    let grid: Vec<[f64; N]> = setup::<N, S>(&scene)
        .unwrap()
        .bodies
        .iter()
        .map(|b| b.position)
        .collect();
    assert_eq!(grid.len(), scene.ball_count());
    assert_eq!(grid, all_pairs::<N>(&scene), "{text}");
}

#[test]
fn wall_normals_are_unit_and_exact_when_given_unit() {
    let scene = Scene::from_toml(
        "dim = 2\n[[wall]]\npoint = [0, 0]\nnormal = [\"3/5\", \"4/5\"]\n\
         [[wall]]\npoint = [0, 5]\nnormal = [0, -2]\n[[wall]]\npoint = [9, 0]\nnormal = [-1, -1]\n\
         [[species]]\nmass = 1\nradius = \"1/10\"\n[[ball]]\nspecies = 0\nposition = [2, 2]\n\
         velocity = [1, 0]\n",
        "t.toml",
    )
    .unwrap();
    let normals: Vec<[f64; 2]> = table::<2>(&scene)
        .boundaries
        .iter()
        .map(|b| match b.shape {
            Shape::Wall { normal, .. } => normal,
            _ => unreachable!(),
        })
        .collect();
    // A unit rational normal: each component rounded once; others divided by the norm.
    assert_eq!(normals[0], [0.6, 0.8]);
    assert_eq!(normals[1], [0.0, -1.0]);
    // 1 / fl(sqrt 2), one rounding of the quotient by the (correctly rounded) norm; within
    // an ulp of 1/sqrt(2).
    let h = 1.0 / 2f64.sqrt();
    assert_eq!(normals[2], [-h, -h]);
    assert!((h - std::f64::consts::FRAC_1_SQRT_2).abs() <= f64::EPSILON / 2.0);
}

/// Issue 26, item 6: a normal whose `|n|^2` underflows (`1e-300`) or overflows (`1e200`)
/// in f64, or whose components are beyond f64 altogether (`1e-400`), gave a normal of NaN
/// or 0 and a run of NaN energy; a polygon edge of length `1e-300` the same. Each is now
/// the unit vector of its direction, as for a normal of moderate size.
#[test]
fn normals_of_any_magnitude_are_unit_vectors() {
    let scene = Scene::from_toml(
        "dim = 2\n[[wall]]\npoint = [0, 0]\nnormal = [\"1e-300\", \"1e-300\"]\n\
         [[wall]]\npoint = [9, 9]\nnormal = [\"-1e200\", \"-1e200\"]\n\
         [[wall]]\npoint = [0, 0]\nnormal = [\"1e-400\", \"3e-400\"]\n\
         [[wall]]\npoint = [0, 0]\nnormal = [1, 3]\n\
         [[polygon]]\nvertices = [[\"1e-300\", \"1e-300\"], [\"2e-300\", \"1e-300\"], \
         [\"1e-300\", \"2e-300\"]]\n\
         [[species]]\nmass = 1\nradius = \"1/10\"\n[[ball]]\nspecies = 0\nposition = [2, 2]\n\
         velocity = [1, 0]\n",
        "t.toml",
    )
    .unwrap();
    let normals: Vec<[f64; 2]> = table::<2>(&scene)
        .boundaries
        .iter()
        .filter_map(|b| match b.shape {
            Shape::Wall { normal, .. } | Shape::Edge { normal, .. } => Some(normal),
            _ => None,
        })
        .collect();
    // Directions (1, 1) and (-1, -1): components within an ulp of 1/sqrt(2).
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let near = |a: [f64; 2], b: [f64; 2]| (0..2).all(|k| (a[k] - b[k]).abs() <= f64::EPSILON);
    assert!(near(normals[0], [h, h]), "{normals:?}");
    assert!(near(normals[1], [-h, -h]), "{normals:?}");
    // 1e-400 and 3e-400 are not (1, 3) scaled by a power of two: the same up to rounding.
    assert_eq!(normals[3], unit([1.0, 3.0]));
    assert!(near(normals[2], normals[3]), "{normals:?}");
    // The polygon's edges, of length 1e-300 and sqrt(2) 1e-300: outward normals.
    assert_eq!(normals[4], [0.0, -1.0]);
    assert!(near(normals[5], [h, h]), "{normals:?}");
    assert_eq!(normals[6], [-1.0, 0.0]);
    for n in &normals {
        assert!(
            (n[0] * n[0] + n[1] * n[1] - 1.0).abs() <= 4.0 * f64::EPSILON,
            "{n:?}"
        );
    }
}

#[test]
fn the_grid_places_exactly_as_the_all_pairs_test() {
    // Two species, walls and a periodic axis, an obstacle and an explicit ball, at a
    // packing of about 0.35 (many rejections).
    same_placement::<2, 1>(
        "dim = 2\n[box]\nsize = [30, 20]\nboundary = [\"wall\", \"periodic\"]\n\
         [[species]]\nmass = 2\nradius = 1\ncount = 30\n\
         [[species]]\nmass = 1\nradius = \"1/2\"\ncount = 200\n\
         [[obstacle]]\nposition = [15, 0]\nradius = 3\n\
         [[ball]]\nspecies = 0\nposition = [2, 2]\nvelocity = [1, 0]\n[random]\nseed = 9\n",
    );
    // Sinai-like: small disks around a large obstacle (cells of the obstacle grid are
    // wider than the balls').
    same_placement::<2, 1>(
        "dim = 2\n[box]\nsize = [1, 1]\nboundary = [\"periodic\", \"periodic\"]\n\
         [[species]]\nmass = 1\nradius = \"1/100\"\ncount = 300\n\
         [[obstacle]]\nposition = [\"1/2\", \"1/2\"]\nradius = \"3/10\"\n",
    );
    // An axis of 2 cells and one of 1 (each neighbour cell once).
    same_placement::<3, 3>(
        "dim = 3\n[box]\nsize = [\"2.2\", \"1.5\", 8]\nboundary = [\"periodic\", \"periodic\", \"wall\"]\n\
         [[species]]\nmass = 1\nradius = \"1/2\"\ncount = 12\n[random]\nseed = 2\n",
    );
    // Near saturation in 3D (0.3 of the box; the cover refuses most draws, the batches
    // run ahead), then two species with walls and an obstacle: the cover marks with
    // the smaller radius, so the larger species' draws often need the full test.
    same_placement::<3, 3>(
        "dim = 3\n[box]\nsize = [9, 9, 9]\nboundary = [\"periodic\", \"periodic\", \"periodic\"]\n\
         [[species]]\nmass = 1\nradius = \"1/2\"\ncount = 420\n[random]\nseed = 5\n",
    );
    same_placement::<3, 3>(
        "dim = 3\n[box]\nsize = [9, 9, 7]\nboundary = [\"periodic\", \"wall\", \"periodic\"]\n\
         [[species]]\nmass = 2\nradius = \"3/4\"\ncount = 30\n\
         [[species]]\nmass = 1\nradius = \"1/2\"\ncount = 200\n\
         [[obstacle]]\nposition = [4, 4, 3]\nradius = \"3/2\"\n[random]\nseed = 6\n",
    );
    same_placement::<6, 15>(
        "dim = 6\n[box]\nsize = [3, 3, 3, 3, 3, 4]\nboundary = [\"periodic\", \"periodic\", \"periodic\", \"periodic\", \"periodic\", \"wall\"]\n\
         [[species]]\nmass = 1\nradius = \"1/2\"\ncount = 60\n[random]\nseed = 4\nspin = 1\n",
    );
}

/// The chi-square statistic of `counts` against equal expected counts.
fn chi2(counts: &[usize]) -> f64 {
    let total: usize = counts.iter().sum();
    let expected = total as f64 / counts.len() as f64;
    counts
        .iter()
        .map(|&o| (o as f64 - expected).powi(2) / expected)
        .sum()
}

/// The counts of `centres` in `bins^N` equal boxes of the box of sides `size`.
fn histogram<const N: usize>(centres: &[[f64; N]], size: [f64; N], bins: usize) -> Vec<usize> {
    let mut counts = vec![0; bins.pow(N as u32)];
    for c in centres {
        let cell = (0..N).fold(0, |acc, k| {
            acc * bins + ((c[k] / size[k] * bins as f64) as usize).min(bins - 1)
        });
        counts[cell] += 1;
    }
    counts
}

/// The centres of random placement (the whole of `setup`, cover and batches included)
/// are uniform over a periodic box: the box's translations leave the placement's law
/// unchanged, so every centre is uniform whatever the packing. Over 10 seeds the
/// histograms of the centres in `b^n` boxes (joint, `b = 4`) and along each axis (`b =
/// 16`) must have a chi-square below `k - 1 + 6 sqrt(2 (k - 1))` for `k` boxes, the
/// multinomial mean plus 6 of its standard deviations (hard-core exclusion makes the
/// counts less variable than independent draws, so this bound is generous; the chance
/// that uniform centres exceed it is below 1e-6). A bias of the density by a few percent
/// fails it: the same centres with one coordinate mapped `x -> L (x / L)^1.1` do.
fn uniform<const N: usize, const S: usize>(count: usize, fraction: f64) {
    let ball = match N {
        2 => std::f64::consts::PI / 4.0,
        _ => std::f64::consts::PI / 6.0,
    };
    let side = (count as f64 * ball / fraction).powf(1.0 / N as f64);
    let mut centres: Vec<[f64; N]> = Vec::new();
    let mut size = [0.0; N];
    for seed in 0..10 {
        let axes = vec![format!("\"{side:.12}\""); N].join(", ");
        let periodic = vec!["\"periodic\""; N].join(", ");
        let text = format!(
            "dim = {N}\n[box]\nsize = [{axes}]\nboundary = [{periodic}]\n\
             [[species]]\nmass = 1\nradius = \"1/2\"\ncount = {count}\n\
             [random]\nseed = {seed}\n"
        );
        let scene = noslip_scene::Scene::from_toml(&text, "uniform").unwrap();
        let placed = setup::<N, S>(&scene).unwrap();
        size = placed.size;
        centres.extend(placed.bodies.iter().map(|b| b.position));
    }
    let bound = |k: usize| (k - 1) as f64 + 6.0 * (2.0 * (k - 1) as f64).sqrt();
    let joint = histogram(&centres, size, 4);
    assert!(
        chi2(&joint) < bound(joint.len()),
        "{N}D joint: {}",
        chi2(&joint)
    );
    for k in 0..N {
        let axis: Vec<[f64; 1]> = centres.iter().map(|c| [c[k]]).collect();
        let counts = histogram(&axis, [size[k]], 16);
        assert!(
            chi2(&counts) < bound(16),
            "{N}D axis {k}: {}",
            chi2(&counts)
        );
    }
    let biased: Vec<[f64; 1]> = centres
        .iter()
        .map(|c| [size[0] * (c[0] / size[0]).powf(1.1)])
        .collect();
    let counts = histogram(&biased, [size[0]], 16);
    assert!(chi2(&counts) > bound(16), "{N}D biased: {}", chi2(&counts));
}

#[test]
fn random_centres_are_uniform_over_a_periodic_box() {
    // Close to saturation (0.54 in 2D, 0.39 in 3D), where most draws are refused.
    uniform::<2, 1>(2000, 0.45);
    uniform::<3, 3>(3000, 0.3);
}
