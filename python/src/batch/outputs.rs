//! The outputs of a batch: the caller's arrays (`out=`) checked and borrowed read-write, the
//! output memory as row-major slices, and one row's states written into it as full skew
//! matrices.

use super::inputs::{shape_error, shape_text};
use crate::error::input_error;
use collision_core::batch::StateRowsMut;
use collision_core::{BodyState, Scalar};
use numpy::{Element, PyArray2, PyArray3, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;

/// The output arrays' memory: per body, the `(N, n, n)` angular velocities and the `(N, n)`
/// velocities, row-major.
pub(super) struct Outputs<'a, T> {
    pub(super) spin: [&'a mut [T]; 2],
    pub(super) velocity: [&'a mut [T]; 2],
}

/// Output arrays a caller passes in (`out=`): body 1's and body 2's angular velocities
/// `(N, n, n)` and velocities `(N, n)`, C-contiguous and writeable.
pub(crate) type OutIn<'py, T> = (
    Bound<'py, PyArray3<T>>,
    Bound<'py, PyArray2<T>>,
    Bound<'py, PyArray3<T>>,
    Bound<'py, PyArray2<T>>,
);

/// The caller's output arrays' shapes and layout (`out[b].angular_velocity`,
/// `out[b].velocity` named in the error); whether they can be written is checked when they
/// are borrowed.
pub(super) fn check_out<T: Element>(out: &OutIn<'_, T>, rows: usize, n: usize) -> PyResult<()> {
    let (s1, v1, s2, v2) = out;
    for (b, spin, velocity) in [(0, s1, v1), (1, s2, v2)] {
        for (key, want, got, contiguous) in [
            (
                "angular_velocity",
                vec![rows, n, n],
                spin.shape(),
                spin.is_c_contiguous(),
            ),
            (
                "velocity",
                vec![rows, n],
                velocity.shape(),
                velocity.is_c_contiguous(),
            ),
        ] {
            let field = format!("out[{b}].{key}");
            if got != want.as_slice() {
                return Err(shape_error(&field, shape_text(&want), got));
            }
            if !contiguous {
                return Err(input_error(format!(
                    "{field}: must be C-contiguous (the rows are written in place)"
                )));
            }
        }
    }
    Ok(())
}

/// A read-write borrow of output `field`: refused (naming it) when the array is read-only
/// or shares memory with an input (borrowed read-only) or another output.
pub(super) fn borrow_out<'py, T: Element, D: numpy::ndarray::Dimension>(
    array: &Bound<'py, numpy::PyArray<T, D>>,
    field: &str,
) -> PyResult<numpy::PyReadwriteArray<'py, T, D>> {
    array.try_readwrite().map_err(|e| {
        input_error(match e {
            numpy::BorrowError::NotWriteable => format!("{field}: must be writeable"),
            _ => format!(
                "{field}: shares memory with an input or another output (the outputs must \
                 be arrays of their own)"
            ),
        })
    })
}

/// Both bodies' row-major outputs, as `PairBatch::write_rows` takes them.
pub(crate) fn state_rows_mut<'a, T>(
    [s1, s2]: [&'a mut [T]; 2],
    [v1, v2]: [&'a mut [T]; 2],
) -> [StateRowsMut<'a, T>; 2] {
    [
        StateRowsMut {
            spin: s1,
            velocity: v1,
        },
        StateRowsMut {
            spin: s2,
            velocity: v2,
        },
    ]
}

/// The compact entries as a full skew matrix, row-major, `m_cr = 0 - m_rc` (so a zero entry
/// is `+0` on both sides, as `noslip collide` prints it).
pub(super) fn write_state<T: Scalar + Copy, const N: usize, const S: usize>(
    s: &BodyState<T, N, S>,
    pairs: &[(usize, usize); S],
    spin: &mut [T],
    velocity: &mut [T],
) {
    for (r, row) in spin.chunks_exact_mut(N).enumerate() {
        row[r] = T::zero();
    }
    for (&(r, c), &x) in pairs.iter().zip(&s.spin) {
        spin[r * N + c] = x;
        spin[c * N + r] = T::zero() - x;
    }
    velocity.copy_from_slice(&s.velocity);
}

/// Write body `body`'s state into local row `j` of `out`.
pub(super) fn put<T: Scalar + Copy, const N: usize, const S: usize>(
    out: &mut Outputs<'_, T>,
    j: usize,
    body: usize,
    s: &BodyState<T, N, S>,
    pairs: &[(usize, usize); S],
) {
    write_state(
        s,
        pairs,
        &mut out.spin[body][j * N * N..(j + 1) * N * N],
        &mut out.velocity[body][j * N..(j + 1) * N],
    );
}
