//! Runs every check for the chosen dimensions and variants and collects the results.

use crate::checks::identity::{self, Identity};
use crate::checks::rough::{self, RoughIdentity};
use crate::checks::sequence::{self, Limit};
use crate::checks::walton::{self, WaltonIdentity};
use crate::checks::{inertia, structure};
use crate::report::{CheckResult, Proof};
use crate::sample::SET_SIZE;
use crate::under_test::{generated, ExactKernel};
use collision_core::rng::Rng;
use collision_core::{Exact, ExactRelaxed, Generated, Kernel, RoughKernel, WaltonKernel};
use noslip_codegen::model::Variant;
use std::time::Instant;

/// The most random points per identity check a run takes: at the default 16 the
/// Schwartz-Zippel bound is already below `1e-35` for every no-slip and rough check, and below
/// `1e-37` for the Walton kernels' central identities (docs/verification.md §3b; their derived
/// sliding identities, of loose degree bounds, are weaker), and each point costs about a
/// sixteenth of the default run.
pub const MAX_POINTS: usize = 1024;

/// `points` if it is in `1..=`[`MAX_POINTS`] (0 would check nothing), else the reason, for
/// the caller to prefix with the option's name (`--points`, `--check`, `points`).
pub fn check_points(points: usize) -> Result<usize, String> {
    if (1..=MAX_POINTS).contains(&points) {
        Ok(points)
    } else {
        Err(format!("must be in 1..={MAX_POINTS}, got {points}"))
    }
}

/// How much to sample.
#[derive(Clone, Copy, Debug)]
pub struct Options {
    /// Random points per identity check.
    pub points: usize,
    /// Random configurations per structural check.
    pub configurations: usize,
    /// The seed of every random stream (each check derives its own from it).
    pub seed: u64,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            points: 16,
            configurations: 2,
            seed: 2026,
        }
    }
}

/// The Schwartz-Zippel bound `(degree / |S|)^points` on the probability that a false
/// identity passed.
pub fn sz_bound(degree: u64, points: usize) -> f64 {
    ((degree as f64) / (SET_SIZE as f64))
        .min(1.0)
        .powi(points as i32)
}

/// The number of checks [`run_dim`] performs for one dimension (for progress bars).
pub fn checks_per_dim() -> usize {
    Variant::ALL
        .iter()
        .map(|&v| {
            Identity::for_variant(v).len()
                + 2
                + RoughIdentity::for_variant(v).len()
                + WaltonIdentity::for_variant(v).len()
        })
        .sum::<usize>()
        + 3
}

/// The identity checks of the rough-ball kernels of `variant` (docs/derivation.md §15),
/// asking `interrupted` before each point (see [`run_interruptible`]).
pub fn rough_checks<const N: usize, const S: usize>(
    variant: Variant,
    opts: &Options,
    progress: &mut dyn FnMut(&CheckResult),
    interrupted: &dyn Fn() -> bool,
) -> Vec<CheckResult>
where
    Generated: RoughKernel<ExactRelaxed, N, S> + Kernel<ExactRelaxed, N, S>,
{
    RoughIdentity::for_variant(variant)
        .iter()
        .enumerate()
        .map(|(k, &check)| {
            let seed = opts.seed + 100 + k as u64;
            let (outcome, seconds) =
                timed(|| rough::run::<N, S>(variant, check, opts.points, seed, interrupted));
            let degree = rough::degree(N, variant, check);
            let r = identity_result(
                N,
                RoughIdentity::variant_name(variant),
                check.name(),
                opts.points,
                degree,
                outcome,
                seconds,
            );
            progress(&r);
            r
        })
        .collect()
}

