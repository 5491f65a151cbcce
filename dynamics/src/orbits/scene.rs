//! A scene with one ball as a [`Table`]: every boundary of the scene's table, kept exact (the
//! scene's rationals) where it can be.
//!
//! The boundaries, by index (the contact sequence of an orbit names them so):
//!
//! 1. the box's walls: `2k` at `x_k = 0` and `2k + 1` at `x_k = L_k` for each walled axis `k`
//!    in order (none without a box);
//! 2. the fixed ball obstacles, in file order;
//! 3. the scene's table boundaries in its order ([`noslip_scene::Scene::boundaries`]: the
//!    `[[wall]]`s, the `[table]` polygon's or wedge's walls, the `[[container]]`s, each
//!    `[[polygon]]` obstacle's edges then its vertices), the engine's boundary `b` being
//!    index `offset + b` here ([`OneBall::offset`]). A wall's normal is normalised, an edge
//!    becomes a [`Boundary::Edge`], a vertex a sphere of radius 0.
//!
//! Each boundary's law is its contact kind in the scene (`contact = "smooth"`, default
//! no-slip; the box walls are no-slip), unless one law is given for all.
//!
//! **Exact or not.** The table is also built in exact rationals when every normal's length is
//! rational (an axis wall, a normal such as `(3, 4)`): then the return map of a rational start
//! on a flat wall is exact. A polygon whose edge normals have irrational lengths (the shipped
//! triangle's `sqrt(3)/2` is given as a decimal, so its edges' normals have irrational length)
//! has only the `f64` table.

use crate::law::Law;
use crate::root::Root;
use crate::table::{Boundary, Table};
use collision_core::{Ball, BodyState, Exact, Scalar};
use noslip_scene::{Boundary as Axis, Scene, Shape};

/// The scene crate's exact numbers.
type SceneNumber = num_rational::BigRational;

/// A scene number as collision-core's [`Exact`].
fn exact_of(x: &SceneNumber) -> Exact {
    Exact::from_fraction(x)
}

/// A one-ball scene's table and its ball's start.
#[derive(Clone, Debug)]
pub struct OneBall<const N: usize, const S: usize> {
    /// The table in exact rationals, `None` where a normal's length is irrational.
    pub exact: Option<Table<Exact, N>>,
    /// The table in `f64` (normals normalised in `f64`).
    pub float: Table<f64, N>,
    /// The index of the scene's first table boundary (engine boundary 0).
    pub offset: usize,
    /// The ball's centre at the start.
    pub x: [Exact; N],
    /// The ball's state at the start.
    pub state: BodyState<Exact, N, S>,
}

/// The scene's table (every contact's law `law` if given, else each boundary's kind) and its
/// ball's start; an error names the place.
pub fn table<const N: usize, const S: usize>(
    scene: &Scene,
    law: Option<Law>,
) -> Result<OneBall<N, S>, String> {
    let balls: usize = scene.balls_per_species().iter().sum();
    if balls != 1 || scene.balls.len() != 1 {
        return Err(format!(
            "{}: a one-ball table is needed (one [[ball]], no species count), found {balls} balls",
            scene.origin
        ));
    }
    if scene.thermostat.is_some() {
        return Err(format!(
            "{}: thermostat: a driven table's random kicks have no exact return map: orbits \
             take undriven scenes",
            scene.origin
        ));
    }
    let rough = |c: &noslip_scene::ContactKind| Law::of(c.into()).is_none();
    let places = scene
        .obstacles
        .iter()
        .enumerate()
        .map(|(o, x)| (format!("obstacle[{o}]"), &x.contact));
    let box_walls = scene.boundary.contains(&Axis::Wall);
    let mut places = places
        .chain(
            scene
                .boundaries
                .iter()
                .map(|b| (b.place.clone(), &b.contact)),
        )
        .chain(box_walls.then(|| ("box".to_string(), &scene.box_contact)));
    if let (Some((place, _)), None) = (places.find(|(_, c)| rough(c)), law) {
        return Err(format!(
            "{}: {place}.contact: a rough law (e < 1 or |beta| < 1) has no exact return map \
             here: orbits take no-slip and smooth contacts (or --contact for every contact)",
            scene.origin
        ));
    }
    let exact = build::<Exact, N>(scene, law, &|x| x.clone());
    let float = build::<f64, N>(scene, law, &Scalar::to_f64).expect("f64 has every square root");
    let spec = &scene.balls[0];
    Ok(OneBall {
        exact,
        float,
        offset: 2 * scene.boundary.iter().filter(|a| **a == Axis::Wall).count()
            + scene.obstacles.len(),
        x: std::array::from_fn(|k| exact_of(&spec.position[k])),
        state: BodyState {
            velocity: std::array::from_fn(|k| exact_of(&spec.velocity[k])),
            spin: std::array::from_fn(|k| exact_of(&spec.spin[k])),
        },
    })
}

