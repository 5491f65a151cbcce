//! Row-major arrays in and out of the blocked layout: contacts gathered from the arrays of
//! NumPy or C (one contact per row: `nu` `(len, n)`, angular velocities `(len, n, n)`,
//! velocities `(len, n)`, ball parameters `(len,)` or one shared value) straight into the
//! lane arrays of a [`FreeBatch`], and results scattered from a [`PairBatch`] straight into
//! such arrays, with no per-contact [`Contact`](super::Contact) or
//! [`BodyState`](crate::BodyState) in between.
//!
//! The result is the same batch as [`Batch::push`](super::Batch::push) of each row's item would build (padding
//! lanes included: copies of their block's first contact), and the rows written are what
//! [`Batch::get`](super::Batch::get) returns, each compact state as its full skew matrix (`+0` on the diagonal,
//! `U_cr = 0 - U_rc`: a zero entry is `+0` on both sides).
//!
//! - `gather.rs`: rows into blocks ([`FreeBatch::fill_from_rows`]);
//! - `scatter.rs`: blocks into rows ([`PairBatch::write_rows`](super::PairBatch::write_rows));
//! - `exec.rs`: both around the kernel, a few blocks at a time
//!   ([`Exec::free_rows`](super::Exec::free_rows)), so that the blocks stay in the L1 cache
//!   and the row-major arrays are read and written once, in address order;
//! - `law.rs`, `pass.rs`, `rough_exec.rs`: the same under laws of the rough-ball family
//!   given as columns, one shared or one per row
//!   ([`Exec::rough_free_rows`](super::Exec::rough_free_rows));
//! - `rough_fixed.rs`: the family's `fixed` kernels (body 1 immovable) on row-major arrays
//!   ([`Exec::rough_fixed_rows`](super::Exec::rough_fixed_rows), [`FixedRows`]).
//!
//! - `plan.rs`, `avx512.rs`: a full block's transpose in `f64` at AVX-512 for n <= 3, as
//!   two-source permutes (`vpermt2pd`) planned at compile time.
//!
//! The gather and the scatter are compiled for each instruction-set level, as the kernels
//! are (`dispatch::at_level`), and run on the level [`Isa::detect`](super::Isa::detect)
//! picks (or the `Exec`'s own level in `free_rows`).

// The AVX-512 intrinsics are stable from Rust 1.89: this module is compiled only from that
// version on (`cfg(noslip_avx512_intrinsics)`, set by build.rs), and the crate's older minimum
// still builds, with the portable transposes at every level.
#[cfg(all(target_arch = "x86_64", noslip_avx512_intrinsics))]
#[clippy::msrv = "1.89"]
mod avx512;
mod exec;
mod gather;
mod law;
mod pass;
#[cfg(any(test, all(target_arch = "x86_64", noslip_avx512_intrinsics)))]
mod plan;
mod rough_exec;
mod rough_fixed;
#[cfg(test)]
mod rough_fixed_tests;

pub use exec::{ROWS_IN_CACHE_BYTES, ROWS_PASS_BYTES, ROWS_PASS_BYTES_OUT_OF_CACHE};
pub use law::{LawRowError, LawRows, RestitutionRows, WaltonRows};
pub use rough_fixed::FixedRows;
#[cfg(test)]
mod law_tests;
mod scatter;
#[cfg(test)]
mod tests;

use std::ops::Range;

/// One body's states, one contact per row: contact `i`'s angular velocity `U` is the full
/// `n x n` matrix `spin[i n^2 .. (i + 1) n^2]`, row-major (entry `U_rc` at `r n + c`), and
/// its velocity `u` is `velocity[i n .. (i + 1) n]`. Gathering reads the entries above the
/// diagonal, `U_rc` with `r < c` (the compact state); it does not check that `U` is skew.
#[derive(Clone, Copy, Debug)]
pub struct StateRows<'a, T> {
    /// The angular velocities, `n^2` entries per contact.
    pub spin: &'a [T],
    /// The velocities, `n` entries per contact.
    pub velocity: &'a [T],
}

/// [`StateRows`] to write into.
#[derive(Debug)]
pub struct StateRowsMut<'a, T> {
    /// The angular velocities, `n^2` entries per contact.
    pub spin: &'a mut [T],
    /// The velocities, `n` entries per contact.
    pub velocity: &'a mut [T],
}

