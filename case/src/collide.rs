//! The whole input: one case or an array of cases, in, and the same shape out.

use crate::case::Case;
use crate::error::join;
use crate::error::CaseError;
use crate::keys::{first_repeated_key, has_every_key, PathStep};
use crate::node::Node;
use crate::number::InputScalar;
use crate::output::{render, write};
use crate::solve::solve;
use crate::text;
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

/// One case, JSON in, JSON text out (one line).
pub fn collide_case<T, V: Node>(case: &V) -> Result<String, CaseError>
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
pub fn collide_floats<T, V: Node>(case: &V) -> Result<String, CaseError>
where
    T: InputScalar,
    for<'a> &'a T::Unbounded: RefArith<T::Unbounded>,
{
    let case = Case::<T>::from_floats(case)?;
    let out = solve(&case)?;
    render(&case, &out)
}

/// Append the output of one case to `json`.
fn collide_into<T, V: Node>(case: &V, json: &mut String) -> Result<(), CaseError>
where
    T: InputScalar,
    for<'a> &'a T::Unbounded: RefArith<T::Unbounded>,
{
    let case = Case::<T>::from_json(case)?;
    let out = solve(&case)?;
    write(&case, &out, json)
}

/// Append the output of every case of `input` (a case, or an array of cases) to `json`;
/// the index of the first invalid case and its error otherwise.
fn collide_all<V: Node>(input: &V, mode: Mode, json: &mut String) -> Result<(), RunError> {
    let one = |i: usize, case: &V, json: &mut String| {
        match mode {
            Mode::Float => collide_into::<f64, V>(case, json),
            Mode::Exact => collide_into::<Exact, V>(case, json),
        }
        .map_err(|e| RunError::Case(i, e))
    };
    if let Some(cases) = input.as_array() {
        json.push('[');
        for (i, c) in cases.iter().enumerate() {
            if i > 0 {
                json.push(',');
            }
            one(i, c, json)?;
        }
        json.push(']');
        Ok(())
    } else if input.as_object().is_some() {
        one(0, input, json)
    } else {
        Err(RunError::Shape(format!(
            "expected a case (a JSON object) or an array of cases, got {}",
            input.kind()
        )))
    }
}

/// Collide every case of `input` (a case, or an array of cases) and return the output
/// JSON (one line, no trailing newline): an array for an array, an object for an object.
/// A key given twice in one object is an error (naming its case and path). Stops at the
/// first invalid case; nothing is output then.
///
/// In exact mode a plain case (one case, matrix spins, short numbers: `crate::plain`) that
/// passes every check on machine integers is run straight from the text (`crate::direct`).
/// Otherwise the input is read in one pass into a borrowed tree ([`crate::text`]) when it
/// can be; when it cannot, or when any case fails, it is read again by serde_json and run
/// again from the start, so that every error (the JSON's, a repeated key's, a case's) is
/// the one that path reports.
pub fn collide_json(input: &str, mode: Mode) -> Result<String, RunError> {
    if mode == Mode::Exact {
        if let Some(json) = crate::direct::collide(input) {
            return Ok(json);
        }
    }
    if let Some(tree) = text::parse(input) {
        // Room for an answer of about twice the input (exact answers run longer than the
        // case), so that it is rarely grown.
        let mut json = String::with_capacity(2 * input.len() + 256);
        if collide_all(&tree, mode, &mut json).is_ok() {
            return Ok(json);
        }
    }
    collide_json_serde(input, mode)
}

/// The direct path alone: `Some` of [`collide_json`]`(text, Mode::Exact)`'s answer when
/// `text` is one plain case (`crate::plain`: matrix spins, short numbers, no contact law)
/// that passes every check on machine integers, `None` otherwise (an array, another form,
/// an error: the caller then takes the general path, which reports it). For callers that
/// collide one case and never an array, such as the Python package's `collide_case`.
pub fn collide_plain_exact(text: &str) -> Option<String> {
    crate::direct::collide(text)
}

/// [`collide_json`] without the direct path: the borrowed tree when it reads the input and
/// every case passes, serde_json otherwise (the reference the direct path is tested
/// against, `case/tests/direct_path.rs`).
pub fn collide_json_general(input: &str, mode: Mode) -> Result<String, RunError> {
    if let Some(tree) = text::parse(input) {
        let mut json = String::with_capacity(2 * input.len() + 256);
        if collide_all(&tree, mode, &mut json).is_ok() {
            return Ok(json);
        }
    }
    collide_json_serde(input, mode)
}

/// [`collide_json`] by serde_json alone: the input read into a `Value` (and searched for a
/// repeated key), then every case. The path of every input the fast path does not read,
/// and of every error; the reference the fast path is tested against
/// (`case/tests/fast_path.rs`).
pub fn collide_json_serde(input: &str, mode: Mode) -> Result<String, RunError> {
    let value: Value = serde_json::from_str(input).map_err(RunError::Json)?;
    if !has_every_key(input, &value) {
        if let Some(path) = first_repeated_key(input) {
            return Err(repeated_key(&value, &path));
        }
    }
    let mut json = String::new();
    collide_all(&value, mode, &mut json)?;
    Ok(json)
}
