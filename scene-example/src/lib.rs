//! Kernels specialised to shipped scenes by `build.rs` (noslip-codegen's build-script API),
//! run by the simulator (`noslip-sim`, whose scene setup and placement it uses as they are).

/// `scenes/disk_between_walls.toml`: ball-wall kernels for the two walls of axis 1.
pub mod disk_between_walls {
    include!(concat!(env!("OUT_DIR"), "/disk_between_walls.rs"));
}

/// `scenes/gas2d.toml`: ball-ball for species (0,0), (0,1), (1,1) and ball-wall.
pub mod gas2d {
    include!(concat!(env!("OUT_DIR"), "/gas2d.rs"));
}

/// `scenes/sinai.toml`: the ball-obstacle kernel.
pub mod sinai {
    include!(concat!(env!("OUT_DIR"), "/sinai.rs"));
}

/// `walton_box.toml` (not a shipped scene): every kind of kernel with a Walton law folded in,
/// for `tests/walton.rs`.
pub mod walton_box {
    include!(concat!(env!("OUT_DIR"), "/walton_box.rs"));
}

use noslip_scene::PairSet;
use num_rational::BigRational;

/// The shipped scene files whose kernels `build.rs` compiles, by module name.
pub const COMPILED: [(&str, &str); 3] = [
    (
        "disk_between_walls",
        include_str!("../../scenes/disk_between_walls.toml"),
    ),
    ("gas2d", include_str!("../../scenes/gas2d.toml")),
    ("sinai", include_str!("../../scenes/sinai.toml")),
];

/// Whether the kernels compiled for `compiled` serve `scene`: the same dimension and
/// species constants (`inv_mass`, `radius`, `gamma2`; counts may differ), and every pair
/// kind `scene` can meet among the compiled ones. A scene file that merely shares a
/// shipped scene's name does not get its kernels.
pub fn kernels_fit(compiled: &PairSet, scene: &PairSet) -> bool {
    let constants = |s: &PairSet| -> Vec<[BigRational; 3]> {
        s.species
            .iter()
            .map(|x| [x.inv_mass.clone(), x.radius.clone(), x.gamma2.clone()])
            .collect()
    };
    compiled.dim == scene.dim
        && constants(compiled) == constants(scene)
        && scene
            .ball_ball
            .iter()
            .all(|p| compiled.ball_ball.contains(p))
        && scene
            .ball_wall
            .iter()
            .all(|p| compiled.ball_wall.contains(p))
        && scene
            .ball_obstacle
            .iter()
            .all(|p| compiled.ball_obstacle.contains(p))
}

#[cfg(test)]
mod tests {
    use super::*;
    use noslip_scene::Scene;

    #[test]
    fn each_compiled_scene_fits_itself_and_not_another() {
        let sets: Vec<PairSet> = COMPILED
            .iter()
            .map(|(name, text)| {
                Scene::from_toml(text, &format!("{name}.toml"))
                    .unwrap()
                    .pairs()
            })
            .collect();
        for (i, a) in sets.iter().enumerate() {
            for (j, b) in sets.iter().enumerate() {
                assert_eq!(kernels_fit(a, b), i == j, "{} for {}", a.name, b.name);
            }
        }
        // Other constants under the same name do not fit.
        let text = COMPILED[1].1.replace("mass = 4", "mass = 5");
        let changed = Scene::from_toml(&text, "gas2d.toml").unwrap().pairs();
        assert!(!kernels_fit(&sets[1], &changed));
    }
}