/// The table in `T` (numbers by `of`), or `None` if a normal's length has no root in `T`.
fn build<T: Root, const N: usize>(
    scene: &Scene,
    law: Option<Law>,
    of: &dyn Fn(&Exact) -> T,
) -> Option<Table<T, N>> {
    let v = |a: &[SceneNumber]| -> [T; N] { std::array::from_fn(|k| of(&exact_of(&a[k]))) };
    let unit = |n: &[SceneNumber]| -> Option<[T; N]> {
        let n = v(n);
        let len = n
            .iter()
            .fold(T::zero(), |s, x| s + x.clone() * x.clone())
            .root()?;
        Some(std::array::from_fn(|k| n[k].clone() / len.clone()))
    };
    // Rough laws were refused by `table`.
    let law_of = |kind: &noslip_scene::ContactKind| law.or_else(|| Law::of(kind.into()));
    let mut boundaries = Vec::new();
    let mut laws = Vec::new();
    for (k, axis) in scene.boundary.iter().enumerate() {
        if *axis == Axis::Wall {
            let e = |s: i64| -> [T; N] {
                std::array::from_fn(|a| {
                    if a == k {
                        of(&Exact::from_integer(s))
                    } else {
                        T::zero()
                    }
                })
            };
            let mut far = e(0);
            far[k] = of(&exact_of(&scene.size[k]));
            boundaries.push(Boundary::Wall {
                point: e(0),
                normal: e(1),
            });
            boundaries.push(Boundary::Wall {
                point: far,
                normal: e(-1),
            });
            laws.extend([law_of(&scene.box_contact).expect("rough laws refused"); 2]);
        }
    }
    for o in &scene.obstacles {
        boundaries.push(Boundary::Sphere {
            centre: v(&o.position),
            radius: of(&exact_of(&o.radius)),
        });
        laws.push(law_of(&o.contact)?);
    }
    for b in &scene.boundaries {
        boundaries.push(match &b.shape {
            Shape::Wall { point, normal } => Boundary::Wall {
                point: v(point),
                normal: unit(normal)?,
            },
            Shape::Container { centre, radius } => Boundary::Container {
                centre: v(centre),
                radius: of(&exact_of(radius)),
            },
            Shape::Edge { from, to, normal } => Boundary::Edge {
                from: v(from),
                to: v(to),
                normal: unit(normal)?,
            },
            Shape::Vertex { point } => Boundary::Sphere {
                centre: v(point),
                radius: T::zero(),
            },
        });
        laws.push(law_of(&b.contact)?);
    }
    let species = &scene.species[scene.balls[0].species];
    Some(Table {
        boundaries,
        period: std::array::from_fn(|k| {
            (scene.boundary.get(k) == Some(&Axis::Periodic)).then(|| of(&exact_of(&scene.size[k])))
        }),
        ball: Ball {
            inv_mass: T::one() / of(&exact_of(&species.mass)),
            radius: of(&exact_of(&species.radius)),
            gamma2: of(&exact_of(&species.gamma2)),
        },
        laws,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The shipped sector: a wedge's two walls and a container, in that order after no box
    /// walls; the walls' normals are unit in `f64`; the per-boundary kinds and the override.
    #[test]
    fn the_sector_is_two_walls_and_a_container() {
        let text = include_str!("../../../scenes/sector.toml");
        let scene = Scene::from_toml(text, "sector").unwrap();
        let t = table::<2, 1>(&scene, None).unwrap();
        assert_eq!(t.offset, 0);
        let b = &t.float.boundaries;
        assert_eq!(b.len(), 3);
        assert!(matches!(b[0], Boundary::Wall { .. }));
        assert!(matches!(b[1], Boundary::Wall { .. }));
        assert!(matches!(b[2], Boundary::Container { radius, .. } if radius == 1.0));
        for w in &b[..2] {
            let Boundary::Wall { normal, .. } = w else {
                unreachable!()
            };
            assert!((normal[0].hypot(normal[1]) - 1.0).abs() < 1e-15);
        }
        assert_eq!(t.float.laws, vec![Law::NoSlip; 3]);
        let smooth = text.replace("radius = 1\n", "radius = 1\ncontact = \"smooth\"\n");
        let scene = Scene::from_toml(&smooth, "sector").unwrap();
        let t = table::<2, 1>(&scene, None).unwrap();
        assert_eq!(t.float.laws, vec![Law::NoSlip, Law::NoSlip, Law::Smooth]);
        let t = table::<2, 1>(&scene, Some(Law::NoSlip)).unwrap();
        assert_eq!(t.float.laws, vec![Law::NoSlip; 3]);
    }

    /// The box's walls take `[box] contact`: smooth walls are smooth laws (the override still
    /// wins), a rough box is refused naming `box.contact`.
    #[test]
    fn the_box_walls_take_the_box_contact() {
        let text = include_str!("../../../scenes/disk_between_walls.toml");
        let with = |contact: &str| {
            let t = text.replacen("[box]\n", &format!("[box]\ncontact = {contact}\n"), 1);
            Scene::from_toml(&t, "box").unwrap()
        };
        let walls = 2 * Scene::from_toml(text, "box")
            .unwrap()
            .boundary
            .iter()
            .filter(|a| **a == Axis::Wall)
            .count();
        let t = table::<2, 1>(&with("\"smooth\""), None).unwrap();
        assert_eq!(t.float.laws[..walls], vec![Law::Smooth; walls]);
        let t = table::<2, 1>(&with("\"smooth\""), Some(Law::NoSlip)).unwrap();
        assert_eq!(t.float.laws[..walls], vec![Law::NoSlip; walls]);
        let Err(e) = table::<2, 1>(&with("{ e = 0.5, beta = 0 }"), None) else {
            panic!("a rough box was accepted")
        };
        assert!(e.contains("box.contact: a rough law"), "{e}");
    }
}
