//! The scene file as written: serde structures with unknown keys refused.

pub use crate::contact::ContactKind;
use crate::number::Number;
pub use crate::pair_law::{RawPair, SpeciesRef};
use serde::Deserialize;

/// A scene file's top level as written, before validation into a [`Scene`](crate::Scene).
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawScene {
    /// `dim`: the dimension `n` (validation asks for `2..=6`).
    pub dim: usize,
    /// `description`: free text.
    #[serde(default)]
    pub description: Option<String>,
    /// The `[box]` table; a scene without one is bounded only by its other boundaries
    /// (`[[wall]]`, `[[container]]`, `[table]`) and may be unbounded (a strip, a wedge).
    #[serde(rename = "box", default)]
    pub domain: Option<RawBox>,
    /// The `[[species]]` tables, in order.
    pub species: Vec<RawSpecies>,
    /// The `[[ball]]` tables: explicitly placed balls.
    #[serde(default)]
    pub ball: Vec<RawBall>,
    /// The `[[obstacle]]` tables: fixed balls at rest.
    #[serde(default)]
    pub obstacle: Vec<RawObstacle>,
    /// The `[[wall]]` tables: flat walls `(x - point) . normal = 0`.
    #[serde(default)]
    pub wall: Vec<RawWall>,
    /// The `[[container]]` tables: spheres the balls move inside.
    #[serde(default)]
    pub container: Vec<RawContainer>,
    /// The `[[polygon]]` tables: 2D convex polygon obstacles.
    #[serde(default)]
    pub polygon: Vec<RawPolygon>,
    /// The `[table]` table: a 2D convex polygon or a wedge, expanded to walls.
    #[serde(default)]
    pub table: Option<RawTable>,
    /// The `[contact]` table: the contact kind of ball-ball pairs.
    #[serde(default)]
    pub contact: RawContact,
    /// The `[random]` table (its defaults when absent).
    #[serde(default)]
    pub random: RawRandom,
    /// The `[simulation]` table (its defaults when absent).
    #[serde(default)]
    pub simulation: RawSimulation,
    /// The `[thermostat]` table: a driven steady state (absent: no forcing).
    #[serde(default)]
    pub thermostat: Option<RawThermostat>,
}

/// Each axis of the box is bounded by two flat walls or is periodic.
#[derive(Deserialize, Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[serde(rename_all = "lowercase")]
pub enum Boundary {
    /// `"wall"`: flat walls at `x_k = 0` and `x_k = L_k`.
    Wall,
    /// `"periodic"`: `x_k` is taken modulo `L_k`.
    Periodic,
}

/// The `[box]` table: the box `[0, L_0] x .. x [0, L_{n-1}]`.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawBox {
    /// `size`: the side lengths `L_k`, one per axis.
    pub size: Vec<Number>,
    /// `boundary`: `"wall"` or `"periodic"`, one per axis.
    pub boundary: Vec<Boundary>,
    /// `contact`: the contact kind of the box's walls: `"no-slip"` (default), `"smooth"`,
    /// `{ e = ..., beta = ... }` or `{ e = ..., mu = ..., beta0 = ... }`.
    #[serde(default)]
    pub contact: ContactKind,
}

/// A species' mass distribution named instead of its `lambda` or `gamma2`.
#[derive(Deserialize, Debug, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Distribution {
    /// Uniform density: `lambda = R^2/(n+2)`, `gamma^2 = 2/(n+2)`.
    Uniform,
    /// All mass on the sphere: `lambda = R^2/n`, `gamma^2 = 2/n`.
    Shell,
}

