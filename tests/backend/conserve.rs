//! The contacts of the energy-conserving correction's faithfulness tests
//! (`c_backend/conserve.rs`, `opencl_backend/conserve.rs`): cases drawn from every regime of
//! the accuracy report, the Rust kernels' outputs for them, and the Rust correction
//! (`collision_core::conserve`) of those outputs, which the foreign correction must return
//! bit for bit.

use super::{draw, state};
use collision_core::{conserve, BodyState, Generated, Kernel};
use noslip_accuracy::case::Case;
use noslip_accuracy::regime::Regime;

/// Drawn `f64` cases with their regimes ([`draw`]).
pub type Drawn<const N: usize, const S: usize> = Vec<(Regime, Case<f64, N, S>)>;

/// One drawn contact, every state as its values in the records' order ([`state`]).
pub struct Contact {
    /// `{inv_mass, radius, gamma2}` of ball 1 and ball 2.
    pub balls: [[f64; 3]; 2],
    /// The states before the contact.
    pub before: [Vec<f64>; 2],
    /// The free kernel's outputs.
    pub after: [Vec<f64>; 2],
    /// The fixed kernel's output for ball 2 against an immovable ball 1.
    pub fixed: Vec<f64>,
    /// [`Contact::fixed`] corrected in Rust (`conserve::fixed` of ball 2).
    pub want_fixed: Vec<f64>,
    /// [`Contact::after`] corrected in Rust (`conserve::free`).
    pub want_free: [Vec<f64>; 2],
}

/// `count` contacts of dimension `N` drawn with `seed`, their cases, and how many of the
/// `2 count` corrections changed something.
pub fn contacts<const N: usize, const S: usize>(
    count: usize,
    seed: u64,
) -> (Drawn<N, S>, Vec<Contact>, usize)
where
    Generated: Kernel<f64, N, S>,
{
    let cases = draw::<N, S>(count, seed).f64;
    let mut changed = 0;
    let flat = |s: &BodyState<f64, N, S>| state(s).collect::<Vec<_>>();
    let contacts = cases
        .iter()
        .map(|(_, c)| {
            let [b1, b2] = &c.balls;
            let [s1, s2] = &c.states;
            let [o1, o2] = Generated::free(&c.nu, b1, b2, s1, s2);
            let fixed = Generated::fixed(&c.nu, &b1.radius, b2, &BodyState::zero(), s2);
            let f = conserve::fixed(b2, s2, &fixed);
            let [c1, c2] = conserve::free(b1, b2, [s1, s2], [&o1, &o2]);
            changed += usize::from(f != fixed) + usize::from(c1 != o1 || c2 != o2);
            Contact {
                balls: [b1, b2].map(|b| [b.inv_mass, b.radius, b.gamma2]),
                before: [flat(s1), flat(s2)],
                after: [flat(&o1), flat(&o2)],
                fixed: flat(&fixed),
                want_fixed: flat(&f),
                want_free: [flat(&c1), flat(&c2)],
            }
        })
        .collect();
    (cases, contacts, changed)
}
