//! The input schema of one case, read from JSON into typed values. Every error names its
//! field by path (`normal[2]`, `bodies[1].angular_velocity[0]`, ...).
//!
//! ```json
//! {"dim": 3, "normal": ["0", "3/5", "4/5"],
//!  "bodies": [{"mass": "2", "radius": "1", "lambda": "1/5",
//!              "angular_velocity": [["0","1","-2"],["-1","0","3"],["2","-3","0"]],
//!              "velocity": ["1","0","1/2"]},
//!             {"mass": "inf", "radius": "3/2", "gamma2": "2/5",
//!              "angular_velocity": [["0","0","0"],["0","0","0"],["0","0","0"]],
//!              "velocity": ["0","0","0"]}]}
//! ```
//!
//! An optional `contact` key gives the contact law ([`crate::contact`]; no-slip by default).
//!
//! Sizes are checked against `dim` before any number is read, and `dim` is bounded by
//! [`MAX_DIM`], so nothing of size `dim` is built from a short input.

pub use crate::body::{BodyInput, Spin};
use crate::contact::{contact_from_json, Contact};
use crate::error::{clip, join, quote, CaseError};
use crate::node::{Members, Node};
use crate::number::{integer_literal, read, scalar_from_json, InputScalar};
use crate::tiny::Tiny;
use collision_core::{Inertia, Mass};

/// The largest `dim` accepted. Above 6 the general-n reference runs; its work grows like
/// `n^4` arithmetic operations (a Gram matrix of `n(n+1)` x `n` impulse columns, then
/// Gaussian elimination), each on rationals as long as the inputs in `--exact`. At 16 a case
/// with 17-digit decimals takes about a second in `--exact`; 32 took 30 s with exponents
/// near the exact limit.
pub const MAX_DIM: usize = 16;

/// The keys of a case.
pub const CASE_KEYS: [&str; 4] = ["dim", "normal", "bodies", "contact"];
/// The keys of a body.
pub const BODY_KEYS: [&str; 7] = [
    "mass",
    "radius",
    "lambda",
    "gamma2",
    "distribution",
    "angular_velocity",
    "velocity",
];
const INERTIA_KEYS: [&str; 3] = ["lambda", "gamma2", "distribution"];

/// `bodies[i]`, the path of body `i`.
const BODY_PATHS: [&str; 2] = ["bodies[0]", "bodies[1]"];

/// `bodies[i].KEY` for each of [`BODY_KEYS`], spelled once (a case reads a dozen of them).
const BODY_FIELDS: [[&str; 7]; 2] = [
    [
        "bodies[0].mass",
        "bodies[0].radius",
        "bodies[0].lambda",
        "bodies[0].gamma2",
        "bodies[0].distribution",
        "bodies[0].angular_velocity",
        "bodies[0].velocity",
    ],
    [
        "bodies[1].mass",
        "bodies[1].radius",
        "bodies[1].lambda",
        "bodies[1].gamma2",
        "bodies[1].distribution",
        "bodies[1].angular_velocity",
        "bodies[1].velocity",
    ],
];

/// The field of `key` (one of [`BODY_KEYS`]) of body `index` (0 or 1).
fn body_field(index: usize, key: &str) -> &'static str {
    let k = BODY_KEYS.iter().position(|&b| b == key);
    k.map_or("", |k| BODY_FIELDS[index][k])
}

/// One case as given; `normal` and `velocity` have length `dim`, a `Matrix` spin is
/// `dim x dim`.
#[derive(Clone, Debug, PartialEq)]
pub struct Case<T> {
    /// `dim`: the dimension `n` (at most [`MAX_DIM`]).
    pub dim: usize,
    /// `normal`: the unit contact normal `nu`, from body 1 to body 2.
    pub normal: Vec<T>,
    /// `bodies`: body 1 and body 2.
    pub bodies: [BodyInput<T>; 2],
    /// `contact`: the contact law, no-slip unless given ([`crate::contact`]).
    pub contact: Contact<T>,
}

fn object<'a, V: Node>(value: &'a V, path: &str, what: &str) -> Result<&'a V::Object, CaseError> {
    value
        .as_object()
        .ok_or_else(|| CaseError::new(path, format!("expected {what}, got {}", value.kind())))
}

fn no_unknown_keys<V: Node>(obj: &V::Object, path: &str, known: &[&str]) -> Result<(), CaseError> {
    match obj.unknown_key(known) {
        Some(k) => Err(CaseError::new(
            join(path, k),
            format!("unknown key (the keys are: {})", known.join(", ")),
        )),
        None => Ok(()),
    }
}

fn get<'a, V: Node>(obj: &'a V::Object, path: &str, key: &str) -> Result<&'a V, CaseError> {
    obj.get(key)
        .ok_or_else(|| CaseError::new(join(path, key), "missing (required)"))
}

