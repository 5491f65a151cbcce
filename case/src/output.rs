//! The output of one case: `{"bodies":[{"angular_velocity":..,"velocity":[..]},..]}`, each
//! body's angular velocity in the form it was given (matrix, 2D scalar, 3D omega), written
//! straight into a `String` as serde_json's compact form of that value would be (keys in
//! order, no spaces; each number as [`InputScalar::write_json`] writes it).

use crate::case::{Case, Spin};
use crate::error::CaseError;
use crate::number::InputScalar;
use crate::solve::BodyOutput;
use collision_core::{skew_pairs, State2, State3};

/// The error of a result that is not a finite `f64`, at `field` (`bodies[i].velocity`, ...).
fn not_finite(field: &str) -> CaseError {
    CaseError::new(
        field,
        "the result is not a finite f64 (the inputs are too large for float arithmetic; \
         --exact computes it)",
    )
}

fn internal(what: &str) -> CaseError {
    CaseError::new("", format!("internal error: {what}"))
}

/// Body `i`'s field `key`, for messages.
fn field(i: usize, key: &str) -> String {
    format!("bodies[{i}].{key}")
}

/// `x`, or the error at body `i`'s `key`.
fn number<T: InputScalar>(x: &T, i: usize, key: &str, json: &mut String) -> Result<(), CaseError> {
    if x.write_json(json) {
        Ok(())
    } else {
        Err(not_finite(&field(i, key)))
    }
}

/// `[x_0,x_1,..]`.
fn numbers<T: InputScalar>(
    xs: &[T],
    i: usize,
    key: &str,
    json: &mut String,
) -> Result<(), CaseError> {
    json.push('[');
    for (k, x) in xs.iter().enumerate() {
        if k > 0 {
            json.push(',');
        }
        number(x, i, key, json)?;
    }
    json.push(']');
    Ok(())
}

/// The form an angular velocity was given in, which its output keeps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Form {
    /// The full matrix.
    Matrix,
    /// 2D: the scalar `c` of `U = c J`.
    Scalar,
    /// 3D: the vector `omega`.
    Omega,
}

impl<T> Spin<T> {
    /// The form of this angular velocity.
    pub(crate) fn form(&self) -> Form {
        match self {
            Spin::Matrix(_) => Form::Matrix,
            Spin::Scalar(_) => Form::Scalar,
            Spin::Omega(_) => Form::Omega,
        }
    }
}

/// Body `i`'s angular velocity (compact entries `spin`, velocity `velocity`) in the given form.
fn spin<T: InputScalar>(
    form: Form,
    out: (&[T], &[T]),
    dim: usize,
    i: usize,
    json: &mut String,
) -> Result<(), CaseError> {
    const KEY: &str = "angular_velocity";
    let (spin, velocity) = out;
    match form {
        Form::Scalar => {
            let [x] = <[T; 1]>::try_from(spin.to_vec()).map_err(|_| internal("2D spin"))?;
            let [v0, v1] =
                <[T; 2]>::try_from(velocity.to_vec()).map_err(|_| internal("2D velocity"))?;
            let s = State2 {
                spin: [x],
                velocity: [v0, v1],
            };
            number(&s.scalar_spin(), i, KEY, json)
        }
        Form::Omega => {
            let spin = <[T; 3]>::try_from(spin.to_vec()).map_err(|_| internal("3D spin"))?;
            let velocity =
                <[T; 3]>::try_from(velocity.to_vec()).map_err(|_| internal("3D velocity"))?;
            numbers(&State3 { spin, velocity }.omega(), i, KEY, json)
        }
        Form::Matrix => {
            if spin.len() != dim * (dim - 1) / 2 {
                return Err(internal("spin length"));
            }
            // Entry (r, c), r < c, is compact entry `at[r * dim + c]`; the one below the
            // diagonal is its negation `0 - x` ([`InputScalar::write_negated_json`]).
            let mut at = vec![0; dim * dim];
            for (k, (r, c)) in skew_pairs(dim).enumerate() {
                at[r * dim + c] = k;
            }
            let zero = T::zero();
            json.push('[');
            for r in 0..dim {
                json.push_str(if r > 0 { ",[" } else { "[" });
                for c in 0..dim {
                    if c > 0 {
                        json.push(',');
                    }
                    match r.cmp(&c) {
                        std::cmp::Ordering::Equal => number(&zero, i, KEY, json)?,
                        std::cmp::Ordering::Less => number(&spin[at[r * dim + c]], i, KEY, json)?,
                        std::cmp::Ordering::Greater => {
                            let x = &spin[at[c * dim + r]];
                            if !x.write_negated_json(json) {
                                return Err(not_finite(&field(i, KEY)));
                            }
                        }
                    }
                }
                json.push(']');
            }
            json.push(']');
            Ok(())
        }
    }
}

/// Append the JSON output of a case to `json`. On an error, what was appended is to be
/// discarded.
pub fn write<T: InputScalar>(
    case: &Case<T>,
    out: &[BodyOutput<T>; 2],
    json: &mut String,
) -> Result<(), CaseError> {
    let forms = [case.bodies[0].spin.form(), case.bodies[1].spin.form()];
    let parts = [0, 1].map(|b| (out[b].spin.as_slice(), out[b].velocity.as_slice()));
    write_parts(forms, parts, case.dim, json)
}

/// [`write()`] from the parts: each body's form, and its compact spin entries and velocity
/// after the collision (the direct path's writer too, [`crate::direct`]).
pub(crate) fn write_parts<T: InputScalar>(
    forms: [Form; 2],
    parts: [(&[T], &[T]); 2],
    dim: usize,
    json: &mut String,
) -> Result<(), CaseError> {
    json.push_str("{\"bodies\":[");
    for (i, (form, body)) in forms.into_iter().zip(parts).enumerate() {
        json.push_str(if i > 0 {
            ",{\"angular_velocity\":"
        } else {
            "{\"angular_velocity\":"
        });
        spin(form, body, dim, i, json)?;
        json.push_str(",\"velocity\":");
        numbers(body.1, i, "velocity", json)?;
        json.push('}');
    }
    json.push_str("]}");
    Ok(())
}

/// The JSON output of a case, as a string ([`write()`]).
pub fn render<T: InputScalar>(
    case: &Case<T>,
    out: &[BodyOutput<T>; 2],
) -> Result<String, CaseError> {
    let mut json = String::new();
    write(case, out, &mut json)?;
    Ok(json)
}
