//! A search for the periodic orbits of a scene's table, as `noslip orbits` and
//! `noslip.orbits` run it: starts from given states, a 2D grid or the scene's ball after its
//! first contact; Newton from each; the orbits merged; and for each given start the exact
//! return map where the table and the start are rational.

use super::{exact, exact_start, first_contact, grid, merge, nearest, newton_within, project};
use super::{Budget, ExactReturn, Miss, Orbit};
use crate::law::Law;
use crate::Dual;
use collision_core::{BodyState, Exact, Generated, Kernel, Scalar};
use noslip_scene::Scene;
use serde::Serialize;
use std::fmt;

/// The most starts a grid may make.
pub const MAX_STARTS: usize = 100_000;
/// The longest period.
pub const MAX_PERIOD: usize = 1000;
/// The default bound on the contacts a search follows ([`Search::max_contacts`]): one to two
/// minutes of the 2D search (measured 0.5-0.9 million contacts a second, Newton's steps
/// included, in a release build; docs/dynamics.md).
pub const DEFAULT_MAX_CONTACTS: u64 = 50_000_000;

/// What a search is asked for.
#[derive(Clone, Debug)]
pub struct Search {
    /// The period `K` (contacts per orbit), in `1..=MAX_PERIOD`.
    pub period: usize,
    /// Starts `[x, u, U]` (`2n + S` numbers each), moved along the normal onto the nearest
    /// boundary.
    pub from: Vec<Vec<Exact>>,
    /// 2D: `M` for `M^3` starts per boundary (positions x angles x spins).
    pub grid: Option<usize>,
    /// The law of every contact, overriding the scene's per-boundary kinds; `None`: each
    /// boundary's kind from the scene.
    pub law: Option<Law>,
    /// The most contacts the search follows (each evaluation of `P^K` with its derivative
    /// follows `K`), at least 1; the search stops there and says so ([`Report::stopped`]).
    pub max_contacts: u64,
}

/// How far a search has gone: reported after each start.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Progress {
    /// Starts done.
    pub done: usize,
    /// Starts in all.
    pub starts: usize,
    /// Orbits found so far (each once).
    pub orbits: usize,
    /// Contacts followed so far.
    pub contacts: u64,
}

/// The orbits found (as `orbits.json`).
#[derive(Clone, Debug, Serialize)]
pub struct Report {
    /// The period.
    pub period: usize,
    /// Starts made.
    pub starts: usize,
    /// Starts run to their end (all of them unless the search [`stopped`](Report::stopped)).
    pub tried: usize,
    /// Starts run to their end that gave no orbit.
    pub misses: usize,
    /// Contacts followed (each evaluation of `P^K` follows `K`).
    pub contacts: u64,
    /// Why the search stopped before trying every start (its bound on contacts), if it did.
    pub stopped: Option<String>,
    /// The orbits, each once.
    pub orbits: Vec<Orbit>,
    /// Per given start, the exact return map (`None` where a contact time or the start's
    /// projection is irrational).
    pub exact: Vec<Option<ExactReturn>>,
}

/// Why a search could not run; each names the input at fault.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum SearchError {
    /// The period is out of range.
    Period(String),
    /// Start `index` of [`Search::from`] is bad.
    From {
        /// Its index.
        index: usize,
        /// Why.
        message: String,
    },
    /// The grid is bad.
    Grid(String),
    /// The bound on contacts is bad.
    MaxContacts(String),
    /// The scene is not a one-ball table, or its ball never touches it (the message starts
    /// with the scene's origin).
    Scene(String),
    /// The caller's hook asked the search to stop ([`search_interruptible`]).
    Interrupted,
}

impl SearchError {
    /// The input at fault (`period`, `from[2]`, `grid`), `None` for the scene.
    pub fn field(&self) -> Option<String> {
        match self {
            SearchError::Period(_) => Some("period".into()),
            SearchError::From { index, .. } => Some(format!("from[{index}]")),
            SearchError::Grid(_) => Some("grid".into()),
            SearchError::MaxContacts(_) => Some("max-contacts".into()),
            SearchError::Scene(_) | SearchError::Interrupted => None,
        }
    }

    /// What is wrong with it.
    pub fn message(&self) -> &str {
        match self {
            SearchError::Period(m)
            | SearchError::Grid(m)
            | SearchError::MaxContacts(m)
            | SearchError::Scene(m) => m,
            SearchError::From { message, .. } => message,
            SearchError::Interrupted => "interrupted",
        }
    }
}

impl fmt::Display for SearchError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.field() {
            Some(field) => write!(f, "{field}: {}", self.message()),
            None => f.write_str(self.message()),
        }
    }
}

impl std::error::Error for SearchError {}

/// Run the search on `scene` (a one-ball table in R^N).
pub fn search<const N: usize, const S: usize>(
    scene: &Scene,
    ask: &Search,
) -> Result<Report, SearchError>
where
    Generated: Kernel<f64, N, S>
        + Kernel<Dual<f64>, N, S>
        + Kernel<Exact, N, S>
        + Kernel<Dual<Exact>, N, S>,
{
    search_observed::<N, S>(scene, ask, &mut |_| {})
}

/// [`search`], calling `progress` after each start.
pub fn search_observed<const N: usize, const S: usize>(
    scene: &Scene,
    ask: &Search,
    progress: &mut dyn FnMut(Progress),
) -> Result<Report, SearchError>
where
    Generated: Kernel<f64, N, S>
        + Kernel<Dual<f64>, N, S>
        + Kernel<Exact, N, S>
        + Kernel<Dual<Exact>, N, S>,
{
    search_interruptible::<N, S>(scene, ask, progress, &|| false)
}

