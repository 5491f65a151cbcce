//! The checked path around the kernels: inputs validated and clamped under [the rounding
//! allowance](crate::allowance), moved into the unbounded-exponent arithmetic
//! ([`Scalar::Unbounded`]), and the results rounded back only where they fit.
//!
//! In floats the kernels then run in [`crate::Wide`]: every intermediate quantity keeps
//! the precision of the format whatever its magnitude (`R_2 U_2` for `R_2 = 8e307`,
//! `1/(R_2 D)`, products of tiny inverse masses), and the result is the format's kernel
//! result bit for bit wherever that kernel stays in range. A result is refused only when it
//! does not fit the format: a component beyond its range, or a body whose whole result lies
//! below its normal range (it would come back with fewer significant bits than the rounding
//! allowance). The error names the inputs that drive it.

use crate::allowance;
use crate::error::{BodyField, Field, InputError};
use crate::scalar::{allowance, two};
use crate::{Ball, Scalar};
use num_traits::{One, Zero};

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
/// rule), for any `n = nu.len()`.
pub(crate) fn prepare<T: Scalar>(
    nu: &[T],
    balls: [&Ball<T>; 2],
    states: Parts<'_, T>,
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
    let slack =
        allowance(&norm2) * T::Unbounded::from_ratio(i64::from(ulps), i64::from(allowance::ULPS));
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
    if !b1.is_immovable() && !b2.is_immovable() && b1.gamma2.is_zero() && b2.gamma2.is_zero() {
        return Err(InputError::new(
            Field::Bodies,
            "both bodies are point masses (lambda = 0): the no-slip map is undefined; at most one may be",
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
        scale += nu_k.abs() * (u[0][k].abs() + u[1][k].abs());
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

/// Which input sets the speed scale of the contact: the largest of `|u_i|` and `R_i |U_i|`
/// (entries' magnitudes), with the input field to blame and how to say it.
fn speed_source<W: Scalar>(p: &Prepared<W>) -> (W, Field, String) {
    let mut best: Option<(W, Field, String)> = None;
    for b in 0..2 {
        let u = max_abs(&p.velocities[b]);
        let r = p.balls[b].radius.clone();
        let spin = r.clone() * max_abs(&p.spins[b]);
        let candidates = [
            (
                u,
                Field::Body(b, BodyField::Velocity),
                "the speed".to_string(),
            ),
            (
                spin,
                Field::Body(b, BodyField::AngularVelocity),
                format!(
                    "with body {}'s radius R = {}, the contact-point speed R |U|",
                    b + 1,
                    r.show()
                ),
            ),
        ];
        for c in candidates {
            if best.as_ref().is_none_or(|(v, _, _)| c.0 > *v) {
                best = Some(c);
            }
        }
    }
    best.unwrap_or_else(|| unreachable!("two bodies"))
}

/// The error for a result of body `b` (`spin` or velocity) beyond the range of `T`, naming the
/// input at fault: the velocity results are bounded by a few times the speed scale `V` (see
/// [`speed_source`]), so its source is named; the angular ones by `V / R_b`, so the radius is
/// named when it brings more of the magnitude (`R_b V < 1`), else the source of `V`.
fn overflow<T: Scalar>(
    p: &Prepared<T::Unbounded>,
    b: usize,
    spin: bool,
    value: &T::Unbounded,
) -> InputError {
    let (speed, field, what) = speed_source(p);
    let tail = format!(
        "overflow {} (about {}); exact arithmetic computes it",
        T::NAME,
        value.show()
    );
    if !spin {
        return InputError::new(
            field,
            format!(
                "{what} up to {} makes body {}'s velocity after contact {tail}",
                speed.show(),
                b + 1
            ),
        );
    }
    let radius = p.balls[b].radius.clone();
    let rate = speed.clone() / radius.clone();
    if radius.clone() * speed.clone() < T::Unbounded::one() {
        return InputError::new(
            Field::Body(b, BodyField::Radius),
            format!(
                "{} is so small that the contact-point speed, up to {}, spins the body at up to \
                 {}: its angular velocity after contact would {tail}",
                radius.show(),
                speed.show(),
                rate.show()
            ),
        );
    }
    InputError::new(
        field,
        format!(
            "{what} up to {}, over body {}'s radius {}, spins it at up to {}: its angular \
             velocity after contact would {tail}",
            speed.show(),
            b + 1,
            radius.show(),
            rate.show()
        ),
    )
}

/// The error for a body whose whole result lies below the normal range of `T`.
fn underflow<T: Scalar>(
    p: &Prepared<T::Unbounded>,
    b: usize,
    largest: &T::Unbounded,
) -> InputError {
    let other = p.balls[1 - b].inv_mass.clone();
    let own = p.balls[b].inv_mass.clone();
    let tail = format!(
        "the result of body {} (largest component about {}) is below the normal range of {} \
         and would lose precision; exact arithmetic computes it",
        b + 1,
        largest.show(),
        T::NAME
    );
    // A 2^-64 share of the impulse: the mass ratio suppresses the body's change.
    let ratio = T::Unbounded::from_ratio(1, 1 << 32);
    if own < other * ratio.clone() * ratio {
        return InputError::new(
            Field::Body(b, BodyField::Mass),
            format!("the body is so much heavier than the other that {tail}"),
        );
    }
    let (speed, field, what) = speed_source(p);
    InputError::new(
        field,
        format!("{what}, up to {}, is so small that {tail}", speed.show()),
    )
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
        let spin_weight = ball.gamma2.clone() * ball.radius.clone() * ball.radius.clone();
        let (mut err2, mut norm2) = (T::Unbounded::zero(), T::Unbounded::zero());
        let mut round = |ys: &[T::Unbounded], weight: &T::Unbounded, spin: bool| {
            ys.iter()
                .map(|y| {
                    let x = T::from_unbounded(y);
                    if !x.is_finite() {
                        return Err(overflow::<T>(p, b, spin, y));
                    }
                    let e = x.unbounded() - y.clone();
                    err2 += weight.clone() * e.clone() * e;
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
            let (s, u) = (max_abs(results[b].0), max_abs(results[b].1));
            return Err(underflow::<T>(p, b, if s > u { &s } else { &u }));
        }
        out[b] = (spin, velocity);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use crate::{collide, collide_unchecked, Ball, BodyField, BodyState, Exact, Field, Generated};
    use crate::{Inertia, Kernel, Mass, Scalar, State2};
    use rand::{Rng as _, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn ball(mass: f64, radius: f64) -> Ball<f64> {
        Ball::new(2, Mass::Finite(mass), radius, Inertia::Uniform).unwrap()
    }

    fn exact(x: f64) -> Exact {
        Exact::from_float(x).unwrap()
    }

    /// The exact kernel on the same (f64) inputs.
    fn exact_result(
        nu: [f64; 2],
        balls: [&Ball<f64>; 2],
        s: [&State2<f64>; 2],
    ) -> [State2<Exact>; 2] {
        let b = balls.map(|b| Ball {
            inv_mass: exact(b.inv_mass),
            radius: exact(b.radius),
            gamma2: exact(b.gamma2),
        });
        let s = s.map(|s| BodyState {
            spin: s.spin.map(exact),
            velocity: s.velocity.map(exact),
        });
        collide_unchecked(&nu.map(exact), [&b[0], &b[1]], [&s[0], &s[1]])
    }

    /// A normal `d / |d|` computed in `f64`, in every dimension the checked entry points take
    /// (2 to 16), is accepted; one beyond `(8 + 2n) eps` of `|nu|^2 = 1` is refused.
    #[test]
    fn normalised_normals_are_accepted_in_every_dimension_and_no_further_one() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let eps = f64::EPSILON;
        for n in 2..=16usize {
            let b = Ball::new(n, Mass::Finite(1.0), 1.0, Inertia::Uniform).unwrap();
            let spin = vec![0.0; n * (n - 1) / 2];
            let velocity = vec![0.0; n];
            let parts = [(&spin[..], &velocity[..]), (&spin[..], &velocity[..])];
            for _ in 0..2000 {
                let d: Vec<f64> = (0..n)
                    .map(|_| rng.random_range(-1.0..1.0) * 10f64.powf(rng.random_range(-3.0..3.0)))
                    .collect();
                let norm = d.iter().map(|x| x * x).sum::<f64>().sqrt();
                let nu: Vec<f64> = d.iter().map(|x| x / norm).collect();
                assert!(super::prepare(&nu, [&b, &b], parts).is_ok(), "{nu:?}");
            }
            // |nu|^2 = (1 + k eps)^2 = 1 + 2k eps (rounded): k = 4 + n is the allowance's edge.
            let edge = 4.0 + n as f64;
            let mut nu = vec![0.0; n];
            nu[0] = 1.0 + edge * eps;
            assert!(
                super::prepare(&nu, [&b, &b], parts).is_ok(),
                "{n}: at the edge"
            );
            nu[0] = 1.0 + (edge + 1.0) * eps;
            let e = super::prepare(&nu, [&b, &b], parts).unwrap_err();
            assert_eq!(e.field, Field::Normal, "{n}: beyond the edge");
        }
    }

    #[test]
    fn a_huge_radius_gives_the_exact_answer() {
        // Issue 16: R_2 = 8e307. The f64 kernel's R_2 D overflows, so rho_2 = 2 w_2 g_1 /
        // (R_2 D) is 0 and body 2's spin comes back unchanged; the right change is
        // rho_2 (nu ^ t) with nu ^ t ~ R_2 U_2: O(1).
        let balls = [ball(0.5, 1.0), ball(0.5, 8e307)];
        let s = [
            State2::from_scalar_spin(1.0, [-1.0, 0.5]),
            State2::from_scalar_spin(0.125, [-2.0, 0.0]),
        ];
        let nu = [1.0, 0.0];
        let [b1, b2] = [&balls[0], &balls[1]];
        let plain = collide_unchecked(&nu, [b1, b2], [&s[0], &s[1]]);
        assert_eq!(plain[1].spin, s[1].spin, "the f64 kernel's defect");
        let got = collide(&nu, [b1, b2], [&s[0], &s[1]]).unwrap();
        let want = exact_result(nu, [b1, b2], [&s[0], &s[1]]);
        for b in 0..2 {
            for (x, y) in got[b]
                .spin
                .iter()
                .chain(&got[b].velocity)
                .zip(want[b].spin.iter().chain(&want[b].velocity))
            {
                // Each component to a few ulps of itself (none is a cancellation here).
                let y = Scalar::to_f64(y);
                assert!(
                    (x - y).abs() <= 8.0 * f64::EPSILON * y.abs(),
                    "body {b}: {x} vs {y}"
                );
            }
        }
        assert_ne!(got[1].spin, s[1].spin);
    }

    #[test]
    fn f32_computes_with_an_unbounded_exponent_too() {
        // R_2 = 2e38 (f32 ends at 3.4e38): the f32 kernel's R_2 D overflows as f64's did.
        let ball32 = |m: f32, r: f32| Ball::new(2, Mass::Finite(m), r, Inertia::Uniform).unwrap();
        let balls = [ball32(0.5, 1.0), ball32(0.5, 2e38)];
        let s = [
            State2::<f32>::from_scalar_spin(1.0, [-1.0, 0.5]),
            State2::from_scalar_spin(0.125, [-2.0, 0.0]),
        ];
        let plain = collide_unchecked(&[1.0, 0.0], [&balls[0], &balls[1]], [&s[0], &s[1]]);
        assert_eq!(plain[1].spin, s[1].spin, "the f32 kernel's defect");
        let got = collide(&[1.0f32, 0.0], [&balls[0], &balls[1]], [&s[0], &s[1]]).unwrap();
        let wide = balls.clone().map(|b| Ball {
            inv_mass: f64::from(b.inv_mass),
            radius: f64::from(b.radius),
            gamma2: f64::from(b.gamma2),
        });
        let s64 = s.clone().map(|s| BodyState {
            spin: s.spin.map(f64::from),
            velocity: s.velocity.map(f64::from),
        });
        let want = exact_result([1.0, 0.0], [&wide[0], &wide[1]], [&s64[0], &s64[1]]);
        let (x, y) = (f64::from(got[1].spin[0]), Scalar::to_f64(&want[1].spin[0]));
        assert!(
            (x - y).abs() <= 8.0 * f64::from(f32::EPSILON) * y.abs(),
            "{x} vs {y}"
        );
    }

    #[test]
    fn results_beyond_f64_are_refused_naming_the_input_at_fault() {
        let nu = [1.0, 0.0];
        // A tiny radius: the contact-point slip 1e10 over R_1 = 1e-300 spins body 1 at ~1e310.
        let (tiny, one) = (ball(1.0, 1e-300), ball(1.0, 1.0));
        let rest = State2::zero();
        let slip = State2::from_scalar_spin(0.0, [-1.0, 1e10]);
        let e = collide(&nu, [&tiny, &one], [&rest, &slip]).unwrap_err();
        assert_eq!(e.field, Field::Body(0, BodyField::Radius), "{e}");
        assert!(
            e.message.contains("its angular velocity after contact"),
            "{e}"
        );
        // Speeds near the largest f64: the light body bounces back at ~3e308.
        let (light, heavy) = (ball(1.0, 1.0), ball(1e10, 1.0));
        let fast = State2::from_scalar_spin(0.0, [1e308, 0.0]);
        let back = State2::from_scalar_spin(0.0, [-1e308, 0.0]);
        let e = collide(&nu, [&light, &heavy], [&fast, &back]).unwrap_err();
        assert_eq!(e.field, Field::Body(0, BodyField::Velocity), "{e}");
        assert!(e.message.contains("body 1's velocity after contact"), "{e}");
        // A body 1e600 times heavier, at rest: its whole change (~1e-600) is below f64.
        let (heavy, light) = (ball(1e300, 1.0), ball(1e-300, 1.0));
        let hit = State2::from_scalar_spin(0.0, [-1.0, 0.0]);
        let e = collide(&nu, [&heavy, &light], [&rest, &hit]).unwrap_err();
        assert_eq!(e.field, Field::Body(0, BodyField::Mass), "{e}");
        // ... but not when the body moves: then its result is its own velocity, to rounding.
        let moving = State2::from_scalar_spin(0.0, [1.0, 0.0]);
        let [after, _] = collide(&nu, [&heavy, &light], [&moving, &hit]).unwrap();
        assert_eq!(after.velocity, [1.0, 0.0]);
    }

    /// Random typical cases in R^N whose normal is unit in f64 exactly (so that nothing is
    /// renormalised).
    fn same_as_the_f64_kernel<const N: usize, const S: usize>()
    where
        Generated: Kernel<f64, N, S> + Kernel<crate::Wide<f64>, N, S>,
    {
        let mut rng = ChaCha8Rng::seed_from_u64(N as u64);
        let mut checked = 0;
        while checked < 200 {
            let v: [f64; N] = std::array::from_fn(|_| rng.random_range(-1.0..1.0));
            let r = v.iter().map(|x| x * x).sum::<f64>().sqrt();
            let nu = v.map(|x| x / r);
            if nu.iter().fold(0.0, |s, x| s + x * x) != 1.0 {
                continue;
            }
            let fixed = rng.random_range(0..4) == 0;
            let mut body = |fixed: bool| {
                let ball = Ball {
                    inv_mass: if fixed {
                        0.0
                    } else {
                        rng.random_range(0.25..4.0)
                    },
                    radius: rng.random_range(0.5..2.0),
                    gamma2: rng.random_range(0.01..2.0 / N as f64),
                };
                let state = BodyState::<f64, N, S> {
                    spin: std::array::from_fn(|_| rng.random_range(-1.0..1.0)),
                    velocity: std::array::from_fn(|_| rng.random_range(-1.0..1.0)),
                };
                (ball, state)
            };
            let ((b1, mut s1), (b2, s2)) = (body(fixed), body(false));
            let dn: f64 = (0..N)
                .map(|k| (s2.velocity[k] - s1.velocity[k]) * nu[k])
                .sum();
            if dn > 0.0 {
                s1.velocity = s1.velocity.map(|x| -x);
                if (0..N)
                    .map(|k| (s2.velocity[k] - s1.velocity[k]) * nu[k])
                    .sum::<f64>()
                    > 0.0
                {
                    continue;
                }
            }
            let balls = [&b1, &b2];
            let states = [&s1, &s2];
            assert_eq!(
                collide(&nu, balls, states).unwrap(),
                collide_unchecked(&nu, balls, states),
                "n = {N}"
            );
            checked += 1;
        }
    }

    #[test]
    fn in_range_the_result_is_the_f64_kernels_bit_for_bit() {
        same_as_the_f64_kernel::<2, 1>();
        same_as_the_f64_kernel::<3, 3>();
        same_as_the_f64_kernel::<4, 6>();
        same_as_the_f64_kernel::<5, 10>();
        same_as_the_f64_kernel::<6, 15>();
    }
}
