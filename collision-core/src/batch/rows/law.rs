//! Laws of the rough-ball family as row-major columns: `(e, beta)` ([`RestitutionRows`]) or
//! `(e, mu, beta0)` ([`WaltonRows`]), each column one value per contact or a single value
//! shared by every contact, as the balls' parameters are ([`super::BallRows`]). Checked
//! before a call runs ([`LawRows::check`]: the shape, then every value's range, naming the
//! field and the row); gathered into the lanes of the `_each` kernels a pass at a time.

use crate::batch::lanes::{Lanes, LANES};
use crate::batch::law_lanes::{FamilyLaw, RestitutionLanes, WaltonLanes, WithLaw};
use crate::error::{Field, InputError};
use crate::{Restitution, Scalar, Walton};
use std::fmt;
use std::ops::Range;

/// Normal and tangential restitutions, one per contact or one shared (a slice of one value).
#[derive(Clone, Copy, Debug)]
pub struct RestitutionRows<'a, T> {
    /// `e` in `[0, 1]`.
    pub e: &'a [T],
    /// `beta` in `[-1, 1]`.
    pub beta: &'a [T],
}

/// Walton laws, each column one value per contact or one shared.
#[derive(Clone, Copy, Debug)]
pub struct WaltonRows<'a, T> {
    /// `e` in `[0, 1]`.
    pub e: &'a [T],
    /// `mu >= 0`.
    pub mu: &'a [T],
    /// `beta0` in `[-1, 1]`.
    pub beta0: &'a [T],
}

/// A refused column of laws: its shape (`row` none), or the value of one row.
#[derive(Clone, Debug, PartialEq)]
pub struct LawRowError {
    /// The row whose law is refused; `None` for a column of the wrong length, or a refused
    /// value that every row shares (a column of one value).
    pub row: Option<usize>,
    /// The field and what is wrong with it (`restitution e: must be in [0, 1], got 1.5`).
    pub error: InputError,
}

impl fmt::Display for LawRowError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.row {
            Some(row) => write!(f, "row {row}: {}", self.error),
            None => write!(f, "{}", self.error),
        }
    }
}

impl std::error::Error for LawRowError {}

/// Columns of laws of the family ([`RestitutionRows`], [`WaltonRows`]).
pub trait LawRows<T>: Sync {
    /// The law of one contact.
    type Law: FamilyLaw + Sync;

    /// The law of row `i` (a shared column's one value for every row), unchecked.
    fn law(&self, i: usize) -> Self::Law;

    /// The one law of every row when every column is shared (a single value).
    fn shared(&self) -> Option<Self::Law> {
        self.columns()
            .iter()
            .all(|(_, c)| c.len() == 1)
            .then(|| self.law(0))
    }

    /// The columns, in the law's order, with their fields.
    fn columns(&self) -> Vec<(Field, &[T])>;

    /// Rows `range` (a shared column stays shared).
    fn slice(&self, range: Range<usize>) -> Self;

    /// The laws of rows `start..end` (at most 8) into `lanes`, lane `l` row `start + l`, the
    /// lanes past `end` repeating row `start`'s law.
    fn gather_block(&self, start: usize, end: usize, lanes: &mut <Self::Law as FamilyLaw>::Lanes);

    /// Checked for `len` contacts: every column one value per contact or a single one, and
    /// every row's law within its ranges (`Restitution::new` / `Walton::new`: `e` in
    /// `[0, 1]`, `beta` in `[-1, 1]`, `mu >= 0`, none NaN); the error names the field and,
    /// for a value, the row (the first refused).
    fn check(&self, len: usize) -> Result<(), LawRowError>;
}

/// The length check of the columns, in order: each one value per contact or one shared.
fn shapes<T>(columns: &[(Field, &[T])], len: usize) -> Result<(), LawRowError> {
    for &(field, column) in columns {
        if column.len() != len && column.len() != 1 {
            return Err(LawRowError {
                row: None,
                error: InputError::new(
                    field,
                    format!(
                        "{} values for {len} contacts (give one per contact, or one shared)",
                        column.len()
                    ),
                ),
            });
        }
    }
    Ok(())
}

/// `x[i]`, or the one value of a shared column.
fn at<T: Clone>(x: &[T], i: usize) -> T {
    x[if x.len() == 1 { 0 } else { i }].clone()
}

/// Rows `start..end` (at most 8) of `column` into `lanes`, the lanes past `end` repeating
/// row `start`: 8 consecutive values copied as they are, or the one value of a shared column.
#[inline(always)]
fn column_into<T: Clone>(column: &[T], start: usize, end: usize, lanes: &mut Lanes<T>) {
    if column.len() == 1 {
        lanes.fill(column[0].clone());
    } else if end - start == LANES {
        lanes.clone_from_slice(&column[start..end]);
    } else {
        for (l, x) in lanes.iter_mut().enumerate() {
            let i = if start + l < end { start + l } else { start };
            *x = column[i].clone();
        }
    }
}

/// Whether every value of `column` is in `[lo, hi]` (NaN is not; a loop without early exit
/// that LLVM vectorizes: the fast path of the checks).
fn all_within<T: Scalar>(column: &[T], lo: &T, hi: &T) -> bool {
    column.iter().fold(true, |ok, x| ok & (lo <= x) & (x <= hi))
}

