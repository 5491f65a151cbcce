//! Characteristic polynomials (exact in rationals) and eigenvalues (f64).

use collision_core::Scalar;
use nalgebra::linalg::Schur;
use nalgebra::DMatrix;

/// The characteristic polynomial `det(lambda I - A)` of the matrix with these columns,
/// coefficients from the constant term up (`c_0, .., c_n = 1`), by Faddeev-LeVerrier:
/// `M_0 = 0`, `M_k = A M_{k-1} + c_{n-k+1} I`, `c_{n-k} = -tr(A M_k) / k`. Exact in
/// rationals (it divides only by `k`).
#[allow(clippy::needless_range_loop)]
pub fn charpoly<T: Scalar>(columns: &[Vec<T>]) -> Vec<T> {
    let n = columns.len();
    let a = |i: usize, j: usize| columns[j][i].clone();
    let mut c = vec![T::zero(); n + 1];
    c[n] = T::one();
    let mut m = vec![vec![T::zero(); n]; n]; // M_k, row-major
    for k in 1..=n {
        // M_k = A M_{k-1} + c_{n-k+1} I
        let mut next = vec![vec![T::zero(); n]; n];
        for i in 0..n {
            for j in 0..n {
                let mut s = if i == j {
                    c[n - k + 1].clone()
                } else {
                    T::zero()
                };
                for l in 0..n {
                    s += a(i, l) * m[l][j].clone();
                }
                next[i][j] = s;
            }
        }
        m = next;
        let mut trace = T::zero();
        for i in 0..n {
            for l in 0..n {
                trace += a(i, l) * m[l][i].clone();
            }
        }
        c[n - k] = -trace / T::from_ratio(k as i64, 1);
    }
    c
}

/// `p(lambda) / lambda` for a polynomial with `p(0) = 0` (coefficients from the constant up).
pub fn deflate_zero<T: Scalar>(p: &[T]) -> Vec<T> {
    p[1..].to_vec()
}

/// Shifted QR sweeps allowed per row of the matrix in one attempt at its real Schur form
/// (LAPACK's `dlahqr` allows 30, and at least 300 in all).
pub const SCHUR_SWEEPS_PER_ROW: usize = 30;

/// The deflation thresholds tried in turn, relative to the two neighbouring diagonal entries
/// of the (scaled) Hessenberg matrix: `eps`, `4 eps`, `16 eps`, `64 eps`.
///
/// nalgebra's `complex_eigenvalues` runs the implicit double-shift QR iteration with no cap on
/// its sweeps and no exceptional shift, and splits the matrix only where a subdiagonal entry
/// is below `eps (|t_ii| + |t_i+1,i+1|)`. At a multiple eigenvalue (the triangle's period-4
/// orbits have `1` three times) each sweep leaves subdiagonal entries of a few ulps, never
/// below that threshold, and the iteration ran forever (nalgebra issues 611, 764, 1528).
/// A larger threshold is a backward error of that size relative to the largest entry: it
/// moves a simple eigenvalue by about that times its condition number, a double one by its
/// square root (`sqrt(64 eps) = 1.2e-7`), below the verdict's tolerance
/// ([`super::STABILITY_TOL`] = `1e-6`).
pub const DEFLATION: [f64; 4] = [
    f64::EPSILON,
    4.0 * f64::EPSILON,
    16.0 * f64::EPSILON,
    64.0 * f64::EPSILON,
];

/// The eigenvalues `(re, im)` of the matrix with these columns, from its real Schur form:
/// at most [`SCHUR_SWEEPS_PER_ROW`] `max(n, 10)` sweeps for each threshold of [`DEFLATION`];
/// `None` if none converged (bounded work in every case).
pub fn eigenvalues(columns: &[Vec<f64>]) -> Option<Vec<(f64, f64)>> {
    let n = columns.len();
    let m = DMatrix::from_fn(n, n, |i, j| columns[j][i]);
    let sweeps = SCHUR_SWEEPS_PER_ROW * n.max(10);
    DEFLATION.iter().find_map(|&eps| {
        Schur::try_new(m.clone(), eps, sweeps).map(|schur| {
            schur
                .complex_eigenvalues()
                .iter()
                .map(|z| (z.re, z.im))
                .collect()
        })
    })
}

