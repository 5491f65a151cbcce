//! Granular-gas observables sampled over a run (docs/granular.md): the translational and
//! rotational granular temperatures, the collision frequency and the kinetic energy lost per
//! contact kind, written as CSV with the units in the header.
//!
//! With `N_b` balls in R^n, `S = n(n-1)/2`, masses `m_i` and moments of inertia `I_i = 2 m_i
//! lambda_i` (the project's convention: a ball's kinetic energy is `1/2 m |u|^2 + 1/2 I
//! sum_{k<l} U_kl^2`, docs/derivation.md), the temperatures per degree of freedom are
//!
//! ```text
//! T_tr  = sum_i m_i |u_i - V|^2 / (n (N_b - 1)),
//! T_rot = sum_i I_i sum_{k<l} (U_i)_kl^2 / (S N_rot),
//! ```
//!
//! `V = sum_i m_i u_i / sum_i m_i` the centre of mass's velocity: its motion is taken out
//! (conserved in a periodic box, it is no thermal motion), leaving `n (N_b - 1)` translational
//! degrees of freedom; `N_rot` the balls with `lambda > 0` (a point mass has no rotational
//! degrees of freedom).
//! The collision frequency between two samples is `2 C_bb / (N_b dt)`: ball-ball contacts
//! `C_bb` in the interval, two balls each, per ball and unit time. The energy lost by a
//! contact is the kinetic energy of its balls before minus after.
//!
//! A row is written at the first contact at or after each multiple of the interval `every`
//! (and one at the start): the row's time is that contact's, and the state is the one just
//! after it (the velocities are constant between contacts, so the row is exact at its time).

use crate::observe::energy_of;
use crate::{Contact, Event, PairKernels, Simulation};
use collision_core::Ball;

/// The contact kinds the losses are kept by, in the order of [`Row::lost`]: ball-ball,
/// ball-wall (the box), ball-obstacle, ball-boundary (the table's other boundaries).
pub const KINDS: [&str; 4] = ["ball_ball", "ball_wall", "ball_obstacle", "ball_boundary"];

/// The columns of a row, in order: name and unit, in the scene's units of mass `M`, length
/// `L` and time `T` (`1` a count). The CSV's header, the Parquet table's columns and the
/// Python package's arrays share these names.
pub const COLUMNS: [(&str, &str); 10] = [
    ("time", "T"),
    ("contacts", "1"),
    ("T_tr", "M L^2 T^-2"),
    ("T_rot", "M L^2 T^-2"),
    ("energy", "M L^2 T^-2"),
    ("collision_frequency", "T^-1"),
    ("lost_ball_ball", "M L^2 T^-2"),
    ("lost_ball_wall", "M L^2 T^-2"),
    ("lost_ball_obstacle", "M L^2 T^-2"),
    ("lost_ball_boundary", "M L^2 T^-2"),
];

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
}

impl Row {
    /// The row's numbers in the order of [`COLUMNS`] (`contacts` as a double: exact below
    /// `2^53`).
    pub fn values(&self) -> [f64; COLUMNS.len()] {
        let [a, b, c, d] = self.lost;
        [
            self.time,
            self.contacts as f64,
            self.t_tr,
            self.t_rot,
            self.energy,
            self.frequency,
            a,
            b,
            c,
            d,
        ]
    }
}

/// `[T_tr, T_rot]` of the balls now (module docs).
pub fn temperatures<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
    sim: &Simulation<N, S, K>,
    species: &[Ball<f64>],
) -> [f64; 2] {
    let (mut mass, mut p) = (0.0, [0.0; N]);
    for i in 0..sim.len() {
        let m = 1.0 / species[sim.species_of(i)].inv_mass;
        mass += m;
        for (pk, uk) in p.iter_mut().zip(&sim.state(i).velocity) {
            *pk += m * uk;
        }
    }
    let v = p.map(|pk| pk / mass);
    let (mut tr, mut rot, mut rotating) = (0.0, 0.0, 0usize);
    for i in 0..sim.len() {
        let b = &species[sim.species_of(i)];
        let m = 1.0 / b.inv_mass;
        let s = sim.state(i);
        tr += m * (0..N).map(|k| (s.velocity[k] - v[k]).powi(2)).sum::<f64>();
        if b.lambda() > 0.0 {
            rot += 2.0 * m * b.lambda() * s.spin.iter().map(|x| x * x).sum::<f64>();
            rotating += 1;
        }
    }
    [
        tr / (N * (sim.len().max(1) - 1)) as f64,
        rot / (S * rotating) as f64,
    ]
}

