//! The generated kernels (plain and FMA), instantiated with exact rationals, against the
//! general-n reference and the exact facts of docs/derivation.md, for n = 2..6 and both variants.

#![allow(clippy::needless_range_loop)] // matrix entries are indexed by (row, col) on purpose

use collision_core::{
    collide, collide_unchecked, collide_unchecked_fma, reference, Ball, BodyState, Exact,
    Generated, Kernel, Scalar, State2,
};
use noslip_tests::*;
use num_traits::{One, Zero};

const POINTS: usize = 12;

fn q(p: i64, d: i64) -> Exact {
    Exact::from_ratio(p, d)
}

/// A random valid case; body 1 immovable when `fixed`.
fn case<const N: usize, const S: usize>(
    rng: &mut Rng,
    fixed: bool,
) -> ([Exact; N], [Ball<Exact>; 2], [BodyState<Exact, N, S>; 2]) {
    let nu = unit_normal::<N>(rng);
    let mut b1 = free_ball(rng, N);
    if fixed {
        b1.inv_mass = Exact::zero();
    }
    let balls = [b1, free_ball(rng, N)];
    let mut states = [state::<N, S>(rng), state::<N, S>(rng)];
    approaching(&nu, &mut states);
    (nu, balls, states)
}

fn kernels_equal_reference<const N: usize, const S: usize>()
where
    Generated: Kernel<Exact, N, S>,
{
    let mut rng = Rng::new(N as u64);
    for fixed in [false, true] {
        for _ in 0..POINTS {
            let (nu, balls, states) = case::<N, S>(&mut rng, fixed);
            let balls = [&balls[0], &balls[1]];
            let states = [&states[0], &states[1]];
            let kernel = collide(&nu, balls, states).unwrap();
            let reference = reference::collide(&nu, balls, states).unwrap();
            assert_eq!(kernel, reference, "n = {N}, fixed = {fixed}");
            let fused = collide_unchecked_fma(&nu, balls, states);
            assert_eq!(fused, reference, "FMA kernels, n = {N}, fixed = {fixed}");
            if fixed {
                assert_eq!(&kernel[0], states[0], "an immovable body is unchanged");
            }
        }
    }
}

fn conservation_and_involution<const N: usize, const S: usize>()
where
    Generated: Kernel<Exact, N, S>,
{
    let mut rng = Rng::new(100 + N as u64);
    for _ in 0..POINTS {
        let (nu, balls, states) = case::<N, S>(&mut rng, false);
        let b = [&balls[0], &balls[1]];
        let after = collide(&nu, b, [&states[0], &states[1]]).unwrap();
        // Kinetic energy.
        let e = |s: &[BodyState<Exact, N, S>; 2]| energy(b[0], &s[0]) + energy(b[1], &s[1]);
        assert_eq!(e(&after), e(&states), "energy, n = {N}");
        // Total linear momentum.
        let p = |s: &[BodyState<Exact, N, S>; 2]| -> Vec<Exact> {
            (0..N)
                .map(|k| &s[0].velocity[k] / &b[0].inv_mass + &s[1].velocity[k] / &b[1].inv_mass)
                .collect()
        };
        assert_eq!(p(&after), p(&states), "linear momentum, n = {N}");
        // Each body's angular momentum about the contact point.
        for i in 0..2 {
            assert_eq!(
                angular_momentum(i, &nu, b[i], &after[i]),
                angular_momentum(i, &nu, b[i], &states[i]),
                "angular momentum of body {i}, n = {N}"
            );
        }
        // The normal relative velocity flips.
        assert_eq!(
            relative_normal_velocity(&nu, &after),
            -relative_normal_velocity(&nu, &states)
        );
        // C o C = id (the post state separates, so the unchecked path).
        let twice = collide_unchecked(&nu, b, [&after[0], &after[1]]);
        assert_eq!(twice, states, "C o C, n = {N}");
    }
}

macro_rules! per_dim {
    ($(($name:ident $n:literal $s:literal))*) => {$(
        mod $name {
            #[test]
            fn generated_kernels_equal_the_reference_exactly() {
                super::kernels_equal_reference::<$n, $s>();
            }
            #[test]
            fn energy_momenta_conserved_and_involution() {
                super::conservation_and_involution::<$n, $s>();
            }
        }
    )*};
}

collision_core::for_each_dim!(per_dim);

/// 2D coordinates of a body: `(gamma R c, u . tau, u . nu)` with `U = c J`,
/// `J = [[0, -1], [1, 0]]` and the tangent `tau = -J nu = (nu_2, -nu_1)`.
fn coords2(gamma: &Exact, radius: &Exact, nu: &[Exact; 2], s: &State2<Exact>) -> [Exact; 3] {
    let tau = [nu[1].clone(), -nu[0].clone()];
    let dot = |a: &[Exact; 2]| &s.velocity[0] * &a[0] + &s.velocity[1] * &a[1];
    [gamma * radius * s.scalar_spin(), dot(&tau), dot(nu)]
}

fn state2(gamma: &Exact, radius: &Exact, nu: &[Exact; 2], x: &[Exact]) -> State2<Exact> {
    let tau = [nu[1].clone(), -nu[0].clone()];
    let c = &x[0] / (gamma * radius);
    State2::from_scalar_spin(c, std::array::from_fn(|k| &x[1] * &tau[k] + &x[2] * &nu[k]))
}

