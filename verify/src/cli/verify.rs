//! `noslip verify`: every exact check for the chosen dimensions, reports, golden copy.

use super::{parse_dims, Dims};
use indicatif::{ProgressBar, ProgressStyle};
use noslip_verify::report::{diff, write_atomic, Report};
use noslip_verify::run::{checks_per_dim, run, Options};
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

const LONG_ABOUT: &str = "\
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

Writes OUT/verify.md and OUT/verify.json atomically; exits 1 if any check fails.";

#[derive(clap::Args)]
#[command(long_about = LONG_ABOUT)]
pub struct Args {
    /// Dimensions, as a range `2..6` (inclusive) or a list `2,3,5`.
    #[arg(long, default_value = "2..6", value_parser = parse_dims)]
    dims: Dims,
    /// Directory for verify.md and verify.json.
    #[arg(long, default_value = "out")]
    out: PathBuf,
    /// Random points per identity check.
    #[arg(long, default_value_t = Options::default().points)]
    points: usize,
    /// Compare the results (without timings) with the golden copy and print a diff on change.
    #[arg(long)]
    check_golden: bool,
    /// Rewrite the golden copy from this run.
    #[arg(long)]
    update_golden: bool,
    /// The golden copy.
    #[arg(long, default_value = "docs/reports/verify.json")]
    golden: PathBuf,
}

pub fn run_cmd(args: &Args) -> ExitCode {
    let opts = Options {
        points: args.points,
        ..Options::default()
    };
    let dims = &args.dims.0;
    let bar = ProgressBar::new((dims.len() * checks_per_dim()) as u64);
    bar.set_style(
        ProgressStyle::with_template("{bar:30} {pos}/{len} checks  {msg}").expect("template"),
    );
    let start = Instant::now();
    let results = run(dims, &opts, &mut |r| {
        bar.set_message(format!("n = {} {}: {}", r.dim, r.variant, r.check));
        bar.inc(1);
        if !r.passed {
            bar.println(format!(
                "FAIL n = {} {} {}: {}",
                r.dim, r.variant, r.check, r.detail
            ));
        }
    });
    bar.finish_and_clear();
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
        let path = args.out.join(name);
        if let Err(e) = write_atomic(&path, &text) {
            eprintln!("error: cannot write {}: {e}", path.display());
            return ExitCode::from(1);
        }
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
    println!(
        "verify: {} checks for n = {:?}, {} failed, {:.1} s; largest Schwartz-Zippel bound {:.1e}; reports in {}",
        report.results.len(),
        dims,
        failed,
        report.seconds,
        worst,
        args.out.display()
    );
    let golden_text = report.without_timings().to_json();
    if args.update_golden {
        if let Err(e) = write_atomic(&args.golden, &golden_text) {
            eprintln!("error: cannot write {}: {e}", args.golden.display());
            return ExitCode::from(1);
        }
        println!("golden copy written to {}", args.golden.display());
    }
    if args.check_golden {
        match std::fs::read_to_string(&args.golden) {
            Err(e) => {
                eprintln!(
                    "error: cannot read the golden copy {}: {e}",
                    args.golden.display()
                );
                return ExitCode::from(1);
            }
            Ok(golden) => match diff(&golden, &golden_text) {
                None => println!("golden copy {}: unchanged", args.golden.display()),
                Some(d) => {
                    eprintln!(
                        "the results differ from the golden copy {}:\n{d}",
                        args.golden.display()
                    );
                    return ExitCode::from(1);
                }
            },
        }
    }
    if failed > 0 {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    }
}
