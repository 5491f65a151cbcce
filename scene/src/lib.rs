//! # noslip-scene
//!
//! The scene format: a simulation setup read from TOML (see `docs/scenes.md`): a dimension, a
//! box whose axes are walled or periodic (optional), the table's other boundaries (walls,
//! containers, 2D polygons and wedges, polygon obstacles: [`table`], `docs/tables.md`) and
//! contact kinds, species of balls, explicit balls, fixed ball obstacles, seeded random
//! placement and defaults for the run. The generator
//! (`noslip-codegen`) reads a scene's pair sets from here, the simulator (`noslip-sim`) its
//! placement. This crate parses and validates in exact rationals and nothing else: it knows
//! no kernels, no floating point and no simulation.
//!
//! [`Scene::from_toml`] parses ([`raw`], unknown keys refused) and validates (`validate`)
//! in exact rationals; every error names the place: a line and column for syntax, followed by
//! the key path when the parser's error points at a key or a value (an unknown key, a NaN or
//! a non-number: `line 17, column 15: contact.balls.e`), a key path such as
//! `species[1].radius` or `ball[3].position` for what validation refuses.
//! The generator needs [`Scene::pairs`]; the simulator also needs the placement.

#![warn(missing_docs, unreachable_pub)]

mod contact;
mod convex;
mod ctx;
mod key_path;
mod number;
pub mod pair_law;
mod pairs;
pub mod raw;
mod spin_shape;
pub mod table;
mod thermostat;
mod validate;

pub use number::{parse_exact, Number, MAX_DIGITS};
pub use pair_law::PairContact;
pub use pairs::{Pair, PairLaws, PairSet, WallSide};
pub use raw::{Boundary, ContactKind, Distribution};

pub use table::{Shape, TableBoundary};
pub use thermostat::Thermostat;

use num_rational::BigRational;
use std::fmt;
use std::path::Path;

/// The largest scene file read, 16 MiB (about 10^5 explicit balls; random ones cost a
/// `count`): a larger file is refused before it is read whole.
pub const MAX_SCENE_BYTES: u64 = 16 << 20;

/// One species: every ball of it shares these constants (exact).
#[derive(Clone, Debug, PartialEq)]
pub struct Species {
    /// The species' name (`species<i>` when the file gives none).
    pub name: String,
    /// The mass `m > 0`.
    pub mass: BigRational,
    /// `w = 1/m`.
    pub inv_mass: BigRational,
    /// The radius `R > 0`; `2 R` is below every side of the box.
    pub radius: BigRational,
    /// `gamma^2 = 2 lambda / R^2` in `[0, 2/n]`.
    pub gamma2: BigRational,
    /// The key that set `gamma2` (`"lambda"`, `"gamma2"` or `"distribution"`; `None`: the
    /// default, a uniform ball), for messages.
    pub gamma2_key: Option<&'static str>,
    /// Balls of this species placed at random (besides the explicit ones).
    pub count: usize,
}

/// The most balls a scene may hold, explicit and random together: `2^24`. The simulator keeps
/// every ball in memory several times over (its setup, the engine's state, cell lists and
/// queue: a few hundred bytes each, more in higher dimensions; see docs/scenes.md) and places
/// the random ones one by one; the limit keeps both within an ordinary machine and is
/// checked before anything is allocated, with sums that cannot overflow.
pub const MAX_BALLS: usize = 1 << 24;

/// An explicitly placed ball.
#[derive(Clone, Debug, PartialEq)]
pub struct BallSpec {
    /// The index of its species in [`Scene::species`].
    pub species: usize,
    /// The centre `a`: `R <= a_k <= L_k - R` on a walled axis, `0 <= a_k < L_k` on a periodic one.
    pub position: Vec<BigRational>,
    /// The centre velocity `u` (0 when the file gives none).
    pub velocity: Vec<BigRational>,
    /// Compact skew entries `U_ij`, `i < j`.
    pub spin: Vec<BigRational>,
}

/// An immovable ball at rest.
#[derive(Clone, Debug, PartialEq)]
pub struct Obstacle {
    /// The centre, in `[0, L_k]` on every axis.
    pub position: Vec<BigRational>,
    /// The radius, `> 0`.
    pub radius: BigRational,
    /// No-slip or smooth.
    pub contact: ContactKind,
}

