//! The contact rate of a periodic gas from kinetic theory, to stop a run whose next contact
//! is out of reach sooner than [`MAX_QUIET_BOX_LENGTHS`] (issue 26, item 12).
//!
//! The engine flies a ball across the box cell by cell, a few events per box length, and a
//! contact-free stretch ends the run only after [`MAX_QUIET_BOX_LENGTHS`] box lengths: a
//! million box lengths of crossings, hours for ten balls in 6D (each crossing scans the
//! `3^6` neighbour cells). In a dilute gas that verdict is known long before: ten balls of
//! radius 1 in a 6D periodic box of side `10^6` have a mean free path of about `10^26` box
//! lengths.
//!
//! **The rate.** With every axis periodic and the centres spread uniformly over the box (the
//! kinetic-theory assumption), balls `i` and `j` meet at the rate `c_{n-1} (R_i + R_j)^{n-1}
//! |u_i - u_j| / V` (the relative flight sweeps a tube of cross-section `c_{n-1} (R_i +
//! R_j)^{n-1}`, `c_{n-1}` the volume of the unit ball of `R^{n-1}`, and each image of the
//! partner is in it with probability its volume over `V`), a ball and an obstacle at `c_{n-1}
//! (R_i + R_o)^{n-1} |u_i| / V`. Summed with `|u_i - u_j| <= |u_i| + |u_j|` and `R_i <=
//! R_max`, an upper bound in `O(balls + obstacles)`:
//!
//! `Gamma = c_{n-1} sum_i |u_i| ((N - 1) (2 R_max)^{n-1} + sum_o (R_max + R_o)^{n-1}) / V`.
//!
//! **The stop.** At each quiet notice (first after 1000 box lengths without contact, when the
//! flights have long forgotten where they started), the run ends if `Gamma T < `
//! [`MAX_EXPECTED_CONTACTS`], `T` the time left until every moving ball has travelled
//! [`MAX_QUIET_BOX_LENGTHS`] box lengths: the chance that the full reach would still have
//! found a contact is below `1e-9`. A table with a walled axis or boundaries gets no
//! estimate (a moving ball meets a wall within a box length or flies along it). A Sinai table
//! or any gas dense enough to have a contact within reach has `Gamma T` far above 1, so its
//! corridor flights still run to the full reach. The rule assumes uniform spread: a contact
//! arranged by hand to come after more than 1000 box lengths in such a dilute box (a relative
//! flight winding almost rationally onto the partner) is not waited for.

use crate::no_contact::MAX_QUIET_BOX_LENGTHS;
use crate::setup::log_unit_ball;
use crate::{PairKernels, Simulation};
use collision_core::Ball;

/// The expected number of contacts within the run's remaining reach below which a quiet
/// periodic gas stops (module docs).
pub const MAX_EXPECTED_CONTACTS: f64 = 1e-9;

/// Why a quiet run stops early: the upper bound `Gamma` of the contact rate and the contacts
/// `Gamma T` expected in the remaining reach.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OutOfReach {
    /// The upper bound of the contact rate, per unit time.
    pub rate: f64,
    /// The contacts expected before every moving ball has travelled
    /// [`MAX_QUIET_BOX_LENGTHS`] box lengths.
    pub expected: f64,
}

/// `Gamma` of the module docs, or `None` without a box or with a walled axis or a boundary.
pub fn contact_rate<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
    sim: &Simulation<N, S, K>,
    species: &[Ball<f64>],
) -> Option<f64> {
    if !sim.periodic().iter().all(|&p| p) || !sim.table().boundaries.is_empty() {
        return None;
    }
    // Lengths in units of the longest side, so that no power over- or underflows needlessly.
    let size = sim.box_size();
    let side = sim.longest_side();
    let volume: f64 = size.iter().map(|l| l / side).product();
    let power = |x: f64| (x / side).powi(N as i32 - 1);
    let r_max = (0..sim.len())
        .map(|i| species[sim.species_of(i)].radius)
        .fold(0.0, f64::max);
    let speeds: f64 = (0..sim.len()).map(|i| sim.speed_of(i)).sum();
    let targets = (sim.len().saturating_sub(1)) as f64 * power(2.0 * r_max)
        + sim
            .obstacles()
            .iter()
            .map(|o| power(r_max + o.radius))
            .sum::<f64>();
    let c = log_unit_ball(N - 1).exp();
    Some(c * speeds / side * targets / volume)
}

/// [`OutOfReach`] if the run should stop now: every moving ball has travelled `box_lengths`
/// without a contact, and fewer than [`MAX_EXPECTED_CONTACTS`] are expected before the
/// slowest one has travelled [`MAX_QUIET_BOX_LENGTHS`].
pub fn out_of_reach<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
    sim: &Simulation<N, S, K>,
    species: &[Ball<f64>],
    box_lengths: f64,
) -> Option<OutOfReach> {
    let rate = contact_rate(sim, species)?;
    let slowest = sim.slowest_speed()?;
    let left = (MAX_QUIET_BOX_LENGTHS - box_lengths).max(0.0) * sim.longest_side() / slowest;
    let expected = rate * left;
    (expected < MAX_EXPECTED_CONTACTS).then_some(OutOfReach { rate, expected })
}
