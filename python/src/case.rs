//! One collision from a case in the JSON case format (the `noslip-case` crate: the same
//! parsing, validation and messages as `noslip collide`), in `f64` or exact rationals.
//!
//! The Python layer turns its arguments into that format's JSON (floats as JSON numbers in
//! their shortest round-trip text, `Fraction`s and decimal strings as strings), so a case
//! means the same thing from Python and from the command line, bit for bit; in `f64` the
//! JSON numbers are read as the floats they were ([`noslip_case::case::Case::from_floats`]), so a
//! subnormal float is taken as it is, where the command refuses a decimal that would round
//! below the normal range. The text is read by the command's one-pass reader
//! (`noslip_case::text`) when it can be; otherwise, and whenever the case fails, by
//! serde_json as before, which reports every error. In exact mode a plain case goes first
//! through the command's direct path (`noslip_case::collide::collide_plain_exact`).

use crate::error::input_error;
use collision_core::Exact;
use noslip_case::collide::{collide_case as solve_case, collide_floats, collide_plain_exact};
use noslip_case::CaseError;
use pyo3::prelude::*;
use serde_json::Value;

/// Collide one case given as JSON text; return the output JSON text (the ``noslip collide``
/// output of that case). ``exact``: exact rationals (output numbers are ``"p/q"`` strings).
#[pyfunction]
#[pyo3(signature = (case, exact))]
pub fn collide_case(py: Python<'_>, case: &str, exact: bool) -> PyResult<String> {
    // The one-pass reader first (`noslip_case::text`, as `noslip collide` reads); a text it
    // does not read, or a case that fails, goes to serde_json's `Value` below, so that every
    // error is the one that path reports.
    let fast = py.detach(|| {
        // In exact mode a plain case is run straight from the text (the command's direct
        // path, `noslip_case::collide::collide_plain_exact`): the same bytes, faster.
        if exact {
            if let Some(json) = collide_plain_exact(case) {
                return Some(json);
            }
        }
        let tree = noslip_case::text::parse(case)?;
        if exact {
            solve_case::<Exact, _>(&tree).ok()
        } else {
            collide_floats::<f64, _>(&tree).ok()
        }
    });
    if let Some(json) = fast {
        return Ok(json);
    }
    let value: Value =
        serde_json::from_str(case).map_err(|e| input_error(format!("malformed case: {e}")))?;
    let out: Result<String, CaseError> = py.detach(|| {
        if exact {
            solve_case::<Exact, _>(&value)
        } else {
            collide_floats::<f64, _>(&value)
        }
    });
    out.map_err(|e| input_error(e.to_string()))
}
