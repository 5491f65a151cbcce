//! Validate a case and run the collision: the generated kernels for `n = 2..6`
//! (`collision_core::collide`, the same generic code for `f64` and exact rationals), the
//! general-n reference (`collision_core::reference::collide_coords`) above.
//!
//! collision-core does every check; the checks whose messages carry numbers (ranges, the
//! normal's length, separating bodies) are made here first, so that the numbers print as
//! the user wrote them (`1/3`) rather than as their `Debug` form.

use crate::json::case::{BodyInput, Case, Spin};
use crate::json::error::CaseError;
use crate::json::guard::quietly;
use crate::json::number::InputScalar;
use collision_core::reference::{collide_coords, state_len};
use collision_core::{
    collide, skew_pairs, validate_parts, Ball, BodyState, Field, Generated, Inertia, Kernel, Mass,
    RefArith, State2, State3,
};
use nalgebra::DVector;

/// A body after the collision: the compact angular velocity (the entries `U_ij`, `i < j`, in
/// the order of [`skew_pairs`]) and the velocity.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyOutput<T> {
    pub spin: Vec<T>,
    pub velocity: Vec<T>,
}

/// The post-collision states of a case's two bodies.
pub fn solve<T>(case: &Case<T>) -> Result<[BodyOutput<T>; 2], CaseError>
where
    T: InputScalar,
    for<'a> &'a T: RefArith<T>,
{
    let balls = [
        ball(case.dim, &case.bodies[0], 0)?,
        ball(case.dim, &case.bodies[1], 1)?,
    ];
    macro_rules! by_dim {
        ($($n:literal $s:literal),*) => {
            match case.dim {
                $($n => solve_kernel::<T, $n, $s>(case, &balls),)*
                _ => solve_reference(case, &balls),
            }
        };
    }
    by_dim!(2 1, 3 3, 4 6, 5 10, 6 15)
}

/// A ball, after the range checks of `Ball::new` made here with readable numbers.
fn ball<T: InputScalar>(dim: usize, body: &BodyInput<T>, i: usize) -> Result<Ball<T>, CaseError> {
    let field = |f: &str| format!("bodies[{i}].{f}");
    if body.radius <= T::zero() {
        return Err(CaseError::new(
            field("radius"),
            format!("must be positive, got {}", body.radius.show()),
        ));
    }
    if let Mass::Finite(m) = &body.mass {
        if *m <= T::zero() {
            return Err(CaseError::new(
                field("mass"),
                format!("must be positive (or \"inf\"), got {}", m.show()),
            ));
        }
        if !(T::one() / m.clone()).is_finite() {
            return Err(CaseError::new(
                field("mass"),
                format!("is too small for f64: 1/mass overflows, got {}", m.show()),
            ));
        }
    }
    let n = T::from_ratio(dim as i64, 1);
    let two = T::one() + T::one();
    // The bound as Ball::new computes it, with the same slack for rounded floats.
    let check = |x: &T, bound: T, name: &str, what: &str| {
        if *x < T::zero() || *x > bound.clone() * (T::one() + T::rounding_slack()) {
            Err(CaseError::new(
                field(name),
                format!(
                    "must be in [0, {what}] = [0, {}], got {}",
                    bound.show(),
                    x.show()
                ),
            ))
        } else {
            Ok(())
        }
    };
    match &body.inertia {
        Inertia::Lambda(l) => {
            let r2 = body.radius.clone() * body.radius.clone();
            if !r2.is_finite() || r2.is_zero() {
                return Err(CaseError::new(
                    field("radius"),
                    format!(
                        "R^2 is out of the f64 range, got R = {}; give gamma2 instead of lambda",
                        body.radius.show()
                    ),
                ));
            }
            check(l, r2 / n, "lambda", "R^2/n")?
        }
        Inertia::Gamma2(g) => check(g, two / n, "gamma2", "2/n")?,
        Inertia::Uniform | Inertia::Shell => {}
    }
    Ball::new(
        dim,
        body.mass.clone(),
        body.radius.clone(),
        body.inertia.clone(),
    )
    .map_err(|e| e.at_body(i).into())
}

/// `collision_core::validate_parts`, with the normal's length and the separating velocity
/// printed readably.
fn validate<T: InputScalar>(
    nu: &[T],
    balls: [&Ball<T>; 2],
    states: [(&[T], &[T]); 2],
) -> Result<(), CaseError> {
    validate_parts(nu, balls, states).map_err(|e| match e.field {
        Field::Normal => {
            let norm2 = nu.iter().fold(T::zero(), |s, x| s + x.clone() * x.clone());
            let how = if T::EXACT {
                "exactly".to_string()
            } else {
                format!("| |nu|^2 - 1 | <= {}", T::unit_tolerance().show())
            };
            CaseError::new(
                e.field.to_string(),
                format!(
                    "must be a unit vector ({how}), got |nu|^2 = {}",
                    norm2.show()
                ),
            )
        }
        Field::RelativeVelocity => {
            let [(_, u1), (_, u2)] = states;
            let dn = (0..nu.len()).fold(T::zero(), |s, k| {
                s + (u2[k].clone() - u1[k].clone()) * nu[k].clone()
            });
            CaseError::new(
                e.field.to_string(),
                format!(
                    "the bodies are separating: (u_2 - u_1) . nu = {} > 0 (a collision needs \
                     them approaching or grazing; nu points from bodies[0] to bodies[1])",
                    dn.show()
                ),
            )
        }
        _ => e.into(),
    })
}

