//! The closed form of `docs/derivation.md` §7 written literally, by hand, in `f64`, as a reader
//! would write it: the baseline the generated kernels are measured against (benchmarks,
//! and the "before" of the error report). Use the generated kernels: this form divides by
//! `gamma^2` (`k_i = w_i / g_i`), so a point mass (`gamma2 = 0`) gives NaN, and the literal
//! `nu ^ P` amplifies the rounding of `nu ^ (p_n nu) = 0` by `2 k_i / R_i`.
//!
//! ```text
//! k_i  = w_i / g_i                        (g = gamma^2 = 2 lambda / R^2)
//! mu_t = w_1 + w_2 + k_1 + k_2
//! c    = R_1 U_1 nu + R_2 U_2 nu
//! du   = u_2 - u_1,   dn = du . nu,   t = du - dn nu - c
//! P    = (dn / (w_1 + w_2)) nu + t / mu_t
//! u_1+ = u_1 + 2 w_1 P                    u_2+ = u_2 - 2 w_2 P
//! U_1+ = U_1 + (2 k_1 / R_1) nu ^ P       U_2+ = U_2 + (2 k_2 / R_2) nu ^ P
//! ```
//!
//! with `(a ^ b)_ij = b_i a_j - a_i b_j` on the compact skew entries `i < j`, in the order
//! `(0,1), (0,2), .., (1,2), ..` (as [`crate::BodyState`]).
//!
//! Generic over the dimension with fixed-size loops whose trip counts are constants after
//! monomorphization (`N`, or `S` over a constant table of `(i, j)` pairs), which LLVM
//! unrolls completely: the compiled code is straight-line, with no heap and no branches on
//! data. 6 divisions (`k_1`, `k_2`, `dn / (w_1 + w_2)`, `1 / mu_t`, `2 k_1 / R_1`,
//! `2 k_2 / R_2`); `t / mu_t` is computed as one reciprocal and `N` multiplications, as
//! anyone writing it by hand would.
//!
//! Accumulators start at `-0.0`, the exact additive identity of IEEE addition
//! (`-0.0 + x == x` for every `x`, including `x = -0.0`), so LLVM folds the first addition
//! away; starting at `0.0` would cost one real addition per sum (`0.0 + -0.0 = 0.0`).

use crate::{Ball, BodyState};

/// The `(i, j)`, `i < j`, of each compact skew entry, as a constant table.
struct Pairs<const N: usize, const S: usize>;

impl<const N: usize, const S: usize> Pairs<N, S> {
    const IJ: [(usize, usize); S] = {
        assert!(S == N * (N - 1) / 2, "S must be N(N-1)/2");
        let mut ij = [(0, 0); S];
        let mut p = 0;
        let mut i = 0;
        while i < N {
            let mut j = i + 1;
            while j < N {
                ij[p] = (i, j);
                p += 1;
                j += 1;
            }
            i += 1;
        }
        ij
    };
}

/// `U x` for the skew `U` stored as its compact entries (`U_ji = -U_ij`).
#[inline(always)]
fn skew_mul<const N: usize, const S: usize>(spin: &[f64; S], x: &[f64; N]) -> [f64; N] {
    let mut out = [-0.0; N];
    for (&(i, j), &u) in Pairs::<N, S>::IJ.iter().zip(spin) {
        out[i] += u * x[j];
        out[j] -= u * x[i];
    }
    out
}

/// Compact entries of `a ^ b`: `(a ^ b)_ij = b_i a_j - a_i b_j`.
#[inline(always)]
fn wedge<const N: usize, const S: usize>(a: &[f64; N], b: &[f64; N]) -> [f64; S] {
    let mut out = [0.0; S];
    for (o, &(i, j)) in out.iter_mut().zip(&Pairs::<N, S>::IJ) {
        *o = b[i] * a[j] - a[i] * b[j];
    }
    out
}

/// The no-slip collision of two free balls in R^N: `[body 1, body 2]` after contact. Same
/// inputs, outputs and preconditions as `collision_core::kernels::dN::free::<f64>`.
#[inline]
pub fn free<const N: usize, const S: usize>(
    nu: &[f64; N],
    ball1: &Ball<f64>,
    ball2: &Ball<f64>,
    state1: &BodyState<f64, N, S>,
    state2: &BodyState<f64, N, S>,
) -> [BodyState<f64, N, S>; 2] {
    let (w1, r1, g1) = (ball1.inv_mass, ball1.radius, ball1.gamma2);
    let (w2, r2, g2) = (ball2.inv_mass, ball2.radius, ball2.gamma2);
    let k1 = w1 / g1;
    let k2 = w2 / g2;
    let mu_t = w1 + w2 + k1 + k2;

    let (u1, u2) = (&state1.velocity, &state2.velocity);
    let u1nu = skew_mul(&state1.spin, nu);
    let u2nu = skew_mul(&state2.spin, nu);

    let mut du = [0.0; N];
    let mut dn = -0.0;
    for a in 0..N {
        du[a] = u2[a] - u1[a];
        dn += du[a] * nu[a];
    }

    let p_n = dn / (w1 + w2);
    let inv_mu_t = 1.0 / mu_t;
    let mut p = [0.0; N];
    for a in 0..N {
        let c = r1 * u1nu[a] + r2 * u2nu[a];
        let t = du[a] - dn * nu[a] - c;
        p[a] = p_n * nu[a] + t * inv_mu_t;
    }

    let nu_p: [f64; S] = wedge(nu, &p);
    let (a1, a2) = (2.0 * k1 / r1, 2.0 * k2 / r2);
    let (v1, v2) = (2.0 * w1, 2.0 * w2);
    [
        BodyState {
            spin: std::array::from_fn(|e| state1.spin[e] + a1 * nu_p[e]),
            velocity: std::array::from_fn(|a| u1[a] + v1 * p[a]),
        },
        BodyState {
            spin: std::array::from_fn(|e| state2.spin[e] + a2 * nu_p[e]),
            velocity: std::array::from_fn(|a| u2[a] - v2 * p[a]),
        },
    ]
}
