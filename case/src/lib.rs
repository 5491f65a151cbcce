//! # noslip-case
//!
//! The JSON case format of `noslip collide` (and of the Python package's `noslip.collide`):
//! reading cases, validating them with messages that name the field, running the collision,
//! printing the result. One place for both front ends, so they cannot disagree on what a
//! case means.
//!
//! - [`number`]: the number formats (decimals, rationals) and how `f64` and exact
//!   rationals read and print them.
//! - [`case`]: the input schema of a case; [`contact`]: its optional contact law.
//! - [`keys`]: keys given twice (which `serde_json::Value` would drop silently).
//! - [`node`]: what reading a case needs of a JSON value; [`text`]: the fast path, one pass
//!   from the text into a borrowed tree (serde_json's `Value` reads whatever it does not).
//! - [`solve`]: validation with readable messages, and the dispatch over `dim` to the
//!   generated kernels (2..=6) or the general-n reference.
//! - [`output`]: the output schema.
//! - [`collide`]: a whole input (one case or an array), in and out.
//! - `direct` (with `plain` and `fraction`): `--exact` on a plain case straight from the text,
//!   checked on machine integers (the general path for everything else).
//! - [`error`]: the one-line error of a case, naming the field.

#![warn(missing_docs, unreachable_pub)]

mod body;
pub mod case;
pub mod collide;
pub mod contact;
mod direct;
pub mod error;
mod fraction;
pub mod keys;
pub mod node;
pub mod number;
pub mod output;
mod plain;
mod short;
pub mod solve;
pub mod text;
mod tiny;

pub use collide::{collide_json, Mode, RunError};
pub use error::CaseError;
