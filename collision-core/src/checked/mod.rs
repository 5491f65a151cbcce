//! The checked path around the kernels: inputs validated and clamped under [the rounding
//! allowance](crate::allowance), moved into the unbounded-exponent arithmetic
//! ([`Scalar::Unbounded`]), and the results rounded back only where they fit.
//!
//! In floats the kernels then run in [`crate::Wide`]: every intermediate quantity keeps
//! the precision of the format whatever its magnitude (`R_2 U_2` for `R_2 = 8e307`,
//! `1/(R_2 D)`, products of tiny inverse masses), and the result is the format's kernel
//! result bit for bit wherever that kernel stays in range. A result is refused only when it
//! does not fit the format: a component beyond its range, or a body whose components below
//! the normal range would cost, rounded, more than the rounding allowance of its energy norm
//! `sqrt(gamma2 R^2 |U|^2 + |u|^2)`. The error names the component that costs most and the
//! input that drives it.

use crate::allowance;
use crate::error::{BodyField, Field, InputError};
use crate::scalar::{allowance, two};
use crate::{Ball, Scalar};
use blame::{overflow, underflow, Lost};
use num_traits::{One, Zero};

mod blame;

/// The checks of [`crate::collide()`], for any `n` (the reference uses them too): the
/// checked path's preparation, its result dropped. A quantity within [the rounding
/// allowance](crate::allowance) of its bound passes.
pub fn validate_parts<T: Scalar>(
    nu: &[T],
    balls: [&Ball<T>; 2],
    states: [(&[T], &[T]); 2],
) -> Result<(), InputError> {
    prepare(nu, balls, states, true).map(|_| ())
}

/// The inputs of a collision after the checks, in `W` (the `Unbounded` of the input type):
/// `nu` renormalised, `gamma2` clamped to `[0, 2/n]`, a grazing relative velocity's normal
/// part removed.
#[derive(Clone, Debug)]
pub(crate) struct Prepared<W> {
    pub nu: Vec<W>,
    pub balls: [Ball<W>; 2],
    /// Per body: the compact skew entries of `U`, then `u`.
    pub spins: [Vec<W>; 2],
    pub velocities: [Vec<W>; 2],
}

fn not_finite<T: Scalar>(field: Field, x: &T) -> InputError {
    InputError::new(field, format!("must be finite, got {}", x.show()))
}

fn max_abs<W: Scalar>(xs: &[W]) -> W {
    xs.iter()
        .fold(W::zero(), |m, x| if x.abs() > m { x.abs() } else { m })
}

/// The allowance of `|nu|^2` in dimension `n`, in units of epsilon: `ULPS + 2n`
/// ([`allowance::ULPS`] is 8). A normal computed as `d / |d|` carries up to
/// `(n/2 + 2) eps/2` of relative error per component (the sum of `n` squares, the square
/// root, the division), so its exact `|nu|^2` is within `(n + 4) eps/2` of 1, and the check's
/// own sum of squares adds `n eps/2`: `(n + 2) eps` in all, beyond `ULPS` from `n = 7` on.
/// `ULPS` on top covers the components' decimal writing (16 significant digits are up to
/// `2.25 eps` each, `4.5 eps` on `|nu|^2`).
const fn normal_ulps(n: usize) -> u32 {
    allowance::ULPS + 2 * n as u32
}

