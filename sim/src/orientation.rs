//! Orientation in free flight: `A(t + dt) = exp(dt U) A(t)` with `U` the (constant, spatial)
//! angular velocity.
//!
//! - n = 2: `U = c J`, `exp(dt U)` is the rotation by the angle `c dt`.
//! - n = 3: Rodrigues, `exp(dt U) = I + sin(theta) K + (1 - cos(theta)) K^2` with
//!   `theta = |omega| dt`, `K = U / |omega|`.
//! - n >= 4: nalgebra's matrix exponential (scaling and squaring with a Pade approximant),
//!   accurate to rounding for the moderate `|dt U|` between events.
//!
//! Each is orthogonal to rounding; the error grows with the number of updates, not with time.

use collision_core::skew_pairs;

pub(crate) type Matrix<const N: usize> = [[f64; N]; N];

pub(crate) fn identity<const N: usize>() -> Matrix<N> {
    std::array::from_fn(|i| std::array::from_fn(|j| f64::from(u8::from(i == j))))
}

/// `exp(dt U)` for the compact skew entries `spin`.
pub(crate) fn exp_skew<const N: usize>(spin: &[f64], dt: f64) -> Matrix<N> {
    let mut u: Matrix<N> = [[0.0; N]; N];
    for ((i, j), x) in skew_pairs(N).zip(spin) {
        u[i][j] = x * dt;
        u[j][i] = -x * dt;
    }
    match N {
        2 => {
            // U = c J with J = [[0, -1], [1, 0]]: u[1][0] = c dt.
            let (s, c) = u[1][0].sin_cos();
            let mut r = identity::<N>();
            r[0][0] = c;
            r[0][1] = -s;
            r[1][0] = s;
            r[1][1] = c;
            r
        }
        3 => {
            let w = [u[2][1], u[0][2], u[1][0]];
            let theta = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
            let mut r = identity::<N>();
            if theta == 0.0 {
                return r;
            }
            let (s, c) = theta.sin_cos();
            let k2 = mul(&u, &u);
            for i in 0..N {
                for j in 0..N {
                    r[i][j] += s / theta * u[i][j] + (1.0 - c) / (theta * theta) * k2[i][j];
                }
            }
            r
        }
        _ => {
            let m = nalgebra::DMatrix::from_fn(N, N, |i, j| u[i][j]).exp();
            std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)]))
        }
    }
}

pub(crate) fn mul<const N: usize>(a: &Matrix<N>, b: &Matrix<N>) -> Matrix<N> {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..N).map(|k| a[i][k] * b[k][j]).sum()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn orthogonality_error<const N: usize>(a: &Matrix<N>) -> f64 {
        let mut e: f64 = 0.0;
        for i in 0..N {
            for j in 0..N {
                let dot: f64 = (0..N).map(|k| a[i][k] * a[j][k]).sum();
                e = e.max((dot - f64::from(u8::from(i == j))).abs());
            }
        }
        e
    }

    #[test]
    fn closed_forms_agree_with_the_series_and_stay_orthogonal() {
        // exp(U) against the series sum U^k / k! (40 terms: |U| < 2 converges to rounding).
        fn series<const N: usize>(spin: &[f64]) -> Matrix<N> {
            let mut u: Matrix<N> = [[0.0; N]; N];
            for ((i, j), x) in skew_pairs(N).zip(spin) {
                u[i][j] = *x;
                u[j][i] = -x;
            }
            let (mut term, mut sum) = (identity::<N>(), identity::<N>());
            for k in 1..40 {
                term = mul(&term, &u).map(|r| r.map(|x| x / k as f64));
                for i in 0..N {
                    for j in 0..N {
                        sum[i][j] += term[i][j];
                    }
                }
            }
            sum
        }
        fn check<const N: usize>(spin: &[f64]) {
            let (a, b) = (exp_skew::<N>(spin, 1.0), series::<N>(spin));
            for i in 0..N {
                for j in 0..N {
                    // Both are within a few ulps of the exact exponential (entries <= 1).
                    assert!((a[i][j] - b[i][j]).abs() < 1e-14, "n = {N}: {a:?} vs {b:?}");
                }
            }
            assert!(orthogonality_error(&a) < 1e-15);
        }
        check::<2>(&[0.7]);
        check::<3>(&[0.3, -0.5, 0.9]);
        check::<4>(&[0.3, -0.5, 0.9, 0.1, -0.2, 0.4]);
    }
}
