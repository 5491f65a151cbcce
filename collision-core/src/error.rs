//! Typed input errors that name the offending field, by its place in this crate's API (a
//! front end with a format of its own, such as the `noslip` command's JSON cases, maps
//! [`Field`] to its own names).

use std::fmt;

/// A field of one body.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum BodyField {
    /// The mass `m` (or the inverse mass `w = 1/m` of a [`Ball`](crate::Ball)).
    Mass,
    /// The radius `R`.
    Radius,
    /// The inertia parameter `lambda`, in `[0, R^2/n]`.
    Lambda,
    /// `gamma^2 = 2 lambda / R^2`, in `[0, 2/n]`.
    Gamma2,
    /// The named mass distribution (uniform or shell).
    Distribution,
    /// The angular velocity `U` (skew).
    AngularVelocity,
    /// The centre velocity `u`.
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
    /// The dimension `n`.
    Dim,
    /// The contact normal `nu` (unit, from body 1 to body 2).
    Normal,
    /// A field of body `i` (0-based: body 1 is `Body(0, ..)`).
    Body(usize, BodyField),
    /// Both bodies together (both immovable, both point masses).
    Bodies,
    /// The relative velocity of the bodies (separating).
    RelativeVelocity,
    /// The normal restitution `e` of the rough law ([`crate::Restitution`]).
    RestitutionE,
    /// The tangential restitution `beta` of the rough law ([`crate::Restitution`]).
    RestitutionBeta,
    /// The friction coefficient `mu` of the Walton law ([`crate::Walton`]).
    FrictionMu,
    /// The sticking tangential restitution `beta0` of the Walton law ([`crate::Walton`]).
    WaltonBeta0,
}

impl fmt::Display for Field {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Field::Dim => f.write_str("dim"),
            Field::Normal => f.write_str("nu"),
            Field::Body(i, field) => write!(f, "body {} {}", i + 1, field.name()),
            Field::Bodies => f.write_str("both bodies"),
            Field::RelativeVelocity => f.write_str("relative velocity"),
            Field::RestitutionE => f.write_str("restitution e"),
            Field::RestitutionBeta => f.write_str("restitution beta"),
            Field::FrictionMu => f.write_str("friction mu"),
            Field::WaltonBeta0 => f.write_str("restitution beta0"),
        }
    }
}

/// Invalid input to a checked operation: which field, and what is wrong with it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct InputError {
    /// Where the error is.
    pub field: Field,
    /// What is wrong with it (displayed after the field: `field: message`).
    pub message: String,
}

impl InputError {
    /// The error `message` about `field`.
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
