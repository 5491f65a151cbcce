//! `noslip.verify` and `noslip.report`: the exact verification (`noslip-verify`) and the
//! accuracy report (`noslip-accuracy`), run as `noslip verify` / `noslip report` run them,
//! their reports returned as the JSON text those commands write (the Python layer parses it).

use crate::error::{input_error, unsigned};
use crate::signals::Signals;
use noslip_accuracy::{
    check_samples, dim_result_interruptible, AccuracyReport, Options as ReportOptions, Provenance,
    MAX_SAMPLES,
};
use noslip_verify::report::Report;
use noslip_verify::suite::{self, check_points, Options as VerifyOptions, MAX_POINTS};
use pyo3::prelude::*;
use std::time::Instant;

/// The dimensions asked for, each a known one, sorted, without repeats.
fn check_dims(dims: &[Bound<'_, PyAny>]) -> PyResult<Vec<usize>> {
    let dims = dims
        .iter()
        .enumerate()
        .map(|(i, d)| unsigned(d, &format!("dims[{i}]"), 0, usize::MAX))
        .collect::<PyResult<Vec<usize>>>()?;
    if dims.is_empty() {
        return Err(input_error("dims: give at least one dimension"));
    }
    if let Some(d) = dims.iter().find(|d| !collision_core::DIMS.contains(d)) {
        return Err(input_error(format!(
            "dims: {d} has no generated kernels (the dimensions are {:?})",
            collision_core::DIMS
        )));
    }
    let mut dims = dims.to_vec();
    dims.sort_unstable();
    dims.dedup();
    Ok(dims)
}

/// The exact verification of the generated kernels of ``dims``, ``points`` random points per
/// identity: ``verify.json``'s text.
#[pyfunction]
#[pyo3(signature = (dims, points))]
pub fn verify(
    py: Python<'_>,
    dims: Vec<Bound<'_, PyAny>>,
    points: &Bound<'_, PyAny>,
) -> PyResult<String> {
    let dims = check_dims(&dims)?;
    let points = check_points(unsigned(points, "points", 1, MAX_POINTS)?)
        .map_err(|m| input_error(format!("points: {m}")))?;
    let opts = VerifyOptions {
        points,
        ..VerifyOptions::default()
    };
    // Asked before each point of each identity (milliseconds each in exact rationals): the
    // clock is read every time.
    let signals = Signals::new(1);
    let interrupted = || signals.interrupted();
    let json = py.detach(|| {
        let start = Instant::now();
        let results = suite::run_interruptible(&dims, &opts, &mut |_| {}, &interrupted);
        Report {
            tool: format!("noslip-python {}", env!("CARGO_PKG_VERSION")),
            seed: opts.seed,
            points: opts.points,
            results,
            seconds: start.elapsed().as_secs_f64(),
        }
        .to_json()
    });
    match signals.raised() {
        Some(e) => Err(e),
        None => Ok(json),
    }
}

/// The accuracy report of ``dims``, ``samples`` cases per dimension and regime, seed ``seed``:
/// ``report.json``'s text.
#[pyfunction]
#[pyo3(signature = (dims, samples, seed))]
pub fn report(
    py: Python<'_>,
    dims: Vec<Bound<'_, PyAny>>,
    samples: &Bound<'_, PyAny>,
    seed: &Bound<'_, PyAny>,
) -> PyResult<String> {
    let dims = check_dims(&dims)?;
    let samples = check_samples(unsigned(samples, "samples", 1, MAX_SAMPLES)?)
        .map_err(|m| input_error(format!("samples: {m}")))?;
    let seed = unsigned(seed, "seed", 0, u64::MAX)?;
    let opts = ReportOptions {
        dims: dims.clone(),
        samples,
        seed,
        ..ReportOptions::default()
    };
    // Asked before each case (milliseconds in exact rationals) and each timing.
    let signals = Signals::new(1);
    let interrupted = || signals.interrupted();
    let json = py.detach(|| {
        let start = Instant::now();
        let results = dims
            .iter()
            .map(|&d| dim_result_interruptible(d, &opts, |_| {}, &interrupted))
            .collect::<Option<Vec<_>>>()?;
        Some(
            AccuracyReport {
                tool: format!("noslip-python {}", env!("CARGO_PKG_VERSION")),
                provenance: Provenance::collect(
                    format!("noslip.report(dims={dims:?}, samples={samples}, seed={seed})"),
                    std::path::Path::new("."),
                ),
                options: opts,
                dims: results,
                seconds: start.elapsed().as_secs_f64(),
            }
            .to_json(),
        )
    });
    match (json, signals.raised()) {
        (_, Some(e)) => Err(e),
        (Some(json), None) => Ok(json),
        (None, None) => Err(input_error("internal error: stopped without a signal")),
    }
}
