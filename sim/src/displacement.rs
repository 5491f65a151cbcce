//! The balls' displacements since the start of a run, unwrapped across periodic faces, for
//! the mean square displacement of `granular::Sampler` (docs/granular.md).
//!
//! The engine wraps positions on periodic axes, so they are not differenced: a ball's
//! velocity is constant between its contacts, and its displacement is the sum of its flights,
//!
//! ```text
//! d_i(t) = sum over the flights of i before t of u (t_end - t_start) + u_i (t - t_i),
//! ```
//!
//! `t_i` the time of ball `i`'s last contact or kick (the start if none) and `u_i` its velocity
//! since. Each contact adds its balls' finished flight (`pre.velocity` times the time since
//! their previous contact or kick); a thermostat's kick ([`crate::thermostat`]) ends every
//! ball's flight at its time (`Kick::before` times the time since), as the position is
//! continuous across a kick and only the velocity jumps; a sample adds the flight in progress.
//! This is exact in any box, driven or not (walls, obstacles and boundaries change velocities
//! only at contacts, the thermostat only at kicks), to the rounding of the sums.
//!
//! With `D = sum_i m_i d_i / M` the centre of mass's displacement (`M = sum_i m_i`),
//!
//! ```text
//! msd    = sum_i |d_i|^2 / N_b,
//! msd_cm = sum_i |d_i - D|^2 / N_b.
//! ```
//!
//! `msd_cm` takes out the centre of mass's drift: in a periodic box the total momentum is
//! conserved, so `D = V t` grows ballistically, `|V|^2 ~ n T / (N_b m)` for a random start,
//! and adds `|V|^2 t^2` to `msd` (several per cent of `2 n D t` after tens of collision times
//! with a thousand balls); the self-diffusion coefficient is read from `msd_cm`.

use crate::thermostat::Kick;
use crate::{Event, PairKernels, Simulation};
use collision_core::Ball;

/// The displacement of every ball up to its last contact, and that contact's time.
#[derive(Clone, Debug)]
pub struct Displacements {
    dim: usize,
    /// `d_i` up to `since[i]`, `dim` numbers per ball.
    flown: Vec<f64>,
    since: Vec<f64>,
}

impl Displacements {
    /// Every ball of `sim` at displacement zero now.
    pub fn start<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
        sim: &Simulation<N, S, K>,
    ) -> Displacements {
        Displacements {
            dim: N,
            flown: vec![0.0; N * sim.len()],
            since: vec![sim.now(); sim.len()],
        }
    }

    /// Adds the flights contact `e` ended.
    pub fn contact<const N: usize, const S: usize>(&mut self, e: &Event<N, S>) {
        for (k, i) in e.contact.balls().enumerate() {
            let dt = e.time - self.since[i];
            for (d, u) in self.flown[N * i..N * (i + 1)]
                .iter_mut()
                .zip(&e.pre[k].velocity)
            {
                *d += u * dt;
            }
            self.since[i] = e.time;
        }
    }

    /// The number of balls.
    pub fn balls(&self) -> usize {
        self.since.len()
    }

    /// Adds the flights kick `k` ended: every ball's, at `k.time`, with its velocity before it.
    pub fn kick<const N: usize>(&mut self, k: &Kick<N>) {
        debug_assert_eq!(self.dim, N);
        for (i, u) in k.before.iter().enumerate() {
            let dt = k.time - self.since[i];
            for (d, u) in self.flown[N * i..N * (i + 1)].iter_mut().zip(u) {
                *d += u * dt;
            }
            self.since[i] = k.time;
        }
    }

    /// The displacements `d_i` now, `N` numbers per ball.
    pub fn now<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
        &self,
        sim: &Simulation<N, S, K>,
    ) -> Vec<[f64; N]> {
        debug_assert_eq!(self.dim, N);
        let now = sim.now();
        (0..sim.len())
            .map(|i| {
                let u = &sim.state(i).velocity;
                let dt = now - self.since[i];
                std::array::from_fn(|k| self.flown[N * i + k] + u[k] * dt)
            })
            .collect()
    }

    /// Each ball's displacement about the centre of mass's now, `d_i - D` (module docs), `N`
    /// numbers a ball.
    pub fn about_centre<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
        &self,
        sim: &Simulation<N, S, K>,
        species: &[Ball<f64>],
    ) -> Vec<f64> {
        let d = self.now(sim);
        let (mut mass, mut centre) = (0.0, [0.0; N]);
        for (i, di) in d.iter().enumerate() {
            let m = 1.0 / species[sim.species_of(i)].inv_mass;
            mass += m;
            for (c, x) in centre.iter_mut().zip(di) {
                *c += m * x;
            }
        }
        d.iter()
            .flat_map(|di| std::array::from_fn::<f64, N, _>(|k| di[k] - centre[k] / mass))
            .collect()
    }

    /// `[msd, msd_cm]` now (module docs).
    pub fn msd<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
        &self,
        sim: &Simulation<N, S, K>,
        species: &[Ball<f64>],
    ) -> [f64; 2] {
        let m = self.mean_squares(sim, species);
        [m.msd, m.msd_cm]
    }

    /// [`Displacements::msd`] and `msd_cm` of each species `s`:
    /// `sum over the balls i of s of |d_i - D|^2 / N_s` (`NaN` for a species without balls).
    pub fn mean_squares<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
        &self,
        sim: &Simulation<N, S, K>,
        species: &[Ball<f64>],
    ) -> MeanSquares {
        let d = self.now(sim);
        let (mut mass, mut centre) = (0.0, [0.0; N]);
        for (i, di) in d.iter().enumerate() {
            let m = 1.0 / species[sim.species_of(i)].inv_mass;
            mass += m;
            for (c, x) in centre.iter_mut().zip(di) {
                *c += m * x;
            }
        }
        let centre = centre.map(|c| c / mass);
        let (mut msd, mut msd_cm) = (0.0, 0.0);
        let (mut per, mut count) = (vec![0.0; species.len()], vec![0usize; species.len()]);
        for (i, di) in d.iter().enumerate() {
            let mut about_centre = 0.0;
            for (x, c) in di.iter().zip(&centre) {
                msd += x * x;
                about_centre += (x - c) * (x - c);
            }
            msd_cm += about_centre;
            let s = sim.species_of(i);
            per[s] += about_centre;
            count[s] += 1;
        }
        let balls = d.len() as f64;
        MeanSquares {
            msd: msd / balls,
            msd_cm: msd_cm / balls,
            species_cm: per
                .iter()
                .zip(&count)
                .map(|(&sum, &n)| if n == 0 { f64::NAN } else { sum / n as f64 })
                .collect(),
        }
    }
}

