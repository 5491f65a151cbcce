//! The direct path of `collide --exact` on a plain case ([`crate::plain`]: one case, no
//! contact law, matrix spins, short numbers, `dim` with a generated kernel): the text read
//! into machine fractions, every check of the general path made on integers, exact
//! rationals built only for the kernel's inputs, the kernel run unchecked, the answer
//! written by the general path's writer.
//!
//! The checks, each exact (`crate::fraction`; an integer overflow declines):
//!
//! - lengths: `normal`, each `velocity` and each row of each `angular_velocity` have `dim`
//!   numbers, each matrix `dim` rows;
//! - `|nu|^2 = 1`;
//! - `radius > 0`; `mass > 0` (or `"inf"`); `0 <= gamma2 <= 2/n`;
//!   `0 <= lambda <= R^2/n`;
//! - not both bodies immovable; not both movable point masses (`gamma2 = 0`);
//! - each angular velocity skew: `U_ii = 0`, `U_ij = -U_ji` (fractions in lowest terms are
//!   equal iff their parts are);
//! - approaching or grazing: `(u_2 - u_1) . nu <= 0`.
//!
//! These are the general path's checks in exact arithmetic (`Ball::new`,
//! `collision_core::collide`'s `prepare`, `skew_entries`), where nothing is clamped or
//! renormalised: on a case that passes them the general path runs the same kernel on the same
//! values and writes the same bytes. Wherever one fails, or the case is not plain, [`collide`]
//! answers `None` and the caller takes the general path, which reports the error as before
//! (tested against it in `case/tests/direct_path.rs`).

use crate::fraction::{in_range, is_unit, sign_of_normal_part, times_over_square};
use crate::output::{write_parts, Form};
use crate::plain::{self, Body, Inertia, Plain};
use collision_core::{collide_unchecked, skew_pairs, Ball, BodyState, Exact, Scalar};
use num_traits::Zero;
use std::cmp::Ordering;

/// The answer of `collide_json(text, Mode::Exact)` if `text` is a plain case that passes
/// every check (see the module documentation); `None` otherwise.
pub(crate) fn collide(text: &str) -> Option<String> {
    let case = plain::read(text)?;
    check(&case)?;
    collision_core::with_dim!(
        case.dim,
        |N, S| run::<N, S>(&case, 2 * text.len() + 256),
        None
    )
}

/// Whether `x` holds `n` numbers.
fn has(x: &plain::Numbers, n: usize) -> bool {
    x.len == n
}

/// The checks of the module documentation that need no kernel; `None` where one fails.
fn check(case: &Plain) -> Option<()> {
    let n = case.dim;
    let nu = &case.normal;
    let lengths = has(nu, n)
        && case
            .bodies
            .iter()
            .all(|b| has(&b.velocity, n) && b.rows == n && b.spin[..n].iter().all(|r| has(r, n)));
    if !lengths || !is_unit(nu.as_slice())? {
        return None;
    }
    let mut point_masses = 0;
    for body in &case.bodies {
        if body.radius.sign() != Ordering::Greater
            || body.mass.is_some_and(|m| m.sign() != Ordering::Greater)
        {
            return None;
        }
        let n = n as i128;
        let inside = match body.inertia {
            Inertia::Uniform => true,
            Inertia::Gamma2(g) => {
                point_masses += usize::from(g.p == 0 && body.mass.is_some());
                in_range(g, 2, n)?
            }
            Inertia::Lambda(l) => {
                point_masses += usize::from(l.p == 0 && body.mass.is_some());
                let (c, d) = (i128::from(body.radius.p), i128::from(body.radius.q));
                in_range(l, c.checked_mul(c)?, d.checked_mul(d)?.checked_mul(n)?)?
            }
        };
        if !inside || !skew(body, case.dim) {
            return None;
        }
    }
    let [b1, b2] = &case.bodies;
    if b1.mass.is_none() && b2.mass.is_none() || point_masses == 2 {
        return None;
    }
    let dn = sign_of_normal_part(
        nu.as_slice(),
        b1.velocity.as_slice(),
        b2.velocity.as_slice(),
    )?;
    (dn != Ordering::Greater).then_some(())
}

/// `U_ii = 0` and `U_ij = -U_ji` for the `n x n` matrix of `body`.
fn skew(body: &Body, n: usize) -> bool {
    let at = |i: usize, j: usize| body.spin[i].x[j];
    (0..n).all(|i| at(i, i).p == 0) && skew_pairs(n).all(|(i, j)| at(j, i).neg() == Some(at(i, j)))
}

/// The kernel's ball of a checked body in `R^n`: `w = 1/m` (0 for `"inf"`), `R`, and
/// `gamma2` as given, `2 lambda / R^2`, or `2/(n+2)` (uniform).
fn ball(body: &Body, n: usize) -> Ball<Exact> {
    let gamma2 = match body.inertia {
        Inertia::Uniform => Exact::from_ratio(2, n as i64 + 2),
        Inertia::Gamma2(g) => g.exact(),
        Inertia::Lambda(l) => match times_over_square(2, l, body.radius) {
            Some(g) => g.exact(),
            None => {
                let r = body.radius.exact();
                Exact::from_integer(2) * l.exact() / (r.clone() * r)
            }
        },
    };
    Ball {
        inv_mass: body
            .mass
            .map_or_else(Exact::zero, |m| m.inverse_of_positive().exact()),
        radius: body.radius.exact(),
        gamma2,
    }
}

/// The kernel's state of a checked body: the compact entries `U_ij`, `i < j`, in the order
/// of [`skew_pairs`], and `u`.
fn state<const N: usize, const S: usize>(body: &Body) -> BodyState<Exact, N, S> {
    let mut spin: [Exact; S] = std::array::from_fn(|_| Exact::zero());
    for (x, (i, j)) in spin.iter_mut().zip(skew_pairs(N)) {
        *x = body.spin[i].x[j].exact();
    }
    BodyState {
        spin,
        velocity: std::array::from_fn(|k| body.velocity.x[k].exact()),
    }
}

/// The kernel on a checked case, and the answer (in a `String` of `capacity`).
fn run<const N: usize, const S: usize>(case: &Plain, capacity: usize) -> Option<String>
where
    collision_core::Generated: collision_core::Kernel<Exact, N, S>,
{
    let nu: [Exact; N] = std::array::from_fn(|k| case.normal.x[k].exact());
    let balls = [ball(&case.bodies[0], N), ball(&case.bodies[1], N)];
    let states: [BodyState<Exact, N, S>; 2] = [state(&case.bodies[0]), state(&case.bodies[1])];
    let out = collide_unchecked(&nu, [&balls[0], &balls[1]], [&states[0], &states[1]]);
    let mut json = String::with_capacity(capacity);
    let parts = [0, 1].map(|b| (out[b].spin.as_slice(), out[b].velocity.as_slice()));
    write_parts([Form::Matrix; 2], parts, N, &mut json).ok()?;
    Some(json)
}

#[cfg(test)]
mod tests;