/// An array of exactly `len` numbers at `field` (at `field[row]` for a row of a matrix);
/// the length is checked before any number is read. The fields of components below the
/// normal range of `T` are pushed on `tiny`. Fields are spelled out only when needed.
fn vector<T: InputScalar, V: Node>(
    value: &V,
    (field, row): (&str, Option<usize>),
    len: usize,
    floats: bool,
    tiny: &mut Vec<String>,
) -> Result<Vec<T>, CaseError> {
    let field = || match row {
        Some(r) => format!("{field}[{r}]"),
        None => field.to_string(),
    };
    let items = value.as_array().ok_or_else(|| {
        CaseError::new(
            field(),
            format!("expected an array of {len} numbers, got {}", value.kind()),
        )
    })?;
    if items.len() != len {
        return Err(CaseError::new(
            field(),
            format!("expected {len} numbers (dim = {len}), got {}", items.len()),
        ));
    }
    items
        .iter()
        .enumerate()
        .map(|(k, x)| {
            let field = || format!("{}[{k}]", field());
            let (x, below) = read(x, floats).map_err(|m| CaseError::new(field(), m))?;
            if below {
                tiny.push(field());
            }
            Ok(x)
        })
        .collect()
}

fn dim<V: Node>(value: &V) -> Result<usize, CaseError> {
    let err = |m: String| CaseError::new("dim", m);
    let Some(n) = value.as_number() else {
        return Err(err(format!(
            "expected an integer >= 2, got {}",
            value.kind()
        )));
    };
    match integer_literal(n) {
        None => Err(err(format!(
            "expected an integer >= 2, got {}",
            clip(n, 40)
        ))),
        Some((true, _)) | Some((false, 0..=1)) => {
            Err(err(format!("must be at least 2, got {}", clip(n, 40))))
        }
        Some((false, d)) if d > MAX_DIM => Err(err(format!(
            "at most {MAX_DIM} is supported (dims above 6 run the general-n reference, \
             whose cost grows like n^4), got {}",
            clip(n, 40)
        ))),
        Some((false, d)) => Ok(d),
    }
}

/// The forms `angular_velocity` may take in `dim` dimensions, for messages.
fn spin_forms(dim: usize) -> String {
    match dim {
        2 => "a 2 x 2 skew matrix or a number c (U = c J)".into(),
        3 => "a 3 x 3 skew matrix or a 3-vector omega (U x = omega x x)".into(),
        n => format!("a {n} x {n} skew matrix (an array of {n} rows of {n} numbers)"),
    }
}

fn spin<T: InputScalar, V: Node>(
    value: &V,
    field: &str,
    dim: usize,
    floats: bool,
    tiny: &mut Vec<String>,
) -> Result<Spin<T>, CaseError> {
    let wrong =
        |what: String| CaseError::new(field, format!("expected {}, got {what}", spin_forms(dim)));
    if dim == 2 && (value.is_number() || value.as_str().is_some()) {
        let (c, below) = read(value, floats).map_err(|m| CaseError::new(field, m))?;
        if below {
            tiny.push(field.to_string());
        }
        return Ok(Spin::Scalar(c));
    }
    let Some(items) = value.as_array() else {
        return Err(wrong(value.kind().into()));
    };
    if !items.is_empty() && items.iter().all(V::is_array) {
        if items.len() != dim {
            return Err(wrong(format!("{} rows", items.len())));
        }
        items
            .iter()
            .enumerate()
            .map(|(r, row)| vector(row, (field, Some(r)), dim, floats, tiny))
            .collect::<Result<_, _>>()
            .map(Spin::Matrix)
    } else if dim == 3 && items.len() == 3 && !items.iter().any(V::is_array) {
        let omega: Vec<T> = vector(value, (field, None), 3, floats, tiny)?;
        Ok(Spin::Omega([0, 1, 2].map(|k| omega[k].clone())))
    } else if items.is_empty() {
        Err(wrong("an empty array".into()))
    } else if items.iter().any(V::is_array) {
        Err(wrong("an array mixing rows and numbers".into()))
    } else {
        Err(wrong(format!("an array of {} numbers", items.len())))
    }
}

/// The inertia of body `index`.
fn inertia<T: InputScalar, V: Node>(
    obj: &V::Object,
    index: usize,
    floats: bool,
) -> Result<Inertia<T>, CaseError> {
    let mut given = INERTIA_KEYS
        .into_iter()
        .filter_map(|k| obj.get(k).map(|v| (k, v)));
    let first = given.next();
    if let (Some((first, _)), Some((second, _))) = (first, given.next()) {
        return Err(CaseError::new(
            body_field(index, second),
            format!("conflicts with {first}: give at most one of lambda, gamma2, distribution"),
        ));
    }
    let field = |k: &str| body_field(index, k);
    Ok(match first {
        None => Inertia::Uniform,
        Some(("lambda", v)) => Inertia::Lambda(scalar_from_json(v, field("lambda"), floats)?),
        Some(("gamma2", v)) => Inertia::Gamma2(scalar_from_json(v, field("gamma2"), floats)?),
        Some((_, v)) => match v.as_str() {
            Some("uniform") => Inertia::Uniform,
            Some("shell") => Inertia::Shell,
            got => {
                let got = match got {
                    Some(s) => quote(s, 40),
                    None => v.kind().to_string(),
                };
                return Err(CaseError::new(
                    field("distribution"),
                    format!("expected \"uniform\" or \"shell\", got {got}"),
                ));
            }
        },
    })
}

