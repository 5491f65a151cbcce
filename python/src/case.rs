//! One collision from a case in the JSON case format (the `noslip-case` crate: the same
//! parsing, validation and messages as `noslip collide`), in `f64` or exact rationals.
//!
//! The Python layer turns its arguments into that format's JSON (floats as JSON numbers in
//! their shortest round-trip text, `Fraction`s and decimal strings as strings), so a case
//! means the same thing from Python and from the command line, bit for bit; in `f64` the
//! JSON numbers are read as the floats they were ([`noslip_case::case::Case::from_floats`]), so a
//! subnormal float is taken as it is, where the command refuses a decimal that would round
//! below the normal range.

use crate::error::input_error;
use collision_core::Exact;
use noslip_case::collide::{collide_case as solve_case, collide_floats};
use noslip_case::CaseError;
use pyo3::prelude::*;
use serde_json::Value;

/// Collide one case given as JSON text; return the output JSON text (the ``noslip collide``
/// output of that case). ``exact``: exact rationals (output numbers are ``"p/q"`` strings).
#[pyfunction]
#[pyo3(signature = (case, exact))]
pub fn collide_case(py: Python<'_>, case: &str, exact: bool) -> PyResult<String> {
    let value: Value =
        serde_json::from_str(case).map_err(|e| input_error(format!("malformed case: {e}")))?;
    let out: Result<String, CaseError> = py.detach(|| {
        if exact {
            solve_case::<Exact>(&value)
        } else {
            collide_floats::<f64>(&value)
        }
    });
    out.map_err(|e| input_error(e.to_string()))
}
