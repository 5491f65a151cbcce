//! The contacts a scene can meet: which species pairs, which walls, whether obstacles.

use crate::{Boundary, ContactKind, Scene, Species};

/// The wall at `x_k = 0` (`Lower`, normal `+e_k` into the box) or at `x_k = L_k` (`Upper`,
/// normal `-e_k`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum WallSide {
    /// The wall at `x_k = 0`, normal `+e_k` into the box.
    Lower,
    /// The wall at `x_k = L_k`, normal `-e_k` into the box.
    Upper,
}

impl WallSide {
    /// Both sides, lower first (the emission order).
    pub const BOTH: [WallSide; 2] = [WallSide::Lower, WallSide::Upper];

    /// `lower` or `upper`: the side's part of a kernel's function name.
    pub fn name(self) -> &'static str {
        match self {
            WallSide::Lower => "lower",
            WallSide::Upper => "upper",
        }
    }
}

/// What the generator must emit for one dimension: the species' constants and the pair
/// kinds present. Build it from a scene ([`Scene::pairs`]) or by hand.
#[derive(Clone, Debug, PartialEq)]
pub struct PairSet {
    /// The module name (a Rust identifier).
    pub name: String,
    /// The dimension `n`.
    pub dim: usize,
    /// The species' exact constants, indexed as in the scene; the pairs refer to them by index.
    pub species: Vec<Species>,
    /// Ball-ball pairs `(a, b)`, `a <= b`, species indices.
    pub ball_ball: Vec<(usize, usize)>,
    /// Ball-wall contacts `(species, axis, side)`.
    pub ball_wall: Vec<(usize, usize, WallSide)>,
    /// Species that can hit a fixed ball obstacle.
    pub ball_obstacle: Vec<usize>,
}

/// A contact kind of a [`PairSet`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pair {
    /// Two balls, of species `a <= b`.
    BallBall(usize, usize),
    /// A ball of species `s` against the wall on `side` of axis `k`: `(s, k, side)`.
    BallWall(usize, usize, WallSide),
    /// A ball of species `s` against a fixed ball obstacle.
    BallObstacle(usize),
}

impl Pair {
    /// The function name of the specialised kernel.
    pub fn fn_name(self) -> String {
        match self {
            Pair::BallBall(a, b) => format!("ball_ball_{a}_{b}"),
            Pair::BallWall(s, k, side) => format!("ball_wall_{s}_{k}_{}", side.name()),
            Pair::BallObstacle(s) => format!("ball_obstacle_{s}"),
        }
    }

    /// `ball-ball`, `ball-wall` or `ball-obstacle`.
    pub fn kind(self) -> &'static str {
        match self {
            Pair::BallBall(..) => "ball-ball",
            Pair::BallWall(..) => "ball-wall",
            Pair::BallObstacle(..) => "ball-obstacle",
        }
    }
}

impl PairSet {
    /// Every pair kind, in emission order.
    pub fn all(&self) -> Vec<Pair> {
        let bb = self.ball_ball.iter().map(|&(a, b)| Pair::BallBall(a, b));
        let bw = self
            .ball_wall
            .iter()
            .map(|&(s, k, d)| Pair::BallWall(s, k, d));
        let bo = self.ball_obstacle.iter().map(|&s| Pair::BallObstacle(s));
        bb.chain(bw).chain(bo).collect()
    }
}

/// A Rust identifier from a file stem: lower case, `_` for anything else.
pub(crate) fn module_name(stem: &str) -> String {
    let mut s: String = stem
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '_'
            }
        })
        .collect();
    if !s.starts_with(|c: char| c.is_ascii_alphabetic()) {
        s.insert_str(0, "scene_");
    }
    s
}

impl Scene {
    /// The pair kinds this scene can meet: ball-ball for every pair of species present
    /// (a species with itself only if it has two balls) unless ball-ball contacts are not
    /// no-slip, ball-wall for every present species and walled axis side of the box (unless the
    /// box's contact is not no-slip), ball-obstacle for
    /// every present species if there are obstacles or other boundaries ([`Scene::boundaries`])
    /// with no-slip contact: the ball-obstacle kernel is the `fixed` map with the local normal
    /// that every immovable boundary uses.
    pub fn pairs(&self) -> PairSet {
        let stem = std::path::Path::new(&self.origin)
            .file_stem()
            .map_or("scene".into(), |s| s.to_string_lossy().into_owned());
        let count = self.balls_per_species();
        let present: Vec<usize> = (0..self.species.len()).filter(|&k| count[k] > 0).collect();
        let mut ball_ball = Vec::new();
        for (i, &a) in present.iter().enumerate() {
            for &b in &present[i..] {
                if a != b || count[a] >= 2 {
                    ball_ball.push((a, b));
                }
            }
        }
        let no_slip = |c: &ContactKind| *c == ContactKind::NoSlip;
        // Box walls of another kind use no `fixed` kernel of their own (smooth: none; a
        // rough or Walton law: the generic rough kernels).
        let walls: Vec<usize> = (0..self.boundary.len())
            .filter(|&k| self.boundary[k] == Boundary::Wall && no_slip(&self.box_contact))
            .collect();
        let ball_wall = present
            .iter()
            .flat_map(|&s| {
                walls
                    .iter()
                    .flat_map(move |&k| WallSide::BOTH.map(|side| (s, k, side)))
            })
            .collect();
        // Every other immovable boundary with no-slip contact uses the ball-obstacle kernel
        // (the `fixed` map with the local normal); smooth contacts use no kernel.
        let fixed = self.obstacles.iter().any(|o| no_slip(&o.contact))
            || self.boundaries.iter().any(|b| no_slip(&b.contact));
        let ball_obstacle = if fixed { present.clone() } else { Vec::new() };
        if !no_slip(&self.ball_contact) {
            ball_ball.clear();
        }
        PairSet {
            name: module_name(&stem),
            dim: self.dim,
            species: self.species.clone(),
            ball_ball,
            ball_wall,
            ball_obstacle,
        }
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn module_names_are_identifiers() {
        assert_eq!(super::module_name("gas-2d"), "gas_2d");
        assert_eq!(super::module_name("3d gas"), "scene_3d_gas");
    }
}
