//! `noslip.lyapunov`: Lyapunov exponents of a scene (`noslip_dynamics::lyapunov`, as
//! `noslip lyapunov` runs them), the spectrum and its running estimate as NumPy arrays;
//! `noslip.orbits`: the periodic orbits of a one-ball table
//! (`noslip_dynamics::orbits::search`, as `noslip orbits` runs it), as the JSON text of
//! `orbits.json`.

use crate::error::{input_error, unsigned, unsigned_opt};
use crate::scene::Scene;
use crate::signals::Signals;
use collision_core::Generated;
use noslip_dynamics::lyapunov::stats::Estimate;
use noslip_dynamics::lyapunov::{
    qr_interruptible, two_trajectory_interruptible, Dim, Options, Spectrum, MAX_BLOCKS,
};
use noslip_dynamics::orbits::search::{
    search_interruptible, Search, SearchError, DEFAULT_MAX_CONTACTS,
};
use noslip_dynamics::Law;
use noslip_scene::parse_exact;
use noslip_sim::setup::setup;
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

fn spectrum<const N: usize, const S: usize>(
    scene: &noslip_scene::Scene,
    options: &Options,
    two: bool,
    signals: &Signals,
) -> Result<Spectrum, String>
where
    Generated: Dim<N, S>,
{
    let setup = setup::<N, S>(scene).map_err(|e| format!("{}: {e}", scene.origin))?;
    let interrupted = || signals.interrupted();
    let result = if two {
        two_trajectory_interruptible(setup, options, &interrupted)
    } else {
        qr_interruptible(setup, options, &interrupted)
    };
    // The engine's messages name the command's options (`--k`, `--events`): here they are
    // the keyword arguments of the same names.
    result.map_err(|e| {
        let text = e.to_string();
        match text.strip_prefix("--") {
            Some(rest) => rest.to_string(),
            None => format!("{}: {text}", scene.origin),
        }
    })
}

/// The contact law named by `contact`.
fn parse_law(contact: &str) -> PyResult<Law> {
    match contact {
        "no-slip" => Ok(Law::NoSlip),
        "smooth" => Ok(Law::Smooth),
        c => Err(input_error(format!(
            "contact: must be \"no-slip\" or \"smooth\", got {c:?}"
        ))),
    }
}

/// Values and standard errors as two arrays.
fn estimates<'py>(
    py: Python<'py>,
    e: &[Estimate],
) -> (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>) {
    (
        PyArray1::from_iter(py, e.iter().map(|x| x.value)),
        PyArray1::from_iter(py, e.iter().map(|x| x.error)),
    )
}

/// Lyapunov exponents of ``scene`` (see the Python docstring of ``noslip.lyapunov``).
#[pyfunction]
#[pyo3(signature = (scene, events, k, method, seed, blocks, every, contact))]
#[allow(clippy::too_many_arguments)]
pub fn lyapunov<'py>(
    py: Python<'py>,
    scene: &Bound<'py, Scene>,
    events: &Bound<'py, PyAny>,
    k: Option<Bound<'py, PyAny>>,
    method: &str,
    seed: &Bound<'py, PyAny>,
    blocks: &Bound<'py, PyAny>,
    every: Option<Bound<'py, PyAny>>,
    contact: Option<&str>,
) -> PyResult<Bound<'py, PyDict>> {
    let events = unsigned(events, "events", 1, u64::MAX)?;
    let k = unsigned_opt(k.as_ref(), "k", 1, usize::MAX)?;
    let seed = unsigned(seed, "seed", 0, u64::MAX)?;
    let blocks = unsigned(blocks, "blocks", 1, MAX_BLOCKS)?;
    let every = unsigned_opt(every.as_ref(), "every", 1, u64::MAX)?;
    let two = match method {
        "qr" => false,
        "two-trajectory" => true,
        m => {
            return Err(input_error(format!(
                "method: must be \"qr\" or \"two-trajectory\", got {m:?}"
            )))
        }
    };
    let law = contact.map(parse_law).transpose()?;
    if every == Some(0) {
        return Err(input_error("every: must be at least 1"));
    }
    if two && k.is_some_and(|k| k != 1) {
        return Err(input_error(
            "k: two-trajectory gives the largest exponent only (k=1)",
        ));
    }
    let options = Options {
        events,
        k,
        blocks,
        seed,
        law,
        every,
    };
    let scene = &scene.get().inner;
    let n = scene.dim;
    // Asked before every contact (a few µs each with the tangent maps): the clock is read
    // every 256.
    let signals = Signals::new(256);
    let s = py.detach(|| {
        collision_core::with_dim!(
            n,
            |N, S| spectrum::<N, S>(scene, &options, two, &signals),
            Err(format!("{}: dimension {n} has no kernels", scene.origin))
        )
    });
    if let Some(e) = signals.raised() {
        return Err(e);
    }
    let s = s.map_err(input_error)?;
    let out = PyDict::new(py);
    out.set_item("method", s.method)?;
    out.set_item("contact", contact.unwrap_or("scene"))?;
    out.set_item("dimension", s.dimension)?;
    out.set_item("contacts", s.contacts)?;
    out.set_item("warmup", s.warmup)?;
    out.set_item("every", s.every)?;
    out.set_item("time", s.time)?;
    out.set_item("per_time", estimates(py, &s.per_time))?;
    out.set_item("per_contact", estimates(py, &s.per_contact))?;
    out.set_item("sum", (s.sum.value, s.sum.error))?;
    let k = s.per_time.len();
    let rows: Vec<Vec<f64>> = s.running.iter().map(|r| r.exponents.clone()).collect();
    let running = if rows.is_empty() {
        PyArray2::zeros(py, [0, k], false)
    } else {
        PyArray2::from_vec2(py, &rows).map_err(|e| input_error(format!("internal error: {e}")))?
    };
    out.set_item(
        "running_contacts",
        PyArray1::from_iter(py, s.running.iter().map(|r| r.contacts)),
    )?;
    out.set_item(
        "running_time",
        PyArray1::from_iter(py, s.running.iter().map(|r| r.time)),
    )?;
    out.set_item("running_exponents", running)?;
    Ok(out)
}