/// The identity checks of the Walton kernels of `variant` (docs/derivation.md §15.1), on
/// each side of the sticking/sliding switch ([`walton`]), asking `interrupted` before each
/// point.
pub fn walton_checks<const N: usize, const S: usize>(
    variant: Variant,
    opts: &Options,
    progress: &mut dyn FnMut(&CheckResult),
    interrupted: &dyn Fn() -> bool,
) -> Vec<CheckResult>
where
    Generated: WaltonKernel<Exact, N, S>,
{
    WaltonIdentity::for_variant(variant)
        .iter()
        .enumerate()
        .map(|(k, &check)| {
            let seed = opts.seed + 200 + k as u64;
            let (outcome, seconds) =
                timed(|| walton::run::<N, S>(variant, check, opts.points, seed, interrupted));
            let degree = walton::degree(N, variant, check);
            let r = identity_result(
                N,
                WaltonIdentity::variant_name(variant),
                check.name(),
                opts.points,
                degree,
                outcome,
                seconds,
            );
            progress(&r);
            r
        })
        .collect()
}

/// The result of an identity check of `degree` at `points` random points: its
/// Schwartz-Zippel bound `(degree / SET_SIZE)^points` ([`sz_bound`]) and its outcome.
fn identity_result(
    dim: usize,
    variant: String,
    check: &str,
    points: usize,
    degree: u64,
    outcome: Result<(), String>,
    seconds: f64,
) -> CheckResult {
    CheckResult {
        dim,
        variant,
        check: check.into(),
        passed: outcome.is_ok(),
        points,
        proof: Proof::Identity {
            degree,
            set_size: SET_SIZE,
            bound: sz_bound(degree, points),
        },
        detail: outcome.err().unwrap_or_default(),
        seconds,
    }
}

fn timed<T>(f: impl FnOnce() -> T) -> (T, f64) {
    let start = Instant::now();
    let out = f();
    (out, start.elapsed().as_secs_f64())
}

/// The identity checks of one variant for a given kernel (the compiled one, or a corrupted
/// one in the verifier's own tests).
pub fn identity_checks<const N: usize, const S: usize>(
    kernel: &ExactKernel<N, S>,
    variant: Variant,
    opts: &Options,
    progress: &mut dyn FnMut(&CheckResult),
) -> Vec<CheckResult>
where
    Generated: Kernel<Exact, N, S> + Kernel<collision_core::ExactRelaxed, N, S>,
{
    identity_checks_interruptible(kernel, variant, opts, progress, &|| false)
}

/// [`identity_checks`], asking `interrupted` before each point (see [`run_interruptible`]).
fn identity_checks_interruptible<const N: usize, const S: usize>(
    kernel: &ExactKernel<N, S>,
    variant: Variant,
    opts: &Options,
    progress: &mut dyn FnMut(&CheckResult),
    interrupted: &dyn Fn() -> bool,
) -> Vec<CheckResult>
where
    Generated: Kernel<Exact, N, S> + Kernel<collision_core::ExactRelaxed, N, S>,
{
    Identity::for_variant(variant)
        .iter()
        .enumerate()
        .map(|(k, &check)| {
            let (outcome, seconds) = timed(|| {
                identity::run::<N, S>(
                    kernel,
                    variant,
                    check,
                    opts.points,
                    opts.seed + k as u64,
                    interrupted,
                )
            });
            let degree = identity::degree(N, variant, check);
            let r = identity_result(
                N,
                variant.name().into(),
                check.name(),
                opts.points,
                degree,
                outcome,
                seconds,
            );
            progress(&r);
            r
        })
        .collect()
}

