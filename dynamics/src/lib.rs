//! # noslip-dynamics
//!
//! The tangent dynamics of no-slip billiards and rough-ball gases, and what is built on them:
//! Lyapunov spectra and periodic orbits of the boundary map.
//!
//! - [`dual`]: dual numbers as a `Scalar`, so the generated kernels give their exact
//!   derivative with respect to the contact normal.
//! - [`geometry`] and [`law`]: a contact as its surface's curvature ([`Geometry`]) and its
//!   velocity map ([`Law`]: no-slip or smooth); a new boundary kind is one variant of each
//!   that applies.
//! - [`tangent`]: the free-flight and contact tangent maps.
//! - [`lyapunov`]: Lyapunov spectra along the engine's trajectory (tangent space with QR,
//!   and two trajectories as the independent check); [`lyapunov::touch`] maps the engine's
//!   contacts to geometries.
//! - [`table`] and [`orbits`]: a one-ball table in any scalar (exact for flat walls), its
//!   boundary map and periodic orbits (Newton with the exact derivative, exact characteristic
//!   polynomials). [`root`]: square roots where the scalar has them.
//!
//! The derivation and the measured figures: `docs/dynamics.md`.
//!
//! It must not parse command lines, print or write files (that is the `noslip` command), nor
//! change how the engine (`noslip-sim`) finds or resolves contacts: it follows the engine's
//! events.

#![warn(missing_docs, unreachable_pub)]

pub mod dual;
pub mod geometry;
pub mod law;
pub mod lyapunov;
pub mod orbits;
pub mod root;
pub mod table;
pub mod tangent;

pub use dual::Dual;
pub use geometry::Geometry;
pub use law::{Law, LawKernels};
pub use root::Root;
