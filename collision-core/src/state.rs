//! A body's velocity state: angular velocity `U` in so(n), stored as its independent entries,
//! and centre velocity `u` in R^n.

use crate::allowance;
use crate::error::{BodyField, Field, InputError};
use crate::scalar::{allowance, two, Scalar};
use num_traits::{Signed, Zero};

/// Angular velocity `U` (skew, `n(n-1)/2` entries `U_ij`, `i < j`, in the order
/// `(0,1), (0,2), .., (0,n-1), (1,2), ..`) and centre velocity `u`. `S = N(N-1)/2`.
///
/// The velocity of the body point `x` is `U (x - a) + u`, `a` the centre.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyState<T, const N: usize, const S: usize> {
    /// Compact skew entries `U_ij`, `i < j`, of the angular velocity `U`.
    pub spin: [T; S],
    /// The centre velocity `u`.
    pub velocity: [T; N],
}

/// A body's state in R^2 (`S = 1`).
pub type State2<T> = BodyState<T, 2, 1>;
/// A body's state in R^3 (`S = 3`).
pub type State3<T> = BodyState<T, 3, 3>;
/// A body's state in R^4 (`S = 6`).
pub type State4<T> = BodyState<T, 4, 6>;
/// A body's state in R^5 (`S = 10`).
pub type State5<T> = BodyState<T, 5, 10>;
/// A body's state in R^6 (`S = 15`).
pub type State6<T> = BodyState<T, 6, 15>;

/// The `(i, j)` index of each compact skew entry, for `n x n`.
pub fn skew_pairs(n: usize) -> impl Iterator<Item = (usize, usize)> {
    (0..n).flat_map(move |i| (i + 1..n).map(move |j| (i, j)))
}

/// The compact entries `U_ij`, `i < j`, of a full `n x n` angular velocity matrix (rows of
/// any slice type), which must be skew under [the rounding allowance](crate::allowance):
/// `|U_ij + U_ji|` and `|U_ii|` at most `rounding_slack() max|U|` (so exactly skew in exact
/// arithmetic); the skew part `(U_ij - U_ji)/2` is kept. Errors name `angular_velocity` of body
/// `body` (0-based).
pub fn skew_entries<T: Scalar, R: AsRef<[T]>>(
    body: usize,
    matrix: &[R],
) -> Result<Vec<T>, InputError> {
    let n = matrix.len();
    let field = Field::Body(body, BodyField::AngularVelocity);
    if let Some(i) = (0..n).find(|&i| matrix[i].as_ref().len() != n) {
        return Err(InputError::new(
            field,
            format!(
                "row {i} has {} entries, expected {n}",
                matrix[i].as_ref().len()
            ),
        ));
    }
    if T::EXACT {
        // No allowance: the checks below with a tolerance of 0, `U_ii = 0` and `U_ij = -U_ji`,
        // compared without arithmetic; the kept entry `(U_ij - U_ji)/2` is then `U_ij`.
        let at = |i: usize, j: usize| &matrix[i].as_ref()[j];
        if let Some(i) = (0..n).find(|&i| !at(i, i).is_zero()) {
            return Err(InputError::new(
                field,
                format!("not skew: diagonal entry ({i},{i}) is not 0"),
            ));
        }
        if let Some((i, j)) = skew_pairs(n).find(|&(i, j)| *at(i, j) != -at(j, i).clone()) {
            return Err(InputError::new(
                field,
                format!("not skew: entries ({i},{j}) and ({j},{i}) are not opposite"),
            ));
        }
        return Ok(skew_pairs(n).map(|(i, j)| at(i, j).clone()).collect());
    }
    // A NaN or an infinity is named as such (it failed the skew test below, and was reported
    // as a matrix that is not skew).
    for (i, row) in matrix.iter().enumerate() {
        if let Some((j, x)) = row
            .as_ref()
            .iter()
            .enumerate()
            .find(|(_, x)| !x.is_finite())
        {
            return Err(InputError::new(
                field,
                format!("entry ({i},{j}) must be finite, got {}", x.show()),
            ));
        }
    }
    // In the unbounded type: U_ij + U_ji and U_ij - U_ji do not overflow.
    let at = |i: usize, j: usize| matrix[i].as_ref()[j].unbounded();
    let scale = matrix
        .iter()
        .flat_map(|r| r.as_ref())
        .fold(T::Unbounded::zero(), |m, x| {
            if x.unbounded().abs() > m {
                x.unbounded().abs()
            } else {
                m
            }
        });
    let zero = T::Unbounded::zero();
    let tol = allowance(&scale);
    let skew = |x: T::Unbounded| allowance::within(&x, &zero, &zero, &tol).is_some();
    if let Some(i) = (0..n).find(|&i| !skew(at(i, i))) {
        return Err(InputError::new(
            field,
            format!("not skew: diagonal entry ({i},{i}) is not 0"),
        ));
    }
    if let Some((i, j)) = skew_pairs(n).find(|&(i, j)| !skew(at(i, j) + at(j, i))) {
        return Err(InputError::new(
            field,
            format!("not skew: entries ({i},{j}) and ({j},{i}) are not opposite"),
        ));
    }
    Ok(skew_pairs(n)
        .map(|(i, j)| T::from_unbounded(&((at(i, j) - at(j, i)) / two::<T::Unbounded>())))
        .collect())
}