/// Every check for dimension `N`; `interrupted` as in [`run_interruptible`].
pub fn run_dim<const N: usize, const S: usize>(
    opts: &Options,
    progress: &mut dyn FnMut(&CheckResult),
    interrupted: &dyn Fn() -> bool,
) -> Vec<CheckResult>
where
    Generated: Kernel<Exact, N, S>
        + Kernel<collision_core::ExactRelaxed, N, S>
        + RoughKernel<ExactRelaxed, N, S>
        + WaltonKernel<Exact, N, S>,
{
    let mut out = Vec::new();
    for variant in Variant::ALL {
        out.extend(identity_checks_interruptible::<N, S>(
            generated::<N, S>(variant).as_ref(),
            variant,
            opts,
            progress,
            interrupted,
        ));
        let mut rng = Rng::new(opts.seed ^ (N as u64) << 8);
        let mut decomposition = Ok(());
        let mut dimensions = Ok(());
        let ((), seconds) = timed(|| {
            for _ in 0..opts.configurations {
                match structure::check_at::<N, S>(variant, &mut rng) {
                    Ok(s) => {
                        if dimensions.is_ok() {
                            dimensions = structure::dimensions_ok(N, variant, &s);
                        }
                    }
                    Err(e) => decomposition = Err(e),
                }
            }
        });
        for (name, outcome) in [
            (
                "decomposition: G_q, Ebar_q, n_q orthogonal, n_q unit and outward",
                decomposition,
            ),
            (
                "dimensions: Ebar_q = n-1, E_q = n, G_q = N-n, span N",
                dimensions,
            ),
        ] {
            let r = CheckResult {
                dim: N,
                variant: variant.name().into(),
                check: name.into(),
                passed: outcome.is_ok(),
                points: opts.configurations,
                proof: Proof::ExactAtConfigurations,
                detail: outcome.err().unwrap_or_default(),
                seconds: seconds / 2.0,
            };
            progress(&r);
            out.push(r);
        }
    }
    for (variant, limit, name) in [
        (
            Variant::Fixed,
            Limit::Mass,
            "limit m_1 = 10^k -> inf: error ~ 1/m_1",
        ),
        (
            Variant::Free,
            Limit::PointMass,
            "limit gamma2_1 = 10^-k -> 0: error ~ gamma2_1",
        ),
    ] {
        let (outcome, seconds) = timed(|| sequence::check::<N, S>(limit, opts.seed));
        let r = CheckResult {
            dim: N,
            variant: variant.name().into(),
            check: name.into(),
            passed: outcome.is_ok(),
            points: 8,
            proof: Proof::ExactComputation,
            detail: match outcome {
                Ok(e) => format!(
                    "errors for k = 1..8: {}",
                    e.iter()
                        .map(|x| format!("{x:.2e}"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
                Err(e) => e,
            },
            seconds,
        };
        progress(&r);
        out.push(r);
    }
    let (outcome, seconds) = timed(|| inertia::check(N, opts.seed));
    let r = CheckResult {
        dim: N,
        variant: "any".into(),
        check: "inertia: 0 <= lambda <= R^2/n from radial densities".into(),
        passed: outcome.is_ok(),
        points: *outcome.as_ref().unwrap_or(&0),
        proof: Proof::ExactComputation,
        detail: outcome.err().unwrap_or_default(),
        seconds,
    };
    progress(&r);
    out.push(r);
    for variant in Variant::ALL {
        out.extend(rough_checks::<N, S>(variant, opts, progress, interrupted));
    }
    for variant in Variant::ALL {
        out.extend(walton_checks::<N, S>(variant, opts, progress, interrupted));
    }
    out
}

/// Every check for each dimension in `dims` (each in [`collision_core::DIMS`]).
pub fn run(
    dims: &[usize],
    opts: &Options,
    progress: &mut dyn FnMut(&CheckResult),
) -> Vec<CheckResult> {
    run_interruptible(dims, opts, progress, &|| false)
}

/// [`run`], asking `interrupted` before each point of each identity check (a front end's
/// Ctrl-C: Python checks its signals there). Once it says stop, each identity check left
/// fails at once ("interrupted at point k") and the results are to be discarded; the other
/// checks (decomposition, limits, inertia) are not asked, each takes well under a second.
pub fn run_interruptible(
    dims: &[usize],
    opts: &Options,
    progress: &mut dyn FnMut(&CheckResult),
    interrupted: &dyn Fn() -> bool,
) -> Vec<CheckResult> {
    dims.iter()
        .flat_map(|&n| {
            collision_core::with_dim!(
                n,
                |N, S| run_dim::<N, S>(opts, progress, interrupted),
                panic!(
                    "dimension {n} has no generated kernels ({:?})",
                    collision_core::DIMS
                )
            )
        })
        .collect()
}
