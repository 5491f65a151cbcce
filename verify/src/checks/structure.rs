//! Structural checks at exact sample configurations: the orthogonal decomposition
//! `T_q M = G_q (+) Ebar_q (+) R n_q` and its dimensions, built from the definitions:
//! `G_q` as the null space of the no-slip condition `V_1(Q) = V_2(Q)`, `E_q` from the
//! velocity changes of impulses at `Q`, the kinetic metric `M`. For the fixed variant the
//! space is the movable body's.

use crate::sample::point;
use collision_core::linalg::{nullspace, rank};
use collision_core::reference::{impulse_basis, state_len};
use collision_core::rng::Rng;
use collision_core::{skew_pairs, Exact};
use nalgebra::{DMatrix, DVector};
use noslip_codegen::model::Variant;
use num_traits::{One, Zero};

/// What the structural checks found at one configuration.
#[derive(Debug)]
pub struct Structure {
    /// `dim G_q`: the rank of the no-slip subspace's basis.
    pub dim_g: usize,
    /// `dim Ebar_q`: the rank of the tangential impulses' velocity changes.
    pub dim_ebar: usize,
    /// `dim E_q`: the rank of all impulses' velocity changes.
    pub dim_e: usize,
    /// The rank of `G_q`, `Ebar_q` and `n_q` together.
    pub span: usize,
    /// The dimension of the movable bodies' state space (`n(n-1) + 2n` for two free bodies).
    pub space: usize,
}

fn fail(what: &str) -> Result<Structure, String> {
    Err(what.to_string())
}