/// The mean square displacements of [`Displacements::mean_squares`].
#[derive(Clone, Debug, PartialEq)]
pub struct MeanSquares {
    /// `msd` (module docs).
    pub msd: f64,
    /// `msd_cm` (module docs).
    pub msd_cm: f64,
    /// `msd_cm` over the balls of each species.
    pub species_cm: Vec<f64>,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{GenericKernels, Step};

    /// `[msd, msd_cm]` of a 10 x 10 periodic box holding `balls` at `until`.
    fn msd_at(balls: &str, until: f64) -> [f64; 2] {
        let text = format!(
            "dim = 2\n[box]\nsize = [10, 10]\nboundary = [\"periodic\", \"periodic\"]\n\
             [[species]]\nmass = 1\nradius = \"1/2\"\n{balls}"
        );
        let scene = noslip_scene::Scene::from_toml(&text, "t.toml").unwrap();
        let setup = crate::setup::setup::<2, 1>(&scene).unwrap();
        let species = setup.species.clone();
        let kernels = GenericKernels {
            species: species.clone(),
        };
        let mut sim = Simulation::new(setup, kernels).unwrap();
        let mut d = Displacements::start(&sim);
        while let Step::Contact(e) = sim.step(until) {
            d.contact(&e);
        }
        assert_eq!(sim.now(), until);
        d.msd(&sim, &species)
    }

    /// Ball 0 flies 30 along x (three box lengths, back where it started once wrapped),
    /// ball 1 rests: `d = (30, 0)` and `(0, 0)`, `msd = 900 / 2`, and about the centre of
    /// mass (`D = (15, 0)`) `msd_cm = 225`.
    #[test]
    fn a_flight_across_periodic_faces_is_unwrapped() {
        let balls = "[[ball]]\nspecies = 0\nposition = [1, 2]\nvelocity = [3, 0]\n\
                     [[ball]]\nspecies = 0\nposition = [5, 7]\n";
        assert_eq!(msd_at(balls, 10.0), [450.0, 225.0]);
    }

    /// Head on at unit speeds, 2 apart: they touch at t = 1 and swap velocities; at t = 3.5
    /// ball 0 is at `+1 - 2.5 = -1.5` (across the face x = 0) and ball 1 at `+1.5`.
    #[test]
    fn contacts_end_flights() {
        let balls = "[[ball]]\nspecies = 0\nposition = [1, 5]\nvelocity = [1, 0]\n\
                     [[ball]]\nspecies = 0\nposition = [4, 5]\nvelocity = [-1, 0]\n";
        let [msd, msd_cm] = msd_at(balls, 3.5);
        assert!((msd - 2.25).abs() < 1e-12, "{msd}");
        assert!((msd_cm - 2.25).abs() < 1e-12, "{msd_cm}");
    }
}
