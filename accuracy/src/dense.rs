//! The dense-matrix form a reader of the notes would write: build the `N x N` block matrix
//! of the notes' page 22 for each collision, then multiply it by the state
//! `xi = [U_1, u_1, U_2, u_2]` (`N = n(n-1) + 2n`).
//!
//! With `Gamma(U) = U nu` (`n x s`), `E(u) = nu ^ u` (`s x n`, `E = Gamma^T` on compact skew
//! entries), `Lambda = E Gamma` (`nu ^ U nu`), `Pi = I - nu nu^T`, and the inverse-mass
//! coefficients of the closed form, `a = 1/(w_1 + w_2)`, `p_t = g_1 g_2 / D`,
//! `rho_i = 2 w_i g_j / (R_i D)`, `K = a nu nu^T + p_t Pi`:
//!
//! ```text
//!          U_1                    u_1          U_2                 u_2
//! U_1+ [ I - rho_1 R_1 Lambda,  -rho_1 E,    -rho_1 R_2 Lambda,   rho_1 E    ]
//! u_1+ [ -2 w_1 p_t R_1 Gamma,  I - 2 w_1 K, -2 w_1 p_t R_2 Gamma, 2 w_1 K    ]
//! U_2+ [ -rho_2 R_1 Lambda,     -rho_2 E,    I - rho_2 R_2 Lambda, rho_2 E    ]
//! u_2+ [ 2 w_2 p_t R_1 Gamma,   2 w_2 K,     2 w_2 p_t R_2 Gamma,  I - 2 w_2 K]
//! ```
//!
//! An immovable body (`w = 0`) gets identity rows: no dispatch, no special case.

use collision_core::reference::{coords, from_coords};
use collision_core::{skew_pairs, Ball, BodyState, Scalar};
use nalgebra::DMatrix;

/// The collision matrix `C` with `xi+ = C xi`.
pub fn matrix<T: Scalar>(nu: &[T], balls: [&Ball<T>; 2]) -> DMatrix<T> {
    let n = nu.len();
    let s = n * (n - 1) / 2;
    let mut gamma = DMatrix::from_element(n, s, T::zero());
    for (k, (i, j)) in skew_pairs(n).enumerate() {
        gamma[(i, k)] = nu[j].clone();
        gamma[(j, k)] = -nu[i].clone();
    }
    let e = gamma.transpose();
    let lambda = &e * &gamma;
    let nn = DMatrix::from_fn(n, n, |i, j| nu[i].clone() * nu[j].clone());
    let pi = DMatrix::identity(n, n) - &nn;

    let [b1, b2] = balls;
    let (w1, w2) = (b1.inv_mass.clone(), b2.inv_mass.clone());
    let (g1, g2) = (b1.gamma2.clone(), b2.gamma2.clone());
    let one = T::one();
    let two = T::one() + T::one();
    let d = w1.clone() * g2.clone() * (one.clone() + g1.clone())
        + w2.clone() * g1.clone() * (one + g2.clone());
    let a = T::one() / (w1.clone() + w2.clone());
    let p_t = g1.clone() * g2.clone() / d.clone();
    let rho1 = two.clone() * w1.clone() * g2 / (b1.radius.clone() * d.clone());
    let rho2 = two.clone() * w2.clone() * g1 / (b2.radius.clone() * d);
    let k = nn * a + pi * p_t.clone();
    let (r1, r2) = (b1.radius.clone(), b2.radius.clone());

    let len = 2 * (s + n);
    let mut c = DMatrix::identity(len, len);
    let (spin1, vel1, spin2, vel2) = (0, s, s + n, 2 * s + n);
    let mut add = |row: usize, col: usize, block: DMatrix<T>| {
        let mut view = c.view_mut((row, col), block.shape());
        view += block;
    };
    for (row, rho) in [(spin1, rho1), (spin2, rho2)] {
        add(row, spin1, &lambda * -(rho.clone() * r1.clone()));
        add(row, vel1, &e * -rho.clone());
        add(row, spin2, &lambda * -(rho.clone() * r2.clone()));
        add(row, vel2, &e * rho);
    }
    for (row, coef) in [(vel1, -(two.clone() * w1)), (vel2, two * w2)] {
        add(
            row,
            spin1,
            &gamma * (coef.clone() * p_t.clone() * r1.clone()),
        );
        add(row, vel1, &k * coef.clone());
        add(
            row,
            spin2,
            &gamma * (coef.clone() * p_t.clone() * r2.clone()),
        );
        add(row, vel2, &k * -coef);
    }
    c
}

/// The post-collision states: build the matrix, multiply.
pub fn collide<T: Scalar, const N: usize, const S: usize>(
    nu: &[T; N],
    balls: [&Ball<T>; 2],
    states: [&BodyState<T, N, S>; 2],
) -> [BodyState<T, N, S>; 2] {
    from_coords(&(matrix(nu, balls) * coords(states)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use collision_core::rng::Rng;
    use collision_core::{collide_unchecked, Exact, Generated, Kernel};
    use noslip_verify::sample::point;

    fn equals_generated<const N: usize, const S: usize>()
    where
        Generated: Kernel<Exact, N, S>,
    {
        let mut rng = Rng::new(40 + N as u64);
        for fixed in [false, true] {
            for _ in 0..4 {
                let p = point::<N, S>(&mut rng, fixed);
                let balls = [&p.balls[0], &p.balls[1]];
                let states = [&p.states[0], &p.states[1]];
                assert_eq!(
                    collide(&p.nu, balls, states),
                    collide_unchecked(&p.nu, balls, states),
                    "n = {N}, fixed = {fixed}"
                );
            }
        }
    }

    #[test]
    fn the_dense_form_is_the_generated_map_exactly() {
        equals_generated::<2, 1>();
        equals_generated::<3, 3>();
        equals_generated::<4, 6>();
        equals_generated::<5, 10>();
        equals_generated::<6, 15>();
    }
}
