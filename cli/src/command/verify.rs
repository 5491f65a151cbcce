//! `noslip verify`: every exact check for the chosen dimensions, reports, golden copy.

use crate::dims::{parse_dims, Dims};
use crate::exit::publish_failure;
use crate::exit::{self, Exit, Failure};
use crate::out::outln;
use crate::progress::ProgressDisplay;
use crate::publish::{write_atomic, Staging};
use noslip_verify::report::{golden, Report};
use noslip_verify::suite::{self, check_points, checks_per_dim, Options};
use std::path::{Path, PathBuf};
use std::time::Instant;

pub(crate) const LONG_ABOUT: &str = "\
Prove, in exact rational arithmetic, that the compiled generated kernels are the no-slip map.

For each dimension and kernel variant (free: both bodies move; fixed: body 1 immovable) the
generated kernels run with exact rationals at random points and must satisfy identities built
from the definitions: the metric reflection across the no-slip subspace G_q, conservation of
kinetic energy, linear momentum and each body's angular momentum about the contact point,
C o C = id, the m_1 -> inf limit (fixed variant = free map at w_1 = 0) and the point-mass
limit. Each identity's report gives its degree (bounded on the generator's DAG) and the
Schwartz-Zippel bound (degree / 2^20)^points on the probability that a false identity passed.
Structural checks: the decomposition T_qM = G_q + Ebar_q + R n_q is orthogonal in the metric,
n_q is unit and outward, and the exact ranks are n-1, n, N-n, N. Inertia: lambda from
polynomial and layered radial densities lies in [0, R^2/n]; negative densities are refused.

Writes verify.md and verify.json into the directory --out, replaced as one set (see
docs/verification.md); prints one summary line.";

/// The arguments of `noslip verify`.
#[derive(clap::Args)]
#[command(long_about = LONG_ABOUT, after_long_help = exit::help(CODES))]
pub struct Args {
    /// Dimensions, as a range `2..6` (inclusive) or a list `2,3,5`.
    #[arg(long, default_value = "2..6", value_parser = parse_dims)]
    dims: Dims,
    /// Output directory for verify.md and verify.json, replaced as a whole by each run
    /// (refused if it exists, is not empty and was not made by noslip).
    #[arg(long, default_value = "out/verify")]
    pub out: PathBuf,
    /// Random points per identity check (1 to 1024).
    #[arg(long, default_value_t = Options::default().points)]
    points: usize,
    /// Compare the results (without timings) of the dimensions run with the golden copy;
    /// print a unified diff and exit 1 on a difference.
    #[arg(long)]
    check_golden: bool,
    /// Rewrite the golden copy's results of the dimensions run from this run.
    #[arg(long, conflicts_with = "check_golden")]
    update_golden: bool,
    /// The golden copy [default: docs/reports/verify.json of the source tree this binary
    /// was built from, wherever it runs].
    #[arg(long)]
    golden: Option<PathBuf>,
}

/// What `verify` can return.
pub const CODES: &[Exit] = &[
    Exit::Success,
    Exit::CheckFailed,
    Exit::OutputFailed,
    Exit::BadInput,
];

/// The golden copy shipped in the source tree this binary was built from.
fn shipped_golden() -> PathBuf {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    crate_dir
        .parent()
        .unwrap_or(crate_dir)
        .join("docs/reports/verify.json")
}

/// The run's options from `args`, or the usage error (`--points 0`); nothing is run or
/// read (the fuzz target `cli_args` calls it too).
pub fn options(args: &Args) -> Result<Options, Failure> {
    let points =
        check_points(args.points).map_err(|m| Failure::bad_input(format!("--points: {m}")))?;
    Ok(Options {
        points,
        ..Options::default()
    })
}