/// The kinetic energy contact `e` of `sim` took away: its balls' energy before minus after.
pub fn lost<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
    e: &Event<N, S>,
    sim: &Simulation<N, S, K>,
    species: &[Ball<f64>],
) -> f64 {
    let balls = match e.contact {
        Contact::Ball { i, j } => vec![i, j],
        Contact::Wall { i, .. } | Contact::Obstacle { i, .. } | Contact::Boundary { i, .. } => {
            vec![i]
        }
    };
    let mut sum = 0.0;
    for (k, &i) in balls.iter().enumerate() {
        let b = &species[sim.species_of(i)];
        sum += energy_of(b, &e.pre[k]) - energy_of(b, &e.post[k]);
    }
    sum
}

/// Rows taken over a run: [`Sampler::start`], then [`Sampler::contact`] after each contact.
#[derive(Clone, Debug)]
pub struct Sampler {
    every: f64,
    next: f64,
    /// Ball-ball contacts so far, and at the last row: `(time, ball-ball contacts)`.
    ball_ball: u64,
    last: (f64, u64),
    lost: [f64; 4],
    rows: Vec<Row>,
}

impl Sampler {
    /// A sampler with a row every `every` (`> 0`) of simulated time, its first row now.
    pub fn start<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
        every: f64,
        sim: &Simulation<N, S, K>,
        species: &[Ball<f64>],
    ) -> Sampler {
        let mut s = Sampler {
            every,
            next: sim.now(),
            ball_ball: 0,
            last: (sim.now(), 0),
            lost: [0.0; 4],
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
        let k = match e.contact {
            Contact::Ball { .. } => 0,
            Contact::Wall { .. } => 1,
            Contact::Obstacle { .. } => 2,
            Contact::Boundary { .. } => 3,
        };
        self.ball_ball += u64::from(k == 0);
        self.lost[k] += lost(e, sim, species);
        if e.time >= self.next {
            self.row(sim, species);
        }
    }

    fn row<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
        &mut self,
        sim: &Simulation<N, S, K>,
        species: &[Ball<f64>],
    ) {
        let time = sim.now();
        let [t_tr, t_rot] = temperatures(sim, species);
        let (t0, c0) = self.last;
        let frequency = if self.rows.is_empty() {
            f64::NAN
        } else {
            2.0 * (self.ball_ball - c0) as f64 / (sim.len() as f64 * (time - t0))
        };
        self.rows.push(Row {
            time,
            contacts: sim.contacts(),
            t_tr,
            t_rot,
            energy: sim.energy(),
            frequency,
            lost: self.lost,
        });
        self.last = (time, self.ball_ball);
        // The next multiple of `every` after `time`.
        self.next = ((time / self.every).floor() + 1.0) * self.every;
    }

    /// The rows so far.
    pub fn rows(&self) -> &[Row] {
        &self.rows
    }

    /// The rows as CSV, one header line naming each column with its units ([`COLUMNS`]:
    /// temperatures and energies `M L^2 T^-2`), numbers in Rust's shortest round-trip form.
    pub fn csv(&self) -> String {
        let header: Vec<String> = COLUMNS.iter().map(|(n, u)| format!("{n} [{u}]")).collect();
        let mut text = header.join(",") + "\n";
        for r in &self.rows {
            let values: Vec<String> = r.values().iter().map(f64::to_string).collect();
            text.push_str(&values.join(","));
            text.push('\n');
        }
        text
    }
}
