//! The conserved quantities of a set of balls.

use collision_core::skew_pairs;
use collision_core::{Ball, BodyState};

/// Totals over all balls, with `m = 1/w`, `lambda = gamma^2 R^2 / 2`:
///
/// - kinetic energy `E = sum 1/2 m (|u|^2 + lambda Tr(U U^T)) = sum 1/2 m (|u|^2 + 2 lambda
///   sum_{i<j} U_ij^2)` (half the metric norm);
/// - linear momentum `p = sum m u`;
/// - angular momentum about the origin `L = sum m (a ^ u) + 2 m lambda U`, compact entries
///   `(a ^ u)_ij = u_i a_j - a_i u_j`.
///
/// Energy is conserved by every contact; `p` by ball-ball contacts and free flight (not by
/// walls or obstacles); `L` also needs no walls, obstacles or periodic wrapping.
#[derive(Clone, Debug, PartialEq)]
pub struct Observables<const N: usize, const S: usize> {
    /// Kinetic energy `E = sum 1/2 m (|u|^2 + 2 lambda sum_{i<j} U_ij^2)`.
    pub energy: f64,
    /// Linear momentum `p = sum m u`.
    pub momentum: [f64; N],
    /// Angular momentum `L` about the origin, compact skew entries `L_ij`, `i < j`.
    pub angular_momentum: [f64; S],
}

/// One ball's kinetic energy `1/2 m (|u|^2 + 2 lambda sum_{i<j} U_ij^2)`, `m = 1/w`: the
/// term [`Observables::of`] sums (the same bits, so that a sum of these in the balls' order
/// is its `energy`).
#[inline]
pub(crate) fn energy_of<const N: usize, const S: usize>(
    ball: &Ball<f64>,
    s: &BodyState<f64, N, S>,
) -> f64 {
    let m = 1.0 / ball.inv_mass;
    let u2: f64 = s.velocity.iter().map(|x| x * x).sum();
    let spin2: f64 = s.spin.iter().map(|x| x * x).sum();
    0.5 * m * (u2 + 2.0 * ball.lambda() * spin2)
}

impl<const N: usize, const S: usize> Observables<N, S> {
    /// The totals over `balls`, each given as (parameters, centre `a`, state).
    pub fn of<'a>(
        balls: impl IntoIterator<Item = (&'a Ball<f64>, &'a [f64; N], &'a BodyState<f64, N, S>)>,
    ) -> Self {
        let mut o = Observables {
            energy: 0.0,
            momentum: [0.0; N],
            angular_momentum: [0.0; S],
        };
        for (ball, a, s) in balls {
            let m = 1.0 / ball.inv_mass;
            let lambda = ball.lambda();
            o.energy += energy_of(ball, s);
            for k in 0..N {
                o.momentum[k] += m * s.velocity[k];
            }
            for (e, (i, j)) in skew_pairs(N).enumerate() {
                let wedge = s.velocity[i] * a[j] - a[i] * s.velocity[j];
                o.angular_momentum[e] += m * wedge + 2.0 * m * lambda * s.spin[e];
            }
        }
        o
    }
}
