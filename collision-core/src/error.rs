//! Typed input errors that name the offending field, by its place in this crate's API (a
//! front end with a format of its own, such as the `noslip` command's JSON cases, maps
//! [`Field`] to its own names).

use std::fmt;

/// A field of one body.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum BodyField {
    Mass,
    Radius,
    Lambda,
    Gamma2,
    Distribution,
    AngularVelocity,
    Velocity,
}

impl BodyField {
    /// The field's name in this crate: the parameter of [`crate::Ball::new`] or the field
    /// of [`crate::Ball`] and [`crate::BodyState`] it is.
    pub fn name(self) -> &'static str {
        match self {
            BodyField::Mass => "mass",
            BodyField::Radius => "radius",
            BodyField::Lambda => "lambda",
            BodyField::Gamma2 => "gamma2",
            BodyField::Distribution => "inertia",
            BodyField::AngularVelocity => "spin",
            BodyField::Velocity => "velocity",
        }
    }
}

/// Where an input error is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Field {
    Dim,
    Normal,
    /// A field of body `i` (0-based: body 1 is `Body(0, ..)`).
    Body(usize, BodyField),
    /// Both bodies together (both immovable, both point masses).
    Bodies,
    /// The relative velocity of the bodies (separating).
    RelativeVelocity,
}

impl fmt::Display for Field {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Field::Dim => f.write_str("dim"),
            Field::Normal => f.write_str("nu"),
            Field::Body(i, field) => write!(f, "body {} {}", i + 1, field.name()),
            Field::Bodies => f.write_str("both bodies"),
            Field::RelativeVelocity => f.write_str("relative velocity"),
        }
    }
}

/// Invalid input to a checked operation: which field, and what is wrong with it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct InputError {
    pub field: Field,
    pub message: String,
}

impl InputError {
    pub fn new(field: Field, message: impl Into<String>) -> Self {
        Self {
            field,
            message: message.into(),
        }
    }

    /// The same error about body `index` (for errors raised before the index was known).
    pub fn at_body(mut self, index: usize) -> Self {
        if let Field::Body(_, f) = self.field {
            self.field = Field::Body(index, f);
        }
        self
    }
}

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.field, self.message)
    }
}

impl std::error::Error for InputError {}