/// Validate and clamp (see [`crate::collide`] for the checks; [`crate::allowance`] for the
/// rule), for any `n = nu.len()`, under a law with a tangential part (`tangential`: the
/// no-slip map, the rough one at `beta > -1`, Walton's) or without one (the rough law at
/// `beta = -1`, smooth): without one, two point masses may meet (the specular map needs no
/// spin inertia).
pub(crate) fn prepare<T: Scalar>(
    nu: &[T],
    balls: [&Ball<T>; 2],
    states: Parts<'_, T>,
    tangential: bool,
) -> Result<Prepared<T::Unbounded>, InputError> {
    let n = nu.len();
    if n < 2 {
        return Err(InputError::new(
            Field::Dim,
            format!("must be at least 2, got {n}"),
        ));
    }
    if let Some(x) = nu.iter().find(|x| !x.is_finite()) {
        return Err(not_finite(Field::Normal, x));
    }
    let nu: Vec<T::Unbounded> = nu.iter().map(Scalar::unbounded).collect();
    let norm2 = nu
        .iter()
        .fold(T::Unbounded::zero(), |s, x| s + x.clone() * x.clone());
    let one = T::Unbounded::one();
    let ulps = normal_ulps(n);
    // Exact arithmetic takes no allowance (`allowance` is 0): no product is made.
    let slack = if T::EXACT {
        T::Unbounded::zero()
    } else {
        allowance(&norm2) * T::Unbounded::from_ratio(i64::from(ulps), i64::from(allowance::ULPS))
    };
    if allowance::within(&norm2, &one, &one, &slack).is_none() {
        let how = if T::EXACT {
            "exactly".to_string()
        } else {
            format!(
                "| |nu|^2 - 1 | <= {ulps} eps |nu|^2 = {}, the rounding allowance in {n}D",
                slack.show()
            )
        };
        return Err(InputError::new(
            Field::Normal,
            format!(
                "must be a unit vector ({how}), got |nu|^2 = {}",
                norm2.show()
            ),
        ));
    }
    // Renormalise: nu (3 - |nu|^2)/2 is nu/|nu| to O((|nu|^2 - 1)^2), far below rounding.
    let nu: Vec<_> = if norm2 == one {
        nu
    } else {
        let factor = (one.clone() + two::<T::Unbounded>() - norm2) / two::<T::Unbounded>();
        nu.into_iter().map(|x| x * factor.clone()).collect()
    };
    let mut clamped = Vec::with_capacity(2);
    for (i, (ball, (spin, velocity))) in balls.iter().zip(states).enumerate() {
        clamped.push(ball.clamped(n).map_err(|e| e.at_body(i))?);
        for (values, field) in [
            (spin, BodyField::AngularVelocity),
            (velocity, BodyField::Velocity),
        ] {
            if let Some(x) = values.iter().find(|x| !x.is_finite()) {
                return Err(not_finite(Field::Body(i, field), x));
            }
        }
    }
    let [b1, b2] = [&clamped[0], &clamped[1]];
    if b1.is_immovable() && b2.is_immovable() {
        return Err(InputError::new(
            Field::Bodies,
            "both bodies are immovable (mass \"inf\"): at most one may be",
        ));
    }
    if tangential && both_point_masses(b1, b2) {
        return Err(InputError::new(
            Field::Bodies,
            "both bodies are point masses (lambda = 0): at most one may be, under a law with a \
             tangential part (the no-slip map, the rough one with beta > -1, Walton's); a \
             smooth law (beta = -1) takes two",
        ));
    }
    let wide = |xs: &[T]| -> Vec<T::Unbounded> { xs.iter().map(Scalar::unbounded).collect() };
    let balls = [0, 1].map(|i| Ball {
        inv_mass: clamped[i].inv_mass.unbounded(),
        radius: clamped[i].radius.unbounded(),
        gamma2: clamped[i].gamma2.unbounded(),
    });
    let spins = [wide(states[0].0), wide(states[1].0)];
    let mut velocities = [wide(states[0].1), wide(states[1].1)];
    graze(&nu, &balls, &mut velocities)?;
    Ok(Prepared {
        nu,
        balls,
        spins,
        velocities,
    })
}

/// Refuse separating bodies, `(u_2 - u_1) . nu > 0`, beyond the rounding allowance (scale
/// `sum_k |nu_k| (|u_1k| + |u_2k|)`); within it the contact is grazing: the normal part
/// `dn nu` of the relative velocity is removed, body `i` taking the share `w_i / (w_1 + w_2)`
/// so that momentum is kept.
fn graze<W: Scalar>(nu: &[W], balls: &[Ball<W>; 2], u: &mut [Vec<W>; 2]) -> Result<(), InputError> {
    let (mut dn, mut scale) = (W::zero(), W::zero());
    for (k, nu_k) in nu.iter().enumerate() {
        dn += nu_k.clone() * (u[1][k].clone() - u[0][k].clone());
        // The scale only sets the allowance, which is 0 in exact arithmetic.
        if !W::EXACT {
            scale += nu_k.abs() * (u[0][k].abs() + u[1][k].abs());
        }
    }
    if dn <= W::zero() {
        return Ok(());
    }
    if allowance::at_most(&dn, &W::zero(), &allowance(&scale)).is_none() {
        return Err(InputError::new(
            Field::RelativeVelocity,
            format!(
                "the bodies are separating: (u_2 - u_1) . nu = {} > 0 (a collision needs them \
                 approaching or grazing; nu points from body 1 to body 2)",
                dn.show()
            ),
        ));
    }
    let total = balls[0].inv_mass.clone() + balls[1].inv_mass.clone();
    for (b, sign) in [(0, W::one()), (1, -W::one())] {
        let share = sign * balls[b].inv_mass.clone() / total.clone() * dn.clone();
        for (x, nu_k) in u[b].iter_mut().zip(nu) {
            *x += share.clone() * nu_k.clone();
        }
    }
    Ok(())
}

