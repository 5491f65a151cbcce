//! Where validation is: the scene file's origin, errors that name their place in it, and the
//! field readers every part of validation shares.

use crate::number::show_q;
use crate::raw::ContactKind;
use crate::{Number, SceneError};
use num_rational::BigRational;
use num_traits::Signed;

type Q = BigRational;

/// The scene file being validated, for errors that name their place in it.
pub(crate) struct Ctx<'a> {
    pub(crate) origin: &'a str,
}

impl Ctx<'_> {
    /// The error `origin: place: message`.
    pub(crate) fn err(&self, place: impl Into<String>, message: impl Into<String>) -> SceneError {
        SceneError {
            origin: self.origin.to_string(),
            place: place.into(),
            message: message.into(),
        }
    }

    /// The vector at `place`, which must have `dim` components.
    pub(crate) fn vector(
        &self,
        place: &str,
        v: &[Number],
        dim: usize,
    ) -> Result<Vec<Q>, SceneError> {
        if v.len() != dim {
            return Err(self.err(
                place,
                format!("has {} components, expected dim = {dim}", v.len()),
            ));
        }
        Ok(v.iter().map(|x| x.0.clone()).collect())
    }

    /// The contact kind at `place`, checked and its elastic members named
    /// ([`ContactKind::checked`]).
    pub(crate) fn contact(
        &self,
        place: &str,
        kind: &ContactKind,
    ) -> Result<ContactKind, SceneError> {
        kind.checked(place)
            .map_err(|(at, message)| self.err(at, message))
    }

    pub(crate) fn positive(&self, place: &str, x: &Number) -> Result<Q, SceneError> {
        if !x.0.is_positive() {
            return Err(self.err(place, format!("must be positive, got {}", show_q(&x.0))));
        }
        Ok(x.0.clone())
    }
}