fn array<T, const K: usize>(v: Vec<T>) -> Result<[T; K], CaseError> {
    v.try_into().map_err(|v: Vec<T>| {
        CaseError::new(
            "",
            format!("internal error: expected {K} values, got {}", v.len()),
        )
    })
}

/// The state of body `i` in the form the kernels take.
fn state<T: InputScalar, const N: usize, const S: usize>(
    body: &BodyInput<T>,
    i: usize,
) -> Result<BodyState<T, N, S>, CaseError> {
    let velocity: [T; N] = array(body.velocity.clone())?;
    match &body.spin {
        Spin::Matrix(rows) => {
            let rows = rows
                .iter()
                .map(|r| array::<T, N>(r.clone()))
                .collect::<Result<Vec<_>, _>>()?;
            Ok(BodyState::from_matrix(i, &array(rows)?, velocity)?)
        }
        Spin::Scalar(c) => {
            let s = State2::from_scalar_spin(c.clone(), array(body.velocity.clone())?);
            Ok(BodyState {
                spin: array(s.spin.to_vec())?,
                velocity,
            })
        }
        Spin::Omega(w) => {
            let s = State3::from_omega(w.clone(), array(body.velocity.clone())?);
            Ok(BodyState {
                spin: array(s.spin.to_vec())?,
                velocity,
            })
        }
    }
}

fn solve_kernel<T, const N: usize, const S: usize>(
    case: &Case<T>,
    balls: &[Ball<T>; 2],
) -> Result<[BodyOutput<T>; 2], CaseError>
where
    T: InputScalar,
    for<'a> &'a T: RefArith<T>,
    Generated: Kernel<T, N, S>,
{
    let states: [BodyState<T, N, S>; 2] = [state(&case.bodies[0], 0)?, state(&case.bodies[1], 1)?];
    let balls = [&balls[0], &balls[1]];
    validate(
        &case.normal,
        balls,
        states
            .each_ref()
            .map(|s| (s.spin.as_slice(), s.velocity.as_slice())),
    )?;
    let nu: [T; N] = array(case.normal.clone())?;
    let out = collide(&nu, balls, [&states[0], &states[1]])?;
    Ok(out.map(|s| BodyOutput {
        spin: s.spin.to_vec(),
        velocity: s.velocity.to_vec(),
    }))
}

/// The compact entries of a full `n x n` matrix, checked skew as `BodyState::from_matrix`
/// does: exactly in exact arithmetic, within `1e-12 max|U|` in floats (the skew part is kept).
fn compact_spin<T: InputScalar>(
    body: &BodyInput<T>,
    i: usize,
    n: usize,
) -> Result<Vec<T>, CaseError> {
    let field = format!("bodies[{i}].angular_velocity");
    let Spin::Matrix(m) = &body.spin else {
        return Err(CaseError::new(
            field,
            format!("expected a {n} x {n} matrix"),
        ));
    };
    let scale = m
        .iter()
        .flatten()
        .fold(T::zero(), |s, x| if x.abs() > s { x.abs() } else { s });
    let two = T::one() + T::one();
    let tol = scale * T::unit_tolerance() / two.clone();
    for (r, row) in m.iter().enumerate() {
        if row[r].abs() > tol {
            return Err(CaseError::new(
                field,
                format!("not skew: diagonal entry ({r},{r}) is not 0"),
            ));
        }
        for (c, x) in row.iter().enumerate().skip(r + 1) {
            if (x.clone() + m[c][r].clone()).abs() > tol {
                return Err(CaseError::new(
                    field,
                    format!("not skew: entries ({r},{c}) and ({c},{r}) are not opposite"),
                ));
            }
        }
    }
    Ok(skew_pairs(n)
        .map(|(r, c)| (m[r][c].clone() - m[c][r].clone()) / two.clone())
        .collect())
}

/// `n > 6`: the general-n reference.
fn solve_reference<T: InputScalar>(
    case: &Case<T>,
    balls: &[Ball<T>; 2],
) -> Result<[BodyOutput<T>; 2], CaseError> {
    let n = case.dim;
    let spins = [
        compact_spin(&case.bodies[0], 0, n)?,
        compact_spin(&case.bodies[1], 1, n)?,
    ];
    let velocities = [&case.bodies[0].velocity, &case.bodies[1].velocity];
    let balls = [&balls[0], &balls[1]];
    validate(
        &case.normal,
        balls,
        [
            (spins[0].as_slice(), velocities[0].as_slice()),
            (spins[1].as_slice(), velocities[1].as_slice()),
        ],
    )?;
    let xi = DVector::from_iterator(
        state_len(n),
        (0..2).flat_map(|b| spins[b].iter().chain(velocities[b]).cloned()),
    );
    let out = quietly(|| collide_coords(&case.normal, balls, &xi))
        .ok_or_else(|| {
            CaseError::new(
                "",
                if T::EXACT {
                    "internal error: the general-n reference failed"
                } else {
                    "the general-n reference (dims above 6) failed in f64: its linear solve \
                     overflowed; the inputs are too extreme for floats, --exact computes it"
                },
            )
        })?
        .map_err(|e| {
            let mut e = CaseError::from(e);
            e.message += " (dims above 6 run the general-n reference)";
            e
        })?;
    let s = spins[0].len();
    let part = |b: usize| BodyOutput {
        spin: out.as_slice()[b * (s + n)..b * (s + n) + s].to_vec(),
        velocity: out.as_slice()[b * (s + n) + s..(b + 1) * (s + n)].to_vec(),
    };
    Ok([part(0), part(1)])
}