impl<T: Scalar, const N: usize, const S: usize> BodyState<T, N, S> {
    /// The state at rest.
    pub fn zero() -> Self {
        Self {
            spin: std::array::from_fn(|_| T::zero()),
            velocity: std::array::from_fn(|_| T::zero()),
        }
    }

    /// From the full `n x n` angular velocity matrix (row by row), which must be skew as
    /// [`skew_entries`] says (the skew part `(U - U^T)/2` is kept). Errors name
    /// `angular_velocity` of body `body` (0-based).
    pub fn from_matrix(
        body: usize,
        matrix: &[[T; N]; N],
        velocity: [T; N],
    ) -> Result<Self, InputError> {
        assert_eq!(S, N * (N - 1) / 2, "S must be N(N-1)/2");
        let entries = skew_entries(body, matrix)?;
        let spin = entries
            .try_into()
            .unwrap_or_else(|_| unreachable!("N(N-1)/2 entries"));
        Ok(Self { spin, velocity })
    }

    /// The full skew matrix `U`.
    pub fn spin_matrix(&self) -> [[T; N]; N] {
        let mut m: [[T; N]; N] = std::array::from_fn(|_| std::array::from_fn(|_| T::zero()));
        for ((i, j), x) in skew_pairs(N).zip(&self.spin) {
            m[i][j] = x.clone();
            m[j][i] = -x.clone();
        }
        m
    }
}

impl<T: Scalar> State2<T> {
    /// 2D: `U = c J`, `J = [[0, -1], [1, 0]]` (counter-clockwise spin `c`).
    pub fn from_scalar_spin(c: T, velocity: [T; 2]) -> Self {
        Self {
            spin: [-c],
            velocity,
        }
    }

    /// The `c` of `U = c J`.
    pub fn scalar_spin(&self) -> T {
        -self.spin[0].clone()
    }
}

impl<T: Scalar> State3<T> {
    /// 3D: `U x = omega x x`, i.e. `U = [[0, -w3, w2], [w3, 0, -w1], [-w2, w1, 0]]`.
    pub fn from_omega(omega: [T; 3], velocity: [T; 3]) -> Self {
        let [w1, w2, w3] = omega;
        Self {
            spin: [-w3, w2, -w1],
            velocity,
        }
    }

