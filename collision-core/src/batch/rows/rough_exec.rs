//! [`Exec::rough_free_rows`]: [`Exec::free_rows`] under laws of the rough-ball family given
//! as row-major columns ([`RestitutionRows`](super::RestitutionRows),
//! [`WaltonRows`](super::WaltonRows)): one law shared by every row, or one per row.

use super::law::{LawRowError, LawRows};
use super::pass::{EachLaw, SharedLaw};
use super::{FreeRows, StateRowsMut};
use crate::batch::each::EachLawBatchKernel;
use crate::batch::law_lanes::FamilyLaw;
use crate::batch::{Exec, RoughBatchKernel};
use crate::kernels::Generated;
use crate::{RefArith, Scalar};

/// The law lanes of a column type's law.
type LanesOf<T, R> = <<R as LawRows<T>>::Law as FamilyLaw>::Lanes;

impl Exec {
    /// [`Exec::free_rows`] under the laws `laws`: row `i` collided by
    /// `kernels::dN::rough::free` (or `walton::free`) under row `i`'s law, bit for bit.
    /// When every column of `laws` is a single value, the shared-law kernel runs
    /// (`rough_free`: what depends on the law alone computed once per call); else the
    /// `_each` kernel, with each row's law gathered into the blocks' law lanes.
    ///
    /// The laws are checked first ([`LawRows::check`]: each column one value per row or a
    /// single one, each value in its range): a refused law is an error naming the field
    /// and the row, and nothing is written. The contacts are not checked (as
    /// [`Exec::free_rows`]).
    ///
    /// # Panics
    /// As [`Exec::free_rows`]: if the lengths of `rows` or `out` do not fit.
    pub fn rough_free_rows<R, T, const N: usize, const S: usize>(
        &self,
        laws: &R,
        rows: &FreeRows<'_, T>,
        out: [StateRowsMut<'_, T>; 2],
    ) -> Result<(), LawRowError>
    where
        R: LawRows<T>,
        T: Scalar + Send + Sync + 'static,
        for<'a> &'a T: RefArith<T>,
        LanesOf<T, R>: 'static,
        Generated: RoughBatchKernel<R::Law, T, N, S> + EachLawBatchKernel<LanesOf<T, R>, T, N, S>,
    {
        laws.check(rows.len::<N>())?;
        match laws.shared() {
            Some(law) => self.rows_in_passes::<T, N, S, _>(&SharedLaw(&law), rows, out),
            None => self.rows_in_passes::<T, N, S, _>(
                &EachLaw(laws.slice(0..rows.len::<N>())),
                rows,
                out,
            ),
        }
        Ok(())
    }
}
