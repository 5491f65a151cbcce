//! Batch kernels: the collision map applied to many contacts at once, `LANES` = 8 at a
//! time, vectorized, on the widest instruction set of the CPU (chosen at run time), and
//! optionally on several threads (feature `parallel`).
//!
//! For every contact `k` of a batch,
//!
//! ```text
//! xi_k+ = 2 P_G(q_k) xi_k- - xi_k-
//! ```
//!
//! computed by the generated scalar kernel's operations on the same operands (the batch
//! kernels are emitted from the same DAG by `noslip_codegen::batch`, in the scalar kernel's
//! order or in one that holds fewer values at once), so that in `f32` and `f64` every result
//! is bit for bit [`crate::kernels`]' result on that contact, and in [`crate::Exact`] the
//! same rational.
//!
//! **Layout.** Blocked structure of arrays (AoSoA): a block holds `LANES` contacts, every
//! scalar field as a `[T; LANES]` lane array ([`lanes`]); a [`Batch`] is a vector of blocks
//! with a length, built from and read back as the per-collision types:
//!
//! | batch | one item | kernel |
//! |---|---|---|
//! | [`FreeBatch`] | `(Contact, [Ball; 2])` | [`Exec::free`]: both bodies free, balls per contact |
//! | [`FixedBatch`] | `(Contact, radius1, Ball)` | [`Exec::fixed`]: body 1 immovable, parameters per contact |
//! | [`ContactBatch`] | [`Contact`] (`nu`, both states) | [`Exec::free_shared`], [`Exec::fixed_shared`]: one set of ball parameters for the batch |
//! | [`PairBatch`] | `[BodyState; 2]` | output of `free`, `free_shared` |
//! | [`StateBatch`] | `BodyState` | output of `fixed`, `fixed_shared` (body 2) |
//!
//! **Execution.** [`Exec`] picks the instruction set ([`Isa`]: the default target, AVX2 +
//! FMA, AVX-512F; [`Exec::auto`] takes the widest this CPU has) and, with the `parallel`
//! feature, splits batches of at least [`PARALLEL_FROM_BYTES`] of input and output across
//! rayon's pool. Its methods [`Exec::free`], [`Exec::fixed`], [`Exec::free_shared`] and
//! [`Exec::fixed_shared`] run the kernels; [`BatchKernel`] reaches the generated block
//! kernels of each n directly.
//!
//! **Preconditions** are those of the scalar kernels (see [`crate::kernels`]); nothing is
//! validated, and invalid contacts give NaN or infinities in their own lanes only.
//!
//! ```
//! use collision_core::batch::{Contact, Exec, FreeBatch, PairBatch};
//! use collision_core::{Ball, Inertia, Mass, State3};
//! let ball = Ball::new(3, Mass::Finite(1.0), 1.0, Inertia::Uniform).unwrap();
//! let falling = State3::from_omega([0.0, 0.0, 2.0], [0.0, -1.0, 0.0]);
//! let contact = Contact { nu: [0.0, 1.0, 0.0], states: [State3::zero(), falling] };
//! let contacts: FreeBatch<f64, 3, 3> =
//!     (0..20).map(|_| (contact.clone(), [ball.clone(), ball.clone()])).collect();
//! let mut after = PairBatch::new();
//! Exec::auto().free(&contacts, &mut after);
//! assert_eq!(after.len(), 20);
//! let [b1, b2] = after.get(19).unwrap();
//! assert_eq!(b1.velocity[1] + b2.velocity[1], -1.0); // momentum is conserved
//! ```

mod container;
mod dispatch;
mod each;
mod exec;
mod kept;
pub mod kernels;
pub mod lanes;
mod law_lanes;
mod prefetch;
mod rough;
mod rows;
#[cfg(feature = "parallel")]
mod share;

#[cfg(test)]
mod tests;

pub use container::Batch;
pub use dispatch::{Isa, AVX2_WIDTH, AVX512_WIDTH, BASELINE_WIDTH};
pub use each::{EachLawBatchKernel, FixedEachBatch, FreeEachBatch};
pub use exec::{BatchError, Exec, PARALLEL_FROM_BYTES};
pub use kernels::BatchKernel;
pub use lanes::{
    BallLanes, Contact, ContactLanes, FixedLanes, FreeLanes, Lane, Lanes, Lanewise, StateLanes,
    BLOCK_ALIGN, LANES,
};
pub use law_lanes::{FamilyLaw, RestitutionLanes, WaltonLanes, WithLaw};
pub use prefetch::{prefetch, prefetch_distance, PREFETCH_BYTES};
pub use rough::RoughBatchKernel;
pub use rows::{
    BallRows, FixedRows, FreeRows, LawRowError, LawRows, RestitutionRows, StateRows, StateRowsMut,
    WaltonRows, ROWS_IN_CACHE_BYTES, ROWS_PASS_BYTES, ROWS_PASS_BYTES_OUT_OF_CACHE,
};
#[cfg(feature = "parallel")]
pub use share::share_rows;

/// Contacts of two free balls with their own parameters.
pub type FreeBatch<T, const N: usize, const S: usize> = Batch<FreeLanes<T, N, S>>;
/// Contacts with an immovable body 1, with their own parameters.
pub type FixedBatch<T, const N: usize, const S: usize> = Batch<FixedLanes<T, N, S>>;
/// Contacts (normal and states) for the shared-parameter kernels.
pub type ContactBatch<T, const N: usize, const S: usize> = Batch<ContactLanes<T, N, S>>;
/// Both bodies' states of every contact.
pub type PairBatch<T, const N: usize, const S: usize> = Batch<[StateLanes<T, N, S>; 2]>;
/// One body's state of every contact.
pub type StateBatch<T, const N: usize, const S: usize> = Batch<StateLanes<T, N, S>>;