    /// The `omega` with `U x = omega x x`.
    pub fn omega(&self) -> [T; 3] {
        let [u01, u02, u12] = self.spin.clone();
        [-u12, u02, -u01]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Exact;

    fn q(n: i64, d: i64) -> Exact {
        Exact::from_ratio(n, d)
    }

    #[test]
    fn omega_form_is_the_cross_product() {
        let s = State3::from_omega(
            [q(1, 1), q(-2, 1), q(3, 1)],
            std::array::from_fn(|_| q(0, 1)),
        );
        let u = s.spin_matrix();
        let x = [q(2, 1), q(5, 1), q(-7, 1)];
        let ux: Vec<Exact> = (0..3)
            .map(|i| (0..3).map(|j| u[i][j].clone() * x[j].clone()).sum())
            .collect();
        // omega x x = (1,-2,3) x (2,5,-7) = (14-15, 6+7, 5+4)
        assert_eq!(ux, vec![q(-1, 1), q(13, 1), q(9, 1)]);
        assert_eq!(s.omega(), [q(1, 1), q(-2, 1), q(3, 1)]);
    }

    #[test]
    fn scalar_spin_is_c_times_j() {
        let s = State2::from_scalar_spin(q(3, 1), [q(0, 1), q(0, 1)]);
        assert_eq!(s.spin_matrix(), [[q(0, 1), q(-3, 1)], [q(3, 1), q(0, 1)]]);
        assert_eq!(s.scalar_spin(), q(3, 1));
    }

    #[test]
    fn matrix_round_trip_and_skew_check() {
        let m = [[0.0, 1.0, -2.0], [-1.0, 0.0, 3.0], [2.0, -3.0, 0.0]];
        let s = State3::<f64>::from_matrix(0, &m, [0.0; 3]).unwrap();
        assert_eq!(s.spin_matrix(), m);
        let bad = [[0.0, 1.0, -2.0], [1.0, 0.0, 3.0], [2.0, -3.0, 0.0]];
        let e = State3::<f64>::from_matrix(1, &bad, [0.0; 3]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "body 2 spin: not skew: entries (0,1) and (1,0) are not opposite"
        );
        let diag = [[q(1, 10), q(0, 1)], [q(0, 1), q(0, 1)]];
        assert!(State2::from_matrix(0, &diag, [q(0, 1), q(0, 1)]).is_err());
    }

    /// Exact arithmetic checks without sums (`U_ii = 0`, `U_ij = -U_ji`) and keeps `U_ij`:
    /// the same entries and the same errors as the general rule with a tolerance of 0.
    #[test]
    fn exact_skew_check_is_the_rule_without_allowance() {
        let m = [
            [q(0, 1), q(1, 3), q(-2, 7)],
            [q(-1, 3), q(0, 1), q(3, 5)],
            [q(2, 7), q(-3, 5), q(0, 1)],
        ];
        let s = State3::from_matrix(0, &m, [q(0, 1), q(0, 1), q(0, 1)]).unwrap();
        assert_eq!(s.spin_matrix(), m);
        assert_eq!(s.spin.to_vec(), skew_entries::<Exact, _>(0, &m).unwrap());
        let mut off = m.clone();
        off[2][1] = q(-3, 5) + q(1, 1_000_000_000_000);
        let e = State3::from_matrix(1, &off, [q(0, 1), q(0, 1), q(0, 1)]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "body 2 spin: not skew: entries (1,2) and (2,1) are not opposite"
        );
        let mut diag = m.clone();
        diag[1][1] = q(-1, 1_000_000_000_000);
        let e = State3::from_matrix(0, &diag, [q(0, 1), q(0, 1), q(0, 1)]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "body 1 spin: not skew: diagonal entry (1,1) is not 0"
        );
    }

    #[test]
    fn skew_takes_eight_eps_of_max_u_and_no_more() {
        let eps = f64::EPSILON;
        // U_01 + U_10 = 8 eps (1 + 8 eps) <= 8 eps max|U|: the skew part is kept.
        let edge = [[0.0, 1.0 + 8.0 * eps], [-1.0, 0.0]];
        let s = State2::<f64>::from_matrix(0, &edge, [0.0; 2]).unwrap();
        assert_eq!(s.spin, [1.0 + 4.0 * eps]);
        let beyond = [[0.0, 1.0 + 10.0 * eps], [-1.0, 0.0]];
        assert!(State2::<f64>::from_matrix(0, &beyond, [0.0; 2]).is_err());
        let diagonal = [[8.0 * eps, 1.0], [-1.0, 0.0]];
        assert_eq!(
            State2::<f64>::from_matrix(0, &diagonal, [0.0; 2])
                .unwrap()
                .spin,
            [1.0]
        );
        let diagonal = [[9.0 * eps, 1.0], [-1.0, 0.0]];
        assert!(State2::<f64>::from_matrix(0, &diagonal, [0.0; 2]).is_err());
        // Entries near the largest f64: the sum and the skew part do not overflow.
        let big = [[0.0, f64::MAX], [-f64::MAX, 0.0]];
        assert_eq!(
            State2::<f64>::from_matrix(0, &big, [0.0; 2]).unwrap().spin,
            [f64::MAX]
        );
    }

    /// A NaN or an infinity is named as not finite, at its entry, not as a matrix that is not
    /// skew (a review found `[[0, inf], [-inf, 0]]` reported as "not opposite").
    #[test]
    fn entries_that_are_not_finite_are_named_as_such() {
        for (m, said) in [
            (
                [[0.0, f64::INFINITY], [-f64::INFINITY, 0.0]],
                "entry (0,1) must be finite, got inf",
            ),
            (
                [[f64::NAN, 1.0], [-1.0, 0.0]],
                "entry (0,0) must be finite, got NaN",
            ),
            (
                [[0.0, 1.0], [f64::NAN, 0.0]],
                "entry (1,0) must be finite, got NaN",
            ),
        ] {
            let e = State2::<f64>::from_matrix(0, &m, [0.0; 2]).unwrap_err();
            assert_eq!(e.to_string(), format!("body 1 spin: {said}"));
        }
    }
}