/// The decomposition at one random configuration.
pub fn check_at<const N: usize, const S: usize>(
    variant: Variant,
    rng: &mut Rng,
) -> Result<Structure, String> {
    let p = point::<N, S>(rng, variant == Variant::Fixed);
    let movable: Vec<usize> = match variant {
        Variant::Free => vec![0, 1],
        Variant::Fixed => vec![1],
    };
    // Coordinates of the movable bodies: [U_i (S entries), u_i (N entries)] each.
    let coords: Vec<usize> = movable
        .iter()
        .flat_map(|&b| (0..S + N).map(move |k| b * (S + N) + k))
        .collect();
    let dim = coords.len();
    // The kinetic metric, diagonal: 2 m lambda = m g R^2 on U entries, m on u entries.
    let metric = DVector::from_iterator(
        dim,
        movable.iter().flat_map(|&b| {
            let ball = &p.balls[b];
            let m = Exact::one() / &ball.inv_mass;
            let rot = &m * &ball.gamma2 * &ball.radius * &ball.radius;
            std::iter::repeat_n(rot, S).chain(std::iter::repeat_n(m, N))
        }),
    );
    let inner = |a: &DMatrix<Exact>, b: &DMatrix<Exact>| {
        a.transpose() * DMatrix::from_diagonal(&metric) * b
    };

    // The no-slip condition as a matrix: column j is V_2(Q) - V_1(Q) of the unit state e_j,
    // with V_1(Q) = R_1 U_1 nu + u_1 and V_2(Q) = -R_2 U_2 nu + u_2 (U as a full matrix).
    let mut slip = DMatrix::from_element(N, dim, Exact::zero());
    for (j, &c) in coords.iter().enumerate() {
        let (b, k) = (c / (S + N), c % (S + N));
        let sign = if b == 0 { -Exact::one() } else { Exact::one() };
        if k < S {
            let (r, s) = skew_pairs(N).nth(k).expect("k < S");
            // U = E_rs - E_sr: (U nu)_r = nu_s, (U nu)_s = -nu_r.
            let scale = if b == 0 {
                p.balls[0].radius.clone()
            } else {
                -p.balls[1].radius.clone()
            };
            slip[(r, j)] = &sign * &scale * &p.nu[s];
            slip[(s, j)] = -(&sign * &scale * &p.nu[r]);
        } else {
            slip[(k - S, j)] = sign;
        }
    }
    let overflow = || "non-finite value in exact arithmetic".to_string();
    let g = nullspace(&slip).ok_or_else(overflow)?;

    // Impulse space: velocity changes of p = e_1..e_n; Ebar: p orthogonal to nu.
    let b_full = impulse_basis(&p.nu, [&p.balls[0], &p.balls[1]]).map_err(|e| e.to_string())?;
    let b = DMatrix::from_fn(dim, N, |i, k| b_full[(coords[i], k)].clone());
    let nu = DMatrix::from_row_slice(1, N, &p.nu);
    let ebar = &b * nullspace(&nu).ok_or_else(overflow)?;
    let n_dir = &b * DMatrix::from_column_slice(N, 1, &p.nu);
    // n_q = n_dir / sqrt(w_1 + w_2): its direction in coordinates is
    // (0, -w_1 nu, 0, w_2 nu); it is unit iff |n_dir|^2 = w_1 + w_2.
    let w_sum = &p.balls[0].inv_mass + &p.balls[1].inv_mass;
    for (i, &c) in coords.iter().enumerate() {
        let (body, k) = (c / (S + N), c % (S + N));
        let expected = if k < S {
            Exact::zero()
        } else if body == 0 {
            -&p.balls[0].inv_mass * &p.nu[k - S]
        } else {
            &p.balls[1].inv_mass * &p.nu[k - S]
        };
        if n_dir[(i, 0)] != expected {
            return fail("n_q is not (0, -nu/m_1, 0, nu/m_2) normalised");
        }
    }
    if inner(&n_dir, &n_dir)[(0, 0)] != w_sum {
        return fail("n_q is not a unit vector in the metric");
    }
    // Pointing into the allowed region: d/dt |a_2 - a_1| = (u_2 - u_1) . nu > 0.
    if w_sum <= Exact::zero() {
        return fail("n_q does not point into the allowed region");
    }
    let zero = |m: &DMatrix<Exact>| m.iter().all(Zero::is_zero);
    if !zero(&inner(&g, &ebar)) {
        return fail("G_q and Ebar_q are not orthogonal");
    }
    if !zero(&inner(&g, &n_dir)) {
        return fail("G_q and n_q are not orthogonal");
    }
    if !zero(&inner(&ebar, &n_dir)) {
        return fail("Ebar_q and n_q are not orthogonal");
    }
    let all = DMatrix::from_fn(dim, g.ncols() + ebar.ncols() + 1, |i, j| {
        if j < g.ncols() {
            g[(i, j)].clone()
        } else if j < g.ncols() + ebar.ncols() {
            ebar[(i, j - g.ncols())].clone()
        } else {
            n_dir[(i, 0)].clone()
        }
    });
    let rank = |m: &DMatrix<Exact>| rank(m).ok_or_else(overflow);
    Ok(Structure {
        dim_g: rank(&g)?,
        dim_ebar: rank(&ebar)?,
        dim_e: rank(&b)?,
        span: rank(&all)?,
        space: dim,
    })
}

/// The expected dimensions: `dim Ebar = n - 1`, `dim E = n`, `dim G = space - n`, and the
/// three parts span the space (`N = n(n-1) + 2n` for two free bodies).
pub fn dimensions_ok(n: usize, variant: Variant, s: &Structure) -> Result<(), String> {
    let space = match variant {
        Variant::Free => state_len(n),
        Variant::Fixed => state_len(n) / 2,
    };
    let expect = [
        ("dim G_q", s.dim_g, space - n),
        ("dim Ebar_q", s.dim_ebar, n - 1),
        ("dim E_q", s.dim_e, n),
        ("rank of G_q + Ebar_q + R n_q", s.span, space),
        ("dim T_q M", s.space, space),
    ];
    for (what, got, want) in expect {
        if got != want {
            return Err(format!("{what} = {got}, expected {want}"));
        }
    }
    Ok(())
}
