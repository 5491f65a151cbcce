//! The scene file as written: serde structures with unknown keys refused.

use crate::number::Number;
use serde::Deserialize;

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawScene {
    pub dim: usize,
    #[serde(default)]
    pub description: Option<String>,
    #[serde(rename = "box")]
    pub domain: RawBox,
    pub species: Vec<RawSpecies>,
    #[serde(default)]
    pub ball: Vec<RawBall>,
    #[serde(default)]
    pub obstacle: Vec<RawObstacle>,
    #[serde(default)]
    pub random: RawRandom,
    #[serde(default)]
    pub simulation: RawSimulation,
}

/// Each axis of the box is bounded by two flat walls or is periodic.
#[derive(Deserialize, Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[serde(rename_all = "lowercase")]
pub enum Boundary {
    Wall,
    Periodic,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawBox {
    pub size: Vec<Number>,
    pub boundary: Vec<Boundary>,
}

#[derive(Deserialize, Debug, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Distribution {
    Uniform,
    Shell,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawSpecies {
    #[serde(default)]
    pub name: Option<String>,
    pub mass: Number,
    pub radius: Number,
    #[serde(default)]
    pub lambda: Option<Number>,
    #[serde(default)]
    pub gamma2: Option<Number>,
    #[serde(default)]
    pub distribution: Option<Distribution>,
    #[serde(default)]
    pub count: usize,
}

/// An angular velocity: `c` (2D, `U = c J`), `omega` (3D, `U x = omega x x`), or the
/// `n x n` skew matrix row by row.
#[derive(Deserialize, Debug)]
#[serde(untagged)]
pub enum RawSpin {
    Scalar(Number),
    Vector(Vec<Number>),
    Matrix(Vec<Vec<Number>>),
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawBall {
    pub species: usize,
    pub position: Vec<Number>,
    #[serde(default)]
    pub velocity: Option<Vec<Number>>,
    #[serde(default)]
    pub angular_velocity: Option<RawSpin>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawObstacle {
    pub position: Vec<Number>,
    pub radius: Number,
}

#[derive(Deserialize, Debug, Default)]
#[serde(deny_unknown_fields)]
pub struct RawRandom {
    #[serde(default)]
    pub seed: u64,
    #[serde(default)]
    pub speed: Option<Number>,
    #[serde(default)]
    pub spin: Option<Number>,
}

#[derive(Deserialize, Debug, Default)]
#[serde(deny_unknown_fields)]
pub struct RawSimulation {
    #[serde(default)]
    pub events: Option<u64>,
    #[serde(default)]
    pub time: Option<Number>,
    #[serde(default)]
    pub orientation: bool,
}
