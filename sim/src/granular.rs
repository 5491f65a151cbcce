//! Granular-gas observables sampled over a run (docs/granular.md): the translational and
//! rotational granular temperatures (of the whole gas and, in a mixture, of each species), the
//! collision frequency, the kinetic energy lost per contact kind (and in a mixture per pair of
//! species, with the pairs' contacts: [`crate::pair_losses`]) and injected by a thermostat's
//! kicks, the pressure, the
//! velocity distribution's cumulant `a_2` and the mean square displacement (of the balls'
//! unwrapped displacements, also about the centre of mass: [`crate::displacement`]), written
//! as CSV with the units in the header; on request the pair correlation `g(r)`
//! ([`Sampler::with_pair_correlation`], [`crate::pair_correlation`]) and the self-diffusion
//! coefficient ([`Sampler::with_self_diffusion`], [`crate::self_diffusion`]).
//!
//! With `N_b` balls in R^n, `S = n(n-1)/2`, masses `m_i` and moments of inertia `I_i = 2 m_i
//! lambda_i` (the project's convention: a ball's kinetic energy is `1/2 m |u|^2 + 1/2 I
//! sum_{k<l} U_kl^2`, docs/derivation.md), the temperatures per degree of freedom are
//!
//! ```text
//! T_tr  = sum_i m_i |c_i|^2 / (n (N_b - 1)),          c_i = u_i - V,
//! T_rot = sum_i I_i sum_{k<l} (U_i)_kl^2 / (S N_rot),
//! ```
//!
//! `V = sum_i m_i u_i / M` (`M = sum_i m_i`) the centre of mass's velocity: its motion is taken
//! out (conserved in a periodic box, it is no thermal motion), leaving `n (N_b - 1)`
//! translational degrees of freedom; `N_rot` the balls with `lambda > 0` (a point mass has no
//! rotational degrees of freedom). Of species `s` (`N_s` balls of total mass `M_s`):
//! `T_tr,s = sum_{i in s} m_i |c_i|^2 / (n (N_s - M_s / M))` (at equal temperatures
//! `E[m_i |c_i|^2] = n T (1 - m_i / M)` for Maxwellian velocities, so the `n (N_s - M_s/M)`
//! degrees of freedom add up to the whole gas's) and `T_rot,s` as `T_rot` over its balls.
//!
//! The collision frequency between two samples is `2 C_bb / (N_b dt)`: ball-ball contacts
//! `C_bb` in the interval, two balls each, per ball and unit time. The energy lost by a
//! contact is the kinetic energy of its balls before minus after; the energy injected by a
//! kick is the balls' kinetic energy after minus before ([`crate::Simulation::kick`]). Both are
//! kept as totals since the start, so that between any two rows
//!
//! ```text
//! E_b - E_a = (injected_b - injected_a) - sum over the kinds of (lost_b - lost_a),
//! ```
//!
//! an identity up to rounding (`sim/tests/driven_observables.rs` bounds it).
//!
//! The pressure of a periodic box of volume `V_box` without obstacles or other boundaries
//! (NaN otherwise: they take momentum the bulk formula does not count) is the kinetic part now plus the
//! collisional virial over the interval since the previous row,
//!
//! ```text
//! P = sum_i m_i |c_i|^2 / (n V_box) + sum_{ball-ball contacts in dt} r_ij . J_i / (n V_box dt),
//! ```
//!
//! `r_ij = x_i - x_j = -(R_i + R_j) nu` at contact and `J_i = m_i (u_i' - u_i)` the impulse on
//! ball `i` (only its normal part counts: `r_ij` is along `nu`), NaN in the first row. The
//! cumulant `a_2 = n / (n + 2) <|c|^4> / <|c|^2>^2 - 1` over the balls (0 for a Maxwellian).
//!
//! A row is written at the first contact at or after each multiple of the interval `every`
//! (and one at the start): the row's time is that contact's, and the state is the one just
//! after it (the velocities are constant between contacts, so the row is exact at its time).