/// Where the species' `count` balls go (`random.placement`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Placement {
    /// `"random"` (the default): centres uniform in the box, redrawn while they overlap.
    #[default]
    Random,
    /// `"lattice"`: centres on sites of the checkerboard lattice `D_n` (integer points with an
    /// even coordinate sum; the square lattice in 2D, face-centred cubic in 3D) scaled to
    /// fill the box, the sites taken in a seeded random order; for packings random placement
    /// cannot reach.
    Lattice,
}

/// Seeded placement of the species' `count` balls: positions uniform in the box, no overlaps
/// (rejection sampling), or on a lattice ([`Placement`]); velocity components uniform in
/// `[-speed, speed]`, skew entries of `U` uniform in `[-spin, spin]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Random {
    /// The seed of the placement's ChaCha8 stream (`random.seed`, default 0).
    pub seed: u64,
    /// Random or lattice centres (`random.placement`, default random).
    pub placement: Placement,
    /// Velocity components are uniform in `[-speed, speed]`; `>= 0`, default 1.
    pub speed: BigRational,
    /// Skew entries of `U` are uniform in `[-spin, spin]`; `>= 0`, default 0.
    pub spin: BigRational,
    /// `Some(T)` (`random.velocities = "maxwellian"`, `random.temperature`, `T > 0`, default
    /// 1): instead of `speed` and `spin`, each velocity component is normal with mean 0 and
    /// variance `T / m`, each skew entry `U_ij` (`i < j`) normal with variance `T / I`,
    /// `I = 2 m lambda` (0 when `lambda = 0`): a Maxwellian at granular temperature `T` in
    /// every translational and rotational degree of freedom (docs/granular.md).
    pub temperature: Option<BigRational>,
}

/// Defaults of a run (the command line overrides them).
#[derive(Clone, Debug, PartialEq, Default)]
pub struct RunDefaults {
    /// Stop after this many contacts (at least 1).
    pub events: Option<u64>,
    /// Stop at this simulated time (`> 0`).
    pub time: Option<BigRational>,
    /// Track each ball's orientation `A_i` in SO(n).
    pub orientation: bool,
}

/// A validated scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// Where it came from (a file name), for messages.
    pub origin: String,
    /// The scene's free-text `description` (empty when it has none).
    pub description: String,
    /// The dimension `n`, in `2..=6`.
    pub dim: usize,
    /// The box is `[0, size_0] x .. x [0, size_{n-1}]`; empty when the scene has no `[box]`
    /// (the table is then bounded by [`Scene::boundaries`] alone, or unbounded).
    pub size: Vec<BigRational>,
    /// Per axis `k`: two flat walls (at 0 and `size_k`) or periodic; empty without a box.
    pub boundary: Vec<Boundary>,
    /// The table's other boundaries (walls, containers, polygon pieces), in the order of
    /// [`table`]: the index is the boundary id. Never with a periodic axis.
    pub boundaries: Vec<TableBoundary>,
    /// The polygons (the table's and the obstacles'), counterclockwise, that polygon pieces
    /// of [`Scene::boundaries`] refer to.
    pub polygons: Vec<Vec<Vec<BigRational>>>,
    /// The contact kind of every ball-ball pair of species not in [`Scene::pair_contacts`]
    /// (`[contact] balls`); [`Scene::ball_law`] gives any pair's.
    pub ball_contact: ContactKind,
    /// The ball-ball laws of the species pairs the scene lists (`[[contact.pair]]`, in file
    /// order, each unordered pair at most once); every other pair has
    /// [`Scene::ball_contact`].
    pub pair_contacts: Vec<PairContact>,
    /// The contact kind of the box's walls (`[box] contact`; no-slip without a box).
    pub box_contact: ContactKind,
    /// The TC model's contact duration (`[contact] tc`, `> 0`): a contact of a ball within
    /// `tc` of its previous contact is elastic (docs/granular.md). `None`: every contact
    /// follows its law.
    pub tc: Option<BigRational>,
    /// The species, indexed as in the file (`species[i]`).
    pub species: Vec<Species>,
    /// The explicitly placed balls (`[[ball]]`), in file order.
    pub balls: Vec<BallSpec>,
    /// The fixed ball obstacles (`[[obstacle]]`).
    pub obstacles: Vec<Obstacle>,
    /// How the species' `count` balls are placed (`[random]`).
    pub random: Random,
    /// The run's defaults (`[simulation]`).
    pub simulation: RunDefaults,
    /// The white-noise thermostat of a driven steady state (`[thermostat]`); `None`: no
    /// forcing.
    pub thermostat: Option<Thermostat>,
}

