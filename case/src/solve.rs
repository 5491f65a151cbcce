//! Validate a case and run the collision: the generated kernels for `n = 2..6`
//! (`collision_core::collide`, the same generic code for `f64` and exact rationals), the
//! general-n reference (`collision_core::reference::collide_coords`) above.
//!
//! collision-core does every check and writes every message; this module only shapes the
//! case into its types.

use crate::case::{BodyInput, Case, Spin};
use crate::contact::Contact;
use crate::error::CaseError;
use crate::number::InputScalar;
use collision_core::reference::state_len;
use collision_core::{
    collide, collide_general, collide_rough, collide_walton, skew_entries, Ball, BodyState,
    Generated, Kernel, RefArith, RoughKernel, State2, State3, WaltonKernel,
};
use nalgebra::DVector;

/// A body after the collision: the compact angular velocity (the entries `U_ij`, `i < j`, in
/// the order of [`collision_core::skew_pairs`]) and the velocity.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyOutput<T> {
    /// Compact entries `U_ij`, `i < j`, of the angular velocity after the collision.
    pub spin: Vec<T>,
    /// The centre velocity `u` after the collision.
    pub velocity: Vec<T>,
}

/// The post-collision states of a case's two bodies.
pub fn solve<T>(case: &Case<T>) -> Result<[BodyOutput<T>; 2], CaseError>
where
    T: InputScalar,
    for<'a> &'a T::Unbounded: RefArith<T::Unbounded>,
{
    let balls = [
        ball(case.dim, &case.bodies[0], 0)?,
        ball(case.dim, &case.bodies[1], 1)?,
    ];
    if case.contact != Contact::NoSlip && !collision_core::DIMS.contains(&case.dim) {
        return Err(CaseError::new(
            "contact",
            format!(
                "the rough-ball and Walton laws have kernels for dim in {:?} only, got dim = {}",
                collision_core::DIMS,
                case.dim
            ),
        ));
    }
    collision_core::with_dim!(
        case.dim,
        |N, S| solve_kernel::<T, N, S>(case, &balls),
        solve_reference(case, &balls)
    )
}

/// A validated ball (collision-core's checks and messages).
fn ball<T: InputScalar>(dim: usize, body: &BodyInput<T>, i: usize) -> Result<Ball<T>, CaseError> {
    Ball::new(
        dim,
        body.mass.clone(),
        body.radius.clone(),
        body.inertia.clone(),
    )
    .map_err(|e| e.at_body(i).into())
}

fn array<T, const K: usize>(v: Vec<T>) -> Result<[T; K], CaseError> {
    v.try_into().map_err(|v: Vec<T>| wrong_length::<K>(v.len()))
}

/// The error of a vector of `len` values where `K` were expected (an internal error: the
/// case's reader checks every length).
fn wrong_length<const K: usize>(len: usize) -> CaseError {
    CaseError::new(
        "",
        format!("internal error: expected {K} values, got {len}"),
    )
}

/// [`array`] of a borrowed slice: its values cloned straight into the array.
fn array_of<T: Clone, const K: usize>(v: &[T]) -> Result<[T; K], CaseError> {
    if v.len() != K {
        return Err(wrong_length::<K>(v.len()));
    }
    Ok(std::array::from_fn(|k| v[k].clone()))
}

/// The state of body `i` in the form the kernels take.
fn state<T: InputScalar, const N: usize, const S: usize>(
    body: &BodyInput<T>,
    i: usize,
) -> Result<BodyState<T, N, S>, CaseError> {
    let velocity: [T; N] = array_of(&body.velocity)?;
    match &body.spin {
        Spin::Matrix(rows) => {
            if let Some(row) = rows.iter().find(|r| r.len() != N) {
                return Err(wrong_length::<N>(row.len()));
            }
            if rows.len() != N {
                return Err(wrong_length::<N>(rows.len()));
            }
            let rows: [[T; N]; N] =
                std::array::from_fn(|r| std::array::from_fn(|c| rows[r][c].clone()));
            Ok(BodyState::from_matrix(i, &rows, velocity)?)
        }
        Spin::Scalar(c) => {
            let s = State2::from_scalar_spin(c.clone(), array(body.velocity.clone())?);
            Ok(BodyState {
                spin: array(s.spin.to_vec())?,
                velocity,
            })
        }
        Spin::Omega(w) => {
            let s = State3::from_omega(w.clone(), array(body.velocity.clone())?);
            Ok(BodyState {
                spin: array(s.spin.to_vec())?,
                velocity,
            })
        }
    }
}

fn solve_kernel<T, const N: usize, const S: usize>(
    case: &Case<T>,
    balls: &[Ball<T>; 2],
) -> Result<[BodyOutput<T>; 2], CaseError>
where
    T: InputScalar,
    Generated: Kernel<T::Unbounded, N, S>
        + RoughKernel<T::Unbounded, N, S>
        + WaltonKernel<T::Unbounded, N, S>,
{
    let states: [BodyState<T, N, S>; 2] = [state(&case.bodies[0], 0)?, state(&case.bodies[1], 1)?];
    let balls = [&balls[0], &balls[1]];
    let nu: [T; N] = array(case.normal.clone())?;
    let states = [&states[0], &states[1]];
    let out = match &case.contact {
        Contact::NoSlip => collide(&nu, balls, states)?,
        Contact::Rough(law) => collide_rough(&nu, balls, law, states)?,
        Contact::Walton(law) => collide_walton(&nu, balls, law, states)?,
    };
    Ok(out.map(|s| BodyOutput {
        spin: s.spin.to_vec(),
        velocity: s.velocity.to_vec(),
    }))
}

/// The compact entries of a full `n x n` angular velocity (collision-core's skew check).
fn compact_spin<T: InputScalar>(
    body: &BodyInput<T>,
    i: usize,
    n: usize,
) -> Result<Vec<T>, CaseError> {
    let Spin::Matrix(m) = &body.spin else {
        return Err(CaseError::new(
            format!("bodies[{i}].angular_velocity"),
            format!("expected a {n} x {n} matrix"),
        ));
    };
    Ok(skew_entries(i, m)?)
}

/// `n > 6`: the general-n reference (collision-core's checks and arithmetic as for the kernels).
fn solve_reference<T: InputScalar>(
    case: &Case<T>,
    balls: &[Ball<T>; 2],
) -> Result<[BodyOutput<T>; 2], CaseError> {
    let n = case.dim;
    let spins = [
        compact_spin(&case.bodies[0], 0, n)?,
        compact_spin(&case.bodies[1], 1, n)?,
    ];
    let velocities = [&case.bodies[0].velocity, &case.bodies[1].velocity];
    let balls = [&balls[0], &balls[1]];
    let xi = DVector::from_iterator(
        state_len(n),
        (0..2).flat_map(|b| spins[b].iter().chain(velocities[b]).cloned()),
    );
    let out = collide_general(&case.normal, balls, &xi)?;
    let s = spins[0].len();
    let part = |b: usize| BodyOutput {
        spin: out.as_slice()[b * (s + n)..b * (s + n) + s].to_vec(),
        velocity: out.as_slice()[b * (s + n) + s..(b + 1) * (s + n)].to_vec(),
    };
    Ok([part(0), part(1)])
}
