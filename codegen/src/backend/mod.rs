//! Back ends for languages other than Rust: the same [`Program`]s, spelled in C99
//! ([`C`]) and OpenCL C ([`OpenCl`]).
//!
//! There is one generator: a kernel is built as a DAG ([`crate::model`]), scheduled, fused
//! and named once ([`Program::lower`]); the Rust emitter ([`crate::emit`]) and these back ends
//! only spell its steps, in the same order. What differs between languages is the
//! [`Language`] trait: scalar types, the fused multiply-add's name, function qualifiers, the
//! file's prelude and epilogue, and what follows each function (OpenCL's batch `__kernel`).
//! The body of every function (load the live inputs, bind the constants, one `const` per
//! step, store the outputs) is written once, in `function.rs`, for every C-family language.
//!
//! Adding a language: implement [`Language`] (see [`OpenCl`], about 100 lines), add it to
//! [`Lang`], and give it a faithfulness test that compiles the emitted source and compares
//! its results with the Rust kernels bit for bit (`tests/c_backend.rs`).
//!
//! The parts: the float formats (`precision.rs`), a kernel ready to be spelled (`unit.rs`),
//! a language's hooks (`language.rs`) and the languages (`lang.rs`, `c.rs`), one function's
//! text (`function.rs`), the kernel families' units (`units.rs`) and the comment of a generic
//! kernel (`doc.rs`), a whole file (`file.rs`); the energy-conserving correction, handwritten
//! (`conserve.rs`).
//!
//! # ABI
//!
//! Each kernel is a `void` function over arrays of its scalar type (`double` or `float`):
//!
//! ```text
//! free : (nu[N], ball1[3], ball2[3], state1[S+N], state2[S+N], out1[S+N], out2[S+N])
//! fixed: (nu[N], radius1,  ball2[3], state1[S+N], state2[S+N], out2[S+N])
//! rough_free, rough_fixed: the same with law[2] = {e, beta} after ball2
//! ball = {inv_mass, radius, gamma2}; state = {U_01, U_02, .., U_(n-2)(n-1), u_0, .., u_(n-1)}
//! ```
//!
//! mirroring the Rust kernels (`Ball`, `BodyState` with the strict upper triangle of `U` in
//! row-major order, then `u`). Every input is read before any output is written, so an
//! output may alias an input. No allocation, no global state.
//!
//! [`Program`]: crate::program::Program
//! [`Program::lower`]: crate::program::Program::lower

mod c;
mod conserve;
mod doc;
mod file;
mod function;
mod lang;
mod language;
mod precision;
mod unit;
mod units;

pub use c::{OpenCl, C};
pub use file::{
    file_name, generate, generate_scene, kernels_source, scene_file_name, source, source_with,
};
pub use function::{constant_literal, function};
pub use lang::Lang;
pub use language::Language;
pub use precision::Precision;
pub use unit::{BatchParam, Param, Unit};
pub use units::{generic_units, rough_units, scene_units, walton_units};