/// `inf` or `infinity`, any case, any sign.
fn is_infinity(s: &str) -> bool {
    let body = s.strip_prefix(['+', '-']).unwrap_or(s);
    body.eq_ignore_ascii_case("inf") || body.eq_ignore_ascii_case("infinity")
}

impl<T: InputScalar> BodyInput<T> {
    /// Body `index` of a case in `dim` dimensions. Its velocity's and angular velocity's
    /// components below the normal range of `T` are recorded in `tiny` (whether they can be
    /// taken depends on the other body: see [`Tiny`]).
    fn from_json<V: Node>(
        value: &V,
        index: usize,
        dim: usize,
        floats: bool,
        tiny: &mut Tiny,
    ) -> Result<Self, CaseError> {
        let path = BODY_PATHS[index];
        let obj = object(
            value,
            path,
            "a body (an object with keys mass, radius, angular_velocity, velocity and at most \
             one of lambda, gamma2, distribution)",
        )?;
        no_unknown_keys::<V>(obj, path, &BODY_KEYS)?;
        let field = |k: &str| body_field(index, k);
        let mass = get::<V>(obj, path, "mass")?;
        let mass = match mass.as_str() {
            Some("inf") => Mass::Infinite,
            Some(s) if is_infinity(s) => {
                let message = if s.starts_with('-') {
                    "must be positive (or \"inf\" for an immovable body)"
                } else {
                    "write \"inf\" for an immovable body"
                };
                return Err(CaseError::new(
                    field("mass"),
                    format!("{message}, got {}", quote(s, 40)),
                ));
            }
            _ => Mass::Finite(scalar_from_json(mass, field("mass"), floats)?),
        };
        let radius = scalar_from_json(get::<V>(obj, path, "radius")?, field("radius"), floats)?;
        let inertia = inertia::<T, V>(obj, index, floats)?;
        let velocity = vector(
            get::<V>(obj, path, "velocity")?,
            (field("velocity"), None),
            dim,
            floats,
            &mut tiny.velocity,
        )?;
        let spin = spin(
            get::<V>(obj, path, "angular_velocity")?,
            field("angular_velocity"),
            dim,
            floats,
            &mut tiny.spin[index],
        )?;
        Ok(BodyInput {
            mass,
            radius,
            inertia,
            spin,
            velocity,
        })
    }
}

impl<T: InputScalar> Case<T> {
    /// One case of the input, every number read as the decimal or rational it spells.
    pub fn from_json<V: Node>(value: &V) -> Result<Self, CaseError> {
        Self::read(value, false)
    }

    /// One case whose JSON numbers (not strings) are floats of `T` written in their
    /// shortest round-trip form, as the Python package writes its floats: each is read as
    /// that float, so one below the normal range is taken as it is (it lost nothing), where
    /// [`Case::from_json`] refuses it or measures its rounding (`case/src/tiny.rs`). Strings
    /// are read as in [`Case::from_json`].
    pub fn from_floats<V: Node>(value: &V) -> Result<Self, CaseError> {
        Self::read(value, true)
    }

    fn read<V: Node>(value: &V, floats: bool) -> Result<Self, CaseError> {
        let obj = object(
            value,
            "",
            "a case (an object with keys dim, normal, bodies)",
        )?;
        no_unknown_keys::<V>(obj, "", &CASE_KEYS)?;
        let dim = dim(get::<V>(obj, "", "dim")?)?;
        // A normal's components are measured against |nu| = 1: one below the normal range
        // is off by at most 2^-1075, far inside the allowance of |nu|^2.
        let normal = vector(
            get::<V>(obj, "", "normal")?,
            ("normal", None),
            dim,
            floats,
            &mut Vec::new(),
        )?;
        let bodies = get::<V>(obj, "", "bodies")?;
        let list = bodies.as_array().ok_or_else(|| {
            CaseError::new(
                "bodies",
                format!("expected an array of 2 bodies, got {}", bodies.kind()),
            )
        })?;
        if list.len() != 2 {
            return Err(CaseError::new(
                "bodies",
                format!("expected 2 bodies, got {}", list.len()),
            ));
        }
        let mut tiny = Tiny::default();
        let bodies = [
            BodyInput::from_json(&list[0], 0, dim, floats, &mut tiny)?,
            BodyInput::from_json(&list[1], 1, dim, floats, &mut tiny)?,
        ];
        tiny.check(&bodies)?;
        let contact = contact_from_json(obj.get("contact"), floats)?;
        Ok(Case {
            dim,
            normal,
            bodies,
            contact,
        })
    }
}

#[cfg(test)]
#[path = "case_tests.rs"]
mod tests;
