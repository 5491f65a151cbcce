//! The optional contact law of a case, key `contact` (docs/derivation.md §15):
//!
//! ```json
//! "contact": "no-slip"                        (the default: the no-slip map)
//! "contact": "smooth"                         (specular: (e, beta) = (1, -1))
//! "contact": {"e": "9/10", "beta": "1/2"}     (the rough-ball law)
//! ```
//!
//! `e` is the normal restitution (`dn+ = -e dn`, in `[0, 1]`), `beta` the tangential one
//! (`t+ = -beta t`, in `[-1, 1]`); both are required in the object form. Their ranges are
//! checked by collision-core (`Restitution::new`), whose error names `contact.e` or
//! `contact.beta`.

use crate::error::join;
use crate::error::{kind, quote, CaseError};
use crate::number::{scalar_from_json, InputScalar};
use collision_core::Restitution;
use serde_json::Value;

/// The keys of the object form.
pub const CONTACT_KEYS: [&str; 2] = ["e", "beta"];

/// A case's contact law.
#[derive(Clone, Debug, PartialEq)]
pub enum Contact<T> {
    /// The no-slip map (the generated `free`/`fixed` kernels), the default.
    NoSlip,
    /// The rough-ball law `(e, beta)` (the kernels `rough::free`/`rough::fixed`); `"smooth"`
    /// is `(1, -1)`.
    Rough(Restitution<T>),
}

/// Read `contact` (absent: [`Contact::NoSlip`]). Numbers are read as every other number of
/// the case (`floats` as in `Case::from_floats`); ranges are checked when the case runs.
pub fn contact_from_json<T: InputScalar>(
    value: Option<&Value>,
    floats: bool,
) -> Result<Contact<T>, CaseError> {
    let Some(value) = value else {
        return Ok(Contact::NoSlip);
    };
    let forms = "\"no-slip\", \"smooth\" or an object {\"e\": .., \"beta\": ..}";
    match value {
        Value::String(s) if s == "no-slip" => Ok(Contact::NoSlip),
        Value::String(s) if s == "smooth" => Ok(Contact::Rough(Restitution::smooth())),
        Value::Object(obj) => {
            if let Some(k) = obj.keys().find(|k| !CONTACT_KEYS.contains(&k.as_str())) {
                return Err(CaseError::new(
                    join("contact", k),
                    format!("unknown key (the keys are: {})", CONTACT_KEYS.join(", ")),
                ));
            }
            let read = |key: &str| -> Result<T, CaseError> {
                let field = join("contact", key);
                let x = obj.get(key).ok_or_else(|| {
                    CaseError::new(field.as_str(), "missing (required in the object form)")
                })?;
                scalar_from_json::<T>(x, &field, floats)
            };
            Ok(Contact::Rough(Restitution {
                e: read("e")?,
                beta: read("beta")?,
            }))
        }
        Value::String(s) => Err(CaseError::new(
            "contact",
            format!("expected {forms}, got {}", quote(s, 40)),
        )),
        other => Err(CaseError::new(
            "contact",
            format!("expected {forms}, got {}", kind(other)),
        )),
    }
}