/// The periodic orbits of period ``period`` of a one-ball table (see the Python docstring of
/// ``noslip.orbits``): ``orbits.json``'s text. ``starts`` are rationals or decimals as text.
/// ``max_contacts`` bounds the search's work as ``noslip orbits --max-contacts`` does (default
/// ``DEFAULT_MAX_CONTACTS``): the search stops there and ``orbits.json`` says so (``stopped``).
#[pyfunction]
#[pyo3(signature = (scene, period, starts, grid, contact, max_contacts=None))]
pub fn orbits(
    py: Python<'_>,
    scene: &Bound<'_, Scene>,
    period: &Bound<'_, PyAny>,
    starts: Vec<Vec<String>>,
    grid: Option<Bound<'_, PyAny>>,
    contact: Option<&str>,
    max_contacts: Option<Bound<'_, PyAny>>,
) -> PyResult<String> {
    let period = unsigned(period, "period", 1, usize::MAX)?;
    let grid = unsigned_opt(grid.as_ref(), "grid", 1, usize::MAX)?;
    let max_contacts = unsigned_opt(max_contacts.as_ref(), "max_contacts", 1, u64::MAX)?
        .unwrap_or(DEFAULT_MAX_CONTACTS);
    let law = contact.map(parse_law).transpose()?;
    let mut from = Vec::with_capacity(starts.len());
    for (i, start) in starts.iter().enumerate() {
        let z = start
            .iter()
            .enumerate()
            .map(|(k, x)| {
                parse_exact(x)
                    .map(|x| collision_core::Exact::from_fraction(&x))
                    .map_err(|e| input_error(format!("starts[{i}][{k}]: {e}")))
            })
            .collect::<PyResult<Vec<_>>>()?;
        from.push(z);
    }
    let ask = Search {
        period,
        from,
        grid,
        law,
        max_contacts,
    };
    let scene = &scene.get().inner;
    let n = scene.dim;
    // Asked before each start (milliseconds to a second of Newton's method each): the
    // clock is read every time.
    let signals = Signals::new(1);
    let interrupted = || signals.interrupted();
    let report = py.detach(|| {
        collision_core::with_dim!(
            n,
            |N, S| search_interruptible::<N, S>(scene, &ask, &mut |_| {}, &interrupted)
                .map_err(|e| message(&e)),
            Err(format!("{}: dimension {n} has no kernels", scene.origin))
        )
    });
    if let Some(e) = signals.raised() {
        return Err(e);
    }
    let report = report.map_err(input_error)?;
    serde_json::to_string(&report).map_err(|e| input_error(format!("internal error: {e}")))
}

/// The search's error naming the keyword argument (`starts[i]` for the search's `from[i]`).
fn message(e: &SearchError) -> String {
    match (e, e.field()) {
        (SearchError::From { index, message }, _) => format!("starts[{index}]: {message}"),
        (_, Some(field)) => format!("{}: {}", field.replace('-', "_"), e.message()),
        (_, None) => e.message().to_string(),
    }
}