use crate::displacement::Displacements;
use crate::observe::energy_of;
use crate::pair_correlation::PairCorrelation;
use crate::pair_losses::{pair_names, PairLosses};
use crate::self_diffusion::SelfDiffusion;
use crate::thermostat::Kick;
use crate::{Contact, Event, PairKernels, Simulation};
use collision_core::Ball;

/// The contact kinds the losses are kept by, in the order of [`Row::lost`]: ball-ball,
/// ball-wall (the box), ball-obstacle, ball-boundary (the table's other boundaries).
pub const KINDS: [&str; 4] = ["ball_ball", "ball_wall", "ball_obstacle", "ball_boundary"];

/// The unit of temperatures and energies, in the scene's mass `M`, length `L` and time `T`.
const ENERGY: &str = "M L^2 T^-2";

/// One sample.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// The simulated time.
    pub time: f64,
    /// Contacts so far.
    pub contacts: u64,
    /// `T_tr` (`NaN` with a single ball: it has no translational degree of freedom left).
    pub t_tr: f64,
    /// `T_rot` (`NaN` when no ball has rotational degrees of freedom).
    pub t_rot: f64,
    /// The kinetic energy.
    pub energy: f64,
    /// Ball-ball contacts per ball and unit time since the previous row (`NaN` in the first).
    pub frequency: f64,
    /// Energy lost so far per contact kind ([`KINDS`]).
    pub lost: [f64; 4],
    /// Energy injected so far by the thermostat's kicks (0 without one).
    pub injected: f64,
    /// The pressure (module docs; `NaN` in the first row and outside a periodic box).
    pub pressure: f64,
    /// The cumulant `a_2` of the translational velocities (module docs).
    pub a2: f64,
    /// The mean square displacement since the start, unwrapped ([`crate::displacement`]).
    pub msd: f64,
    /// The same about the centre of mass ([`crate::displacement`]).
    pub msd_cm: f64,
    /// `[T_tr,s, T_rot,s]` of each species `s`, in a mixture (empty with one species).
    pub species: Vec<[f64; 2]>,
    /// `msd_cm` over the balls of each species `s`, in a mixture (empty with one species;
    /// [`crate::displacement::MeanSquares`]).
    pub msd_species: Vec<f64>,
    /// Energy lost so far at the ball-ball contacts of each unordered pair of species, in a
    /// mixture, in the pairs' order of [`crate::pair_losses`] (empty with one species).
    pub pair_lost: Vec<f64>,
    /// Ball-ball contacts so far of each pair of species, in a mixture (empty with one).
    pub pair_contacts: Vec<u64>,
}

impl Row {
    /// The row's numbers in the order of [`Sampler::columns`] (`contacts` as a double:
    /// exact below `2^53`).
    pub fn values(&self) -> Vec<f64> {
        let mut v = vec![
            self.time,
            self.contacts as f64,
            self.t_tr,
            self.t_rot,
            self.energy,
            self.frequency,
        ];
        v.extend(self.lost);
        v.push(self.injected);
        v.extend([self.pressure, self.a2, self.msd, self.msd_cm]);
        v.extend(self.species.iter().flatten());
        v.extend(&self.msd_species);
        v.extend(&self.pair_lost);
        // Counts as doubles: exact below 2^53.
        v.extend(self.pair_contacts.iter().map(|&c| c as f64));
        v
    }
}

/// The translational and rotational moments of the balls now (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Moments {
    /// `[T_tr, T_rot]`.
    pub temperatures: [f64; 2],
    /// `sum_i m_i |c_i|^2`.
    pub kinetic: f64,
    /// `a_2`.
    pub a2: f64,
    /// `[T_tr,s, T_rot,s]` of every species (also with one).
    pub species: Vec<[f64; 2]>,
}

