//! The ball-ball contact law of each pair of species (a scene's `[[contact.pair]]`): a
//! `species x species` table built once from the scene, looked up by the two balls' species
//! indices at each contact (no allocation, no name), [`crate::Table::ball_law`].

use crate::law::ContactKind;

/// The law of species pair `(a, b)` at `laws[a * species + b]`, symmetric; empty (the
/// default): no pair has a law of its own, and every ball-ball contact takes
/// [`crate::Table::ball_contact`].
#[derive(Clone, Debug, PartialEq, Default)]
pub struct SpeciesLaws {
    species: usize,
    laws: Vec<ContactKind>,
}

impl SpeciesLaws {
    /// The table of `species` species with `law(a, b)` for each pair (`law` is asked for
    /// `a <= b` only and the table filled symmetrically).
    pub fn new(species: usize, law: impl Fn(usize, usize) -> ContactKind) -> Self {
        let mut laws = vec![ContactKind::default(); species * species];
        for a in 0..species {
            for b in a..species {
                let k = law(a, b);
                laws[a * species + b] = k;
                laws[b * species + a] = k;
            }
        }
        SpeciesLaws { species, laws }
    }

    /// The law of species `a` and `b` (either order); `None` when the table is empty or
    /// does not hold them.
    #[inline]
    pub fn get(&self, a: usize, b: usize) -> Option<ContactKind> {
        if a >= self.species || b >= self.species {
            return None;
        }
        self.laws.get(a * self.species + b).copied()
    }

    /// Whether no pair has a law here.
    pub fn is_empty(&self) -> bool {
        self.laws.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::{ContactKind, SpeciesLaws};

    #[test]
    fn the_table_is_symmetric_and_empty_by_default() {
        let rough = ContactKind::Rough { e: 0.5, beta: 0.25 };
        let t = SpeciesLaws::new(3, |a, b| {
            if (a, b) == (0, 2) {
                rough
            } else {
                ContactKind::Smooth
            }
        });
        assert_eq!(t.get(0, 2), Some(rough));
        assert_eq!(t.get(2, 0), Some(rough));
        assert_eq!(t.get(1, 1), Some(ContactKind::Smooth));
        assert_eq!(t.get(3, 0), None);
        assert_eq!(SpeciesLaws::default().get(0, 0), None);
        assert!(SpeciesLaws::default().is_empty());
    }
}
