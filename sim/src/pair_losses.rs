//! The energy lost and the contacts counted per unordered pair of species, for the
//! observables of a mixture ([`crate::granular::Sampler`], docs/granular.md): with a contact
//! law per pair of species (`[[contact.pair]]`), `lost_ball_ball` splits as
//!
//! ```text
//! lost_ball_ball = sum over the pairs a <= b of lost_ball_ball_{a}-{b},
//! lost_ball_ball_{a}-{b} = sum over the ball-ball contacts of a ball of a with one of b of
//!                          (E_i + E_j before) - (E_i + E_j after),
//! ```
//!
//! each contact's loss [`crate::granular::lost`], the very number added to `lost_ball_ball`,
//! accumulated per pair in contact order (the pairs' columns add up to the total to rounding,
//! not to the bit: the total is one running sum, each pair another). `contacts_{a}-{b}` counts
//! the pair's contacts. The pairs come in the order `(0, 0), (0, 1), ..., (0, K-1), (1, 1),
//! ...`, `K` species: pair `(a, b)` is number `a K - a (a - 1) / 2 + b - a`.

/// The per-pair losses and contact counts of a run with `species` species.
#[derive(Clone, Debug, PartialEq)]
pub struct PairLosses {
    species: usize,
    /// Energy lost so far at the contacts of each pair.
    pub lost: Vec<f64>,
    /// Contacts so far of each pair.
    pub contacts: Vec<u64>,
}

impl PairLosses {
    /// Nothing lost yet, for `species` species (`K (K + 1) / 2` pairs).
    pub fn new(species: usize) -> PairLosses {
        let pairs = species * (species + 1) / 2;
        PairLosses {
            species,
            lost: vec![0.0; pairs],
            contacts: vec![0; pairs],
        }
    }

    /// The number of the unordered pair `{a, b}` (either order) in the pairs' order.
    pub fn pair(&self, a: usize, b: usize) -> usize {
        let (a, b) = (a.min(b), a.max(b));
        a * self.species - a * a.saturating_sub(1) / 2 + b - a
    }

    /// Accounts a contact of a ball of species `a` with one of `b` that lost `loss`.
    pub fn add(&mut self, a: usize, b: usize, loss: f64) {
        let p = self.pair(a, b);
        self.lost[p] += loss;
        self.contacts[p] += 1;
    }
}

/// The names of the `K (K + 1) / 2` pairs of species in the pairs' order, `A-B` from the
/// species' names: the names themselves when each is a non-empty run of ASCII letters, digits
/// and `_` and no two are equal (so that `-` separates them unambiguously and every column has
/// a name of its own), else `species<i>` for every species (the scene's own name of an unnamed
/// species).
pub fn pair_names(names: &[String]) -> Vec<String> {
    let plain =
        |s: &String| !s.is_empty() && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    let distinct = names
        .iter()
        .enumerate()
        .all(|(i, a)| names[..i].iter().all(|b| b != a));
    let names: Vec<String> = if names.iter().all(plain) && distinct {
        names.to_vec()
    } else {
        (0..names.len()).map(|i| format!("species{i}")).collect()
    };
    let mut out = Vec::new();
    for a in 0..names.len() {
        for b in a..names.len() {
            out.push(format!("{}-{}", names[a], names[b]));
        }
    }
    out
}

/// Whether the observables' column `name` is a count (written as an integer: `contacts` and
/// the pairs' `contacts_{a}-{b}`), not a double.
pub fn is_count(name: &str) -> bool {
    name == "contacts" || name.starts_with("contacts_")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pairs_are_numbered_in_order_either_way_round() {
        for k in 1..6 {
            let t = PairLosses::new(k);
            let mut next = 0;
            for a in 0..k {
                for b in a..k {
                    assert_eq!((t.pair(a, b), t.pair(b, a)), (next, next), "{k} {a} {b}");
                    next += 1;
                }
            }
            assert_eq!(next, t.lost.len());
        }
    }

    #[test]
    fn pairs_are_named_by_plain_distinct_names_else_by_index() {
        let s = |v: &[&str]| v.iter().map(|x| x.to_string()).collect::<Vec<_>>();
        assert_eq!(
            pair_names(&s(&["grain", "tracer"])),
            s(&["grain-grain", "grain-tracer", "tracer-tracer"])
        );
        let fallback = s(&[
            "species0-species0",
            "species0-species1",
            "species1-species1",
        ]);
        assert_eq!(pair_names(&s(&["a b", "c"])), fallback);
        assert_eq!(pair_names(&s(&["a-b", "c"])), fallback);
        assert_eq!(pair_names(&s(&["x", "x"])), fallback);
        assert_eq!(pair_names(&s(&["", "c"])), fallback);
        assert!(is_count("contacts") && is_count("contacts_grain-tracer"));
        assert!(!is_count("lost_ball_ball_grain-tracer") && !is_count("collision_frequency"));
    }
}
