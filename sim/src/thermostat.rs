//! The white-noise thermostat of a driven granular gas (`[thermostat]`, docs/granular.md,
//! "A driven steady state"): the stochastic forcing of Williams & MacKintosh (PRE 54, R9
//! (1996)) and van Noije & Ernst (Granular Matter 1, 57 (1998)) applied as kicks.
//!
//! At every time `t_k = k dt` (`k = 1, 2, ...`) each ball `i` gets the velocity increment
//!
//! ```text
//! dv_i = z_i - sum_j m_j z_j / M,    z_i = xi sqrt(dt) (g_1, ..., g_n),   g standard normal,
//! ```
//!
//! `M = sum_j m_j`: independent normal increments of variance `xi^2 dt` per component, less
//! their mass-weighted mean, so that the total momentum `sum_i m_i u_i` is unchanged by a kick
//! (up to rounding). Spins are not kicked: the forcing acts on the centres (a random body
//! force: a shaken container, an interstitial fluid's agitation of translation), and the
//! rotational temperature then has no source but the contacts (docs/granular.md).
//!
//! A kick of equal masses injects on average, with `N` balls in `n` dimensions (the variance
//! of `dv_i` per component is `xi^2 dt (1 - 1/N)`, the velocities are independent of `z`):
//!
//! ```text
//! <Delta E> = sum_i m <|dv_i|^2> / 2 = n (N - 1) m xi^2 dt / 2,
//! ```
//!
//! so the temperature `T_tr` of the `n (N - 1)` translational degrees of freedom about the
//! centre of mass is heated at `dT/dt = m xi^2`.

use collision_core::rng::Rng;

/// The thermostat's parameters (from the scene's `[thermostat]`, rounded once to f64).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Thermostat {
    /// `xi`, `> 0`: a velocity increment of variance `xi^2 dt` per component per kick.
    pub strength: f64,
    /// `dt`, `> 0`: the time between kicks.
    pub interval: f64,
    /// The seed of the kicks' random stream.
    pub seed: u64,
}

/// One kick as a run applied it ([`crate::run::run_watched`] tells its observer, the events
/// log records it): every ball's velocity before and after, `u'_i = u_i + dv_i` (one rounding
/// per component), at the clock's time `t_k`; spins are unchanged.
#[derive(Clone, Debug, PartialEq)]
pub struct Kick<const N: usize> {
    /// The kick's number `k` (1 for the first), so its time is `k dt` ([`Noise::next_time`]).
    pub index: u64,
    /// Its time `t_k`.
    pub time: f64,
    /// `u_i` before the kick, in ball order (the velocity of the flight the kick ends).
    pub before: Vec<[f64; N]>,
    /// `u'_i` after it (of the flight it starts).
    pub after: Vec<[f64; N]>,
    /// The kinetic energy it added, `sum_i m_i (|u'_i|^2 - |u_i|^2) / 2`
    /// ([`crate::Simulation::kick`]).
    pub injected: f64,
}

/// The kicks of a run: the thermostat, its random stream and the index of the next kick.
#[derive(Clone)]
pub struct Noise {
    thermostat: Thermostat,
    rng: Rng,
    next: u64,
}

impl Noise {
    /// The kicks of `thermostat` from the start (`t = 0`): the first at `dt`.
    pub fn new(thermostat: Thermostat) -> Noise {
        Noise {
            thermostat,
            rng: Rng::new(thermostat.seed),
            next: 1,
        }
    }

    /// The absolute time of the next kick, `k dt` (one rounding: the same for every engine).
    pub fn next_time(&self) -> f64 {
        self.next as f64 * self.thermostat.interval
    }

    /// Kicks done so far.
    pub fn done(&self) -> u64 {
        self.next - 1
    }

    /// The increments `dv_i` of the next kick (module docs) for balls of inverse masses
    /// `inv_mass` (in ball order): `n` normal numbers a ball from the stream, then the
    /// mass-weighted mean taken out.
    pub fn kick<const N: usize>(&mut self, inv_mass: &[f64]) -> Vec<[f64; N]> {
        self.next += 1;
        let scale = self.thermostat.strength * self.thermostat.interval.sqrt();
        let mut dv: Vec<[f64; N]> = inv_mass
            .iter()
            .map(|_| std::array::from_fn(|_| scale * crate::maxwell::normal(&mut self.rng)))
            .collect();
        let mass: f64 = inv_mass.iter().map(|w| 1.0 / w).sum();
        let mean: [f64; N] = std::array::from_fn(|k| {
            dv.iter().zip(inv_mass).map(|(z, w)| z[k] / w).sum::<f64>() / mass
        });
        for z in &mut dv {
            for k in 0..N {
                z[k] -= mean[k];
            }
        }
        dv
    }
}

#[cfg(test)]
mod tests {
    use super::{Noise, Thermostat};

    /// A mixture's kicks keep the momentum (to rounding) and have the variance
    /// `xi^2 dt (1 - 2 m_i / M + sum_j m_j^2 / M^2)` per component (the mean's part
    /// subtracted): over 20000 kicks of 4 balls, each estimate of a variance has standard
    /// error `sqrt(2 / 20000)` = 1 % of it; checked to 4 of them.
    #[test]
    fn kicks_keep_the_momentum_and_have_the_variance_of_white_noise() {
        let thermostat = Thermostat {
            strength: 3.0,
            interval: 0.01,
            seed: 5,
        };
        let inv_mass = [1.0, 0.5, 0.25, 2.0];
        let masses: Vec<f64> = inv_mass.iter().map(|w| 1.0 / w).collect();
        let total: f64 = masses.iter().sum();
        let mut noise = Noise::new(thermostat);
        let kicks = 20_000;
        let mut variance = [0.0; 4];
        for _ in 0..kicks {
            let dv = noise.kick::<3>(&inv_mass);
            for k in 0..3 {
                let p: f64 = dv.iter().zip(&masses).map(|(z, m)| m * z[k]).sum();
                assert!(p.abs() < 1e-14, "momentum {p}");
            }
            for (v, z) in variance.iter_mut().zip(&dv) {
                *v += z.iter().map(|x| x * x).sum::<f64>() / (3.0 * kicks as f64);
            }
        }
        assert_eq!(noise.done(), kicks);
        assert_eq!(noise.next_time(), (kicks + 1) as f64 * 0.01);
        let squares: f64 = masses.iter().map(|m| m * m).sum::<f64>() / (total * total);
        for (i, v) in variance.iter().enumerate() {
            let expected = 9.0 * 0.01 * (1.0 - 2.0 * masses[i] / total + squares);
            let error = expected * (2.0 / (3.0 * kicks as f64)).sqrt();
            assert!(
                (v - expected).abs() < 4.0 * error,
                "ball {i}: {v} vs {expected}"
            );
        }
    }
}
