//! # collision-core
//!
//! The runtime of the no-slip collision: the generated kernels, the scalar types they run in,
//! balls and states, the checked `collide`, the batch kernels and the general-n reference.
//! It simulates nothing (that is `noslip-sim`) and reads no files or formats (the `noslip`
//! command and `noslip-scene` do).
//!
//! The no-slip collision of two rigid balls in R^n with radially symmetric mass
//! distributions: at contact, the state `xi = (U_1, u_1, U_2, u_2)` (angular velocities
//! `U_i` in so(n), centre velocities `u_i`) jumps to its reflection, in the kinetic-energy
//! metric, across the no-slip subspace `G_q = { V_1(Q) = V_2(Q) }`:
//!
//! ```text
//! xi+ = 2 P_G xi- - xi-        (P_G: the projection onto G_q, orthogonal in the energy metric)
//! ```
//!
//! The closed form of the kernels is on each generated function (`kernels::d3::free`), made
//! from the generator's model (`noslip_codegen::model`).
//!
//! - [`kernels`]: the generated, unrolled, branch-free kernels for n = 2..6 (`free`, both
//!   bodies move; `fixed`, body 1 immovable), generic over [`Scalar`]: `f32`, `f64`, [`Exact`].
//! - [`collide`]: validates the inputs (typed [`InputError`] naming the field; bounds missed
//!   by rounding are met by [the rounding allowance](allowance)) and runs the kernel with an
//!   unbounded exponent ([`Wide`]), so that no intermediate overflows or underflows;
//!   [`collide_unchecked`] is the fast path.
//! - [`batch`]: the same kernels over blocked batches of contacts, vectorized, with the
//!   instruction set chosen at run time and optional threads (feature `parallel`).
//! - [`reference`](mod@reference): the map built from the definitions (impulse basis, Gram matrix,
//!   projection) for any n: the independent check of the kernels.
//!
//! ```
//! use collision_core::{collide, Ball, Inertia, Mass, State3};
//! let ball = Ball::new(3, Mass::Finite(1.0), 1.0, Inertia::Uniform).unwrap();
//! let wall = Ball::immovable(3, 1.0);
//! let rest = State3::zero();
//! let spin_and_fall = State3::from_omega([0.0, 0.0, 2.0], [0.0, -1.0, 0.0]);
//! // body 1 is the wall below, body 2 the ball: nu points up.
//! let [_, after] = collide(&[0.0, 1.0, 0.0], [&wall, &ball], [&rest, &spin_and_fall]).unwrap();
//! assert_eq!(after.velocity[1], 1.0); // the normal velocity flips
//! ```

#![warn(missing_docs, unreachable_pub)]

// First, so that its macros are in textual scope in every module after it.
#[macro_use]
mod dims;
pub mod allowance;
mod ball;
pub mod batch;
pub mod certified;
mod checked;
mod collide;
pub mod conserve;
mod error;
pub mod exact;
mod float;
pub mod kernels;
pub mod linalg;
pub mod literal;
mod normal;
pub mod reference;
mod restitution;
pub mod rng;
mod scalar;
pub mod smooth;
mod state;
mod walton;
mod wide;

pub use ball::{Ball, Inertia, Mass};
pub use checked::validate_parts;
pub use collide::{
    collide, collide_general, collide_rough, collide_rough_unchecked, collide_unchecked,
    collide_unchecked_fma, collide_walton, collide_walton_unchecked, fma_in_hardware, validate,
};
pub use dims::DIMS;
pub use error::{BodyField, Field, InputError};
#[cfg(feature = "num-rational")]
pub use exact::ExactNumRational;
pub use exact::{collide_exact, Exact, ExactRelaxed, Relaxing};
pub use kernels::{Generated, Kernel, RoughKernel, WaltonKernel};
pub use normal::stereographic_normal;
pub use restitution::Restitution;
pub use scalar::{RefArith, Scalar, ScalarRoot};
pub use state::{skew_entries, skew_pairs, BodyState, State2, State3, State4, State5, State6};
pub use walton::Walton;
pub use wide::{Binary, Wide};
