//! The general-n reference, built from the definitions with nalgebra: any `n >= 2`.
//!
//! Coordinates of a state `xi` (length `N = n(n-1) + 2n`): `[U_1, u_1, U_2, u_2]`, each `U_i`
//! as its compact skew entries (see [`crate::BodyState`]). The kinetic metric is diagonal
//! there: `2 m_i lambda_i` on each entry of `U_i` (`Tr(U U^T) = 2 sum_{i<j} U_ij^2`) and `m_i`
//! on each entry of `u_i`.
//!
//! An impulse `p` at the contact point `Q` (`p` on body 2, `-p` on body 1) changes the state by
//! ```text
//! du_1 = -w_1 p,  dU_1 = -(R_1 w_1 / (2 lambda_1)) nu ^ p,
//! du_2 =  w_2 p,  dU_2 = -(R_2 w_2 / (2 lambda_2)) nu ^ p
//! ```
//! and these velocity changes, for `p = e_1 .. e_n`, are the columns of a basis `B` of the
//! impulse space `E_q`. `M B` is the momentum change of the same impulses,
//! `(-R_1 nu ^ p, -p, -R_2 nu ^ p, p)`: no mass appears, so an immovable body (`w = 0`,
//! zero columns in `B`) needs no infinity. The collision is the metric reflection
//! ```text
//! xi+ = xi - 2 P_E xi,   P_E = B (B^T M B)^{-1} (M B)^T .
//! ```
//! This shares no code or formula with the generated kernels; it is their independent check
//! and the fallback for `n > 6`. It needs `lambda > 0` for each movable body (the point-mass
//! limit is a property of the kernels, checked by the verifier).

use crate::checked::validate_parts;
use crate::error::{BodyField, Field, InputError};
use crate::linalg::solve;
use crate::state::skew_pairs;
use crate::{Ball, BodyState, Scalar};
use nalgebra::{DMatrix, DVector};

/// Length of the coordinate vector of a two-body state in R^n.
pub fn state_len(n: usize) -> usize {
    n * (n - 1) + 2 * n
}

/// `[U_1, u_1, U_2, u_2]` as one vector.
pub fn coords<T: Scalar, const N: usize, const S: usize>(
    states: [&BodyState<T, N, S>; 2],
) -> DVector<T> {
    DVector::from_iterator(
        state_len(N),
        states
            .iter()
            .flat_map(|s| s.spin.iter().chain(&s.velocity).cloned()),
    )
}

/// The inverse of [`coords`].
pub fn from_coords<T: Scalar, const N: usize, const S: usize>(
    xi: &DVector<T>,
) -> [BodyState<T, N, S>; 2] {
    assert_eq!(xi.len(), 2 * (S + N));
    std::array::from_fn(|b| {
        let base = b * (S + N);
        BodyState {
            spin: std::array::from_fn(|k| xi[base + k].clone()),
            velocity: std::array::from_fn(|k| xi[base + S + k].clone()),
        }
    })
}

/// The compact entries of `a ^ b = b a^T - a b^T`: `(a ^ b)_ij = b_i a_j - a_i b_j`.
pub fn wedge<T: Scalar>(a: &[T], b: &[T]) -> Vec<T> {
    skew_pairs(a.len())
        .map(|(i, j)| b[i].clone() * a[j].clone() - a[i].clone() * b[j].clone())
        .collect()
}

fn unit<T: Scalar>(n: usize, k: usize) -> Vec<T> {
    (0..n)
        .map(|i| if i == k { T::one() } else { T::zero() })
        .collect()
}

/// Write one impulse column: body 1 gets `(a_1 nu ^ p, -c_1 p)`, body 2 `(a_2 nu ^ p, c_2 p)`.
fn impulse_columns<T: Scalar>(n: usize, nu: &[T], coef: [(T, T); 2]) -> DMatrix<T> {
    let s = n * (n - 1) / 2;
    let mut m = DMatrix::from_element(state_len(n), n, T::zero());
    for k in 0..n {
        let p = unit::<T>(n, k);
        let nu_p = wedge(nu, &p);
        for (b, (spin, lin)) in coef.iter().enumerate() {
            let base = b * (s + n);
            for (e, x) in nu_p.iter().enumerate() {
                m[(base + e, k)] = spin.clone() * x.clone();
            }
            let sign = if b == 0 { -T::one() } else { T::one() };
            m[(base + s + k, k)] = sign * lin.clone() * p[k].clone();
        }
    }
    m
}

/// `B`: the velocity changes of the impulses `p = e_1 .. e_n` (columns).
pub fn impulse_basis<T: Scalar>(nu: &[T], balls: [&Ball<T>; 2]) -> Result<DMatrix<T>, InputError> {
    let coef = |i: usize| -> Result<(T, T), InputError> {
        let b = balls[i];
        if b.is_immovable() {
            return Ok((T::zero(), T::zero()));
        }
        if b.gamma2.is_zero() {
            return Err(InputError::new(
                Field::Body(i, BodyField::Lambda),
                "the general-n reference (used for n > 6) needs lambda > 0 for a movable body",
            ));
        }
        // R w / (2 lambda) = w / (R gamma^2)
        let spin = -(b.inv_mass.clone() / (b.radius.clone() * b.gamma2.clone()));
        Ok((spin, b.inv_mass.clone()))
    };
    Ok(impulse_columns(nu.len(), nu, [coef(0)?, coef(1)?]))
}

