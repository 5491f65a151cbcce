//! One body of a case as given: its mass, radius, inertia, and its angular velocity in the
//! form given (kept for the output).

use collision_core::{Inertia, Mass};

/// The angular velocity as given: the form is kept for the output.
#[derive(Clone, Debug, PartialEq)]
pub enum Spin<T> {
    /// The full `n x n` matrix, row by row.
    Matrix(Vec<Vec<T>>),
    /// 2D only: `U = c J`, `J = [[0, -1], [1, 0]]`.
    Scalar(T),
    /// 3D only: `U x = omega x x`.
    Omega([T; 3]),
}

/// One body as given.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyInput<T> {
    /// `mass`: a number, or `"inf"` for an immovable body.
    pub mass: Mass<T>,
    /// `radius`: `R`.
    pub radius: T,
    /// From `lambda`, `gamma2` or `distribution` (uniform when none is given).
    pub inertia: Inertia<T>,
    /// `angular_velocity`: `U`, in the form given.
    pub spin: Spin<T>,
    /// `velocity`: the centre velocity `u`.
    pub velocity: Vec<T>,
}
