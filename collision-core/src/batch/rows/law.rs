//! Laws of the rough-ball family as row-major columns: `(e, beta)` ([`RestitutionRows`]) or
//! `(e, mu, beta0)` ([`WaltonRows`]), each column one value per contact or a single value
//! shared by every contact, as the balls' parameters are ([`super::BallRows`]). Checked
//! before a call runs ([`LawRows::check`]: the shape, then every value's range, naming the
//! field and the row); gathered into the lanes of the `_each` kernels a pass at a time.

use crate::batch::lanes::{Lane, Lanewise, LANES};
use crate::batch::law_lanes::{FamilyLaw, WithLaw};
use crate::error::InputError;
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
    /// The row whose law is refused; `None` for a column of the wrong length.
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
            .all(|c| c.len() == 1)
            .then(|| self.law(0))
    }

    /// The columns, in the law's order, with their fields.
    fn columns(&self) -> Vec<&[T]>;

    /// Rows `range` (a shared column stays shared).
    fn slice(&self, range: Range<usize>) -> Self;

    /// Checked for `len` contacts: every column one value per contact or a single one, and
    /// every row's law within its ranges (`Restitution::new` / `Walton::new`: `e` in
    /// `[0, 1]`, `beta` in `[-1, 1]`, `mu >= 0`, none NaN); the error names the field and,
    /// for a value, the row (the first refused).
    fn check(&self, len: usize) -> Result<(), LawRowError>;
}

/// The length check of one column named by `field`.
fn shape<T>(column: &[T], len: usize, field: crate::error::Field) -> Result<(), LawRowError> {
    if column.len() == len || column.len() == 1 {
        return Ok(());
    }
    Err(LawRowError {
        row: None,
        error: InputError::new(
            field,
            format!(
                "{} values for {len} contacts (give one per contact, or one shared)",
                column.len()
            ),
        ),
    })
}

/// `x[i]`, or the one value of a shared column.
fn at<T: Clone>(x: &[T], i: usize) -> T {
    x[if x.len() == 1 { 0 } else { i }].clone()
}

/// Checks each row from 0 to `rows` (1 when every column is shared) with `law`.
fn check_rows<L>(
    rows: usize,
    law: impl Fn(usize) -> Result<L, InputError>,
) -> Result<(), LawRowError> {
    for i in 0..rows {
        law(i).map_err(|error| LawRowError {
            row: Some(i),
            error,
        })?;
    }
    Ok(())
}

/// The number of rows to check: `len`, or 1 when every column is shared.
fn rows_to_check<T>(columns: &[&[T]], len: usize) -> usize {
    if columns.iter().all(|c| c.len() == 1) {
        len.min(1)
    } else {
        len
    }
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

    fn columns(&self) -> Vec<&[T]> {
        vec![self.e, self.beta]
    }

    fn slice(&self, range: Range<usize>) -> Self {
        RestitutionRows {
            e: slice_column(self.e, &range),
            beta: slice_column(self.beta, &range),
        }
    }

    fn check(&self, len: usize) -> Result<(), LawRowError> {
        use crate::error::Field;
        shape(self.e, len, Field::RestitutionE)?;
        shape(self.beta, len, Field::RestitutionBeta)?;
        check_rows(rows_to_check(&self.columns(), len), |i| {
            Restitution::new(at(self.e, i), at(self.beta, i))
        })
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

    fn columns(&self) -> Vec<&[T]> {
        vec![self.e, self.mu, self.beta0]
    }

    fn slice(&self, range: Range<usize>) -> Self {
        WaltonRows {
            e: slice_column(self.e, &range),
            mu: slice_column(self.mu, &range),
            beta0: slice_column(self.beta0, &range),
        }
    }

    fn check(&self, len: usize) -> Result<(), LawRowError> {
        use crate::error::Field;
        shape(self.e, len, Field::RestitutionE)?;
        shape(self.mu, len, Field::FrictionMu)?;
        shape(self.beta0, len, Field::WaltonBeta0)?;
        check_rows(rows_to_check(&self.columns(), len), |i| {
            Walton::new(at(self.e, i), at(self.mu, i), at(self.beta0, i))
        })
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
        for l in Lane::all() {
            let i = start + l.index();
            let i = if i < range.end { i } else { start };
            block.law.set_lane(l, laws.law(i));
        }
    }
}
