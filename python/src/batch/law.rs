//! `collide_batch(..., contact=law)`: the rough-ball family on every row, each row's law from
//! columns `e`, `beta` (the rough law) or `e`, `mu`, `beta0` (Walton), each `(N,)` or one
//! value shared by every row.
//!
//! The columns are checked first (`LawRows::check`: their lengths, then every value's range;
//! the error names the row and the field, `row 3: contact.e: must be in [0, 1], got 1.5`).
//! With `validate`, each row goes through `collision_core::collide_rough` /
//! `collide_walton` (`collide`'s checks, unbounded-exponent kernel and rounding, under the
//! row's law), on the calling thread. Without, row-major arrays go through
//! `Exec::rough_free_rows` (the shared-law kernel when every column is one value, else the
//! `_each` kernel: the scalar family kernel's bits on every row), then the rows with an
//! immovable body are gathered and rerun by `Exec::rough_fixed_rows` (the `fixed` kernel, as
//! `collide_unchecked` routes it: `fixed_law.rs`); other strides go row by row through
//! `collide_rough_unchecked` / `collide_walton_unchecked`. Not split on the validated path, and not interrupted by Ctrl-C (a batch of 10^6
//! rows takes about 0.1 s unvalidated, 1-2 s validated).

use super::inputs::{nu_row, Inputs, LawColumns};
use super::outputs::{put, state_rows_mut, Outputs};
use collision_core::batch::{
    EachLawBatchKernel, Exec, LawRowError, LawRows, RestitutionLanes, RoughBatchKernel, WaltonLanes,
};
use collision_core::kernels::{RoughKernel, WaltonKernel};
use collision_core::{
    collide_rough, collide_rough_unchecked, collide_walton, collide_walton_unchecked, BodyState,
    Generated, RefArith, Restitution, Scalar, ScalarRoot, Walton,
};
use noslip_case::CaseError;

/// A refused column, named as the case format names the law's fields (`contact.e`, ...).
fn law_error(e: LawRowError) -> String {
    let field = CaseError::from(e.error);
    match e.row {
        Some(row) => format!("row {row}: {field}"),
        None => field.to_string(),
    }
}

/// Every row of `input` under `laws` into `out`; a refused law or (with `validate`) row
/// is the error message.
///
/// `fresh`: `out` is new memory, never written. The row path then runs its passes from the
/// last rows to the first ([`Exec::last_rows_first`]); from 16 MiB of outputs, new or not,
/// its results are streamed (`run::row_exec`, as for the no-slip map): the same results,
/// and the same error, since every law is checked before any row runs.
pub(super) fn run_law<T, const N: usize, const S: usize>(
    input: &Inputs<'_, T>,
    laws: &LawColumns<'_, T>,
    validate: bool,
    parallel: bool,
    fresh: bool,
    mut out: Outputs<'_, T>,
) -> Result<(), String>
where
    T: Scalar + ScalarRoot + Copy + Send + Sync + 'static,
    T::Unbounded: ScalarRoot,
    for<'x> &'x T: RefArith<T>,
    Generated: RoughKernel<T, N, S>
        + WaltonKernel<T, N, S>
        + RoughKernel<T::Unbounded, N, S>
        + WaltonKernel<T::Unbounded, N, S>
        + RoughBatchKernel<Restitution<T>, T, N, S>
        + RoughBatchKernel<Walton<T>, T, N, S>
        + EachLawBatchKernel<RestitutionLanes<T>, T, N, S>
        + EachLawBatchKernel<WaltonLanes<T>, T, N, S>,
{
    let rows = input.rows;
    match laws {
        LawColumns::Rough(l) => l.check(rows),
        LawColumns::Walton(l) => l.check(rows),
    }
    .map_err(law_error)?;
    let pairs: [(usize, usize); S] = {
        let all: Vec<(usize, usize)> = collision_core::skew_pairs(N).collect();
        std::array::from_fn(|k| all[k])
    };
    let [a, b] = &input.bodies;
    let row = |i: usize| {
        let nu = nu_row::<T, N>(input, i);
        (nu, [a.ball(i), b.ball(i)])
    };
    if validate {
        for i in 0..rows {
            let (nu, [b1, b2]) = row(i);
            let s1 = a.checked_state::<N, S>(i, 0);
            let s2 = b.checked_state::<N, S>(i, 1);
            let done = s1.and_then(|s1| {
                let s2 = s2?;
                match laws {
                    LawColumns::Rough(l) => collide_rough(&nu, [&b1, &b2], &l.law(i), [&s1, &s2]),
                    LawColumns::Walton(l) => collide_walton(&nu, [&b1, &b2], &l.law(i), [&s1, &s2]),
                }
            });
            let [p1, p2] =
                done.map_err(|e| format!("row {i}: {}", super::checked::row_error(e)))?;
            put(&mut out, i, 0, &p1, &pairs);
            put(&mut out, i, 1, &p2, &pairs);
        }
        return Ok(());
    }
    let unchecked = |i: usize| -> [BodyState<T, N, S>; 2] {
        let (nu, [b1, b2]) = row(i);
        let (s1, s2) = (a.state::<N, S>(i, &pairs), b.state::<N, S>(i, &pairs));
        match laws {
            LawColumns::Rough(l) => collide_rough_unchecked(&nu, [&b1, &b2], &l.law(i), [&s1, &s2]),
            LawColumns::Walton(l) => {
                collide_walton_unchecked(&nu, [&b1, &b2], &l.law(i), [&s1, &s2])
            }
        }
    };
    let Some(free_rows) = input.rows() else {
        for i in 0..rows {
            let [p1, p2] = unchecked(i);
            put(&mut out, i, 0, &p1, &pairs);
            put(&mut out, i, 1, &p2, &pairs);
        }
        return Ok(());
    };
    let exec = if parallel {
        Exec::auto()
    } else {
        Exec::auto().serial()
    };
    let exec = super::run::row_exec::<T, N>(exec, fresh, rows);
    {
        let Outputs {
            spin: [s1, s2],
            velocity: [v1, v2],
        } = &mut out;
        let target = state_rows_mut([s1, s2], [v1, v2]);
        match laws {
            LawColumns::Rough(l) => exec.rough_free_rows::<_, T, N, S>(l, &free_rows, target),
            LawColumns::Walton(l) => exec.rough_free_rows::<_, T, N, S>(l, &free_rows, target),
        }
        .map_err(law_error)?;
    }
    // The rows with an immovable body: the `fixed` kernel on the row path, as
    // `collide_unchecked` routes them (none to look for when both bodies share a finite mass).
    let zero = T::zero();
    let [w1, w2] = [&a.inv_mass, &b.inv_mass];
    if w1.len() == 1 && w2.len() == 1 && w1[0] != zero && w2[0] != zero {
        return Ok(());
    }
    super::fixed_law::run_fixed_rows::<T, N, S>(input, laws, exec, &mut out).map_err(law_error)
}