/// The [`Moments`] of the balls of `sim` now.
pub fn moments<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
    sim: &Simulation<N, S, K>,
    species: &[Ball<f64>],
) -> Moments {
    let (mut mass, mut p) = (0.0, [0.0; N]);
    let mut species_mass = vec![0.0; species.len()];
    let mut count = vec![0usize; species.len()];
    for i in 0..sim.len() {
        let s = sim.species_of(i);
        let m = 1.0 / species[s].inv_mass;
        mass += m;
        species_mass[s] += m;
        count[s] += 1;
        for (pk, uk) in p.iter_mut().zip(&sim.state(i).velocity) {
            *pk += m * uk;
        }
    }
    let v = p.map(|pk| pk / mass);
    let (mut tr, mut rot, mut rotating) = (0.0, 0.0, 0usize);
    let (mut c2, mut c4) = (0.0, 0.0);
    // Per species: sum m |c|^2, sum I |U|^2, balls with lambda > 0.
    let mut per = vec![(0.0, 0.0, 0usize); species.len()];
    for i in 0..sim.len() {
        let s = sim.species_of(i);
        let b = &species[s];
        let m = 1.0 / b.inv_mass;
        let state = sim.state(i);
        let c: f64 = (0..N).map(|k| (state.velocity[k] - v[k]).powi(2)).sum();
        tr += m * c;
        per[s].0 += m * c;
        c2 += c;
        c4 += c * c;
        if b.lambda() > 0.0 {
            let r = 2.0 * m * b.lambda() * state.spin.iter().map(|x| x * x).sum::<f64>();
            rot += r;
            rotating += 1;
            per[s].1 += r;
            per[s].2 += 1;
        }
    }
    let balls = sim.len() as f64;
    let (n, s) = (N as f64, S as f64);
    Moments {
        temperatures: [
            tr / (n * (balls.max(1.0) - 1.0)),
            rot / (s * rotating as f64),
        ],
        kinetic: tr,
        a2: n / (n + 2.0) * (c4 / balls) / (c2 / balls).powi(2) - 1.0,
        species: per
            .iter()
            .zip(count.iter().zip(&species_mass))
            .map(|(&(tr, rot, rotating), (&count, &ms))| {
                [
                    tr / (n * (count as f64 - ms / mass)),
                    rot / (s * rotating as f64),
                ]
            })
            .collect(),
    }
}

/// `[T_tr, T_rot]` of the balls now (module docs).
pub fn temperatures<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
    sim: &Simulation<N, S, K>,
    species: &[Ball<f64>],
) -> [f64; 2] {
    moments(sim, species).temperatures
}

/// The kinetic energy contact `e` of `sim` took away: its balls' energy before minus after.
pub fn lost<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
    e: &Event<N, S>,
    sim: &Simulation<N, S, K>,
    species: &[Ball<f64>],
) -> f64 {
    let mut sum = 0.0;
    for (k, i) in e.contact.balls().enumerate() {
        let b = &species[sim.species_of(i)];
        sum += energy_of(b, &e.pre[k]) - energy_of(b, &e.post[k]);
    }
    sum
}

/// `r_ij . J_i` of a ball-ball contact `e` (module docs): `-(R_i + R_j) nu . m_i (u_i' - u_i)`.
fn virial<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
    e: &Event<N, S>,
    i: usize,
    j: usize,
    sim: &Simulation<N, S, K>,
    species: &[Ball<f64>],
) -> f64 {
    let (bi, bj) = (&species[sim.species_of(i)], &species[sim.species_of(j)]);
    let impulse: f64 = (0..N)
        .map(|k| e.nu[k] * (e.post[0].velocity[k] - e.pre[0].velocity[k]))
        .sum();
    -(bi.radius + bj.radius) * impulse / bi.inv_mass
}