/// A bad scene: where (`file: place`) and what.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SceneError {
    /// Where the scene came from (a file name).
    pub origin: String,
    /// `line 4, column 1` (a syntax error), `line 4, column 15: contact.balls.e` (a value or
    /// key the parser refuses: a NaN, a non-number, an unknown key), or a key path like
    /// `species[1].radius` (what validation refuses).
    pub place: String,
    /// What is wrong, in one line.
    pub message: String,
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(f, "{}: {}: {}", self.origin, self.place, self.message)
    }
}

impl std::error::Error for SceneError {}

fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let column = before.len() - before.rfind('\n').map_or(0, |i| i + 1) + 1;
    (line, column)
}

impl Scene {
    /// Parse and validate scene `text`; `origin` names it in errors.
    pub fn from_toml(text: &str, origin: &str) -> Result<Scene, SceneError> {
        let raw: raw::RawScene = toml::from_str(text).map_err(|e| {
            // A missing key's span is its table's: name the table (or the top level).
            let missing = e.message().starts_with("missing field");
            let place = match e.span() {
                Some(span) if missing => match key_path::table_path(text, &span).as_deref() {
                    Some("") | None => "the top level".to_string(),
                    Some(table) => {
                        let (l, c) = line_column(text, span.start);
                        format!("line {l}, column {c}: {table}")
                    }
                },
                Some(span) => {
                    let (l, c) = line_column(text, span.start);
                    let path = key_path::key_path(text, span.start)
                        .or_else(|| key_path::line_key(text, span.start));
                    match path {
                        Some(path) => format!("line {l}, column {c}: {path}"),
                        None => format!("line {l}, column {c}"),
                    }
                }
                None => "scene".to_string(),
            };
            SceneError {
                origin: origin.to_string(),
                place,
                message: e.message().trim().replace('\n', " "),
            }
        })?;
        validate::validate(raw, origin)
    }

    /// Read, parse and validate a scene file.
    pub fn from_file(path: &Path) -> Result<Scene, SceneError> {
        use std::io::Read;
        let origin = path.display().to_string();
        let error = |message: String| SceneError {
            origin: origin.clone(),
            place: "file".into(),
            message,
        };
        let mut bytes = Vec::new();
        std::fs::File::open(path)
            .and_then(|f| f.take(MAX_SCENE_BYTES + 1).read_to_end(&mut bytes))
            .map_err(|e| error(format!("cannot read: {e}")))?;
        if bytes.len() as u64 > MAX_SCENE_BYTES {
            return Err(error(format!(
                "larger than {} MiB, the limit of a scene file",
                MAX_SCENE_BYTES >> 20
            )));
        }
        let text = String::from_utf8(bytes)
            .map_err(|_| error("cannot read: stream did not contain valid UTF-8".into()))?;
        Scene::from_toml(&text, &origin)
    }

    /// Number of balls: explicit ones and those placed at random.
    pub fn ball_count(&self) -> usize {
        self.balls.len() + self.species.iter().map(|s| s.count).sum::<usize>()
    }

    /// The ball-ball law of species `a` and `b` (either order): the law
    /// `[[contact.pair]]` gives the pair, else `[contact] balls`.
    pub fn ball_law(&self, a: usize, b: usize) -> &ContactKind {
        let key = [a.min(b), a.max(b)];
        self.pair_contacts
            .iter()
            .find(|p| p.species == key)
            .map_or(&self.ball_contact, |p| &p.contact)
    }

    /// Balls of each species (explicit and random).
    pub fn balls_per_species(&self) -> Vec<usize> {
        let mut n: Vec<usize> = self.species.iter().map(|s| s.count).collect();
        for b in &self.balls {
            n[b.species] += 1;
        }
        n
    }
}
