//! The boundary map of a one-ball table as a map of section states, and its exact derivative.
//!
//! A section state `z = (x, u, U)` (`2n + S` numbers) is the ball just after a contact: its
//! centre on the contact surface of a boundary, its velocity and spin. `P(z)` is the state
//! just after the next contact. Its derivative is the tangent maps' (flight, contact) followed
//! by the projection onto the section along the flow: the perturbed ball reaches the section
//! `dt = -(nu . dx') / (nu . u')` later, so
//!
//! ```text
//! DP dz = dz' + (u', 0, 0) dt,    dz' = (contact tangent map) (flight) dz
//! ```
//!
//! In `R^(2n+S)` the matrix `DP^K` has the eigenvalue 0 along the flow direction `(u, 0, 0)` at
//! the start (a start moved along its own orbit lands on the same section points); the other
//! `2n + S - 1` eigenvalues are those of the return map on the section, and its
//! characteristic polynomial is that of `DP^K` divided by `lambda`.

use crate::dual::Dual;
use crate::geometry::dot;
use crate::root::Root;
use crate::table::{NoHit, Table};
use crate::tangent::{block_len, boundary_contact, flight};
use collision_core::{BodyState, Generated, Kernel, RefArith};

/// A section state `(x, u, U)`.
#[derive(Clone, Debug, PartialEq)]
pub struct Section<T, const N: usize, const S: usize> {
    /// The centre, on a boundary's contact surface.
    pub x: [T; N],
    /// The velocity and spin just after the contact.
    pub state: BodyState<T, N, S>,
}

impl<T: Clone, const N: usize, const S: usize> Section<T, N, S> {
    /// `[x, u, U]` as one vector.
    pub fn to_vec(&self) -> Vec<T> {
        self.x
            .iter()
            .chain(&self.state.velocity)
            .chain(&self.state.spin)
            .cloned()
            .collect()
    }

    /// From `[x, u, U]`.
    pub fn from_slice(v: &[T]) -> Self {
        Section {
            x: std::array::from_fn(|k| v[k].clone()),
            state: BodyState {
                velocity: std::array::from_fn(|k| v[N + k].clone()),
                spin: std::array::from_fn(|k| v[2 * N + k].clone()),
            },
        }
    }
}

/// `K` steps of the return map: the state after each contact and the boundaries touched,
/// and (columns) the derivative `DP^K` of the whole.
#[derive(Clone, Debug)]
pub struct Return<T, const N: usize, const S: usize> {
    /// The section states after contacts `1..=K`.
    pub states: Vec<Section<T, N, S>>,
    /// The boundaries touched, in order.
    pub boundaries: Vec<usize>,
    /// `DP^K` as `2n + S` columns (column `a` is the image of `e_a`).
    pub columns: Vec<Vec<T>>,
}

/// `K` steps of the return map from `z`, with its derivative.
pub fn return_map<T: Root, const N: usize, const S: usize>(
    table: &Table<T, N>,
    z: &Section<T, N, S>,
    k: usize,
) -> Result<Return<T, N, S>, NoHit>
where
    for<'a> &'a T: RefArith<T>,
    for<'a> &'a Dual<T>: RefArith<Dual<T>>,
    Generated: Kernel<T, N, S> + Kernel<Dual<T>, N, S>,
{
    let len = block_len(N, S);
    let mut columns: Vec<Vec<T>> = (0..len)
        .map(|a| {
            (0..len)
                .map(|b| if a == b { T::one() } else { T::zero() })
                .collect()
        })
        .collect();
    let mut z = z.clone();
    let mut states = Vec::with_capacity(k);
    let mut boundaries = Vec::with_capacity(k);
    for _ in 0..k {
        let hit = table.next_hit(&z.x, &z.state.velocity)?;
        let geometry = table.boundaries[hit.boundary].geometry(&table.ball.radius);
        let after = table.laws[hit.boundary].boundary(&hit.nu, &table.ball, &z.state);
        for c in columns.iter_mut() {
            flight::<T, N>(c, &hit.time);
            boundary_contact(
                &geometry,
                table.laws[hit.boundary],
                &table.ball,
                &hit.nu,
                &z.state,
                c,
            );
            let dx: [T; N] = std::array::from_fn(|i| c[i].clone());
            let dt = -dot(&hit.nu, &dx) / dot(&hit.nu, &after.velocity);
            for (ci, ui) in c.iter_mut().zip(&after.velocity) {
                *ci = ci.clone() + ui.clone() * dt.clone();
            }
        }
        z = Section {
            x: hit.position,
            state: after,
        };
        states.push(z.clone());
        boundaries.push(hit.boundary);
    }
    Ok(Return {
        states,
        boundaries,
        columns,
    })
}
