//! Lyapunov exponents of a scene run by the engine (`noslip-sim`), whose events give the
//! reference trajectory:
//!
//! - [`qr`]: the spectrum (or its `k` largest exponents) from `k` tangent vectors carried by
//!   the tangent maps ([`crate::tangent`]) and re-orthonormalised by Gram-Schmidt every few
//!   contacts; exponent `i` is the mean growth rate of the `i`-th diagonal entry of `R`.
//! - [`two_trajectory`]: the largest exponent from a second run started `d0` away and pulled
//!   back to distance `d0` every few contacts (Benettin's method): an independent check, with
//!   no tangent map at all.
//!
//! Both report per unit time and per contact (all contacts of the scene), with the standard
//! error over blocks ([`stats`]) after a warm-up block that is not measured.
//!
//! [`qr_interruptible`] and [`two_trajectory_interruptible`] take an [`Interrupted`] hook,
//! asked before every contact (a front end's Ctrl-C: Python checks its signals there); the
//! run then ends with [`LyapunovError::Interrupted`] and no result.

pub mod cost;
mod qr;
pub mod stats;
pub mod touch;
mod two;

pub use qr::{choice, qr, qr_interruptible};
pub use two::{two_trajectory, two_trajectory_interruptible, D0};

/// A caller's request to stop a long run: asked before every contact, `true` ends the run
/// with [`LyapunovError::Interrupted`]. It is called millions of times a second, so it must
/// be cheap (a counter, a clock read every few thousand calls).
pub type Interrupted<'a> = &'a (dyn Fn() -> bool + Sync);

/// The hook of a run that is never interrupted.
pub fn never() -> bool {
    false
}

use crate::law::Law;
use collision_core::{Ball, BodyState, Generated, Kernel};
use noslip_sim::{Event, Setup, SetupError, Simulation, Step};
use serde::Serialize;
use stats::Estimate;
use std::fmt;

/// What a Lyapunov run is asked for.
#[derive(Clone, Debug)]
pub struct Options {
    /// Contacts to run (warm-up included).
    pub events: u64,
    /// How many exponents (the largest); `None`: the default of [`cost::choose`] (all of
    /// them when they fit its memory and work budget).
    pub k: Option<usize>,
    /// Measured blocks (after one warm-up block of the same length).
    pub blocks: usize,
    /// Seed of the initial tangent vectors or perturbation.
    pub seed: u64,
    /// The law of every contact, overriding the scene's per-contact kinds (`--contact`);
    /// `None`: each contact follows its own kind from the scene ([`noslip_sim::Table`]'s
    /// boundaries, obstacles, box and ball pairs), in the trajectory and in the tangent map.
    pub law: Option<Law>,
    /// Contacts between re-orthonormalisations (or renormalisations); `None`: the method's
    /// default.
    pub every: Option<u64>,
}

/// One row of the running estimate.
#[derive(Clone, Debug, Serialize)]
pub struct Running {
    /// Contacts so far (warm-up included).
    pub contacts: u64,
    /// Time so far.
    pub time: f64,
    /// The exponents per unit time over the measured part so far.
    pub exponents: Vec<f64>,
}

/// The result of a Lyapunov run.
#[derive(Clone, Debug, Serialize)]
pub struct Spectrum {
    /// `"qr"` or `"two-trajectory"`.
    pub method: &'static str,
    /// The override of every contact's law, if any (`None`: the scene's kinds).
    pub law: Option<Law>,
    /// The phase-space dimension `balls (2n + S)`.
    pub dimension: usize,
    /// Contacts run, and of them the warm-up.
    pub contacts: u64,
    /// Warm-up contacts (not measured).
    pub warmup: u64,
    /// Contacts between re-orthonormalisations.
    pub every: u64,
    /// Time of the measured part.
    pub time: f64,
    /// Exponents per unit time, largest first, with their errors.
    pub per_time: Vec<Estimate>,
    /// Exponents per contact.
    pub per_contact: Vec<Estimate>,
    /// The sum of the exponents computed, per unit time.
    pub sum: Estimate,
    /// The running estimate.
    pub running: Vec<Running>,
}

