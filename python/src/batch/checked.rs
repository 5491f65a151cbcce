//! The validated rows of `collide_batch`: each row through `collision_core::collide`
//! itself, so that a row is accepted or refused, and its result rounded, exactly as
//! `noslip.collide` does it.
//!
//! `collide` checks the inputs under the rounding allowance (and clamps: `nu`
//! renormalised, `gamma2` set to its bound, a grazing normal velocity removed), runs the
//! kernel with an unbounded exponent (`collision_core::Wide`) and rounds the results back,
//! refusing a result beyond the float type's range or one whose components below the
//! normal range would cost more than the rounding allowance of the body's energy norm. The batch kernels in the float type agree with it only where no
//! intermediate leaves the range and nothing is clamped: a velocity of `1e308` against an
//! immovable body overflowed to `-inf` in the kernel where `collide` returns the finite
//! `3.3e307`, and a velocity of `5e-324` came back subnormal where `collide` refuses it
//! (issue 26). Both now come from `collide`, bit for bit, whatever the range checks of
//! `collide` become: they are called, not copied.

use super::inputs::{nu_row, Inputs};
use super::outputs::{put, Outputs};
use collision_core::{collide, BodyState, Generated, Kernel, Scalar};
use collision_core::{BodyField, Field};
use noslip_case::CaseError;

/// A bad row: its index and the message (`row 17: bodies[1].gamma2: ...`).
pub(super) type RowError = (usize, String);

/// `collide` on row `i`: `U` read as `BodyState::from_matrix` reads it (skew within the
/// allowance, its skew part kept), then `collide`'s checks, kernel and rounding. The error,
/// built only here, names the row and the field.
pub(super) fn collide_row<T, const N: usize, const S: usize>(
    input: &Inputs<'_, T>,
    i: usize,
) -> Result<[BodyState<T, N, S>; 2], RowError>
where
    T: Scalar + Copy,
    Generated: Kernel<T::Unbounded, N, S>,
{
    let [a, b] = &input.bodies;
    let nu = nu_row::<T, N>(input, i);
    let (b1, b2) = (a.ball(i), b.ball(i));
    a.checked_state::<N, S>(i, 0)
        .and_then(|s1| Ok((s1, b.checked_state::<N, S>(i, 1)?)))
        .and_then(|(s1, s2)| collide::<T, N, S>(&nu, [&b1, &b2], [&s1, &s2]))
        .map_err(|e| (i, format!("row {i}: {}", row_error(e))))
}

/// Rows `start..start + out.velocity[0].len() / N`, each by [`collide_row`], into `out`;
/// the first bad row's error.
pub(super) fn run_chunk_checked<T, const N: usize, const S: usize>(
    input: &Inputs<'_, T>,
    start: usize,
    mut out: Outputs<'_, T>,
    pairs: &[(usize, usize); S],
) -> Result<(), RowError>
where
    T: Scalar + Copy,
    Generated: Kernel<T::Unbounded, N, S>,
{
    for j in 0..out.velocity[0].len() / N {
        let [s1, s2] = collide_row::<T, N, S>(input, start + j)?;
        put(&mut out, j, 0, &s1, pairs);
        put(&mut out, j, 1, &s2, pairs);
    }
    Ok(())
}

/// `collide`'s error on a row, its field named by the batch's keys: the batch takes
/// `inv_mass` where `collide` takes `mass` (collision-core's `BodyField::Mass` stands for
/// both), so that field is `bodies[b].inv_mass`; the others are named as in a case.
pub(super) fn row_error(e: collision_core::InputError) -> CaseError {
    match e.field {
        Field::Body(b, BodyField::Mass) => {
            CaseError::new(format!("bodies[{b}].inv_mass"), e.message)
        }
        _ => CaseError::from(e),
    }
}
