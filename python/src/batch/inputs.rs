//! The inputs of a batch as arrays: shapes checked, one row's normal, balls and states
//! read out of them (as row-major slices for `collision_core::batch::FreeRows` when they
//! are C-contiguous).

use crate::error::input_error;
use collision_core::batch::{BallRows, FreeRows, RestitutionRows, StateRows, WaltonRows};
use collision_core::{Ball, BodyState, Scalar};
use numpy::ndarray::{ArrayView1, ArrayView2, ArrayView3};
use pyo3::prelude::*;

/// The law's columns, as Python passes them (already of the batch's dtype, 1-D, contiguous).
pub(crate) enum LawColumns<'a, T> {
    /// `e`, `beta`.
    Rough(RestitutionRows<'a, T>),
    /// `e`, `mu`, `beta0`.
    Walton(WaltonRows<'a, T>),
}

/// The arrays of one body: `angular_velocity` `(N, n, n)`, `velocity` `(N, n)`, and the
/// kernel parameters `inv_mass`, `radius`, `gamma2`, each of length `N` or 1 (shared).
pub(super) struct BodyArrays<'a, T> {
    pub(super) spin: ArrayView3<'a, T>,
    pub(super) velocity: ArrayView2<'a, T>,
    pub(super) inv_mass: ArrayView1<'a, T>,
    pub(super) radius: ArrayView1<'a, T>,
    pub(super) gamma2: ArrayView1<'a, T>,
}

/// One body's arrays as views: angular velocity, velocity, `inv_mass`, `radius`, `gamma2`.
pub(crate) type BodyViews<'a, T> = (
    ArrayView3<'a, T>,
    ArrayView2<'a, T>,
    ArrayView1<'a, T>,
    ArrayView1<'a, T>,
    ArrayView1<'a, T>,
);

/// Every input of a batch, shapes checked.
pub(crate) struct Inputs<'a, T> {
    pub(super) rows: usize,
    pub(super) dim: usize,
    pub(super) nu: ArrayView2<'a, T>,
    pub(super) bodies: [BodyArrays<'a, T>; 2],
}

/// A shape as NumPy prints it: `(5, 3)`, `(5,)`, `()`.
pub(super) fn shape_text(shape: &[usize]) -> String {
    match shape {
        [one] => format!("({one},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(usize::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// The one shape message of the package: `field: expected shape (5, 3), got (6, 3)`.
pub(super) fn shape_error(field: &str, expected: String, got: &[usize]) -> PyErr {
    input_error(format!(
        "{field}: expected shape {expected}, got {}",
        shape_text(got)
    ))
}

impl<'a, T: Copy> Inputs<'a, T> {
    pub(crate) fn new(nu: ArrayView2<'a, T>, bodies: [BodyViews<'a, T>; 2]) -> PyResult<Self> {
        let (rows, dim) = nu.dim();
        if !collision_core::DIMS.contains(&dim) {
            return Err(input_error(format!(
                "normal: expected shape (N, n) with n in {}..={} (the dimensions with batch \
                 kernels; noslip.collide takes n up to 16), got {}",
                collision_core::DIMS[0],
                collision_core::DIMS[collision_core::DIMS.len() - 1],
                shape_text(nu.shape())
            )));
        }
        let mut checked = Vec::with_capacity(2);
        for (b, (spin, velocity, inv_mass, radius, gamma2)) in bodies.into_iter().enumerate() {
            let field = |k: &str| format!("bodies[{b}].{k}");
            if spin.dim() != (rows, dim, dim) {
                return Err(shape_error(
                    &field("angular_velocity"),
                    format!("({rows}, {dim}, {dim})"),
                    spin.shape(),
                ));
            }
            if velocity.dim() != (rows, dim) {
                return Err(shape_error(
                    &field("velocity"),
                    format!("({rows}, {dim})"),
                    velocity.shape(),
                ));
            }
            for (name, p) in [
                ("inv_mass", &inv_mass),
                ("radius", &radius),
                ("gamma2", &gamma2),
            ] {
                if p.len() != rows && p.len() != 1 {
                    return Err(shape_error(
                        &field(name),
                        format!("({rows},) or a scalar"),
                        p.shape(),
                    ));
                }
            }
            checked.push(BodyArrays {
                spin,
                velocity,
                inv_mass,
                radius,
                gamma2,
            });
        }
        let [b1, b2]: [BodyArrays<'a, T>; 2] = checked
            .try_into()
            .unwrap_or_else(|_| unreachable!("two bodies"));
        Ok(Inputs {
            rows,
            dim,
            nu,
            bodies: [b1, b2],
        })
    }
}

impl<'a, T> Inputs<'a, T> {
    /// The arrays as row-major slices (`collision_core::batch::FreeRows`), when every one is
    /// in standard layout (C-contiguous).
    pub(crate) fn rows(&self) -> Option<FreeRows<'a, T>> {
        let state = |b: &BodyArrays<'a, T>| {
            Some(StateRows {
                spin: b.spin.to_slice()?,
                velocity: b.velocity.to_slice()?,
            })
        };
        let ball = |b: &BodyArrays<'a, T>| {
            Some(BallRows {
                inv_mass: b.inv_mass.to_slice()?,
                radius: b.radius.to_slice()?,
                gamma2: b.gamma2.to_slice()?,
            })
        };
        let [a, b] = &self.bodies;
        Some(FreeRows {
            nu: self.nu.to_slice()?,
            states: [state(a)?, state(b)?],
            balls: [ball(a)?, ball(b)?],
        })
    }
}

