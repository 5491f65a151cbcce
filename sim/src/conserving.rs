//! Kernels whose conservative contacts are corrected onto the energy of their inputs
//! ([`collision_core::conserve`], issue 28 item 4): a long run's energy then random-walks
//! (proportional to the square root of the number of contacts) instead of drifting by the
//! kernels' bias (`docs/accuracy.md`, "An energy-conserving correction").
//!
//! The correction runs after each kernel call whose law conserves energy (the no-slip map,
//! the specular one): [`collision_core::conserve::free`] for a pair, `fixed` for a wall or
//! any other boundary. A dissipative law's contacts (rough, Walton) are left as the kernels
//! give them. The events are those of the uncorrected run only until the first corrected
//! contact: the states differ by an ulp or two there, and a chaotic table amplifies that.

use crate::law::FoldedLaws;
use crate::{ContactKind, GenericKernels, PairKernels};
use collision_core::{conserve, Ball, BodyState};

/// `kernels` with their conservative contacts corrected onto the inputs' energy, or as they
/// are if `enabled` is false (so that a program can choose at run time without a second
/// type).
#[derive(Clone, Debug)]
pub struct Conserving<K> {
    /// The kernels corrected.
    pub kernels: K,
    /// Each species' parameters, by species index (the energy's weights).
    pub species: Vec<Ball<f64>>,
    /// Whether to correct.
    pub enabled: bool,
}

impl Conserving<GenericKernels<f64>> {
    /// The generic kernels of `species`, corrected if `enabled`.
    pub fn generic(species: Vec<Ball<f64>>, enabled: bool) -> Self {
        Conserving {
            kernels: GenericKernels {
                species: species.clone(),
            },
            species,
            enabled,
        }
    }
}

/// Whether a contact of law `kind` conserves energy.
fn conservative(kind: Option<ContactKind>) -> bool {
    matches!(kind, Some(ContactKind::NoSlip | ContactKind::Smooth))
}

impl<K: PairKernels<f64, N, S>, const N: usize, const S: usize> PairKernels<f64, N, S>
    for Conserving<K>
{
    fn laws(&self) -> FoldedLaws {
        self.kernels.laws()
    }

    fn ball_law(&self, a: usize, b: usize) -> Option<ContactKind> {
        self.kernels.ball_law(a, b)
    }

    fn ball_ball(
        &self,
        a: usize,
        b: usize,
        nu: &[f64; N],
        state1: &BodyState<f64, N, S>,
        state2: &BodyState<f64, N, S>,
    ) -> [BodyState<f64, N, S>; 2] {
        let after = self.kernels.ball_ball(a, b, nu, state1, state2);
        if !(self.enabled && conservative(self.kernels.ball_law(a, b))) {
            return after;
        }
        let (b1, b2) = (&self.species[a], &self.species[b]);
        conserve::free(b1, b2, [state1, state2], [&after[0], &after[1]])
    }

    fn ball_wall(
        &self,
        species: usize,
        axis: usize,
        upper: bool,
        state: &BodyState<f64, N, S>,
    ) -> BodyState<f64, N, S> {
        let after = self.kernels.ball_wall(species, axis, upper, state);
        if !(self.enabled && conservative(self.kernels.laws().wall)) {
            return after;
        }
        conserve::fixed(&self.species[species], state, &after)
    }

    fn ball_obstacle(
        &self,
        species: usize,
        nu: &[f64; N],
        state: &BodyState<f64, N, S>,
    ) -> BodyState<f64, N, S> {
        let after = self.kernels.ball_obstacle(species, nu, state);
        if !(self.enabled && conservative(self.kernels.laws().fixed)) {
            return after;
        }
        conserve::fixed(&self.species[species], state, &after)
    }
}

#[cfg(test)]
mod tests;
