//! `noslip report`: error against run time for every kernel variant and regime.

use crate::dims::{parse_dims, Dims};
use crate::exit::publish_failure;
use crate::exit::{self, Exit, Failure};
use crate::out::outln;
use crate::progress::ProgressDisplay;
use crate::publish::Staging;
use noslip_accuracy::plot::svg;
use noslip_accuracy::{check_samples, dim_result, AccuracyReport, Options, Provenance};
use std::path::PathBuf;
use std::time::Instant;

pub(crate) const LONG_ABOUT: &str = "\
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

Writes report.md, report.json and error-vs-time-nN.svg into the directory --out, replaced as
one set; prints one summary line.";

/// The arguments of `noslip report`.
#[derive(clap::Args)]
#[command(long_about = LONG_ABOUT, after_long_help = exit::help(CODES))]
pub struct Args {
    /// Dimensions, as a range `2..6` (inclusive) or a list `2,3,5`.
    #[arg(long, default_value = "2..6", value_parser = parse_dims)]
    dims: Dims,
    /// Output directory for report.md, report.json and the plots, replaced as a whole by each
    /// run (refused if it exists, is not empty and was not made by noslip).
    #[arg(long, default_value = "out/report")]
    pub out: PathBuf,
    /// Sampled cases per dimension and regime (1 to 100000).
    #[arg(long, default_value_t = Options::default().samples)]
    samples: usize,
    /// Seed of the sampling.
    #[arg(long, default_value_t = Options::default().seed)]
    seed: u64,
}

/// What `report` can return.
pub const CODES: &[Exit] = &[
    Exit::Success,
    Exit::CheckFailed,
    Exit::OutputFailed,
    Exit::BadInput,
];

/// The run's options from `args`, or the usage error (`--samples 0`); nothing is run (the
/// fuzz target `cli_args` calls it too).
pub fn options(args: &Args) -> Result<Options, Failure> {
    let opts = Options {
        dims: args.dims.0.clone(),
        samples: args.samples,
        seed: args.seed,
        ..Options::default()
    };
    check_samples(opts.samples).map_err(|m| Failure::bad_input(format!("--samples: {m}")))?;
    Ok(opts)
}

/// Run the accuracy report for `--dims` and publish it into `--out`.
pub fn run(args: &Args) -> Result<Exit, Failure> {
    let opts = options(args)?;
    let command = format!(
        "cargo run --release -p noslip -- report --dims {} --samples {} --seed {} --out {}",
        opts.dims
            .iter()
            .map(|d| d.to_string())
            .collect::<Vec<_>>()
            .join(","),
        opts.samples,
        opts.seed,
        args.out.display()
    );
    let mut staging = Staging::new(&args.out).map_err(|e| publish_failure(&e))?;
    let regimes = opts.regimes.len();
    let progress = ProgressDisplay::new((opts.dims.len() * regimes) as u64, "regimes");
    let start = Instant::now();
    let mut done = 0;
    let dims = opts
        .dims
        .iter()
        .map(|&dim| {
            progress.set_message(format!("n = {dim}"));
            dim_result(dim, &opts, |r| {
                if !r.stability.passed {
                    progress.println(format!(
                        "FAIL n = {dim} {}: max normwise {:.2} eps, {} beyond conditioning, {} non-finite",
                        r.name,
                        r.stability.max_normwise_eps,
                        r.stability.over_conditioning,
                        r.stability.non_finite
                    ));
                }
                done += 1;
                progress.inc(Some(format!(
                    "report: n = {dim} {} done ({done} of {} regimes), {:.0} s",
                    r.name,
                    opts.dims.len() * regimes,
                    start.elapsed().as_secs_f64()
                )));
            })
        })
        .collect();
    progress.finish();
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
        let text = svg(d)
            .map_err(|e| Failure::output(format!("cannot draw the plot for n = {}: {e}", d.dim)))?;
        files.push((format!("error-vs-time-n{}.svg", d.dim), text));
    }
    for (name, text) in &files {
        staging
            .write(name, text.as_bytes())
            .map_err(|e| publish_failure(&e))?;
    }
    staging.commit().map_err(|e| publish_failure(&e))?;
    let mut failing: Vec<String> = report
        .dims
        .iter()
        .flat_map(|d| {
            let family = d.family.iter().filter(|r| !r.passed()).map(|r| &r.name);
            d.regimes
                .iter()
                .filter(|r| !r.stability.passed)
                .map(|r| &r.name)
                .chain(family)
                .map(move |name| format!("n = {} {name}", d.dim))
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
    outln!(
        "report: n = {:?}, {} regimes and {} of the rough-ball family, {} cases each, {:.1} s; generated f64 worst normwise error {:.2} eps; {}; reports in {}",
        report.options.dims,
        report.options.regimes.len(),
        report.options.family.len(),
        report.options.samples,
        report.seconds,
        worst,
        if failing.is_empty() { "stability requirement met".to_string() } else { format!("FAILS in {}", failing.join(", ")) },
        args.out.display()
    )?;
    Ok(if failing.is_empty() {
        Exit::Success
    } else {
        Exit::CheckFailed
    })
}