/// [`search_observed`], asking `interrupted` before each start's exact return map and
/// before each start's Newton search ([`SearchError::Interrupted`] when it says stop: a
/// front end's Ctrl-C). One start's work between two asks is bounded by `period` and
/// Newton's steps, not by the number of starts.
pub fn search_interruptible<const N: usize, const S: usize>(
    scene: &Scene,
    ask: &Search,
    progress: &mut dyn FnMut(Progress),
    interrupted: &(dyn Fn() -> bool + Sync),
) -> Result<Report, SearchError>
where
    Generated: Kernel<f64, N, S>
        + Kernel<Dual<f64>, N, S>
        + Kernel<Exact, N, S>
        + Kernel<Dual<Exact>, N, S>,
{
    if ask.max_contacts == 0 {
        return Err(SearchError::MaxContacts("must be at least 1, got 0".into()));
    }
    if !(1..=MAX_PERIOD).contains(&ask.period) {
        return Err(SearchError::Period(format!(
            "must be in 1..={MAX_PERIOD}, got {}",
            ask.period
        )));
    }
    let one = super::scene::table::<N, S>(scene, ask.law).map_err(SearchError::Scene)?;
    let f = &one.float;
    let len = 2 * N + S;
    let mut starts: Vec<Vec<f64>> = Vec::new();
    let mut exact_reports = Vec::new();
    for (index, z) in ask.from.iter().enumerate() {
        let bad = |message: String| SearchError::From { index, message };
        if z.len() != len {
            return Err(bad(format!(
                "has {} numbers, expected 2n + S = {len} (x, u, then the spin entries U_ij, i < j)",
                z.len()
            )));
        }
        let zf: Vec<f64> = z.iter().map(Scalar::to_f64).collect();
        // The search runs in f64 from the start's nearest f64 values.
        if let Some(k) = zf.iter().position(|x| !x.is_finite()) {
            return Err(bad(format!(
                "number {k} is beyond the f64 range (|x| < 1.8e308)"
            )));
        }
        let xf: [f64; N] = std::array::from_fn(|k| zf[k]);
        let (b, _) = nearest(f, &xf);
        let (_, nu) = project(f, b, &xf);
        let inward: f64 = zf[N..2 * N].iter().zip(&nu).map(|(u, n)| u * n).sum();
        if inward <= 0.0 {
            return Err(bad(format!(
                "the velocity must point into the table (u . nu > 0) at its nearest boundary {b}"
            )));
        }
        starts.push(zf);
        if interrupted() {
            return Err(SearchError::Interrupted);
        }
        exact_reports.push(one.exact.as_ref().and_then(|table| {
            exact_start::<N, S>(table, z).and_then(|s| exact(table, &s, ask.period).ok())
        }));
    }
    if let Some(m) = ask.grid {
        let per = f.boundaries.len().saturating_mul(m.saturating_pow(3));
        if m == 0 || per > MAX_STARTS {
            return Err(SearchError::Grid(format!(
                "must be at least 1 and make at most {MAX_STARTS} starts (M^3 per boundary), got {m}"
            )));
        }
        // The box, or the region a table without one is drawn in.
        let (lo, size) = noslip_sim::setup::extent::<N>(scene);
        let bounds: [(f64, f64); N] = std::array::from_fn(|k| match f.period[k] {
            Some(l) => (0.0, l),
            None => (lo[k] + f.ball.radius, lo[k] + size[k] - f.ball.radius),
        });
        starts.extend(grid(f, &bounds, m).ok_or_else(|| {
            SearchError::Grid(
                "starts on a grid are made in 2D only; give the starts instead".into(),
            )
        })?);
    }
    if ask.from.is_empty() && ask.grid.is_none() {
        let xf = one.x.clone().map(|v| v.to_f64());
        let sf = BodyState {
            velocity: one.state.velocity.clone().map(|v| v.to_f64()),
            spin: one.state.spin.clone().map(|v| v.to_f64()),
        };
        starts.push(first_contact(f, &xf, &sf).map_err(|e| {
            SearchError::Scene(format!(
                "{}: the ball never touches the table: {e}",
                scene.origin
            ))
        })?);
    }
    let mut found: Vec<Orbit> = Vec::new();
    let (mut misses, mut tried, mut stopped) = (0, 0, None);
    let mut budget = Budget::new(ask.max_contacts);
    for z in &starts {
        if interrupted() {
            return Err(SearchError::Interrupted);
        }
        match newton_within::<N, S>(f, z, ask.period, &mut budget) {
            Ok(o) => merge(f, &mut found, o),
            Err(Miss::Budget) => {
                stopped = Some(format!(
                    "the search followed {} contacts, its bound is {}: {tried} of {} starts were \
                     tried, the other {} were not",
                    budget.used,
                    ask.max_contacts,
                    starts.len(),
                    starts.len() - tried
                ));
                break;
            }
            Err(
                Miss::NoHit(_) | Miss::NoConvergence { .. } | Miss::LeftSection | Miss::Resting,
            ) => misses += 1,
        }
        tried += 1;
        progress(Progress {
            done: tried,
            starts: starts.len(),
            orbits: found.len(),
            contacts: budget.used,
        });
    }
    Ok(Report {
        period: ask.period,
        starts: starts.len(),
        tried,
        misses,
        contacts: budget.used,
        stopped,
        orbits: found,
        exact: exact_reports,
    })
}
