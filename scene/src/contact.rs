//! The contact law of a scene's contacts: `contact = "no-slip"`, `"smooth"`, or the rough-ball
//! law `contact = { e = ..., beta = ... }` (`docs/derivation.md` §15): at contact the normal
//! relative velocity of the contact point becomes `-e` times itself and its tangential part
//! `-beta` times itself, `0 <= e <= 1`, `-1 <= beta <= 1`. `(1, 1)` is the no-slip law and
//! `(1, -1)` the smooth one; validation ([`ContactKind::checked`]) turns those two into
//! [`ContactKind::NoSlip`] and [`ContactKind::Smooth`], so that an elastic member runs the
//! very path (and gives the very bits) of the named kind. The Walton law
//! `contact = { e = ..., mu = ..., beta0 = ... }` (§15.1) takes `beta = min(beta0, beta_C)`,
//! `beta_C` the restitution at which the tangential impulse is `mu` times the normal one:
//! `mu >= 0`, `beta0` in `[-1, 1]`. With `mu = 0` or `beta0 = -1` its `beta` is `-1` at every
//! contact, and validation names it the rough law `{ e, beta = -1 }` (smooth at `e = 1`).

use crate::number::{show_q, Number};
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
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
    /// `{ e = ..., mu = ..., beta0 = ... }`: the Walton law, exact; after validation
    /// `mu > 0` and `beta0 > -1` (else it is the rough law `{ e, beta = -1 }`).
    Walton {
        /// `e`: `dn+ = -e dn`.
        e: BigRational,
        /// `mu`: the friction coefficient, `|J_t| <= mu |J_n|`.
        mu: BigRational,
        /// `beta0`: `t+ = -beta0 t` while the contact sticks.
        beta0: BigRational,
    },
}

impl ContactKind {
    /// The kind with its numbers checked (`e` in `[0, 1]`, `beta` and `beta0` in `[-1, 1]`,
    /// `mu >= 0`; an error names `place.e`, `place.beta`, `place.mu` or `place.beta0`) and its
    /// special members named: rough `(1, 1)` is [`ContactKind::NoSlip`], `(1, -1)`
    /// [`ContactKind::Smooth`]; a Walton law with `mu = 0` or `beta0 = -1` is the rough law
    /// `{ e, beta = -1 }`.
    pub fn checked(&self, place: &str) -> Result<ContactKind, (String, String)> {
        let one = BigRational::one();
        let outside = |key: &str, x: &BigRational, range: &str| {
            Err((
                format!("{place}.{key}"),
                format!("must be {range}, got {}", show_q(x)),
            ))
        };
        match self {
            ContactKind::NoSlip | ContactKind::Smooth => Ok(self.clone()),
            ContactKind::Walton { e, mu, beta0 } => {
                if mu.is_negative() {
                    return outside("mu", mu, ">= 0");
                }
                if beta0.abs() > one {
                    return outside("beta0", beta0, "in [-1, 1]");
                }
                if e.is_negative() || e > &one {
                    return outside("e", e, "in [0, 1]");
                }
                if mu.is_zero() || beta0 == &-&one {
                    // beta = -1 at every contact: the rough law, named as such.
                    let rough = ContactKind::Rough {
                        e: e.clone(),
                        beta: -one,
                    };
                    return rough.checked(place);
                }
                Ok(self.clone())
            }
            ContactKind::Rough { e, beta } => {
                if e.is_negative() || e > &one {
                    return outside("e", e, "in [0, 1]");
                }
                if beta.abs() > one {
                    return outside("beta", beta, "in [-1, 1]");
                }
                Ok(match (e == &one, beta.abs() == one) {
                    (true, true) if beta.is_positive() => ContactKind::NoSlip,
                    (true, true) => ContactKind::Smooth,
                    _ => self.clone(),
                })
            }
        }
    }

    /// The normal restitution `e`: 1 for [`ContactKind::NoSlip`] and [`ContactKind::Smooth`].
    pub fn e(&self) -> BigRational {
        match self {
            ContactKind::NoSlip | ContactKind::Smooth => BigRational::one(),
            ContactKind::Rough { e, .. } | ContactKind::Walton { e, .. } => e.clone(),
        }
    }

    /// Whether the law has a tangential part: every kind but [`ContactKind::Smooth`] and the
    /// rough law with `beta = -1` (whose tangential impulse is 0).
    pub fn tangential(&self) -> bool {
        match self {
            ContactKind::NoSlip => true,
            ContactKind::Smooth => false,
            ContactKind::Rough { beta, .. } => beta != &-BigRational::one(),
            ContactKind::Walton { .. } => true,
        }
    }
}

/// A law's table as written: `e` and `beta` (rough), or `e`, `mu` and `beta0` (Walton).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRough {
    e: Number,
    beta: Option<Number>,
    mu: Option<Number>,
    beta0: Option<Number>,
}

struct KindVisitor;

impl<'de> Visitor<'de> for KindVisitor {
    type Value = ContactKind;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(
            r#""no-slip", "smooth", a table { e = ..., beta = ... } or { e = ..., mu = ..., beta0 = ... }"#,
        )
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<ContactKind, E> {
        match v {
            "no-slip" => Ok(ContactKind::NoSlip),
            "smooth" => Ok(ContactKind::Smooth),
            _ => Err(E::custom(format!(
                r#"unknown contact kind {v:?}: expected "no-slip", "smooth", a table {{ e = ..., beta = ... }} or {{ e = ..., mu = ..., beta0 = ... }}"#
            ))),
        }
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<ContactKind, A::Error> {
        let raw = RawRough::deserialize(de::value::MapAccessDeserializer::new(map))?;
        match (raw.beta, raw.mu, raw.beta0) {
            (Some(beta), None, None) => Ok(ContactKind::Rough {
                e: raw.e.0,
                beta: beta.0,
            }),
            (None, Some(mu), Some(beta0)) => Ok(ContactKind::Walton {
                e: raw.e.0,
                mu: mu.0,
                beta0: beta0.0,
            }),
            _ => Err(de::Error::custom(
                "a contact table is { e = ..., beta = ... } (rough) or { e = ..., mu = ..., beta0 = ... } (Walton)",
            )),
        }
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

    fn walton(e: BigRational, mu: BigRational, beta0: BigRational) -> ContactKind {
        ContactKind::Walton { e, mu, beta0 }
    }

    #[test]
    fn walton_laws_are_checked_and_their_frictionless_members_named() {
        let checked = |e, mu, beta0| walton(e, mu, beta0).checked("contact.balls");
        assert_eq!(
            checked(q(9, 10), q(1, 4), q(1, 2)).unwrap(),
            walton(q(9, 10), q(1, 4), q(1, 2))
        );
        // mu = 0 or beta0 = -1: beta = -1 at every contact.
        assert_eq!(
            checked(q(9, 10), q(0, 1), q(1, 2)).unwrap(),
            rough(q(9, 10), q(-1, 1))
        );
        assert_eq!(
            checked(q(1, 1), q(1, 4), q(-1, 1)).unwrap(),
            ContactKind::Smooth
        );
        let err = |e, mu, beta0| checked(e, mu, beta0).unwrap_err().0;
        assert_eq!(err(q(9, 10), q(-1, 4), q(1, 2)), "contact.balls.mu");
        assert_eq!(err(q(9, 10), q(1, 4), q(3, 2)), "contact.balls.beta0");
        assert_eq!(err(q(3, 2), q(1, 4), q(1, 2)), "contact.balls.e");
    }
}
