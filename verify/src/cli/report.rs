//! `noslip report`: error against run time for every kernel variant and regime.

use super::{parse_dims, Dims};
use indicatif::{ProgressBar, ProgressStyle};
use noslip_verify::accuracy::plot::svg;
use noslip_verify::accuracy::{dim_result, AccuracyReport, Options, Provenance};
use noslip_verify::report::write_atomic;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

const LONG_ABOUT: &str = "\
Measure every kernel variant's error against exact rational ground truth, and its run time.

Variants: the generated kernels in f64, in f64 with fused multiply-adds, in f32 and in exact
rationals; the general-n nalgebra reference in f64; the notes' dense N x N matrix built per
collision, in f64. Regimes: typical inputs, mass ratios to 1e15 both ways, an immovable body,
gamma^2 down to 1e-15 and exactly 0, radius ratios to 1e6, velocity and spin scales from
1e-100 to 1e100, spin-dominated states, near-grazing contact.

Errors: bits per output component (log2(ulps + 1)), and the normwise error of each body in its
own kinetic-energy norm in units of the format's epsilon, with each body's conditioning. The
generated f64 kernel must stay within 16 eps (typical) and 64 eps (elsewhere), or within the
problem's conditioning; no NaN or infinity anywhere.

Writes OUT/report.md, OUT/report.json and OUT/error-vs-time-nN.svg atomically; exits 1 if the
stability requirement fails or a file cannot be written.";

#[derive(clap::Args)]
#[command(long_about = LONG_ABOUT)]
pub struct Args {
    /// Dimensions, as a range `2..6` (inclusive) or a list `2,3,5`.
    #[arg(long, default_value = "2..6", value_parser = parse_dims)]
    dims: Dims,
    /// Directory for report.md, report.json and the plots.
    #[arg(long, default_value = "out")]
    out: PathBuf,
    /// Sampled cases per dimension and regime.
    #[arg(long, default_value_t = Options::default().samples)]
    samples: usize,
    /// Seed of the sampling.
    #[arg(long, default_value_t = Options::default().seed)]
    seed: u64,
}

pub fn run_cmd(args: &Args) -> ExitCode {
    let opts = Options {
        dims: args.dims.0.clone(),
        samples: args.samples,
        seed: args.seed,
        ..Options::default()
    };
    if opts.samples == 0 {
        eprintln!("error: --samples must be at least 1");
        return ExitCode::from(2);
    }
    let command = format!(
        "cargo run --release -p noslip-verify -- report --dims {} --samples {} --seed {} --out {}",
        opts.dims
            .iter()
            .map(|d| d.to_string())
            .collect::<Vec<_>>()
            .join(","),
        opts.samples,
        opts.seed,
        args.out.display()
    );
    let bar = ProgressBar::new((opts.dims.len() * opts.regimes.len()) as u64);
    bar.set_style(
        ProgressStyle::with_template("{bar:30} {pos}/{len} regimes  {msg}").expect("template"),
    );
    let start = Instant::now();
    let dims = opts
        .dims
        .iter()
        .map(|&dim| {
            bar.set_message(format!("n = {dim}"));
            dim_result(dim, &opts, |r| {
                bar.inc(1);
                if !r.stability.passed {
                    bar.println(format!(
                        "FAIL n = {dim} {}: max normwise {:.2} eps, {} beyond conditioning, {} non-finite",
                        r.name,
                        r.stability.max_normwise_eps,
                        r.stability.over_conditioning,
                        r.stability.non_finite
                    ));
                }
            })
        })
        .collect();
    bar.finish_and_clear();
    let report = AccuracyReport {
        tool: format!("noslip {}", env!("CARGO_PKG_VERSION")),
        provenance: Provenance::collect(command, &args.out),
        options: opts,
        dims,
        seconds: start.elapsed().as_secs_f64(),
    };
    let mut files = vec![
        ("report.md".to_string(), report.to_markdown()),
        ("report.json".to_string(), report.to_json()),
    ];
    for d in &report.dims {
        match svg(d) {
            Ok(text) => files.push((format!("error-vs-time-n{}.svg", d.dim), text)),
            Err(e) => {
                eprintln!("error: cannot draw the plot for n = {}: {e}", d.dim);
                return ExitCode::from(1);
            }
        }
    }
    for (name, text) in &files {
        let path = args.out.join(name);
        if let Err(e) = write_atomic(&path, text) {
            eprintln!("error: cannot write {}: {e}", path.display());
            return ExitCode::from(1);
        }
    }
    let mut failing: Vec<String> = report
        .dims
        .iter()
        .flat_map(|d| {
            d.regimes
                .iter()
                .filter(|r| !r.stability.passed)
                .map(move |r| format!("n = {} {}", d.dim, r.name))
        })
        .collect();
    if failing.is_empty() && !report.passed() {
        failing.push("continuity at the limits".into());
    }
    let worst = report
        .dims
        .iter()
        .flat_map(|d| &d.regimes)
        .map(|r| r.stability.max_normwise_eps)
        .fold(0.0, f64::max);
    println!(
        "report: n = {:?}, {} regimes, {} cases each, {:.1} s; generated f64 worst normwise error {:.2} eps; {}; reports in {}",
        report.options.dims,
        report.options.regimes.len(),
        report.options.samples,
        report.seconds,
        worst,
        if failing.is_empty() { "stability requirement met".to_string() } else { format!("FAILS in {}", failing.join(", ")) },
        args.out.display()
    );
    if failing.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    }
}
