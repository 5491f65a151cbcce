//! The sim crate's integration tests, one module a file, compiled as one test binary (one
//! link and one copy of the engine's monomorphised code at opt-level 3, instead of one per
//! file): `cargo test -p noslip-sim --test sim MODULE::` runs one file's tests.

mod common;

mod boltzmann;
mod collapse;
mod contacts;
mod cooling_state;
mod driven;
mod driven_observables;
mod elastic_members;
mod extreme_normals;
mod free_energy_bias_forms;
mod free_energy_first_order;
mod granular;
mod large_polygons;
// Not `observables`: a filter `observables::` would run `driven_observables` too.
#[path = "observables.rs"]
mod gas_observables;
mod pair_laws;
mod portraits;
mod self_diffusion;
mod simulate;
mod tables;
