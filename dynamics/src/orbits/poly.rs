//! Characteristic polynomials (exact in rationals) and eigenvalues (f64).

use collision_core::Scalar;
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

/// The eigenvalues `(re, im)` of the matrix with these columns.
pub fn eigenvalues(columns: &[Vec<f64>]) -> Vec<(f64, f64)> {
    let n = columns.len();
    let m = DMatrix::from_fn(n, n, |i, j| columns[j][i]);
    m.complex_eigenvalues()
        .iter()
        .map(|z| (z.re, z.im))
        .collect()
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
        let e = eigenvalues(&[vec![0.0, 1.0], vec![-1.0, 0.0]]);
        assert!(e
            .iter()
            .all(|(re, im)| re.abs() < 1e-15 && (im.abs() - 1.0).abs() < 1e-15));
    }
}