/// Rows taken over a run: [`Sampler::start`], then [`Sampler::contact`] after each contact.
#[derive(Clone, Debug)]
pub struct Sampler {
    every: f64,
    next: f64,
    dim: usize,
    /// Species in the run: per-species columns when more than one.
    species: usize,
    /// Whether the box is periodic on every axis, without obstacles or other boundaries (the
    /// pressure and `g(r)` are defined).
    periodic: bool,
    /// Ball-ball contacts so far, and at the last row: `(time, ball-ball contacts)`.
    ball_ball: u64,
    last: (f64, u64),
    /// `sum r_ij . J_i` over the ball-ball contacts since the last row.
    virial: f64,
    lost: [f64; 4],
    /// In a mixture, the ball-ball losses and contacts per pair of species.
    pairs: Option<PairLosses>,
    /// The pairs' names in the columns ([`pair_names`]).
    pair_names: Vec<String>,
    injected: f64,
    displacements: Displacements,
    /// The box's sides: its volume, and the cells of [`Sampler::with_pair_correlation`].
    sides: Vec<f64>,
    pair_correlation: Option<PairCorrelation>,
    self_diffusion: Option<SelfDiffusion>,
    rows: Vec<Row>,
}

impl Sampler {
    /// A sampler with a row every `every` (`> 0`) of simulated time, its first row now.
    pub fn start<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
        every: f64,
        sim: &Simulation<N, S, K>,
        species: &[Ball<f64>],
    ) -> Sampler {
        let periodic = sim.table().boxed
            && sim.periodic().iter().all(|&p| p)
            && sim.obstacles().is_empty()
            && sim.table().boundaries.is_empty();
        let mut s = Sampler {
            every,
            next: sim.now(),
            dim: N,
            species: species.len(),
            periodic,
            ball_ball: 0,
            last: (sim.now(), 0),
            virial: 0.0,
            lost: [0.0; 4],
            pairs: (species.len() > 1).then(|| PairLosses::new(species.len())),
            pair_names: unnamed(species.len()),
            injected: 0.0,
            displacements: Displacements::start(sim),
            sides: sim.box_size().to_vec(),
            pair_correlation: None,
            self_diffusion: None,
            rows: Vec::new(),
        };
        s.row(sim, species);
        s
    }

    /// Accounts contact `e` (the last one `sim` took) and writes a row if a sample is due.
    pub fn contact<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
        &mut self,
        e: &Event<N, S>,
        sim: &Simulation<N, S, K>,
        species: &[Ball<f64>],
    ) {
        let loss = lost(e, sim, species);
        let k = match e.contact {
            Contact::Ball { i, j } => {
                self.virial += virial(e, i, j, sim, species);
                if let Some(p) = &mut self.pairs {
                    p.add(sim.species_of(i), sim.species_of(j), loss);
                }
                0
            }
            Contact::Wall { .. } => 1,
            Contact::Obstacle { .. } => 2,
            Contact::Boundary { .. } => 3,
        };
        self.ball_ball += u64::from(k == 0);
        self.displacements.contact(e);
        self.lost[k] += loss;
        if e.time >= self.next {
            self.row(sim, species);
        }
    }

    /// Accounts kick `k` (the last thing `sim` did, [`crate::run::run_watched`]): it ends every
    /// ball's flight for the displacements and adds its energy to `injected`. No row is
    /// written at a kick (rows are taken at contacts, module docs).
    pub fn kick<const N: usize>(&mut self, k: &Kick<N>) {
        self.displacements.kick(k);
        self.injected += k.injected;
    }

    fn row<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
        &mut self,
        sim: &Simulation<N, S, K>,
        species: &[Ball<f64>],
    ) {
        let time = sim.now();
        let m = moments(sim, species);
        let [t_tr, t_rot] = m.temperatures;
        let squares = self.displacements.mean_squares(sim, species);
        if let Some(g) = &mut self.pair_correlation {
            g.sample(sim);
        }
        if let Some(d) = &mut self.self_diffusion {
            d.sample(time, &self.displacements.about_centre(sim, species));
        }
        let (t0, c0) = self.last;
        let first = self.rows.is_empty();
        let frequency = if first {
            f64::NAN
        } else {
            2.0 * (self.ball_ball - c0) as f64 / (sim.len() as f64 * (time - t0))
        };
        let pressure = match self.volume() {
            Some(v) if !first => {
                let n = N as f64;
                m.kinetic / (n * v) + self.virial / (n * v * (time - t0))
            }
            _ => f64::NAN,
        };
        self.rows.push(Row {
            time,
            contacts: sim.contacts(),
            t_tr,
            t_rot,
            energy: sim.energy(),
            frequency,
            lost: self.lost,
            injected: self.injected,
            pressure,
            a2: m.a2,
            msd: squares.msd,
            msd_cm: squares.msd_cm,
            species: if self.species > 1 {
                m.species
            } else {
                Vec::new()
            },
            msd_species: if self.species > 1 {
                squares.species_cm
            } else {
                Vec::new()
            },
            pair_lost: self
                .pairs
                .as_ref()
                .map_or_else(Vec::new, |p| p.lost.clone()),
            pair_contacts: self
                .pairs
                .as_ref()
                .map_or_else(Vec::new, |p| p.contacts.clone()),
        });
        self.last = (time, self.ball_ball);
        self.virial = 0.0;
        // The next multiple of `every` after `time`.
        self.next = ((time / self.every).floor() + 1.0) * self.every;
    }

    /// Names the pairs' columns by the species' `names` (in species order; [`pair_names`]:
    /// `species<i>` unless every name is plain and distinct). Without it they are named
    /// `species<i>`, the scene's name of an unnamed species.
    pub fn with_species_names(mut self, names: &[String]) -> Sampler {
        assert_eq!(names.len(), self.species, "a name for every species");
        self.pair_names = pair_names(names);
        self
    }

    /// The rows so far.
    pub fn rows(&self) -> &[Row] {
        &self.rows
    }

    /// Samples the pair correlation `g(r)` of the balls' centres at every later row (not the
    /// first, taken by [`Sampler::start`]), in
    /// `bins` bins of `r` in `[0, r_max]` ([`crate::pair_correlation`]): only in a box
    /// periodic on every axis without obstacles or boundaries (as the pressure), with `r_max`
    /// at most half the shortest side (the nearest image only).
    pub fn with_pair_correlation(mut self, r_max: f64, bins: usize) -> Result<Sampler, String> {
        if !self.periodic {
            return Err(
                "the pair correlation needs a box periodic on every axis, without \
                        obstacles or boundaries"
                    .into(),
            );
        }
        self.pair_correlation = Some(PairCorrelation::new(r_max, bins, &self.sides)?);
        Ok(self)
    }

    /// Estimates the self-diffusion coefficient from the rows' displacements in blocks of
    /// `block` of simulated time from the first row at or after `from` (the start's row too,
    /// when called right after [`Sampler::start`])
    /// ([`crate::self_diffusion`]); any box (the displacements are unwrapped and taken about
    /// the centre of mass).
    pub fn with_self_diffusion(mut self, block: f64, from: f64) -> Result<Sampler, String> {
        if block < 4.0 * self.every {
            return Err(format!(
                "the block ({block}) must be at least 4 sampling intervals ({}): its last \
                 four fifths are fitted",
                4.0 * self.every
            ));
        }
        if self.displacements.balls() < 2 {
            return Err(
                "needs at least two balls: the displacements are measured about the \
                        centre of mass, which one ball is, so its D would be 0 by construction"
                    .into(),
            );
        }
        let mut d = SelfDiffusion::new(self.dim, block, from)?;
        // The start's row, taken before: every displacement is zero there.
        if let [start] = self.rows.as_slice() {
            d.sample(
                start.time,
                &vec![0.0; self.dim * self.displacements.balls()],
            );
        }
        self.self_diffusion = Some(d);
        Ok(self)
    }

    /// The self-diffusion blocks so far, if asked for ([`Sampler::with_self_diffusion`]).
    pub fn self_diffusion(&self) -> Option<&SelfDiffusion> {
        self.self_diffusion.as_ref()
    }

    /// The box's volume when it is periodic (`periodic`), else `None` (the pressure is `NaN`).
    fn volume(&self) -> Option<f64> {
        self.periodic.then(|| self.sides.iter().product())
    }

    /// The pair correlation sampled so far, if asked for ([`Sampler::with_pair_correlation`]).
    pub fn pair_correlation(&self) -> Option<&PairCorrelation> {
        self.pair_correlation.as_ref()
    }

    /// The columns of a row, in the order of [`Row::values`]: name and unit, in the scene's
    /// units of mass `M`, length `L` and time `T` (`1` a count or a pure number). The CSV's
    /// header, the Parquet table's columns and the Python package's arrays share these names:
    /// `time`, `contacts`, `T_tr`, `T_rot`, `energy`, `collision_frequency`, `lost_KIND`
    /// ([`KINDS`]), `injected`, `pressure`, `a2`, `msd`, `msd_cm`, and in a mixture `T_tr_s`, `T_rot_s` for each species
    /// index `s`, then `msd_cm_s` for each, then `lost_ball_ball_{a}-{b}` for each unordered
    /// pair of species and `contacts_{a}-{b}` for each ([`crate::pair_losses`],
    /// [`Sampler::with_species_names`]).
    pub fn columns(&self) -> Vec<(String, String)> {
        let mut c: Vec<(String, String)> = [
            ("time", "T"),
            ("contacts", "1"),
            ("T_tr", ENERGY),
            ("T_rot", ENERGY),
            ("energy", ENERGY),
            ("collision_frequency", "T^-1"),
        ]
        .iter()
        .map(|&(a, b)| (a.to_string(), b.to_string()))
        .collect();
        c.extend(KINDS.iter().map(|k| (format!("lost_{k}"), ENERGY.into())));
        c.push(("injected".into(), ENERGY.into()));
        // Force per (n-1)-area: M L^(2-n) T^-2.
        let pressure = match 2 - self.dim as i64 {
            0 => "M T^-2".to_string(),
            p => format!("M L^{p} T^-2"),
        };
        c.push(("pressure".into(), pressure));
        c.push(("a2".into(), "1".into()));
        c.push(("msd".into(), "L^2".into()));
        c.push(("msd_cm".into(), "L^2".into()));
        if self.species > 1 {
            for s in 0..self.species {
                c.push((format!("T_tr_{s}"), ENERGY.into()));
                c.push((format!("T_rot_{s}"), ENERGY.into()));
            }
            for s in 0..self.species {
                c.push((format!("msd_cm_{s}"), "L^2".into()));
            }
            for p in &self.pair_names {
                c.push((format!("lost_ball_ball_{p}"), ENERGY.into()));
            }
            for p in &self.pair_names {
                c.push((format!("contacts_{p}"), "1".into()));
            }
        }
        c
    }

    /// The rows as CSV, one header line naming each column with its units
    /// ([`Sampler::columns`]), numbers in Rust's shortest round-trip form.
    pub fn csv(&self) -> String {
        let header: Vec<String> = self
            .columns()
            .iter()
            .map(|(n, u)| format!("{n} [{u}]"))
            .collect();
        let mut text = header.join(",") + "\n";
        for r in &self.rows {
            let values: Vec<String> = r.values().iter().map(f64::to_string).collect();
            text.push_str(&values.join(","));
            text.push('\n');
        }
        text
    }
}

/// The pairs' names of `species` species named `species<i>` ([`pair_names`]).
fn unnamed(species: usize) -> Vec<String> {
    pair_names(
        &(0..species)
            .map(|i| format!("species{i}"))
            .collect::<Vec<_>>(),
    )
}
