//! # noslip-python
//!
//! The native module `noslip._native` of the Python package `noslip` (PyO3 + rust-numpy,
//! an abi3 wheel built by maturin). It is thin: every check, message and computation is the
//! Rust crates' own; this crate only moves values between Python and them.
//!
//! - [`case`]: one collision from a case (`noslip-case`, the JSON front end's parsing and
//!   validation), in `f64` or exact rationals.
//! - [`batch`]: a batch of collisions on NumPy arrays, the GIL released, rayon threads, the
//!   batch kernels' run-time ISA dispatch.
//! - [`reference`](mod@reference): the benchmark's Rust references for `collide_batch`, timed in Rust.
//! - [`scene`]: the `Scene` class (TOML text, file or dict; picklable).
//! - [`simulate`]: a run of a scene, its events log and energy samples as NumPy arrays.
//! - [`dynamics`]: `lyapunov` (the exponents of a scene and their running estimate) and
//!   `orbits` (the periodic orbits of a one-ball table).
//! - [`checks`]: `verify` and `report`, their reports as JSON text.
//! - [`error`]: `InputError`, a `ValueError` whose message names the field.
//! - [`signals`]: Ctrl-C in the long loops (`simulate`, `lyapunov`, `orbits`, `verify`).

#![warn(missing_docs, unreachable_pub)]

pub mod batch;
pub mod case;
pub mod checks;
pub mod dynamics;
pub mod error;
pub mod reference;
pub mod scene;
mod scene_laws;
pub mod signals;
pub mod simulate;

use pyo3::prelude::*;

/// Large arrays (the engine's records at many balls) on 2 MiB pages, as the `noslip` command
/// has them (`noslip_sim::huge_pages`; measured through `noslip.simulate` in
/// docs/benchmarks.md, session 58).
#[global_allocator]
static ALLOC: noslip_sim::huge_pages::HugePages = noslip_sim::huge_pages::HugePages;

/// The native module: the Python package `noslip` re-exports and documents it.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("InputError", m.py().get_type::<error::InputError>())?;
    m.add_function(wrap_pyfunction!(case::collide_case, m)?)?;
    m.add_function(wrap_pyfunction!(batch::collide_batch_f64, m)?)?;
    m.add_function(wrap_pyfunction!(batch::collide_batch_f32, m)?)?;
    m.add_function(wrap_pyfunction!(batch::collide_batch_law_f64, m)?)?;
    m.add_function(wrap_pyfunction!(batch::collide_batch_law_f32, m)?)?;
    m.add_function(wrap_pyfunction!(reference::reference_seconds, m)?)?;
    m.add_function(wrap_pyfunction!(batch::isa, m)?)?;
    m.add_function(wrap_pyfunction!(batch::params::batch_params_f64, m)?)?;
    m.add_function(wrap_pyfunction!(batch::params::batch_params_f32, m)?)?;
    m.add_class::<scene::Scene>()?;
    m.add_function(wrap_pyfunction!(simulate::simulate, m)?)?;
    m.add_function(wrap_pyfunction!(dynamics::lyapunov, m)?)?;
    m.add_function(wrap_pyfunction!(dynamics::orbits, m)?)?;
    m.add_function(wrap_pyfunction!(checks::verify, m)?)?;
    m.add_function(wrap_pyfunction!(checks::report, m)?)?;
    m.add("DIMS", collision_core::DIMS.to_vec())?;
    // The package's version: the crate's, which python/pyproject.toml repeats (a test
    // checks they agree).
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
