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
    /// The contact law folded into each kind of kernel.
    pub laws: PairLaws,
}

/// The contact law a [`PairSet`]'s kernels of each kind apply, folded into them as exact
/// constants: [`ContactKind::NoSlip`], a [`ContactKind::Rough`] law `(e, beta)` or a
/// [`ContactKind::Walton`] law `(e, mu, beta0)` (its one square root, of the contact's own
/// numbers, stays in the kernel). Smooth contacts need no kernel: pairs with that law are not
/// in the set (and a kind with no pair in the set has the default law here, which nothing
/// applies).
#[derive(Clone, Debug, PartialEq, Default)]
pub struct PairLaws {
    /// The law of every ball-ball pair not in [`PairLaws::pairs`].
    pub ball: ContactKind,
    /// The ball-ball laws of the species pairs `(a, b)`, `a <= b`, whose law is not
    /// [`PairLaws::ball`] (a scene's `[[contact.pair]]`); empty when one law holds for all.
    pub pairs: Vec<((usize, usize), ContactKind)>,
    /// The law of the box walls.
    pub wall: ContactKind,
    /// The law of the ball-obstacle kernel (obstacles and the table's other boundaries).
    pub fixed: ContactKind,
}

impl PairLaws {
    /// The law folded into `pair`'s kernel.
    pub fn of(&self, pair: Pair) -> &ContactKind {
        match pair {
            Pair::BallBall(a, b) => self.ball_law(a, b),
            Pair::BallWall(..) => &self.wall,
            Pair::BallObstacle(..) => &self.fixed,
        }
    }

    /// The law of the ball-ball kernel of species `a` and `b` (either order).
    pub fn ball_law(&self, a: usize, b: usize) -> &ContactKind {
        let key = (a.min(b), a.max(b));
        self.pairs
            .iter()
            .find(|(p, _)| *p == key)
            .map_or(&self.ball, |(_, law)| law)
    }

    /// Whether a kernel can have `law` folded into it: the no-slip map, a rough law and a
    /// Walton law (its `e`, `mu` and `beta0` folded; its square root stays, of the contact's
    /// own numbers).
    pub fn foldable(law: &ContactKind) -> bool {
        matches!(
            law,
            ContactKind::NoSlip | ContactKind::Rough { .. } | ContactKind::Walton { .. }
        )
    }
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
    /// The pair kinds this scene can meet, each with its law folded in ([`PairLaws`]):
    /// ball-ball for every pair of species present (a species with itself only if it has two
    /// balls) if that pair's law ([`Scene::ball_law`]) is no-slip, rough or Walton, each
    /// pair's kernel with its own law (a scene whose pairs use several laws has kernels of
    /// each); ball-wall for every present species and
    /// walled axis side of the box if the box's contact is; ball-obstacle for every present
    /// species if obstacles or other boundaries ([`Scene::boundaries`]) have such a contact:
    /// the ball-obstacle kernel is the `fixed` map with the local normal that every immovable
    /// boundary uses, with the no-slip law if any of them is no-slip (as before rough laws
    /// were folded), else with their rough law if they all have the same one (else none: the
    /// engines run the generic rough kernels for them).
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
        let foldable = PairLaws::foldable;
        // Smooth box walls use no `fixed` kernel of their own.
        let walls: Vec<usize> = (0..self.boundary.len())
            .filter(|&k| self.boundary[k] == Boundary::Wall && foldable(&self.box_contact))
            .collect();
        let ball_wall = present
            .iter()
            .flat_map(|&s| {
                walls
                    .iter()
                    .flat_map(move |&k| WallSide::BOTH.map(|side| (s, k, side)))
            })
            .collect();
        // Every other immovable boundary with a foldable contact uses the ball-obstacle kernel
        // (the `fixed` map with the local normal); smooth contacts use no kernel.
        let fixed_laws: Vec<&ContactKind> = (self.obstacles.iter().map(|o| &o.contact))
            .chain(self.boundaries.iter().map(|b| &b.contact))
            .filter(|c| foldable(c))
            .collect();
        let fixed = if fixed_laws.contains(&&ContactKind::NoSlip) {
            Some(ContactKind::NoSlip)
        } else {
            fixed_laws
                .first()
                .filter(|&&first| fixed_laws.iter().all(|c| c == &first))
                .map(|&c| c.clone())
        };
        let ball_obstacle = if fixed.is_some() {
            present.clone()
        } else {
            Vec::new()
        };
        // Smooth pairs use no kernel.
        ball_ball.retain(|&(a, b)| foldable(self.ball_law(a, b)));
        let folded = |c: &ContactKind| {
            if foldable(c) {
                c.clone()
            } else {
                ContactKind::NoSlip
            }
        };
        // The pairs of `ball_ball` whose law is not the default's (listed pairs with the
        // default's law fold the same kernel, so they need no entry).
        let pairs = (ball_ball.iter())
            .map(|&(a, b)| ((a, b), self.ball_law(a, b)))
            .filter(|&(_, law)| law != &self.ball_contact)
            .map(|(p, law)| (p, law.clone()))
            .collect();
        let laws = PairLaws {
            ball: folded(&self.ball_contact),
            pairs,
            wall: folded(&self.box_contact),
            fixed: fixed.unwrap_or_default(),
        };
        PairSet {
            name: module_name(&stem),
            dim: self.dim,
            species: self.species.clone(),
            ball_ball,
            ball_wall,
            ball_obstacle,
            laws,
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