/// Why a Lyapunov run could not be made.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum LyapunovError {
    /// The engine refused the setup.
    Setup(SetupError),
    /// A contact followed a rough law (`e < 1` or `|beta| < 1`), which has no tangent map
    /// here.
    Rough,
    /// `k` is not in `1..=dimension`.
    K {
        /// The `k` asked for.
        k: usize,
        /// The phase-space dimension.
        dimension: usize,
    },
    /// The `k` tangent vectors would take more than [`cost::MAX_TANGENT_BYTES`].
    Memory {
        /// The `k` asked for (or the default's 1).
        k: usize,
        /// The phase-space dimension.
        dimension: usize,
        /// The memory they need, `8 k d` bytes.
        bytes: u64,
    },
    /// Blocks not in `1..=`[`MAX_BLOCKS`].
    Blocks {
        /// The blocks asked for.
        blocks: usize,
    },
    /// Fewer contacts than twice the blocks + 1.
    Events {
        /// The contacts asked for.
        events: u64,
        /// The blocks asked for.
        blocks: usize,
    },
    /// `every` (asked for) is longer than a block, so some blocks would get no
    /// re-orthonormalisation, no growth and no estimate.
    Every {
        /// The contacts between re-orthonormalisations asked for.
        every: u64,
        /// The block length, the most `every` may be.
        most: u64,
    },
    /// The run ran out of contacts.
    NoContact(String),
    /// The tangent vectors stopped being finite between two re-orthonormalisations more than
    /// one contact apart: they grew by more than about `e^354` (their squares, in the norms
    /// and dot products of Gram-Schmidt, pass the largest `f64`, about `e^709`), or met a
    /// grazing contact.
    Overflow {
        /// The contact of the last re-orthonormalisation (0: the start).
        from: u64,
        /// The contact at which it was found.
        at: u64,
    },
    /// A growth was not finite: a grazing contact (`nu . v_rel = 0`), where the tangent map
    /// is singular, or a collapse of the perturbation.
    Singular {
        /// The contact at which it was found.
        at: u64,
    },
    /// The two trajectories of the two-trajectory method met different contacts.
    Diverged {
        /// The contact at which it was found.
        at: u64,
    },
    /// The caller's [`Interrupted`] hook asked the run to stop.
    Interrupted,
}

impl fmt::Display for LyapunovError {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        match self {
            LyapunovError::Setup(e) => write!(f, "{e}"),
            LyapunovError::Rough => write!(
                f,
                "a contact follows a rough law (e < 1 or |beta| < 1), which has no tangent map \
                 here: Lyapunov spectra take no-slip and smooth contacts (or --contact for \
                 every contact)"
            ),
            LyapunovError::K { k, dimension } => {
                write!(f, "--k: must be in 1..={dimension} (the phase-space dimension), got {k}")
            }
            LyapunovError::Memory {
                k,
                dimension,
                bytes,
            } => write!(
                f,
                "--k: {k} tangent vectors of dimension {dimension} need {} ({bytes} bytes, \
                 8 k d), beyond the cap of {}: at most {} fit",
                cost::show_bytes(*bytes),
                cost::show_bytes(cost::MAX_TANGENT_BYTES),
                cost::MAX_TANGENT_BYTES / 8 / (*dimension).max(1) as u64
            ),
            LyapunovError::Blocks { blocks } => write!(
                f,
                "--blocks: must be in 1..={MAX_BLOCKS} (more blocks only shorten each block), \
                 got {blocks}"
            ),
            LyapunovError::Events { events, blocks } => write!(
                f,
                "--events: {events} contacts cannot make a warm-up and {blocks} blocks: at least {} \
                 are needed",
                (*blocks as u64 + 1) * 2
            ),
            LyapunovError::Every { every, most } => write!(
                f,
                "--every: {every} contacts between re-orthonormalisations would leave blocks \
                 without one (no growth, no error estimate): at most {most}, the contacts of a \
                 block (the measured contacts over --blocks)"
            ),
            LyapunovError::NoContact(why) => write!(f, "the run stopped: {why}"),
            LyapunovError::Overflow { from, at } => write!(
                f,
                "--every: the tangent vectors stopped being finite between contacts {from} and \
                 {at}, {} contacts without re-orthonormalisation: they overflow when they grow \
                 by more than about e^354 in between (their squares pass the largest f64); \
                 renormalise more often (a grazing contact, nu . v_rel = 0, also does this: if \
                 --every 1 fails too, that is the cause)",
                at - from
            ),
            LyapunovError::Singular { at } => write!(
                f,
                "the tangent dynamics became singular near contact {at} (a grazing contact, \
                 nu . v_rel = 0): a run of another length or scene avoids it"
            ),
            LyapunovError::Diverged { at } => write!(
                f,
                "the two trajectories met different contacts near contact {at}: renormalise more \
                 often (--every)"
            ),
            LyapunovError::Interrupted => write!(f, "interrupted"),
        }
    }
}

impl std::error::Error for LyapunovError {}

