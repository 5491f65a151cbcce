//! The output of one case: `{"bodies": [{"angular_velocity": .., "velocity": [..]}, ..]}`,
//! each body's angular velocity in the form it was given (matrix, 2D scalar, 3D omega).

use crate::case::{Case, Spin};
use crate::error::CaseError;
use crate::number::InputScalar;
use crate::solve::BodyOutput;
use collision_core::{skew_pairs, State2, State3};
use serde_json::{Map, Value};

fn number<T: InputScalar>(x: &T, field: &str) -> Result<Value, CaseError> {
    x.to_json().ok_or_else(|| {
        CaseError::new(
            field,
            "the result is not a finite f64 (the inputs are too large for float arithmetic; \
             --exact computes it)",
        )
    })
}

fn numbers<T: InputScalar>(xs: &[T], field: &str) -> Result<Value, CaseError> {
    xs.iter()
        .map(|x| number(x, field))
        .collect::<Result<_, _>>()
        .map(Value::Array)
}

fn internal(what: &str) -> CaseError {
    CaseError::new("", format!("internal error: {what}"))
}

/// The angular velocity in the given form.
fn spin<T: InputScalar>(
    form: &Spin<T>,
    out: &BodyOutput<T>,
    dim: usize,
    field: &str,
) -> Result<Value, CaseError> {
    match form {
        Spin::Scalar(_) => {
            let [x] = <[T; 1]>::try_from(out.spin.clone()).map_err(|_| internal("2D spin"))?;
            let [v0, v1] =
                <[T; 2]>::try_from(out.velocity.clone()).map_err(|_| internal("2D velocity"))?;
            let s = State2 {
                spin: [x],
                velocity: [v0, v1],
            };
            number(&s.scalar_spin(), field)
        }
        Spin::Omega(_) => {
            let spin = <[T; 3]>::try_from(out.spin.clone()).map_err(|_| internal("3D spin"))?;
            let velocity =
                <[T; 3]>::try_from(out.velocity.clone()).map_err(|_| internal("3D velocity"))?;
            numbers(&State3 { spin, velocity }.omega(), field)
        }
        Spin::Matrix(_) => {
            if out.spin.len() != dim * (dim - 1) / 2 {
                return Err(internal("spin length"));
            }
            // Each entry above the diagonal is printed once; the one below is its negation,
            // `0 - x` ([`InputScalar::negated_json`]).
            let zero = number(&T::zero(), field)?;
            let mut m = vec![vec![zero; dim]; dim];
            for ((r, c), x) in skew_pairs(dim).zip(&out.spin) {
                let upper = number(x, field)?;
                m[c][r] = T::negated_json(x, &upper).ok_or_else(|| internal("negation"))?;
                m[r][c] = upper;
            }
            Ok(Value::Array(m.into_iter().map(Value::Array).collect()))
        }
    }
}

/// The JSON output of a case.
pub fn render<T: InputScalar>(
    case: &Case<T>,
    out: &[BodyOutput<T>; 2],
) -> Result<Value, CaseError> {
    let bodies = (0..2)
        .map(|i| {
            let field = |f: &str| format!("bodies[{i}].{f}");
            let mut body = Map::new();
            body.insert(
                "angular_velocity".into(),
                spin(
                    &case.bodies[i].spin,
                    &out[i],
                    case.dim,
                    &field("angular_velocity"),
                )?,
            );
            body.insert(
                "velocity".into(),
                numbers(&out[i].velocity, &field("velocity"))?,
            );
            Ok(Value::Object(body))
        })
        .collect::<Result<Vec<_>, CaseError>>()?;
    let mut case = Map::new();
    case.insert("bodies".into(), Value::Array(bodies));
    Ok(Value::Object(case))
}