/// Whether every value of `column` is finite and `>= 0`.
fn all_finite_non_negative<T: Scalar>(column: &[T]) -> bool {
    let zero = T::zero();
    column
        .iter()
        .fold(true, |ok, x| ok & (&zero <= x) & x.is_finite())
}

/// Checks each row of `len` contacts (one when every column is shared: its one law is checked
/// even for no contacts) with `law`, unless `fast` (every column within its range) says every
/// row passes: `law` then names the first refused row and field, or the field alone if its
/// column (in `columns`) holds one value shared by every row.
fn check_rows<T, L>(
    len: usize,
    fast: bool,
    columns: &[(Field, &[T])],
    law: impl Fn(usize) -> Result<L, InputError>,
) -> Result<(), LawRowError> {
    if fast {
        return Ok(());
    }
    let rows = if columns.iter().all(|(_, c)| c.len() == 1) {
        1
    } else {
        len
    };
    for i in 0..rows {
        law(i).map_err(|error| {
            let shared = columns
                .iter()
                .any(|(field, column)| *field == error.field && column.len() == 1);
            LawRowError {
                row: (!shared).then_some(i),
                error,
            }
        })?;
    }
    Ok(())
}

fn slice_column<'a, T>(x: &'a [T], range: &Range<usize>) -> &'a [T] {
    if x.len() == 1 {
        x
    } else {
        &x[range.clone()]
    }
}

impl<'a, T: Scalar + Send + Sync> LawRows<T> for RestitutionRows<'a, T> {
    type Law = Restitution<T>;

    fn law(&self, i: usize) -> Restitution<T> {
        Restitution {
            e: at(self.e, i),
            beta: at(self.beta, i),
        }
    }

    fn columns(&self) -> Vec<(Field, &[T])> {
        vec![
            (Field::RestitutionE, self.e),
            (Field::RestitutionBeta, self.beta),
        ]
    }

    fn slice(&self, range: Range<usize>) -> Self {
        RestitutionRows {
            e: slice_column(self.e, &range),
            beta: slice_column(self.beta, &range),
        }
    }

    fn check(&self, len: usize) -> Result<(), LawRowError> {
        let columns = self.columns();
        shapes(&columns, len)?;
        let (zero, one) = (T::zero(), T::one());
        let fast = all_within(self.e, &zero, &one) && all_within(self.beta, &-one.clone(), &one);
        check_rows(len, fast, &columns, |i| {
            Restitution::new(at(self.e, i), at(self.beta, i))
        })
    }

    #[inline(always)]
    fn gather_block(&self, start: usize, end: usize, lanes: &mut RestitutionLanes<T>) {
        column_into(self.e, start, end, &mut lanes.e);
        column_into(self.beta, start, end, &mut lanes.beta);
    }
}

impl<'a, T: Scalar + Send + Sync> LawRows<T> for WaltonRows<'a, T> {
    type Law = Walton<T>;

    fn law(&self, i: usize) -> Walton<T> {
        Walton {
            e: at(self.e, i),
            mu: at(self.mu, i),
            beta0: at(self.beta0, i),
        }
    }

    fn columns(&self) -> Vec<(Field, &[T])> {
        vec![
            (Field::RestitutionE, self.e),
            (Field::FrictionMu, self.mu),
            (Field::WaltonBeta0, self.beta0),
        ]
    }

    fn slice(&self, range: Range<usize>) -> Self {
        WaltonRows {
            e: slice_column(self.e, &range),
            mu: slice_column(self.mu, &range),
            beta0: slice_column(self.beta0, &range),
        }
    }

    fn check(&self, len: usize) -> Result<(), LawRowError> {
        let columns = self.columns();
        shapes(&columns, len)?;
        let (zero, one) = (T::zero(), T::one());
        let fast = all_within(self.e, &zero, &one)
            && all_finite_non_negative(self.mu)
            && all_within(self.beta0, &-one.clone(), &one);
        check_rows(len, fast, &columns, |i| {
            Walton::new(at(self.e, i), at(self.mu, i), at(self.beta0, i))
        })
    }

    #[inline(always)]
    fn gather_block(&self, start: usize, end: usize, lanes: &mut WaltonLanes<T>) {
        column_into(self.e, start, end, &mut lanes.e);
        column_into(self.mu, start, end, &mut lanes.mu);
        column_into(self.beta0, start, end, &mut lanes.beta0);
    }
}

/// The laws of rows `range` into the law lanes of the first `range.len().div_ceil(8)` of
/// `blocks`; a last, partial block's lanes past the end repeat its first row's law (as
/// [`Batch::push`](crate::batch::Batch::push) pads).
pub(super) fn gather_laws<T, R: LawRows<T>, B>(
    laws: &R,
    range: Range<usize>,
    blocks: &mut [WithLaw<B, <R::Law as FamilyLaw>::Lanes>],
) {
    for (b, block) in blocks.iter_mut().enumerate() {
        let start = range.start + b * LANES;
        if start >= range.end {
            break;
        }
        laws.gather_block(start, range.end.min(start + LANES), &mut block.law);
    }
}
