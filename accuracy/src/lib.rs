//! # noslip-accuracy
//!
//! Error against run time: every kernel variant measured against exact rational ground
//! truth, in typical and extreme regimes (`noslip report`). It measures and renders (Markdown,
//! JSON, SVG strings); it proves nothing (that is `noslip-verify`) and writes no files (that
//! is the `noslip` command).
//!
//! - [`regime`]: the sampled input distributions.
//! - [`method`]: the variants (generated f64, FMA, f32, exact; the nalgebra reference; the
//!   notes' dense matrix, [`dense`]) and how each runs and is timed ([`timing`]).
//! - [`batched`]: the batch variant's cases, split into `free` and `fixed` batches as
//!   `collide` dispatches them.
//! - [`measure`]: bits of error, normwise error in each body's energy norm, conditioning.
//! - [`family`]: the rough-ball family's kernels (`rough`, `walton`) in their own regimes.
//! - [`proven`]: the proven rounding-error bound of a case, in the measured figure.
//! - [`static_box`]: a regime's box, and the static bound over it (every input in it).
//! - [`report`]: one report run; [`render`]: Markdown and JSON; [`plot`]: the SVG plot.

#![warn(missing_docs, unreachable_pub)]

pub mod batched;
pub mod case;
pub mod dense;
pub mod family;
pub mod measure;
pub mod method;
pub mod plot;
pub mod proven;
pub mod regime;
pub mod render;
pub mod report;
pub mod static_box;
pub mod timing;

pub use case::Case;
pub use method::Method;
pub use regime::Regime;
pub use render::{AccuracyReport, Provenance};
pub use report::{check_samples, dim_result, dim_result_interruptible, Options, MAX_SAMPLES};
