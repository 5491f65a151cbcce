//! The verifier's checks. Each runs the generated kernels in exact rationals against
//! objects built independently from the definitions.

pub mod identity;
pub mod inertia;
pub mod rough;
pub mod sequence;
pub mod specialised;
pub mod structure;
pub mod walton;
