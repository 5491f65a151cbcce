//! The optional contact law of a case, key `contact` (docs/derivation.md §15):
//!
//! ```json
//! "contact": "no-slip"                        (the default: the no-slip map)
//! "contact": "smooth"                         (specular: (e, beta) = (1, -1))
//! "contact": {"e": "9/10", "beta": "1/2"}     (the rough-ball law)
//! "contact": {"e": "9/10", "mu": "1/4", "beta0": "1/2"}   (the Walton law, §15.1)
//! ```
//!
//! `e` is the normal restitution (`dn+ = -e dn`, in `[0, 1]`), `beta` the tangential one
//! (`t+ = -beta t`, in `[-1, 1]`); both are required in the rough form (chosen by `beta`).
//! The Walton form (chosen by `mu` or `beta0` without `beta`) takes `beta = min(beta0, beta_C)`, `beta_C` the restitution
//! of sliding at the Coulomb bound `|J_t| = mu |J_n|`; `e`, `mu >= 0` and `beta0` in `[-1, 1]`
//! are all required. The ranges are checked by collision-core (`Restitution::new`,
//! `Walton::new`), whose error names `contact.e`, `contact.beta`, `contact.mu` or
//! `contact.beta0`.

use crate::error::join;
use crate::error::{quote, CaseError};
use crate::node::{Members, Node};
use crate::number::{scalar_from_json, InputScalar};
use collision_core::{Restitution, Walton};

/// The keys of the rough-ball object form.
pub const CONTACT_KEYS: [&str; 2] = ["e", "beta"];

/// The keys of the Walton object form (chosen by `mu` or `beta0`).
pub const WALTON_KEYS: [&str; 3] = ["e", "mu", "beta0"];

/// A case's contact law.
#[derive(Clone, Debug, PartialEq)]
pub enum Contact<T> {
    /// The no-slip map (the generated `free`/`fixed` kernels), the default.
    NoSlip,
    /// The rough-ball law `(e, beta)` (the kernels `rough::free`/`rough::fixed`); `"smooth"`
    /// is `(1, -1)`.
    Rough(Restitution<T>),
    /// The Walton law `(e, mu, beta0)` (the kernels `walton::free`/`walton::fixed`).
    Walton(Walton<T>),
}

/// Read `contact` (absent: [`Contact::NoSlip`]). Numbers are read as every other number of
/// the case (`floats` as in `Case::from_floats`); ranges are checked when the case runs.
pub fn contact_from_json<T: InputScalar, V: Node>(
    value: Option<&V>,
    floats: bool,
) -> Result<Contact<T>, CaseError> {
    let Some(value) = value else {
        return Ok(Contact::NoSlip);
    };
    let forms = "\"no-slip\", \"smooth\" or an object {\"e\": .., \"beta\": ..} or {\"e\": .., \"mu\": .., \"beta0\": ..}";
    if let Some(obj) = value.as_object() {
        // `beta` means the rough form; otherwise `mu` or `beta0` the Walton form.
        let walton =
            !obj.contains_key("beta") && (obj.contains_key("mu") || obj.contains_key("beta0"));
        let (keys, form): (&[&str], &str) = if walton {
            (&WALTON_KEYS, "the Walton form")
        } else {
            (&CONTACT_KEYS, "the rough form")
        };
        if let Some(k) = obj.unknown_key(keys) {
            return Err(CaseError::new(
                join("contact", k),
                format!(
                    "unknown key (the keys of {form} are: {}; of the {}: {})",
                    keys.join(", "),
                    if walton { "rough form" } else { "Walton form" },
                    if walton {
                        CONTACT_KEYS.join(", ")
                    } else {
                        WALTON_KEYS.join(", ")
                    },
                ),
            ));
        }
        let read = |key: &str| -> Result<T, CaseError> {
            let field = join("contact", key);
            let x = obj.get(key).ok_or_else(|| {
                CaseError::new(field.as_str(), format!("missing (required in {form})"))
            })?;
            scalar_from_json::<T, V>(x, &field, floats)
        };
        if walton {
            return Ok(Contact::Walton(Walton {
                e: read("e")?,
                mu: read("mu")?,
                beta0: read("beta0")?,
            }));
        }
        return Ok(Contact::Rough(Restitution {
            e: read("e")?,
            beta: read("beta")?,
        }));
    }
    match value.as_str() {
        Some("no-slip") => Ok(Contact::NoSlip),
        Some("smooth") => Ok(Contact::Rough(Restitution::smooth())),
        Some(s) => Err(CaseError::new(
            "contact",
            format!("expected {forms}, got {}", quote(s, 40)),
        )),
        None => Err(CaseError::new(
            "contact",
            format!("expected {forms}, got {}", value.kind()),
        )),
    }
}