/// A polynomial (coefficients from the constant up) as text, highest power first:
/// `l^4 + 14/9 l^3 + ...`.
pub fn show<T: Scalar>(p: &[T]) -> String {
    let mut out = String::new();
    for (k, c) in p.iter().enumerate().rev() {
        if c.is_zero() {
            continue;
        }
        let (sign, mag) = if c.is_negative() {
            ("-", -c.clone())
        } else {
            ("+", c.clone())
        };
        if out.is_empty() {
            if sign == "-" {
                out.push('-');
            }
        } else {
            out.push_str(&format!(" {sign} "));
        }
        let unit = mag == T::one();
        match (k, unit) {
            (0, _) => out.push_str(&mag.show()),
            (_, true) => {}
            (_, false) => out.push_str(&format!("{} ", mag.show())),
        }
        match k {
            0 => {}
            1 => out.push('l'),
            _ => out.push_str(&format!("l^{k}")),
        }
    }
    if out.is_empty() {
        out.push('0');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use collision_core::Exact;

    fn q(n: i64, d: i64) -> Exact {
        Exact::from_ratio(n, d)
    }

    /// `[[2, 1], [0, 3]]` (columns (2, 0), (1, 3)): `(l - 2)(l - 3) = l^2 - 5 l + 6`; a 3x3
    /// rotation-like block with a zero column: `l (l^2 + 1)`.
    #[test]
    fn faddeev_leverrier_by_hand() {
        let a = vec![vec![q(2, 1), q(0, 1)], vec![q(1, 1), q(3, 1)]];
        assert_eq!(charpoly(&a), vec![q(6, 1), q(-5, 1), q(1, 1)]);
        let b = vec![
            vec![q(0, 1), q(1, 1), q(0, 1)],
            vec![q(-1, 1), q(0, 1), q(0, 1)],
            vec![q(0, 1), q(0, 1), q(0, 1)],
        ];
        let p = charpoly(&b);
        assert_eq!(p, vec![q(0, 1), q(1, 1), q(0, 1), q(1, 1)]);
        assert_eq!(show(&deflate_zero(&p)), "l^2 + 1");
        assert_eq!(show(&[q(1, 1), q(14, 9), q(-1, 1)]), "-l^2 + 14/9 l + 1");
        let e = eigenvalues(&[vec![0.0, 1.0], vec![-1.0, 0.0]]).unwrap();
        assert!(e
            .iter()
            .all(|(re, im)| re.abs() < 1e-15 && (im.abs() - 1.0).abs() < 1e-15));
    }

    /// The derivative of `P^4` at a period-4 orbit of the shipped triangle (found by
    /// `noslip orbits scenes/triangle.toml --period 4 --grid 1`): eigenvalues `0` (the flow
    /// direction) and `1` four times, the last three of a block equal to the identity up to a
    /// few ulps. nalgebra's uncapped `complex_eigenvalues` never returned on it (the
    /// command ran past 120 s); with the bounded attempts it returns at once.
    #[test]
    fn a_near_identity_block_does_not_stall_the_schur_iteration() {
        let columns = vec![
            vec![-0.0006880172990406366, 0.0011916809184246925, 0.0, 0.0, 0.0],
            vec![-0.5777474961624343, 1.0006880172990407, 0.0, 0.0, 0.0],
            vec![
                -5.551115123125783e-17,
                1.3769367590565906e-16,
                1.0000000000000007,
                3.3306690738754696e-16,
                1.7763568394002505e-15,
            ],
            vec![
                -3.885780586188048e-16,
                6.941062308252199e-16,
                -2.220446049250313e-16,
                1.0000000000000007,
                -7.105427357601002e-15,
            ],
            vec![
                1.0408340855860843e-17,
                -1.4690939437178585e-17,
                1.0408340855860843e-17,
                3.469446951953614e-18,
                1.0000000000000009,
            ],
        ];
        let mut e = eigenvalues(&columns).expect("converges within the bounded attempts");
        e.sort_by(|a, b| a.0.total_cmp(&b.0));
        assert!(e[0].0.abs() < 1e-12 && e[0].1.abs() < 1e-12, "{e:?}");
        for (re, im) in &e[1..] {
            assert!((re - 1.0).abs() < 1e-12 && im.abs() < 1e-12, "{e:?}");
        }
    }
}
