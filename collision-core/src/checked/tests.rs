//! The checked path against the plain kernels and exact arithmetic.
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
fn exact_result(nu: [f64; 2], balls: [&Ball<f64>; 2], s: [&State2<f64>; 2]) -> [State2<Exact>; 2] {
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
            assert!(super::prepare(&nu, [&b, &b], parts, true).is_ok(), "{nu:?}");
        }
        // |nu|^2 = (1 + k eps)^2 = 1 + 2k eps (rounded): k = 4 + n is the allowance's edge.
        let edge = 4.0 + n as f64;
        let mut nu = vec![0.0; n];
        nu[0] = 1.0 + edge * eps;
        assert!(
            super::prepare(&nu, [&b, &b], parts, true).is_ok(),
            "{n}: at the edge"
        );
        nu[0] = 1.0 + (edge + 1.0) * eps;
        let e = super::prepare(&nu, [&b, &b], parts, true).unwrap_err();
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

/// Issue 26, item 1: a body whose angular velocity after contact (about 4.5e-331) is below
/// the range of f64 while it carries as much of the body's motion as its velocity (about
/// 1.7e-120, well inside the range): the refusal must say so, and name the huge radius. The
/// message used to say that the whole result was below the normal range, quoting 1.7e-120.
#[test]
fn a_spin_below_the_range_that_carries_energy_is_refused_naming_the_radius() {
    let b1 = Ball::new(2, Mass::Finite(5625e-306), 12e210, Inertia::Gamma2(0.36)).unwrap();
    let b2 = Ball::new(2, Mass::Finite(9e186), 1.15, Inertia::Gamma2(0.5)).unwrap();
    let s1 = State2::from_scalar_spin(0.0, [-7e-121, -3.7e-120]);
    let s2 = State2::from_scalar_spin(-7e-163, [4.7e-135, -2.3e-135]);
    let nu = [-1.0, 0.0];
    let e = collide(&nu, [&b1, &b2], [&s1, &s2]).unwrap_err();
    assert_eq!(e.field, Field::Body(0, BodyField::Radius), "{e}");
    assert!(
        e.message
            .contains("body 1's angular velocity after contact has an entry of about 4.53"),
        "{e}"
    );
    // The exact answer confirms it: the spin is below f64's smallest subnormal (it rounds
    // to 0), yet R |U| is over a third of the velocity's size, so the energy norm loses far
    // more than 8 eps.
    let want = exact_result(nu, [&b1, &b2], [&s1, &s2]);
    let spin = Scalar::to_f64(&want[0].spin[0]);
    assert_eq!(spin, 0.0);
    let contact = want[0].spin[0].clone() * exact(b1.radius);
    let speed = Scalar::to_f64(&want[0].velocity[1]).abs();
    assert!(speed > 1e-120 && speed < 1e-119, "{speed}");
    assert!(Scalar::to_f64(&contact).abs() > speed / 3.0);
}

/// The other refusal below the range: bodies so slow that a whole result is below the normal
/// range (the speed is blamed, and the message says the velocity).
#[test]
fn a_velocity_below_the_range_is_refused_naming_the_speed() {
    let (one, three) = (ball(1.0, 1.0), ball(3.0, 0.7));
    let slow = State2::from_scalar_spin(0.0, [-1e-310, 3e-311]);
    let e = collide(&[1.0, 0.0], [&three, &one], [&State2::zero(), &slow]).unwrap_err();
    assert_eq!(e.field, Field::Body(1, BodyField::Velocity), "{e}");
    assert!(e.message.contains("velocity after contact (about"), "{e}");
}

/// A result far below the contact's speed scale: an equal partner takes body 1's whole normal
/// velocity (1), and what stays is its tangential component, about 6.7e-321. The speed scale
/// is not small, so the refusal must not say it is (it said "the speed, up to 1.0, is so
/// small that ..."); it names body 1's velocity and says the contact left it little motion.
#[test]
fn a_result_far_below_the_speed_scale_is_blamed_on_the_contact_not_the_speed() {
    let one = ball(1.0, 1.0);
    let moving = State2::from_scalar_spin(0.0, [1e-320, 1.0]);
    let e = collide(&[0.0, 1.0], [&one, &one], [&moving, &State2::zero()]).unwrap_err();
    assert_eq!(e.field, Field::Body(0, BodyField::Velocity), "{e}");
    assert!(
        e.message
            .contains("leaves body 1 with motion far below its speed scale (the speed, up to 1"),
        "{e}"
    );
    assert!(!e.message.contains("so small"), "{e}");
    // The exact answer confirms the size: body 1's velocity is a few 1e-321.
    let want = exact_result([0.0, 1.0], [&one, &one], [&moving, &State2::zero()]);
    let u = Scalar::to_f64(&want[0].velocity[0]).abs();
    assert!(u > 1e-321 && u < 1e-320, "{u}");
}