/// One body's parameters ([`Ball`](crate::Ball)'s fields): each slice holds one value per
/// contact, or a single value shared by every contact.
#[derive(Clone, Copy, Debug)]
pub struct BallRows<'a, T> {
    /// Inverse masses `w = 1/m`.
    pub inv_mass: &'a [T],
    /// Radii `R`.
    pub radius: &'a [T],
    /// `gamma^2 = 2 lambda / R^2`.
    pub gamma2: &'a [T],
}

/// Contacts of two balls with their own parameters, one per row: what
/// [`FreeBatch::fill_from_rows`](crate::batch::FreeBatch::fill_from_rows) reads. The number
/// of contacts is `nu.len() / n`.
#[derive(Clone, Copy, Debug)]
pub struct FreeRows<'a, T> {
    /// The unit normals `nu` (from body 1's centre to body 2's), `n` entries per contact.
    pub nu: &'a [T],
    /// Body 1's and body 2's states.
    pub states: [StateRows<'a, T>; 2],
    /// Body 1's and body 2's parameters.
    pub balls: [BallRows<'a, T>; 2],
}

impl<T> FreeRows<'_, T> {
    /// The number of contacts, `nu.len() / n`, after checking every slice's length.
    ///
    /// # Panics
    /// If a length does not fit: `nu.len()` not a multiple of `n`, a state slice not `n^2`
    /// (angular velocity) or `n` (velocity) entries per contact, a parameter slice neither
    /// one entry per contact nor a single one.
    pub fn len<const N: usize>(&self) -> usize {
        assert_eq!(self.nu.len() % N, 0, "nu: {N} entries per contact");
        let len = self.nu.len() / N;
        for (b, (s, p)) in self.states.iter().zip(&self.balls).enumerate() {
            assert_eq!(s.spin.len(), len * N * N, "body {b}: spin: n^2 per contact");
            assert_eq!(
                s.velocity.len(),
                len * N,
                "body {b}: velocity: n per contact"
            );
            for x in [p.inv_mass, p.radius, p.gamma2] {
                assert!(x.len() == len || x.len() == 1, "body {b}: parameters");
            }
        }
        len
    }

    /// Whether there are no contacts.
    pub fn is_empty(&self) -> bool {
        self.nu.is_empty()
    }
}

impl<'a, T> FreeRows<'a, T> {
    /// Contacts `range` of these rows (a shared parameter stays shared).
    ///
    /// # Panics
    /// If `range` is not within the rows (as slicing does).
    pub fn slice<const N: usize>(&self, range: Range<usize>) -> FreeRows<'a, T> {
        let (a, b) = (range.start, range.end);
        let param = |p: &'a [T]| if p.len() == 1 { p } else { &p[a..b] };
        FreeRows {
            nu: &self.nu[a * N..b * N],
            states: self.states.each_ref().map(|s| StateRows {
                spin: &s.spin[a * N * N..b * N * N],
                velocity: &s.velocity[a * N..b * N],
            }),
            balls: self.balls.each_ref().map(|p| BallRows {
                inv_mass: param(p.inv_mass),
                radius: param(p.radius),
                gamma2: param(p.gamma2),
            }),
        }
    }
}

impl<T> StateRowsMut<'_, T> {
    /// Contacts `range` of these rows, to write into.
    ///
    /// # Panics
    /// If `range` is not within the rows (as slicing does).
    pub fn slice<const N: usize>(&mut self, range: Range<usize>) -> StateRowsMut<'_, T> {
        let (a, b) = (range.start, range.end);
        StateRowsMut {
            spin: &mut self.spin[a * N * N..b * N * N],
            velocity: &mut self.velocity[a * N..b * N],
        }
    }
}

/// The entries `(r, c)`, `r < c`, of an `n x n` skew matrix in the order of
/// [`BodyState::spin`](crate::BodyState::spin) ([`skew_pairs`](crate::skew_pairs)), as a
/// constant: `const { pairs::<N, S>() }` gives the gather and scatter fixed offsets.
pub(crate) const fn pairs<const N: usize, const S: usize>() -> [(usize, usize); S] {
    let mut out = [(0, 0); S];
    let (mut r, mut k) = (0, 0);
    while r < N {
        let mut c = r + 1;
        while c < N {
            out[k] = (r, c);
            k += 1;
            c += 1;
        }
        r += 1;
    }
    assert!(k == S, "S = n (n - 1) / 2");
    out
}
