//! The whole input: one case or an array of cases, in, and the same shape out.

use crate::json::case::Case;
use crate::json::error::{kind, CaseError};
use crate::json::number::InputScalar;
use crate::json::output::render;
use crate::json::solve::solve;
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

impl std::error::Error for RunError {}

/// One case, JSON in, JSON out.
pub fn collide_case<T>(case: &Value) -> Result<Value, CaseError>
where
    T: InputScalar,
    for<'a> &'a T: RefArith<T>,
{
    let case = Case::<T>::from_json(case)?;
    let out = solve(&case)?;
    render(&case, &out)
}

/// Collide every case of `input` (a case, or an array of cases) and return the output
/// JSON (one line, no trailing newline): an array for an array, an object for an object.
/// Stops at the first invalid case; nothing is output then.
pub fn collide_json(input: &str, mode: Mode) -> Result<String, RunError> {
    let value: Value = serde_json::from_str(input).map_err(RunError::Json)?;
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