/// A `[[species]]` table. At most one of `lambda`, `gamma2` and `distribution`; none means uniform.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawSpecies {
    /// `name`: optional (`species<i>` by default).
    #[serde(default)]
    pub name: Option<String>,
    /// `mass`: `m > 0`.
    pub mass: Number,
    /// `radius`: `R > 0`.
    pub radius: Number,
    /// `lambda = (1/(n m)) int |b|^2 dmu`, in `[0, R^2/n]`.
    #[serde(default)]
    pub lambda: Option<Number>,
    /// `gamma2 = 2 lambda / R^2`, in `[0, 2/n]` (3D: `I/(m R^2)`).
    #[serde(default)]
    pub gamma2: Option<Number>,
    /// `distribution`: `"uniform"` or `"shell"`.
    #[serde(default)]
    pub distribution: Option<Distribution>,
    /// `count`: balls of this species placed at random (default 0).
    #[serde(default)]
    pub count: usize,
}

/// An angular velocity: `c` (2D, `U = c J`), `omega` (3D, `U x = omega x x`), or the
/// `n x n` skew matrix row by row. Read by its shape (`spin_shape.rs`), so that a bad
/// entry's own error reaches the message.
#[derive(Debug)]
pub enum RawSpin {
    /// 2D: `c`, with `U = c J`.
    Scalar(Number),
    /// 3D: `omega`, with `U x = omega x x`.
    Vector(Vec<Number>),
    /// Any `n`: the skew matrix `U`, row by row.
    Matrix(Vec<Vec<Number>>),
}

/// A `[[ball]]` table: one explicitly placed ball.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawBall {
    /// `species`: the index of its species.
    pub species: usize,
    /// `position`: the centre, one coordinate per axis.
    pub position: Vec<Number>,
    /// `velocity`: the centre velocity `u` (default 0).
    #[serde(default)]
    pub velocity: Option<Vec<Number>>,
    /// `angular_velocity`: `U` (default 0).
    #[serde(default)]
    pub angular_velocity: Option<RawSpin>,
}

/// An `[[obstacle]]` table: a fixed ball at rest.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawObstacle {
    /// `position`: the centre.
    pub position: Vec<Number>,
    /// `radius`: `> 0`.
    pub radius: Number,
    /// `contact`: `"no-slip"` (default), `"smooth"` or `{ e = ..., beta = ... }`.
    #[serde(default)]
    pub contact: ContactKind,
}

/// A `[[wall]]` table: the flat wall `(x - point) . normal = 0`, the table on the side
/// `normal` points to.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawWall {
    /// `point`: a point of the wall.
    pub point: Vec<Number>,
    /// `normal`: any nonzero vector into the table.
    pub normal: Vec<Number>,
    /// `contact`: `"no-slip"` (default), `"smooth"` or `{ e = ..., beta = ... }`.
    #[serde(default)]
    pub contact: ContactKind,
}

/// A `[[container]]` table: the balls move inside the sphere `|x - centre| = radius`.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawContainer {
    /// `centre`.
    pub centre: Vec<Number>,
    /// `radius`: `> 0`.
    pub radius: Number,
    /// `contact`: `"no-slip"` (default), `"smooth"` or `{ e = ..., beta = ... }`.
    #[serde(default)]
    pub contact: ContactKind,
}

/// A `[[polygon]]` table: a 2D convex polygon obstacle from its vertices (either order).
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawPolygon {
    /// `vertices`: at least 3 points, strictly convex.
    pub vertices: Vec<Vec<Number>>,
    /// `contact`: `"no-slip"` (default), `"smooth"` or `{ e = ..., beta = ... }`.
    #[serde(default)]
    pub contact: ContactKind,
}

/// The `[table]` table: exactly one of `polygon` (a 2D convex polygon table, its vertices in
/// either order) and `wedge`.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawTable {
    /// `polygon`: the table's vertices.
    #[serde(default)]
    pub polygon: Option<Vec<Vec<Number>>>,
    /// `[table.wedge]`: a 2D wedge.
    #[serde(default)]
    pub wedge: Option<RawWedge>,
    /// `contact`: `"no-slip"` (default), `"smooth"` or `{ e = ..., beta = ... }`, for every
    /// wall of the table.
    #[serde(default)]
    pub contact: ContactKind,
}

