//! Gaussian elimination over any [`Scalar`] field, exact for rationals. nalgebra's
//! decompositions need a real or complex field, which rationals are not.

use crate::Scalar;
use nalgebra::{DMatrix, DVector};

/// Row-reduce `m` in place to row echelon form (partial pivoting on the largest `|x|`);
/// returns the pivot columns, or `None` if a non-finite value (a float overflow) appears.
fn echelon<T: Scalar>(m: &mut DMatrix<T>) -> Option<Vec<usize>> {
    let (rows, cols) = m.shape();
    let mut pivots = Vec::new();
    let mut r = 0;
    for c in 0..cols {
        if r == rows {
            break;
        }
        if (r..rows).any(|i| !m[(i, c)].is_finite()) {
            return None;
        }
        let best = (r..rows)
            .filter(|&i| !m[(i, c)].is_zero())
            .max_by(|&i, &j| {
                m[(i, c)]
                    .abs()
                    .partial_cmp(&m[(j, c)].abs())
                    .expect("finite")
            });
        let Some(p) = best else { continue };
        m.swap_rows(r, p);
        for i in r + 1..rows {
            if m[(i, c)].is_zero() {
                continue;
            }
            let f = m[(i, c)].clone() / m[(r, c)].clone();
            for k in c..cols {
                let x = f.clone() * m[(r, k)].clone();
                m[(i, k)] -= x;
            }
        }
        pivots.push(c);
        r += 1;
    }
    Some(pivots)
}

/// The rank of `m` (exact for rationals; for floats, the number of non-zero pivots), or
/// `None` if a non-finite value appears.
pub fn rank<T: Scalar>(m: &DMatrix<T>) -> Option<usize> {
    echelon(&mut m.clone()).map(|p| p.len())
}

/// A basis of the null space `{x : m x = 0}` (columns), exact for rationals; `None` if a
/// non-finite value appears.
pub fn nullspace<T: Scalar>(m: &DMatrix<T>) -> Option<DMatrix<T>> {
    let mut r = m.clone();
    let pivots = echelon(&mut r)?;
    let cols = m.ncols();
    // Back-substitute to reduced row echelon form.
    for (row, &c) in pivots.iter().enumerate().rev() {
        let p = r[(row, c)].clone();
        for k in c..cols {
            r[(row, k)] /= p.clone();
        }
        for above in 0..row {
            let f = r[(above, c)].clone();
            if f.is_zero() {
                continue;
            }
            for k in c..cols {
                let x = f.clone() * r[(row, k)].clone();
                r[(above, k)] -= x;
            }
        }
    }
    let free: Vec<usize> = (0..cols).filter(|c| !pivots.contains(c)).collect();
    let mut basis = DMatrix::from_element(cols, free.len(), T::zero());
    for (j, &f) in free.iter().enumerate() {
        basis[(f, j)] = T::one();
        for (row, &c) in pivots.iter().enumerate() {
            basis[(c, j)] = -r[(row, f)].clone();
        }
    }
    Some(basis)
}

/// The solution of `a x = b` for square non-singular `a`, or `None` if `a` is singular (or,
/// in floats, the elimination overflows).
pub fn solve<T: Scalar>(a: &DMatrix<T>, b: &DVector<T>) -> Option<DVector<T>> {
    let n = a.nrows();
    assert_eq!(a.ncols(), n, "solve needs a square matrix");
    let mut aug = DMatrix::from_fn(n, n + 1, |i, j| {
        if j < n {
            a[(i, j)].clone()
        } else {
            b[i].clone()
        }
    });
    if echelon(&mut aug)? != (0..n).collect::<Vec<_>>() {
        return None;
    }
    let mut x = DVector::from_element(n, T::zero());
    for i in (0..n).rev() {
        let mut s = aug[(i, n)].clone();
        for k in i + 1..n {
            s -= aug[(i, k)].clone() * x[k].clone();
        }
        x[i] = s / aug[(i, i)].clone();
    }
    x.iter().all(Scalar::is_finite).then_some(x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Exact;
    use num_traits::Zero;

    fn q(n: i64) -> Exact {
        Exact::from_ratio(n, 1)
    }

    #[test]
    fn solves_exactly_and_detects_singularity() {
        let a = DMatrix::from_row_slice(
            3,
            3,
            &[q(0), q(2), q(1), q(1), q(1), q(0), q(3), q(0), q(1)],
        );
        let x = DVector::from_vec(vec![Exact::from_ratio(1, 3), q(-2), q(5)]);
        let b = &a * &x;
        assert_eq!(solve(&a, &b), Some(x));
        let singular = DMatrix::from_row_slice(2, 2, &[q(1), q(2), q(2), q(4)]);
        assert_eq!(solve(&singular, &DVector::from_vec(vec![q(1), q(1)])), None);
        assert_eq!(rank(&singular), Some(1));
        assert_eq!(rank(&a), Some(3));
        let k = nullspace(&singular).unwrap();
        assert_eq!(k.ncols(), 1);
        assert!((&singular * &k).iter().all(|x| x.is_zero()));
    }

    #[test]
    fn float_overflow_is_none_not_a_panic() {
        let a = DMatrix::from_row_slice(2, 2, &[f64::NAN, 1.0, 1.0, 1.0]);
        assert_eq!(solve(&a, &DVector::from_vec(vec![1.0, 1.0])), None);
        // x_0 = 1e308 / 1e-308 overflows.
        let tiny = DMatrix::from_row_slice(2, 2, &[1e-308, 0.0, 0.0, 1.0]);
        assert_eq!(solve(&tiny, &DVector::from_vec(vec![1e308, 1.0])), None);
    }
}