/// Run the exact checks for `--dims` and publish the reports into `--out`; compare them with
/// the golden copy or rewrite it when asked.
pub fn run(args: &Args) -> Result<Exit, Failure> {
    let opts = options(args)?;
    let golden_path = args.golden.clone().unwrap_or_else(shipped_golden);
    // Read the golden copy first: a missing one is a usage error, found before the run.
    let golden = if args.check_golden || args.update_golden {
        match std::fs::read_to_string(&golden_path) {
            Ok(text) => Some(text),
            Err(e) if args.update_golden && e.kind() == std::io::ErrorKind::NotFound => None,
            Err(e) => {
                return Err(Failure::bad_input(format!(
                    "cannot read the golden copy {}: {e}",
                    golden_path.display()
                )))
            }
        }
    } else {
        None
    };
    let dims = &args.dims.0;
    let mut staging = Staging::new(&args.out).map_err(|e| publish_failure(&e))?;
    let progress = ProgressDisplay::new((dims.len() * checks_per_dim()) as u64, "checks");
    let start = Instant::now();
    let (mut done, mut failed_in_dim) = (0, 0);
    let results = suite::run(dims, &opts, &mut |r| {
        progress.set_message(format!("n = {} {}: {}", r.dim, r.variant, r.check));
        if !r.passed {
            failed_in_dim += 1;
            progress.println(format!(
                "FAIL n = {} {} {}: {}",
                r.dim, r.variant, r.check, r.detail
            ));
        }
        done += 1;
        let dim_done = done % checks_per_dim() == 0;
        progress.inc(dim_done.then(|| {
            let line = format!(
                "verify: n = {} done ({} of {} checks, {} failed in n = {}), {:.1} s",
                r.dim,
                done,
                dims.len() * checks_per_dim(),
                failed_in_dim,
                r.dim,
                start.elapsed().as_secs_f64()
            );
            failed_in_dim = 0;
            line
        }));
    });
    progress.finish();
    let report = Report {
        tool: format!("noslip {}", env!("CARGO_PKG_VERSION")),
        seed: opts.seed,
        points: opts.points,
        results,
        seconds: start.elapsed().as_secs_f64(),
    };
    for (name, text) in [
        ("verify.md", report.to_markdown()),
        ("verify.json", report.to_json()),
    ] {
        staging
            .write(name, text.as_bytes())
            .map_err(|e| publish_failure(&e))?;
    }
    staging.commit().map_err(|e| publish_failure(&e))?;
    let mut outcome = if report.passed() {
        Exit::Success
    } else {
        Exit::CheckFailed
    };
    if args.update_golden {
        let updated = golden::update(golden.as_deref(), &report, dims).map_err(|e| {
            Failure::bad_input(format!("--update-golden {}: {e}", golden_path.display()))
        })?;
        write_atomic(&golden_path, &updated.to_json())
            .map_err(|e| Failure::output(format!("cannot write {}: {e}", golden_path.display())))?;
    }
    let failed = report.results.iter().filter(|r| !r.passed).count();
    let worst = report
        .results
        .iter()
        .filter_map(|r| match r.proof {
            noslip_verify::report::Proof::Identity { bound, .. } => Some(bound),
            _ => None,
        })
        .fold(0.0f64, f64::max);
    outln!(
        "verify: {} checks for n = {:?}, {} failed, {:.1} s; largest Schwartz-Zippel bound {:.1e}; reports in {}",
        report.results.len(),
        dims,
        failed,
        report.seconds,
        worst,
        args.out.display()
    )?;
    if args.update_golden {
        outln!(
            "golden copy {}: results of n = {:?} written",
            golden_path.display(),
            dims
        )?;
    } else if let (true, Some(golden)) = (args.check_golden, &golden) {
        match golden::compare(golden, &report, dims).map_err(|e| {
            Failure::bad_input(format!("the golden copy {}: {e}", golden_path.display()))
        })? {
            None => outln!(
                "golden copy {}: unchanged for n = {:?}",
                golden_path.display(),
                dims
            )?,
            Some(d) => {
                outln!(
                    "golden copy {}: the results of n = {:?} differ:\n{d}",
                    golden_path.display(),
                    dims
                )?;
                outcome = Exit::CheckFailed;
            }
        }
    }
    Ok(outcome)
}