#[test]
fn disk_on_a_wall_matrix_of_the_derivation() {
    for gamma in [q(1, 2), q(2, 3), q(1, 1)] {
        let g2 = &gamma * &gamma;
        let nu = [q(3, 5), q(4, 5)];
        let wall = Ball::immovable(2, q(7, 3));
        let disk = Ball {
            inv_mass: q(1, 3),
            radius: q(3, 2),
            gamma2: g2.clone(),
        };
        let den = Exact::one() + &g2;
        let a = (Exact::one() - &g2) / &den;
        let b = q(2, 1) * &gamma / &den;
        let expected = [
            [-a.clone(), -b.clone(), q(0, 1)],
            [-b.clone(), a.clone(), q(0, 1)],
            [q(0, 1), q(0, 1), q(-1, 1)],
        ];
        for col in 0..3 {
            let x: Vec<Exact> = (0..3)
                .map(|k| if k == col { q(1, 1) } else { q(0, 1) })
                .collect();
            let before = state2(&gamma, &disk.radius, &nu, &x);
            let [_, after] = collide_unchecked(&nu, [&wall, &disk], [&State2::zero(), &before]);
            let y = coords2(&gamma, &disk.radius, &nu, &after);
            for row in 0..3 {
                assert_eq!(
                    y[row], expected[row][col],
                    "gamma {gamma}, entry ({row},{col})"
                );
            }
        }
        if gamma == q(1, 2) {
            assert_eq!((-a.clone(), -b.clone(), a), (q(-3, 5), q(-4, 5), q(3, 5)));
        }
    }
}

#[test]
fn equal_masses_matrix_of_the_notes_page_17() {
    let gamma = q(2, 3);
    let g2 = &gamma * &gamma;
    let den = Exact::one() + &g2;
    let (a, b, c) = (&g2 / &den, &gamma / &den, Exact::one() / &den);
    let z = q(0, 1);
    let o = q(1, 1);
    #[rustfmt::skip]
    let expected = [
        [a.clone(), b.clone(), z.clone(), -c.clone(), -b.clone(), z.clone()],
        [b.clone(), c.clone(), z.clone(), b.clone(), a.clone(), z.clone()],
        [z.clone(), z.clone(), z.clone(), z.clone(), z.clone(), o.clone()],
        [-c.clone(), b.clone(), z.clone(), a.clone(), -b.clone(), z.clone()],
        [-b.clone(), a.clone(), z.clone(), -b.clone(), c.clone(), z.clone()],
        [z.clone(), z.clone(), o.clone(), z.clone(), z.clone(), z.clone()],
    ];
    let nu = [q(-5, 13), q(12, 13)];
    // Equal masses and distributions, different radii (the matrix does not depend on them).
    let balls = [
        Ball {
            inv_mass: q(2, 7),
            radius: q(1, 2),
            gamma2: g2.clone(),
        },
        Ball {
            inv_mass: q(2, 7),
            radius: q(5, 4),
            gamma2: g2.clone(),
        },
    ];
    for col in 0..6 {
        let x: Vec<Exact> = (0..6)
            .map(|k| if k == col { o.clone() } else { z.clone() })
            .collect();
        let before = [0, 1].map(|i| state2(&gamma, &balls[i].radius, &nu, &x[3 * i..3 * i + 3]));
        let after = collide_unchecked(&nu, [&balls[0], &balls[1]], [&before[0], &before[1]]);
        let y: Vec<Exact> = (0..2)
            .flat_map(|i| coords2(&gamma, &balls[i].radius, &nu, &after[i]))
            .collect();
        for row in 0..6 {
            assert_eq!(y[row], expected[row][col], "entry ({row},{col})");
        }
    }
}

#[test]
fn the_example_case_of_the_issue_separates_and_its_mirror_collides() {
    // The issue's example: body 2 immovable, u_1 = (1, 0, -1/2), nu = (0, 3/5, 4/5), so
    // (u_2 - u_1) . nu = 2/5 > 0: the bodies separate and the checked map refuses it.
    // With u_1 = (1, 0, 1/2) they approach, and the swapped `fixed` kernel must agree with
    // the reference.
    use collision_core::{Field, Inertia, Mass};
    let nu = [q(0, 1), q(3, 5), q(4, 5)];
    let b1 = Ball::new(3, Mass::Finite(q(2, 1)), q(1, 1), Inertia::Lambda(q(1, 5))).unwrap();
    let b2 = Ball::new(3, Mass::Infinite, q(3, 2), Inertia::Gamma2(q(2, 5))).unwrap();
    let m = [
        [q(0, 1), q(1, 1), q(-2, 1)],
        [q(-1, 1), q(0, 1), q(3, 1)],
        [q(2, 1), q(-3, 1), q(0, 1)],
    ];
    let s2 = BodyState::zero();
    let away = BodyState::from_matrix(0, &m, [q(1, 1), q(0, 1), q(-1, 2)]).unwrap();
    let e = collide(&nu, [&b1, &b2], [&away, &s2]).unwrap_err();
    assert_eq!(e.field, Field::RelativeVelocity);
    assert_eq!(
        e.to_string(),
        "relative velocity: the bodies are separating: (u_2 - u_1) . nu = 2/5 > 0 (a collision needs them \
         approaching or grazing; nu points from body 1 to body 2)");
    let toward = BodyState::from_matrix(0, &m, [q(1, 1), q(0, 1), q(1, 2)]).unwrap();
    let out = collide(&nu, [&b1, &b2], [&toward, &s2]).unwrap();
    assert_eq!(
        out,
        reference::collide(&nu, [&b1, &b2], [&toward, &s2]).unwrap()
    );
    assert_eq!(out[1], s2, "the immovable body is unchanged");
    assert_eq!(relative_normal_velocity(&nu, &out), q(2, 5));
}