/// `M B`: the momentum changes of the impulses `p = e_1 .. e_n` (columns).
pub fn momentum_basis<T: Scalar>(nu: &[T], radii: [&T; 2]) -> DMatrix<T> {
    let coef = |r: &T| (-r.clone(), T::one());
    impulse_columns(nu.len(), nu, [coef(radii[0]), coef(radii[1])])
}

/// What both maps solve with: the impulse basis `B`, the momentum basis `M B` and the Gram
/// matrix `B^T M B`.
struct GramSystem<T: Scalar> {
    b: DMatrix<T>,
    mb: DMatrix<T>,
    gram: DMatrix<T>,
}

/// The checks of [`crate::collide`] on the coordinates `xi`, then the [`GramSystem`].
fn gram_system<T: Scalar>(
    nu: &[T],
    balls: [&Ball<T>; 2],
    xi: &DVector<T>,
) -> Result<GramSystem<T>, InputError> {
    let n = nu.len();
    let s = n * (n - 1) / 2;
    if xi.len() != state_len(n) {
        return Err(InputError::new(
            Field::Dim,
            "state length does not match the normal",
        ));
    }
    let part =
        |b: usize, k: usize, len: usize| &xi.as_slice()[b * (s + n) + k..b * (s + n) + k + len];
    validate_parts(
        nu,
        balls,
        [
            (part(0, 0, s), part(0, s, n)),
            (part(1, 0, s), part(1, s, n)),
        ],
    )?;
    let b = impulse_basis(nu, balls)?;
    let mb = momentum_basis(nu, [&balls[0].radius, &balls[1].radius]);
    let gram = b.transpose() * &mb;
    Ok(GramSystem { b, mb, gram })
}

/// The collision map on coordinates, any `n >= 2`, after the checks of
/// [`crate::collide`].
pub fn collide_coords<T: Scalar>(
    nu: &[T],
    balls: [&Ball<T>; 2],
    xi: &DVector<T>,
) -> Result<DVector<T>, InputError> {
    let GramSystem { b, mb, gram } = gram_system(nu, balls, xi)?;
    let rhs = mb.transpose() * xi;
    // B^T M B is positive definite for valid inputs; in floats the elimination can still
    // overflow at extreme parameters.
    let a = solve(&gram, &rhs).ok_or_else(|| {
        InputError::new(
            Field::Bodies,
            format!(
                "the general-n reference (used for n > 6) failed in {}: its Gram solve overflowed at these extreme parameters; exact arithmetic computes it",
                T::NAME
            ),
        )
    })?;
    let two = T::one() + T::one();
    Ok(xi - b * a * two)
}

/// [`collide_coords`] on per-body states.
pub fn collide<T: Scalar, const N: usize, const S: usize>(
    nu: &[T; N],
    balls: [&Ball<T>; 2],
    states: [&BodyState<T, N, S>; 2],
) -> Result<[BodyState<T, N, S>; 2], InputError> {
    collide_coords(nu, balls, &coords(states)).map(|xi| from_coords(&xi))
}

/// The rough-ball map (`docs/derivation.md` §15) on coordinates, from the definitions: the
/// slip `s = (M B)^T xi` (`p . s = <B p, xi>`), its target `s+ = -e (s . nu) nu - beta (s -
/// (s . nu) nu)`, and the one impulse at `Q` that reaches it, `xi+ = xi + B p` with
/// `(B^T M B) p = s+ - s`. Shares no formula with the generated kernels. Inputs are
/// checked as in [`collide_coords`]; `law` is not range-checked (the map is defined for
/// every `(e, beta)`).
pub fn collide_rough_coords<T: Scalar>(
    nu: &[T],
    balls: [&Ball<T>; 2],
    law: &crate::Restitution<T>,
    xi: &DVector<T>,
) -> Result<DVector<T>, InputError> {
    let GramSystem { b, mb, gram } = gram_system(nu, balls, xi)?;
    let slip = mb.transpose() * xi;
    let normal = DVector::from_iterator(nu.len(), nu.iter().cloned());
    let dn = slip.dot(&normal);
    let tangential = &slip - &normal * dn.clone();
    let target = &normal * (-(law.e.clone() * dn)) - tangential * law.beta.clone();
    let p = solve(&gram, &(target - slip)).ok_or_else(|| {
        InputError::new(
            Field::Bodies,
            format!(
                "the general-n reference failed in {}: its Gram solve overflowed at these extreme parameters; exact arithmetic computes it",
                T::NAME
            ),
        )
    })?;
    Ok(xi + b * p)
}

/// [`collide_rough_coords`] on per-body states.
pub fn collide_rough<T: Scalar, const N: usize, const S: usize>(
    nu: &[T; N],
    balls: [&Ball<T>; 2],
    law: &crate::Restitution<T>,
    states: [&BodyState<T, N, S>; 2],
) -> Result<[BodyState<T, N, S>; 2], InputError> {
    collide_rough_coords(nu, balls, law, &coords(states)).map(|xi| from_coords(&xi))
}
