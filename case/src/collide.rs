//! The whole input: one case or an array of cases, in, and the same shape out.

use crate::case::Case;
use crate::error::join;
use crate::error::{kind, CaseError};
use crate::keys::{first_repeated_key, has_every_key, PathStep};
use crate::number::InputScalar;
use crate::output::render;
use crate::solve::solve;
use collision_core::{Exact, RefArith};
use serde_json::Value;
use std::fmt;

/// Arithmetic of the `collide` command.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// `f64`, the default.
    Float,
    /// Exact rationals (`--exact`).
    Exact,
}

/// Why an input was rejected. Every variant displays as one line.
#[derive(Debug)]
#[non_exhaustive]
pub enum RunError {
    /// Not JSON (serde_json's message carries the line and column).
    Json(serde_json::Error),
    /// JSON, but neither a case nor an array of cases.
    Shape(String),
    /// Case `index` (0-based; 0 for a single case) is invalid.
    Case(usize, CaseError),
}

impl fmt::Display for RunError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RunError::Json(e) => write!(f, "malformed JSON: {e}"),
            RunError::Shape(m) => f.write_str(m),
            RunError::Case(i, e) => write!(f, "case {i}: {e}"),
        }
    }
}

impl std::error::Error for RunError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            RunError::Json(e) => Some(e),
            RunError::Case(_, e) => Some(e),
            RunError::Shape(_) => None,
        }
    }
}

/// The error for a key given twice at `path`: its case (the first index of an array input)
/// and its field.
fn repeated_key(input: &Value, path: &[PathStep]) -> RunError {
    let (case, rest) = match (input, path.first()) {
        (Value::Array(_), Some(PathStep::Index(i))) => (*i, &path[1..]),
        _ => (0, path),
    };
    let field = rest.iter().fold(String::new(), |field, step| match step {
        PathStep::Index(i) => format!("{field}[{i}]"),
        PathStep::Key(k) => join(&field, k),
    });
    RunError::Case(
        case,
        CaseError::new(
            field,
            "repeated key: each key may be given once (JSON readers differ on which one wins)",
        ),
    )
}

/// One case, JSON in, JSON out.
pub fn collide_case<T>(case: &Value) -> Result<Value, CaseError>
where
    T: InputScalar,
    for<'a> &'a T::Unbounded: RefArith<T::Unbounded>,
{
    let case = Case::<T>::from_json(case)?;
    let out = solve(&case)?;
    render(&case, &out)
}

/// [`collide_case`] for a case whose JSON numbers are floats of `T` in their shortest
/// round-trip form ([`Case::from_floats`]: the Python package's floats).
pub fn collide_floats<T>(case: &Value) -> Result<Value, CaseError>
where
    T: InputScalar,
    for<'a> &'a T::Unbounded: RefArith<T::Unbounded>,
{
    let case = Case::<T>::from_floats(case)?;
    let out = solve(&case)?;
    render(&case, &out)
}

/// Collide every case of `input` (a case, or an array of cases) and return the output
/// JSON (one line, no trailing newline): an array for an array, an object for an object.
/// A key given twice in one object is an error (naming its case and path). Stops at the
/// first invalid case; nothing is output then.
pub fn collide_json(input: &str, mode: Mode) -> Result<String, RunError> {
    let value: Value = serde_json::from_str(input).map_err(RunError::Json)?;
    if !has_every_key(input, &value) {
        if let Some(path) = first_repeated_key(input) {
            return Err(repeated_key(&value, &path));
        }
    }
    let one = |i: usize, case: &Value| {
        match mode {
            Mode::Float => collide_case::<f64>(case),
            Mode::Exact => collide_case::<Exact>(case),
        }
        .map_err(|e| RunError::Case(i, e))
    };
    let out = match &value {
        Value::Array(cases) => Value::Array(
            cases
                .iter()
                .enumerate()
                .map(|(i, c)| one(i, c))
                .collect::<Result<_, _>>()?,
        ),
        Value::Object(_) => one(0, &value)?,
        other => {
            return Err(RunError::Shape(format!(
                "expected a case (a JSON object) or an array of cases, got {}",
                kind(other)
            )))
        }
    };
    serde_json::to_string(&out).map_err(RunError::Json)
}