/// Two point masses under a smooth law (`beta = -1`): taken, their contact the specular map
/// with restitution `e` exactly (in exact arithmetic: `dv . nu` becomes `-e` times itself,
/// momentum and spins kept, tangential velocities untouched); under any law with a tangential
/// part refused, naming the bodies (no kernel takes them: the rough kernel gave NaN).
#[test]
fn two_point_masses_meet_under_a_smooth_law_only() {
    use crate::{collide_rough, Restitution};
    let q = |p: i64, d: i64| Exact::checked_ratio(p, d).expect("nonzero denominator");
    let point =
        |m: i64| Ball::new(2, Mass::Finite(q(m, 1)), q(1, 1), Inertia::Gamma2(q(0, 1))).unwrap();
    let (b1, b2) = (point(1), point(3));
    let nu = [q(3, 5), q(4, 5)];
    let s1 = State2::from_scalar_spin(q(2, 1), [q(1, 1), q(1, 2)]);
    let s2 = State2::from_scalar_spin(q(-1, 1), [q(-1, 3), q(0, 1)]);
    let dn = |a: &State2<Exact>, b: &State2<Exact>| {
        (0..2).fold(q(0, 1), |s, k| {
            s + (b.velocity[k].clone() - a.velocity[k].clone()) * nu[k].clone()
        })
    };
    for e in [q(1, 1), q(1, 2), q(0, 1)] {
        let law = Restitution::new(e.clone(), q(-1, 1)).unwrap();
        let [p1, p2] = collide_rough(&nu, [&b1, &b2], &law, [&s1, &s2]).unwrap();
        assert_eq!(dn(&p1, &p2), -(e.clone() * dn(&s1, &s2)), "e = {e}");
        assert_eq!((&p1.spin, &p2.spin), (&s1.spin, &s2.spin));
        for k in 0..2 {
            let momentum = |a: &State2<Exact>, b: &State2<Exact>| {
                a.velocity[k].clone() + b.velocity[k].clone() * q(3, 1)
            };
            assert_eq!(momentum(&p1, &p2), momentum(&s1, &s2));
        }
        // The tangential velocities (along (-4/5, 3/5)) are untouched.
        let t =
            |s: &State2<Exact>| s.velocity[0].clone() * q(-4, 5) + s.velocity[1].clone() * q(3, 5);
        assert_eq!((t(&p1), t(&p2)), (t(&s1), t(&s2)));
    }
    // In floats too (the checked path's unbounded arithmetic, then rounded).
    let f = |m: f64| Ball::new(2, Mass::Finite(m), 1.0, Inertia::Gamma2(0.0)).unwrap();
    let smooth = Restitution::new(0.5, -1.0).unwrap();
    let (u1, u2) = (State2::from_scalar_spin(0.0, [0.0, 1.0]), State2::zero());
    let out = collide_rough(&[0.0, 1.0], [&f(1.0), &f(1.0)], &smooth, [&u1, &u2]).unwrap();
    assert_eq!(
        (out[0].velocity, out[1].velocity),
        ([0.0, 0.25], [0.0, 0.75])
    );
    // A tangential part: refused, as the no-slip map is.
    let rough = Restitution::new(0.5, 0.0).unwrap();
    let e = collide_rough(&[0.0, 1.0], [&f(1.0), &f(1.0)], &rough, [&u1, &u2]).unwrap_err();
    assert_eq!(e.field, Field::Bodies, "{e}");
    assert!(
        e.message.contains("a smooth law (beta = -1) takes two"),
        "{e}"
    );
    assert!(collide(&[0.0, 1.0], [&f(1.0), &f(1.0)], [&u1, &u2]).is_err());
}