/// `[table.wedge]`: the 2D wedge with its corner at `corner`, between two edges: from the
/// first direction counterclockwise to the second (`directions`), or from `+x`
/// counterclockwise by `angle_degrees` (in `(0, 180)`).
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawWedge {
    /// `corner`: the apex.
    pub corner: Vec<Number>,
    /// `directions`: the two edge directions, the table counterclockwise from the first.
    #[serde(default)]
    pub directions: Option<Vec<Vec<Number>>>,
    /// `angle_degrees`: the opening angle, the first edge along `+x`.
    #[serde(default)]
    pub angle_degrees: Option<Number>,
}

/// The `[contact]` table.
#[derive(Deserialize, Debug, Default)]
#[serde(deny_unknown_fields)]
pub struct RawContact {
    /// `balls`: the contact kind of every ball-ball pair not listed in `pair` (default
    /// `"no-slip"`; or `"smooth"`, `{ e = ..., beta = ... }` or `{ e = ..., mu = ..., beta0 = ... }`).
    #[serde(default)]
    pub balls: ContactKind,
    /// `tc`: the contact duration of the TC model (Luding & McNamara): a contact of a ball
    /// within `tc` of its previous contact is elastic. `> 0`; absent: none.
    #[serde(default)]
    pub tc: Option<Number>,
    /// `[[contact.pair]]`: a law per unordered pair of species, overriding `balls` for the
    /// pairs listed ([`crate::pair_law`]).
    #[serde(default)]
    pub pair: Vec<RawPair>,
}

/// The `[random]` table: the placement of the species' `count` balls.
#[derive(Deserialize, Debug, Default)]
#[serde(deny_unknown_fields)]
pub struct RawRandom {
    /// `seed`: of the ChaCha8 stream (default 0).
    #[serde(default)]
    pub seed: u64,
    /// `speed`: velocity components uniform in `[-speed, speed]` (default 1).
    #[serde(default)]
    pub speed: Option<Number>,
    /// `spin`: skew entries of `U` uniform in `[-spin, spin]` (default 0).
    #[serde(default)]
    pub spin: Option<Number>,
    /// `velocities`: `"uniform"` (default: `speed`, `spin`) or `"maxwellian"` (`temperature`);
    /// checked by validation.
    #[serde(default)]
    pub velocities: Option<String>,
    /// `temperature`: of the Maxwellian velocities and spins (default 1).
    #[serde(default)]
    pub temperature: Option<Number>,
    /// `placement`: `"random"` (default) or `"lattice"`; checked by validation, so that a bad
    /// value is named by its key.
    #[serde(default)]
    pub placement: Option<String>,
}

/// The `[simulation]` table: defaults for `noslip simulate`, which its flags override.
#[derive(Deserialize, Debug, Default)]
#[serde(deny_unknown_fields)]
pub struct RawSimulation {
    /// `events`: stop after this many contacts.
    #[serde(default)]
    pub events: Option<u64>,
    /// `time`: stop at this simulated time.
    #[serde(default)]
    pub time: Option<Number>,
    /// `orientation`: track each ball's orientation `A_i` in SO(n) (default false).
    #[serde(default)]
    pub orientation: bool,
}

/// The `[thermostat]` table: random kicks of the balls' velocities (docs/granular.md).
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawThermostat {
    /// `kind`: `"white-noise"` (the only one); checked by validation, so that a bad value is
    /// named by its key.
    pub kind: String,
    /// `strength`: `xi`, the noise's strength (a velocity increment of variance `xi^2 dt`
    /// per component in time `dt`); `> 0`.
    pub strength: Number,
    /// `interval`: the time `dt` between kicks; `> 0`.
    pub interval: Number,
    /// `seed`: of the kicks' random stream (default 0).
    #[serde(default)]
    pub seed: u64,
}
