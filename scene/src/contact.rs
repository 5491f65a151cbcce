//! The contact law of a scene's contacts: `contact = "no-slip"`, `"smooth"`, or the rough-ball
//! law `contact = { e = ..., beta = ... }` (`docs/derivation.md` §15): at contact the normal
//! relative velocity of the contact point becomes `-e` times itself and its tangential part
//! `-beta` times itself, `0 <= e <= 1`, `-1 <= beta <= 1`. `(1, 1)` is the no-slip law and
//! `(1, -1)` the smooth one; validation ([`ContactKind::checked`]) turns those two into
//! [`ContactKind::NoSlip`] and [`ContactKind::Smooth`], so that an elastic member runs the
//! very path (and gives the very bits) of the named kind.

use crate::number::Number;
use num_rational::BigRational;
use num_traits::{One, Signed};
use serde::de::{self, Deserializer, MapAccess, Visitor};
use serde::Deserialize;
use std::fmt;

/// How a ball and what it meets exchange momentum at a contact.
#[derive(Clone, Debug, PartialEq, Default)]
pub enum ContactKind {
    /// `"no-slip"`: the no-slip map (the generated kernels); the default.
    #[default]
    NoSlip,
    /// `"smooth"`: specular, spins untouched (`u' = u - 2 (u . nu) nu` on an immovable
    /// body; the elastic smooth-sphere map between balls).
    Smooth,
    /// `{ e = ..., beta = ... }`: the rough-ball law with normal restitution `e` in `[0, 1]`
    /// and tangential restitution `beta` in `[-1, 1]`, exact. After validation never
    /// `(1, 1)` nor `(1, -1)` (those are [`ContactKind::NoSlip`], [`ContactKind::Smooth`]).
    Rough {
        /// `e`: `dn+ = -e dn`.
        e: BigRational,
        /// `beta`: `t+ = -beta t`.
        beta: BigRational,
    },
}

impl ContactKind {
    /// The kind with its numbers checked (`e` in `[0, 1]`, `beta` in `[-1, 1]`; an error
    /// names `place.e` or `place.beta`) and its elastic members named: `(1, 1)` is
    /// [`ContactKind::NoSlip`], `(1, -1)` [`ContactKind::Smooth`].
    pub fn checked(&self, place: &str) -> Result<ContactKind, (String, String)> {
        let ContactKind::Rough { e, beta } = self else {
            return Ok(self.clone());
        };
        let one = BigRational::one();
        if e.is_negative() || e > &one {
            return Err((format!("{place}.e"), format!("must be in [0, 1], got {e}")));
        }
        if beta.abs() > one {
            return Err((
                format!("{place}.beta"),
                format!("must be in [-1, 1], got {beta}"),
            ));
        }
        Ok(match (e == &one, beta.abs() == one) {
            (true, true) if beta.is_positive() => ContactKind::NoSlip,
            (true, true) => ContactKind::Smooth,
            _ => self.clone(),
        })
    }

    /// Whether the law has a tangential part: every kind but [`ContactKind::Smooth`] and the
    /// rough law with `beta = -1` (whose tangential impulse is 0).
    pub fn tangential(&self) -> bool {
        match self {
            ContactKind::NoSlip => true,
            ContactKind::Smooth => false,
            ContactKind::Rough { beta, .. } => beta != &-BigRational::one(),
        }
    }
}

/// The rough law's table as written: `e` and `beta`, nothing else.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRough {
    e: Number,
    beta: Number,
}

struct KindVisitor;

impl<'de> Visitor<'de> for KindVisitor {
    type Value = ContactKind;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(r#""no-slip", "smooth" or a table { e = ..., beta = ... }"#)
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<ContactKind, E> {
        match v {
            "no-slip" => Ok(ContactKind::NoSlip),
            "smooth" => Ok(ContactKind::Smooth),
            _ => Err(E::custom(format!(
                r#"unknown contact kind {v:?}: expected "no-slip", "smooth" or a table {{ e = ..., beta = ... }}"#
            ))),
        }
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<ContactKind, A::Error> {
        let raw = RawRough::deserialize(de::value::MapAccessDeserializer::new(map))?;
        Ok(ContactKind::Rough {
            e: raw.e.0,
            beta: raw.beta.0,
        })
    }
}

impl<'de> Deserialize<'de> for ContactKind {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<ContactKind, D::Error> {
        d.deserialize_any(KindVisitor)
    }
}

#[cfg(test)]
mod tests {
    use super::ContactKind;
    use num_rational::BigRational;

    fn q(p: i64, d: i64) -> BigRational {
        BigRational::new(p.into(), d.into())
    }

    fn rough(e: BigRational, beta: BigRational) -> ContactKind {
        ContactKind::Rough { e, beta }
    }

    #[test]
    fn the_elastic_members_are_named() {
        let checked = |e, beta| rough(e, beta).checked("contact.balls").unwrap();
        assert_eq!(checked(q(1, 1), q(1, 1)), ContactKind::NoSlip);
        assert_eq!(checked(q(1, 1), q(-1, 1)), ContactKind::Smooth);
        assert_eq!(checked(q(9, 10), q(1, 1)), rough(q(9, 10), q(1, 1)));
        assert_eq!(checked(q(1, 1), q(0, 1)), rough(q(1, 1), q(0, 1)));
    }

    #[test]
    fn out_of_range_numbers_are_named() {
        let err = |e, beta| rough(e, beta).checked("wall[2].contact").unwrap_err();
        assert_eq!(err(q(3, 2), q(0, 1)).0, "wall[2].contact.e");
        assert_eq!(err(q(-1, 10), q(0, 1)).0, "wall[2].contact.e");
        assert_eq!(err(q(1, 2), q(-11, 10)).0, "wall[2].contact.beta");
        assert_eq!(err(q(1, 2), q(11, 10)).0, "wall[2].contact.beta");
        assert!(err(q(3, 2), q(0, 1)).1.contains("[0, 1], got 3/2"));
    }

    #[test]
    fn only_smooth_laws_lack_a_tangential_part() {
        assert!(ContactKind::NoSlip.tangential());
        assert!(!ContactKind::Smooth.tangential());
        assert!(!rough(q(1, 2), q(-1, 1)).tangential());
        assert!(rough(q(1, 2), q(-99, 100)).tangential());
    }
}