/// Whether both bodies are movable point masses (`gamma2 = 0`): no law with a tangential
/// part is defined between them, and no kernel takes them.
pub(crate) fn both_point_masses<T: Scalar>(b1: &Ball<T>, b2: &Ball<T>) -> bool {
    !b1.is_immovable() && !b2.is_immovable() && b1.gamma2.is_zero() && b2.gamma2.is_zero()
}

/// Both bodies' `(spin, velocity)`, borrowed.
pub(crate) type Parts<'a, T> = [(&'a [T], &'a [T]); 2];
/// One body's `(spin, velocity)`.
pub(crate) type BodyParts<T> = (Vec<T>, Vec<T>);

/// The movable bodies' results `(spin, velocity)` rounded to `T`, or the error naming the
/// input at fault when one does not fit (see the module docs). An immovable body's result is
/// its input, returned as given.
pub(crate) fn round_results<T: Scalar>(
    p: &Prepared<T::Unbounded>,
    results: Parts<'_, T::Unbounded>,
    inputs: Parts<'_, T>,
) -> Result<[BodyParts<T>; 2], InputError> {
    let mut out: [BodyParts<T>; 2] = Default::default();
    for b in 0..2 {
        let ball = &p.balls[b];
        if ball.is_immovable() {
            out[b] = (inputs[b].0.to_vec(), inputs[b].1.to_vec());
            continue;
        }
        if T::EXACT {
            // Exact arithmetic: every result is its own value (nothing is rounded, nothing is
            // out of range), so the fit check below could only find an error of 0 against an
            // allowance of 0; it is skipped, not weakened.
            let exact = |ys: &[T::Unbounded]| ys.iter().map(T::from_unbounded).collect();
            out[b] = (exact(results[b].0), exact(results[b].1));
            continue;
        }
        let spin_weight = ball.gamma2.clone() * ball.radius.clone() * ball.radius.clone();
        let (mut err2, mut norm2) = (T::Unbounded::zero(), T::Unbounded::zero());
        // The component whose rounding costs the most: (its weighted error, value, spin?).
        let mut worst: Option<(T::Unbounded, T::Unbounded, bool)> = None;
        let mut round = |ys: &[T::Unbounded], weight: &T::Unbounded, spin: bool| {
            ys.iter()
                .map(|y| {
                    let x = T::from_unbounded(y);
                    if !x.is_finite() {
                        return Err(overflow::<T>(p, b, spin, y));
                    }
                    let e = x.unbounded() - y.clone();
                    let cost = weight.clone() * e.clone() * e;
                    if worst.as_ref().is_none_or(|(c, _, _)| cost > *c) {
                        worst = Some((cost.clone(), y.clone(), spin));
                    }
                    err2 += cost;
                    norm2 += weight.clone() * y.clone() * y.clone();
                    Ok(x)
                })
                .collect::<Result<Vec<T>, InputError>>()
        };
        let spin = round(results[b].0, &spin_weight, true)?;
        let velocity = round(results[b].1, &T::Unbounded::one(), false)?;
        // Normal-range components are off by at most eps/2 of themselves; only components
        // below the normal range can break the allowance of the body's energy norm.
        let slack = T::rounding_slack().unbounded();
        if err2 > slack.clone() * slack * norm2 {
            let (_, value, spin) = worst.unwrap_or_else(|| unreachable!("an error needs a part"));
            let speed = max_abs(results[b].1);
            return Err(underflow::<T>(p, b, &Lost { value, spin, speed }));
        }
        out[b] = (spin, velocity);
    }
    Ok(out)
}

#[cfg(test)]
mod tests;