/// Parameter `p` of row `i` (a length-1 array is shared by every row).
pub(super) fn param<T: Copy>(p: &ArrayView1<'_, T>, i: usize) -> T {
    p[if p.len() == 1 { 0 } else { i }]
}

impl<T: Scalar + Copy> BodyArrays<'_, T> {
    pub(super) fn ball(&self, i: usize) -> Ball<T> {
        Ball {
            inv_mass: param(&self.inv_mass, i),
            radius: param(&self.radius, i),
            gamma2: param(&self.gamma2, i),
        }
    }

    /// Row `i`'s state: the compact entries `U_rc`, `r < c` (upper triangle), and `u`.
    pub(super) fn state<const N: usize, const S: usize>(
        &self,
        i: usize,
        pairs: &[(usize, usize); S],
    ) -> BodyState<T, N, S> {
        // Row-major arrays (the usual case) are read as slices, without ndarray's
        // per-element index arithmetic and bounds checks.
        if let (Some(spin), Some(velocity)) = (self.spin.as_slice(), self.velocity.as_slice()) {
            let (spin, velocity) = (
                &spin[i * N * N..(i + 1) * N * N],
                &velocity[i * N..(i + 1) * N],
            );
            return BodyState {
                spin: pairs.map(|(r, c)| spin[r * N + c]),
                velocity: std::array::from_fn(|k| velocity[k]),
            };
        }
        BodyState {
            spin: pairs.map(|(r, c)| self.spin[[i, r, c]]),
            velocity: std::array::from_fn(|k| self.velocity[[i, k]]),
        }
    }

    /// Row `i`'s state as `collide`'s front end reads it (`BodyState::from_matrix`): `U`
    /// checked skew within the rounding allowance and its skew part `(U - U^T)/2` kept.
    pub(super) fn checked_state<const N: usize, const S: usize>(
        &self,
        i: usize,
        b: usize,
    ) -> Result<BodyState<T, N, S>, collision_core::InputError> {
        let m: [[T; N]; N] = std::array::from_fn(|r| std::array::from_fn(|c| self.spin[[i, r, c]]));
        let velocity = std::array::from_fn(|k| self.velocity[[i, k]]);
        BodyState::<T, N, S>::from_matrix(b, &m, velocity)
    }
}

/// Row `i`'s normal `nu`.
pub(super) fn nu_row<T: Copy, const N: usize>(input: &Inputs<'_, T>, i: usize) -> [T; N] {
    match input.nu.as_slice() {
        Some(nu) => std::array::from_fn(|k| nu[i * N + k]),
        None => std::array::from_fn(|k| input.nu[[i, k]]),
    }
}
