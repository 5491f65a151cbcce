//! A ball-ball contact law per unordered pair of species (`[[contact.pair]]`): the pairs a
//! scene lists take their own law, every other pair `contact.balls` (so a scene without
//! pairs means what it meant before they existed).
//!
//! ```toml
//! [[contact.pair]]
//! species = ["grain", "tracer"]      # two species, by name or by index (either order)
//! law = { e = "0.8", beta = "0.3" }  # as contact.balls: "no-slip", "smooth", { e, beta }, { e, mu, beta0 }
//! ```
//!
//! The law is a key of its own (`law`, not `e` and `beta` beside `species`) so that it takes
//! exactly the forms, and the reader, of every other contact law of the format
//! ([`ContactKind`]): a bad one is named `contact.pair[1].law.e`. Validation
//! (`pair_laws`) refuses a pair that does not name two species, an unknown species (or a
//! name two species share), and a pair listed twice in either order.

use crate::ctx::Ctx;
use crate::{ContactKind, SceneError, Species};
use serde::de::{self, Deserializer, Visitor};
use serde::Deserialize;
use std::fmt;

/// A `[[contact.pair]]` table as written.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct RawPair {
    /// `species`: the two species, by name or index.
    pub species: Vec<SpeciesRef>,
    /// `law`: the pair's contact law, in the forms of `contact.balls`.
    pub law: ContactKind,
}

/// A species named in a scene file: by its `name` or by its index in `[[species]]`.
#[derive(Clone, Debug, PartialEq)]
pub enum SpeciesRef {
    /// `"grain"`: the species of that name (`species<i>` when the file gives none).
    Name(String),
    /// `1`: `species[1]`.
    Index(u64),
}

struct SpeciesRefVisitor;

impl Visitor<'_> for SpeciesRefVisitor {
    type Value = SpeciesRef;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a species' name or its index (from 0)")
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<SpeciesRef, E> {
        Ok(SpeciesRef::Name(v.to_string()))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<SpeciesRef, E> {
        u64::try_from(v)
            .map(SpeciesRef::Index)
            .map_err(|_| E::custom(format!("a species index is >= 0, got {v}")))
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<SpeciesRef, E> {
        Ok(SpeciesRef::Index(v))
    }
}

impl<'de> Deserialize<'de> for SpeciesRef {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<SpeciesRef, D::Error> {
        d.deserialize_any(SpeciesRefVisitor)
    }
}

/// A validated `[[contact.pair]]`: the species indices `a <= b` and their checked law.
#[derive(Clone, Debug, PartialEq)]
pub struct PairContact {
    /// The two species, `species[0] <= species[1]` (indices into [`crate::Scene::species`]).
    pub species: [usize; 2],
    /// The pair's law, checked and its elastic members named ([`ContactKind::checked`]).
    pub contact: ContactKind,
}

/// The species `r` (at `place`) refers to.
fn resolve(
    ctx: &Ctx,
    place: &str,
    r: &SpeciesRef,
    species: &[Species],
) -> Result<usize, SceneError> {
    let names = || {
        species
            .iter()
            .map(|s| format!("{:?}", s.name))
            .collect::<Vec<_>>()
            .join(", ")
    };
    match r {
        SpeciesRef::Index(i) => usize::try_from(*i)
            .ok()
            .filter(|&i| i < species.len())
            .ok_or_else(|| {
                ctx.err(
                    place,
                    format!(
                        "no species {i} (the scene has {}, numbered from 0)",
                        species.len()
                    ),
                )
            }),
        SpeciesRef::Name(name) => {
            let found: Vec<usize> = (0..species.len())
                .filter(|&k| &species[k].name == name)
                .collect();
            match found[..] {
                [k] => Ok(k),
                [] => Err(ctx.err(
                    place,
                    format!("no species named {name:?} (the scene has {})", names()),
                )),
                [first, second, ..] => Err(ctx.err(
                    place,
                    format!(
                        "species[{first}] and species[{second}] are both named {name:?}: \
                         name the species by index"
                    ),
                )),
            }
        }
    }
}

/// The scene's `[[contact.pair]]` tables validated: each names two species (by name or
/// index), no unordered pair twice, each law checked at `contact.pair[i].law`.
pub(crate) fn pair_laws(
    ctx: &Ctx,
    raw: &[RawPair],
    species: &[Species],
) -> Result<Vec<PairContact>, SceneError> {
    let mut pairs: Vec<PairContact> = Vec::with_capacity(raw.len());
    for (i, p) in raw.iter().enumerate() {
        let at = format!("contact.pair[{i}]");
        let [x, y] = &p.species[..] else {
            return Err(ctx.err(
                format!("{at}.species"),
                format!(
                    "lists {} species, expected two (a species with itself: the name twice)",
                    p.species.len()
                ),
            ));
        };
        let a = resolve(ctx, &format!("{at}.species[0]"), x, species)?;
        let b = resolve(ctx, &format!("{at}.species[1]"), y, species)?;
        let key = [a.min(b), a.max(b)];
        if let Some(k) = pairs.iter().position(|q| q.species == key) {
            return Err(ctx.err(
                format!("{at}.species"),
                format!(
                    "the pair ({:?}, {:?}) is listed twice: also at contact.pair[{k}] \
                     (a pair is unordered)",
                    species[key[0]].name, species[key[1]].name
                ),
            ));
        }
        let contact = ctx.contact(&format!("{at}.law"), &p.law)?;
        pairs.push(PairContact {
            species: key,
            contact,
        });
    }
    Ok(pairs)
}
