//! The error of one case: which field, and what is wrong with it.

use collision_core::{BodyField, Field, InputError};
use std::fmt;

/// An error in one case of the input, naming the field by its path in the case
/// (`dim`, `normal[2]`, `bodies[1].lambda`, ...). The message is one line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CaseError {
    /// The path of the field in the case; empty for the case as a whole.
    pub field: String,
    /// What is wrong, one line.
    pub message: String,
}

impl CaseError {
    /// The error `message` (kept on one line) about the field at path `field`.
    pub fn new(field: impl Into<String>, message: impl Into<String>) -> Self {
        Self {
            field: field.into(),
            message: one_line(message.into()),
        }
    }
}

impl From<InputError> for CaseError {
    fn from(e: InputError) -> Self {
        CaseError::new(path(e.field), e.message)
    }
}

/// The path in a case of a field of collision-core's inputs: the JSON schema's names.
pub fn path(field: Field) -> String {
    match field {
        Field::Dim => "dim".into(),
        Field::Normal => "normal".into(),
        Field::Body(i, f) => format!("bodies[{i}].{}", key(f)),
        Field::Bodies => "bodies".into(),
        Field::RelativeVelocity => "bodies[*].velocity".into(),
        Field::RestitutionE => "contact.e".into(),
        Field::RestitutionBeta => "contact.beta".into(),
        Field::FrictionMu => "contact.mu".into(),
        Field::WaltonBeta0 => "contact.beta0".into(),
        _ => field.to_string(),
    }
}

/// The key of a body's field in a case.
fn key(field: BodyField) -> &'static str {
    match field {
        BodyField::Mass => "mass",
        BodyField::Radius => "radius",
        BodyField::Lambda => "lambda",
        BodyField::Gamma2 => "gamma2",
        BodyField::Distribution => "distribution",
        BodyField::AngularVelocity => "angular_velocity",
        BodyField::Velocity => "velocity",
        _ => field.name(),
    }
}

impl fmt::Display for CaseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.field.is_empty() {
            f.write_str(&self.message)
        } else {
            write!(f, "{}: {}", self.field, self.message)
        }
    }
}

impl std::error::Error for CaseError {}

/// Replace line breaks so that a message stays on one line.
fn one_line(s: String) -> String {
    if s.contains(['\n', '\r']) {
        s.replace(['\n', '\r'], " ")
    } else {
        s
    }
}

/// `text` quoted for a message: escaped (no line breaks) and cut to `max` characters.
pub fn quote(text: &str, max: usize) -> String {
    let (head, cut) = split(text, max);
    format!("{head:?}{}", if cut { "..." } else { "" })
}

/// `text` cut to `max` characters, for text known to be one plain line (a number literal).
pub fn clip(text: &str, max: usize) -> String {
    let (head, cut) = split(text, max);
    format!("{head}{}", if cut { "..." } else { "" })
}

fn split(text: &str, max: usize) -> (&str, bool) {
    match text.char_indices().nth(max) {
        Some((k, _)) => (&text[..k], true),
        None => (text, false),
    }
}

/// The JSON type of a value, for messages.
pub fn kind(v: &serde_json::Value) -> &'static str {
    match v {
        serde_json::Value::Null => "null",
        serde_json::Value::Bool(_) => "a boolean",
        serde_json::Value::Number(_) => "a number",
        serde_json::Value::String(_) => "a string",
        serde_json::Value::Array(_) => "an array",
        serde_json::Value::Object(_) => "an object",
    }
}

/// `path.key`, the key quoted unless it is plain (letters, digits, `_`).
pub(crate) fn join(path: &str, key: &str) -> String {
    let simple = !key.is_empty() && key.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    let key = if simple {
        key.to_string()
    } else {
        quote(key, 40)
    };
    if path.is_empty() {
        key
    } else {
        format!("{path}.{key}")
    }
}