/// The next contact of the engine. A quiet notice is passed over unless the run should stop
/// there by the rule `simulate` stops by ([`noslip_sim::run::quiet_stop`]: the reach of
/// [`noslip_sim::run::MAX_QUIET_BOX_LENGTHS`] spent, or a periodic gas too dilute to meet
/// within it), so a flight along a corridor cannot hold a run for ever. `interrupted` is
/// asked first, and again at each quiet notice.
fn next_contact<const N: usize, const S: usize, K: noslip_sim::PairKernels<f64, N, S>>(
    sim: &mut Simulation<N, S, K>,
    species: &[Ball<f64>],
    interrupted: Interrupted<'_>,
) -> Result<Event<N, S>, LyapunovError> {
    loop {
        if interrupted() {
            return Err(LyapunovError::Interrupted);
        }
        match sim.step(f64::INFINITY) {
            Step::Contact(e) => return Ok(e),
            Step::Never(why) => return Err(LyapunovError::NoContact(why.to_string())),
            Step::LeftTable(left) => return Err(LyapunovError::NoContact(left.to_string())),
            Step::Quiet { box_lengths } => {
                if let Some(why) = noslip_sim::run::quiet_stop(sim, species, box_lengths) {
                    return Err(LyapunovError::NoContact(why));
                }
            }
            Step::Until => {}
        }
    }
}

/// The most measured blocks a run takes. Block statistics need blocks long compared with the
/// correlation time of the growth, so a few tens are the usual choice; the cap keeps the
/// per-block sums (`(k + 2)` numbers a block) to what the run itself holds.
pub const MAX_BLOCKS: usize = 10_000;

/// The measured plan: the warm-up and the block of each contact.
#[derive(Clone, Copy, Debug)]
struct Plan {
    events: u64,
    warmup: u64,
    blocks: usize,
}

impl Plan {
    fn new(o: &Options) -> Result<Self, LyapunovError> {
        if !(1..=MAX_BLOCKS).contains(&o.blocks) {
            return Err(LyapunovError::Blocks { blocks: o.blocks });
        }
        if o.events < 2 * (o.blocks as u64 + 1) {
            return Err(LyapunovError::Events {
                events: o.events,
                blocks: o.blocks,
            });
        }
        Ok(Plan {
            events: o.events,
            warmup: o.events / (o.blocks as u64 + 1),
            blocks: o.blocks,
        })
    }

    /// The contacts of the shortest block, `floor((events - warmup) / blocks)` (at least 1,
    /// by [`Plan::new`]'s rule): any `every` consecutive contacts with `every` at most this
    /// hold a multiple of `every`, so each block gets a re-orthonormalisation.
    fn block_len(&self) -> u64 {
        (self.events - self.warmup) / self.blocks as u64
    }

    /// The contacts between re-orthonormalisations (or renormalisations): `asked`, refused
    /// beyond [`Plan::block_len`], else `default` shortened to it. With more, blocks got no
    /// growth and their estimates were 0/0 (the errors printed `± NaN`).
    fn every(&self, asked: Option<u64>, default: u64) -> Result<u64, LyapunovError> {
        let most = self.block_len().max(1);
        match asked {
            Some(every) if every > most => Err(LyapunovError::Every { every, most }),
            Some(every) => Ok(every.max(1)),
            None => Ok(default.clamp(1, most)),
        }
    }

    /// The block of contact `c` (1-based), `None` in the warm-up.
    fn block(&self, c: u64) -> Option<usize> {
        (c > self.warmup).then(|| {
            let measured = self.events - self.warmup;
            (((c - self.warmup - 1) * self.blocks as u64) / measured) as usize
        })
    }
}

/// The kernels a run needs: the f64 ones for the engine, the dual ones for the tangent map.
pub trait Dim<const N: usize, const S: usize>:
    Kernel<f64, N, S> + Kernel<crate::Dual<f64>, N, S>
{
}
impl<const N: usize, const S: usize> Dim<N, S> for Generated where
    Generated: Kernel<f64, N, S> + Kernel<crate::Dual<f64>, N, S>
{
}

/// A body's phase-space coordinates `[x, u, U]` appended to `out`.
fn push_state<const N: usize, const S: usize>(
    out: &mut Vec<f64>,
    x: &[f64; N],
    s: &BodyState<f64, N, S>,
) {
    out.extend_from_slice(x);
    out.extend_from_slice(&s.velocity);
    out.extend_from_slice(&s.spin);
}

/// The setup with every contact's kind set to `law` when there is an override: the box, the
/// obstacles, the table's boundaries and the ball pairs. The engine applies the smooth map
/// itself to smooth contacts and calls its kernels for no-slip ones, so after this the
/// trajectory and the tangent map ([`Simulation::contact_kind`]) follow the same law.
pub fn overridden<const N: usize, const S: usize>(
    mut setup: Setup<N, S>,
    law: Option<Law>,
) -> Setup<N, S> {
    if let Some(law) = law {
        let kind = law.kind();
        let table = &mut setup.table;
        table.box_contact = kind;
        table.ball_contact = kind;
        table.pair_contact = Default::default();
        table.obstacle_contact = vec![kind; setup.obstacles.len()];
        for b in &mut table.boundaries {
            b.contact = kind;
        }
    }
    setup
}
