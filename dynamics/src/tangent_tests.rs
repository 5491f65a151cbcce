//! The tangent maps against the full map they linearise: f64 central differences, and exactly
//! (the full map run in dual numbers over rationals, with the contact time solved in them,
//! is a second route to the same derivative, which must agree to the last bit).

use super::*;
use crate::root::Root;
use crate::table::{Boundary, Table};
use collision_core::{Exact, State2, State3};

type Z<T, const N: usize, const S: usize> = ([T; N], BodyState<T, N, S>);

/// The full map: from `z` at time 0, through the first contact, to time `total`.
fn full<T: Root, const N: usize, const S: usize>(
    table: &Table<T, N>,
    z: &Z<T, N, S>,
    total: &T,
) -> (Z<T, N, S>, T)
where
    for<'a> &'a T: RefArith<T>,
    Generated: Kernel<T, N, S>,
{
    let (hit, after) = table.step(&z.0, &z.1).expect("a contact");
    let rest = total.clone() - hit.time.clone();
    let x =
        std::array::from_fn(|k| hit.position[k].clone() + rest.clone() * after.velocity[k].clone());
    ((x, after), hit.time)
}

fn pack<T: Scalar, const N: usize, const S: usize>(z: &Z<T, N, S>) -> Vec<T> {
    z.0.iter()
        .chain(&z.1.velocity)
        .chain(&z.1.spin)
        .cloned()
        .collect()
}

fn unpack<T: Scalar, const N: usize, const S: usize>(v: &[T]) -> Z<T, N, S> {
    (
        std::array::from_fn(|k| v[k].clone()),
        BodyState {
            velocity: std::array::from_fn(|k| v[N + k].clone()),
            spin: std::array::from_fn(|k| v[2 * N + k].clone()),
        },
    )
}

/// The tangent route: flight to the contact, the contact's tangent map, flight on.
fn tangent<T: Root, const N: usize, const S: usize>(
    table: &Table<T, N>,
    z: &Z<T, N, S>,
    total: &T,
    delta: &[T],
) -> Vec<T>
where
    for<'a> &'a T: RefArith<T>,
    for<'a> &'a Dual<T>: RefArith<Dual<T>>,
    Generated: Kernel<T, N, S> + Kernel<Dual<T>, N, S>,
{
    let hit = table.next_hit(&z.0, &z.1.velocity).expect("a contact");
    let mut block = delta.to_vec();
    flight::<T, N>(&mut block, &hit.time);
    let geometry = table.boundaries[hit.boundary].geometry(&table.ball.radius);
    boundary_contact(
        &geometry,
        table.laws[hit.boundary],
        &table.ball,
        &hit.nu,
        &z.1,
        &mut block,
    );
    flight::<T, N>(&mut block, &(total.clone() - hit.time));
    block
}

fn table2(boundary: Boundary<f64, 2>, law: Law) -> Table<f64, 2> {
    Table {
        boundaries: vec![boundary],
        period: [None, None],
        ball: Ball {
            inv_mass: 0.5,
            radius: 0.25,
            gamma2: 0.5,
        },
        laws: vec![law],
    }
}

/// Central differences `(F(z + h e) - F(z - h e)) / 2h`, h = 1e-6, against the tangent map,
/// column by column. The truncation error is `h^2 |F'''| / 6`, about 1e-12 times the
/// curvature factors (`t |u| / R_eff` <= 10 here, cubed), the rounding error about
/// `eps |F| / h` = 2e-10 |F|: 1e-7 (1 + |column|) bounds both with a margin of 100.
fn check_central_differences<const N: usize, const S: usize>(
    table: &Table<f64, N>,
    z: &Z<f64, N, S>,
    total: f64,
) -> f64
where
    Generated: Kernel<f64, N, S> + Kernel<Dual<f64>, N, S>,
{
    let base = pack(z);
    let h = 1e-6;
    let mut worst: f64 = 0.0;
    for a in 0..base.len() {
        let mut e = vec![0.0; base.len()];
        e[a] = 1.0;
        let shifted = |s: f64| {
            let v: Vec<f64> = base.iter().zip(&e).map(|(x, d)| x + s * d).collect();
            pack(&full(table, &unpack::<f64, N, S>(&v), &total).0)
        };
        let (plus, minus) = (shifted(h), shifted(-h));
        let column = tangent(table, z, &total, &e);
        let scale = 1.0 + column.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for k in 0..base.len() {
            let fd = (plus[k] - minus[k]) / (2.0 * h);
            let err = (fd - column[k]).abs() / scale;
            assert!(
                err < 1e-7,
                "column {a}, row {k}: tangent {} vs differences {fd}",
                column[k]
            );
            worst = worst.max(err);
        }
    }
    worst
}

#[test]
fn one_ball_tangent_maps_match_central_differences_in_f64() {
    for law in [Law::NoSlip, Law::Smooth] {
        let z = ([-2.0, 0.7], State2::from_scalar_spin(1.3, [1.1, -0.2]));
        let wall = table2(
            Boundary::Wall {
                point: [0.0, 0.0],
                normal: [0.6, 0.8],
            },
            law,
        );
        check_central_differences(
            &wall,
            &([1.5, 2.0], State2::from_scalar_spin(-0.7, [-0.3, -1.0])),
            4.0,
        );
        let sphere = table2(
            Boundary::Sphere {
                centre: [0.0, 0.0],
                radius: 1.0,
            },
            law,
        );
        check_central_differences(&sphere, &z, 3.0);
        let container = table2(
            Boundary::Container {
                centre: [0.0, 0.0],
                radius: 3.0,
            },
            law,
        );
        check_central_differences(
            &container,
            &([0.5, 0.2], State2::from_scalar_spin(2.0, [0.4, 0.9])),
            5.0,
        );
        // 3D: a sphere obstacle, spin about a skew axis.
        let ball3 = Ball {
            inv_mass: 1.0,
            radius: 0.5,
            gamma2: 0.4,
        };
        let t3 = Table {
            boundaries: vec![Boundary::Sphere {
                centre: [0.0, 0.0, 0.0],
                radius: 1.0,
            }],
            period: [None, None, None],
            ball: ball3,
            laws: vec![law],
        };
        let z3 = (
            [-2.5, 0.4, -0.3],
            State3::from_omega([0.3, -1.0, 0.8], [1.0, -0.1, 0.2]),
        );
        check_central_differences(&t3, &z3, 3.0);
    }
}

fn q(n: i64, d: i64) -> Exact {
    Exact::from_ratio(n, d)
}

/// Exactly: the tangent route in rationals equals the full map run in dual rationals (contact
/// time, contact point and normal all carried in `eps`), for every direction, for a tilted
/// wall (`nu = (3/5, 4/5)`), a sphere and a container whose contact times are rational.
#[test]
fn one_ball_tangent_maps_equal_the_dual_full_map_exactly() {
    let ball = Ball {
        inv_mass: q(1, 2),
        radius: q(1, 1),
        gamma2: q(1, 2),
    };
    let cases: Vec<(Boundary<Exact, 2>, Z<Exact, 2, 1>)> = vec![
        (
            Boundary::Wall {
                point: [q(0, 1), q(0, 1)],
                normal: [q(3, 5), q(4, 5)],
            },
            (
                [q(3, 1), q(4, 1)],
                State2::from_scalar_spin(q(2, 3), [q(-1, 1), q(-1, 2)]),
            ),
        ),
        (
            // R_eff = 4 + 1 = 5; from (-10, 3) along (1, 0) the contact is at (-4, 3), t = 6.
            Boundary::Sphere {
                centre: [q(0, 1), q(0, 1)],
                radius: q(4, 1),
            },
            (
                [q(-10, 1), q(3, 1)],
                State2::from_scalar_spin(q(-1, 5), [q(1, 1), q(0, 1)]),
            ),
        ),
        (
            // R_eff = 6 - 1 = 5; from (0, 3) along (-1, 0) the contact is at (-4, 3), t = 4.
            Boundary::Container {
                centre: [q(0, 1), q(0, 1)],
                radius: q(6, 1),
            },
            (
                [q(0, 1), q(3, 1)],
                State2::from_scalar_spin(q(3, 2), [q(-1, 1), q(0, 1)]),
            ),
        ),
    ];
    for law in [Law::NoSlip, Law::Smooth] {
        for (boundary, z) in &cases {
            let table = Table {
                boundaries: vec![boundary.clone()],
                period: [None, None],
                ball: ball.clone(),
                laws: vec![law],
            };
            let total = q(9, 1);
            let dual_table = table.map(|x| Dual::constant(x.clone()));
            let base = pack(z);
            for a in 0..base.len() {
                let e: Vec<Exact> = (0..base.len()).map(|k| q(i64::from(k == a), 1)).collect();
                let zd: Vec<Dual<Exact>> = base
                    .iter()
                    .zip(&e)
                    .map(|(x, d)| Dual::new(x.clone(), d.clone()))
                    .collect();
                let (out, _) = full(
                    &dual_table,
                    &unpack::<_, 2, 1>(&zd),
                    &Dual::constant(total.clone()),
                );
                let derivative: Vec<Exact> = pack(&out).into_iter().map(|d| d.du).collect();
                assert_eq!(
                    tangent(&table, z, &total, &e),
                    derivative,
                    "{boundary:?}, {law:?}, column {a}"
                );
            }
        }
    }
}

/// Two balls: the pair tangent map against central differences of the full two-ball map (the
/// contact time from `|d + t dv| = sigma`), and exactly against the same map in dual rationals.
#[test]
fn pair_tangent_map_matches_the_full_two_ball_map() {
    fn two_ball<T: Root>(balls: [&Ball<T>; 2], law: Law, z: &[T], total: &T) -> Vec<T>
    where
        for<'a> &'a T: RefArith<T>,
        Generated: Kernel<T, 2, 1>,
    {
        let (z1, z2) = (unpack::<T, 2, 1>(&z[..5]), unpack::<T, 2, 1>(&z[5..]));
        let sigma = balls[0].radius.clone() + balls[1].radius.clone();
        let d: [T; 2] = std::array::from_fn(|k| z2.0[k].clone() - z1.0[k].clone());
        let dv: [T; 2] =
            std::array::from_fn(|k| z2.1.velocity[k].clone() - z1.1.velocity[k].clone());
        let (a, b) = (dot(&dv, &dv), dot(&d, &dv));
        let c = dot(&d, &d) - sigma.clone() * sigma.clone();
        let s = (b.clone() * b.clone() - a * c.clone())
            .root()
            .expect("a rational contact");
        let t = c / (s - b);
        let at = |p: &[T; 2], v: &[T; 2], t: &T| -> [T; 2] {
            std::array::from_fn(|k| p[k].clone() + t.clone() * v[k].clone())
        };
        let (x1, x2) = (at(&z1.0, &z1.1.velocity, &t), at(&z2.0, &z2.1.velocity, &t));
        let nu: [T; 2] = std::array::from_fn(|k| (x2[k].clone() - x1[k].clone()) / sigma.clone());
        let [a1, a2] = law.pair(&nu, balls, [&z1.1, &z2.1]);
        let rest = total.clone() - t;
        let mut out = pack(&(at(&x1, &a1.velocity, &rest), a1));
        out.extend(pack(&(at(&x2, &a2.velocity, &rest), a2)));
        out
    }
    fn route<T: Root>(balls: [&Ball<T>; 2], law: Law, z: &[T], total: &T, e: &[T]) -> Vec<T>
    where
        for<'a> &'a T: RefArith<T>,
        for<'a> &'a Dual<T>: RefArith<Dual<T>>,
        Generated: Kernel<T, 2, 1> + Kernel<Dual<T>, 2, 1>,
    {
        let (z1, z2) = (unpack::<T, 2, 1>(&z[..5]), unpack::<T, 2, 1>(&z[5..]));
        let sigma = balls[0].radius.clone() + balls[1].radius.clone();
        let d: [T; 2] = std::array::from_fn(|k| z2.0[k].clone() - z1.0[k].clone());
        let dv: [T; 2] =
            std::array::from_fn(|k| z2.1.velocity[k].clone() - z1.1.velocity[k].clone());
        let (a, b) = (dot(&dv, &dv), dot(&d, &dv));
        let c = dot(&d, &d) - sigma.clone() * sigma.clone();
        let s = (b.clone() * b.clone() - a * c.clone())
            .root()
            .expect("a rational contact");
        let t = c / (s - b);
        let nu: [T; 2] =
            std::array::from_fn(|k| (d[k].clone() + t.clone() * dv[k].clone()) / sigma.clone());
        let (mut b1, mut b2) = (e[..5].to_vec(), e[5..].to_vec());
        flight::<T, 2>(&mut b1, &t);
        flight::<T, 2>(&mut b2, &t);
        pair_contact(
            &Geometry::Pair { sigma },
            law,
            balls,
            &nu,
            [&z1.1, &z2.1],
            &mut b1,
            &mut b2,
        );
        let rest = total.clone() - t;
        flight::<T, 2>(&mut b1, &rest);
        flight::<T, 2>(&mut b2, &rest);
        b1.extend(b2);
        b1
    }
    for law in [Law::NoSlip, Law::Smooth] {
        // f64: an oblique contact of unequal balls.
        let (p, r) = (
            Ball {
                inv_mass: 1.0,
                radius: 0.5,
                gamma2: 0.5,
            },
            Ball {
                inv_mass: 0.25,
                radius: 1.0,
                gamma2: 0.3,
            },
        );
        let z = [0.0, 0.0, 1.0, 0.3, 0.7, 4.0, 0.9, -0.5, 0.1, -1.2];
        let h = 1e-6;
        for a in 0..10 {
            let e: Vec<f64> = (0..10).map(|k| f64::from(u8::from(k == a))).collect();
            let column = route([&p, &r], law, &z, &5.0, &e);
            let scale = 1.0 + column.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let sh = |s: f64| {
                two_ball(
                    [&p, &r],
                    law,
                    &z.iter().zip(&e).map(|(x, d)| x + s * d).collect::<Vec<_>>(),
                    &5.0,
                )
            };
            let (plus, minus) = (sh(h), sh(-h));
            for k in 0..10 {
                let fd = (plus[k] - minus[k]) / (2.0 * h);
                assert!(
                    (fd - column[k]).abs() / scale < 1e-7,
                    "{law:?} column {a} row {k}: {} vs {fd}",
                    column[k]
                );
            }
        }
        // Exact: d = (5, 0), dv = (-1, 0), sigma = 5/2... contact when |(5 - t, 3/2)| = 5/2:
        // 5 - t = 2, t = 3 (discriminant 4).
        let (p, r) = (
            Ball {
                inv_mass: q(1, 1),
                radius: q(1, 1),
                gamma2: q(1, 2),
            },
            Ball {
                inv_mass: q(1, 3),
                radius: q(3, 2),
                gamma2: q(2, 5),
            },
        );
        let z: Vec<Exact> = [
            (0, 1),
            (0, 1),
            (1, 2),
            (0, 1),
            (1, 1),
            (5, 1),
            (3, 2),
            (-1, 2),
            (0, 1),
            (-2, 1),
        ]
        .iter()
        .map(|&(n, d)| q(n, d))
        .collect();
        let (pd, rd) = (
            Ball {
                inv_mass: Dual::constant(p.inv_mass.clone()),
                radius: Dual::constant(p.radius.clone()),
                gamma2: Dual::constant(p.gamma2.clone()),
            },
            Ball {
                inv_mass: Dual::constant(r.inv_mass.clone()),
                radius: Dual::constant(r.radius.clone()),
                gamma2: Dual::constant(r.gamma2.clone()),
            },
        );
        for a in 0..10 {
            let e: Vec<Exact> = (0..10).map(|k| q(i64::from(k == a), 1)).collect();
            let zd: Vec<Dual<Exact>> = z
                .iter()
                .zip(&e)
                .map(|(x, d)| Dual::new(x.clone(), d.clone()))
                .collect();
            let derivative: Vec<Exact> = two_ball([&pd, &rd], law, &zd, &Dual::constant(q(7, 1)))
                .into_iter()
                .map(|d| d.du)
                .collect();
            assert_eq!(
                route([&p, &r], law, &z, &q(7, 1), &e),
                derivative,
                "{law:?} column {a}"
            );
        }
    }
}

/// The contact tangent map on `(x, u, U)` as columns (2D).
fn contact_matrix(
    geometry: &Geometry<Exact>,
    law: Law,
    ball: &Ball<Exact>,
    nu: &[Exact; 2],
    pre: &State2<Exact>,
) -> Vec<Vec<Exact>> {
    (0..5)
        .map(|col| {
            let mut block: Vec<Exact> = (0..5).map(|k| q(i64::from(k == col), 1)).collect();
            boundary_contact(geometry, law, ball, nu, pre, &mut block);
            block
        })
        .collect()
}

fn contact_cases() -> Vec<(Geometry<Exact>, [Exact; 2], State2<Exact>)> {
    vec![
        (
            Geometry::Flat,
            [q(3, 5), q(4, 5)],
            State2::from_scalar_spin(q(2, 3), [q(-1, 1), q(-1, 2)]),
        ),
        (
            Geometry::Convex { r_eff: q(5, 1) },
            [q(-4, 5), q(3, 5)],
            State2::from_scalar_spin(q(-1, 5), [q(1, 1), q(-1, 3)]),
        ),
        (
            Geometry::Concave { r_eff: q(5, 2) },
            [q(0, 1), q(-1, 1)],
            State2::from_scalar_spin(q(3, 2), [q(1, 7), q(2, 1)]),
        ),
    ]
}

/// Volume: the contact tangent map has determinant `+-1`, exactly, for both laws and every
/// geometry (the flight has determinant 1), so the exponents sum to 0. The sign: the centres
/// are reflected (`dx' = (I - 2 nu nu^T) dx` at a flat wall: -1) and the velocities by an
/// involution that negates the impulse space (no-slip: dimension n, sign `(-1)^n`; smooth:
/// only the normal, -1): in 2D `-1` for no-slip, `+1` for smooth.
#[test]
fn contact_tangent_maps_preserve_volume_exactly() {
    let ball = Ball {
        inv_mass: q(1, 2),
        radius: q(1, 1),
        gamma2: q(1, 2),
    };
    for law in [Law::NoSlip, Law::Smooth] {
        for (geometry, nu, pre) in &contact_cases() {
            let p = crate::orbits::poly::charpoly(&contact_matrix(geometry, law, &ball, nu, pre));
            // det A = (-1)^5 c_0.
            let det = if law == Law::NoSlip {
                q(-1, 1)
            } else {
                q(1, 1)
            };
            assert_eq!(-p[0].clone(), det, "{geometry:?} {law:?}");
        }
    }
}

/// With the orientation angle `theta` put back (2D: `U = omega J`, `omega = -U_01`; it flies as
/// `theta += t omega`, so at a contact `dtheta' = dtheta + (omega - omega') dt_c`, like a
/// centre), the smooth contact's tangent map on `(x, theta, u, omega)` preserves the canonical
/// symplectic form `Omega = [[0, G], [-G, 0]]`, `G = diag(m, m, I)`, `I = m gamma^2 R^2`:
/// `A^T Omega A = Omega`, exactly, for every geometry (the classical billiard is Hamiltonian).
/// The no-slip contact's does not (here at a flat wall the `(x_0, u_0)` entry is `26/25`,
/// not `m = 2`): the pairing of the no-slip spectra does not come from a symplectic structure of
/// this kind (docs/dynamics.md: it comes from time reversibility).
#[test]
fn smooth_contacts_are_symplectic_and_no_slip_ones_are_not() {
    let ball = Ball {
        inv_mass: q(1, 2),
        radius: q(1, 1),
        gamma2: q(1, 2),
    };
    let m = q(2, 1);
    let inertia = m.clone() * ball.gamma2.clone() * ball.radius.clone() * ball.radius.clone();
    let g = [m.clone(), m.clone(), inertia];
    let omega = |i: usize, j: usize| -> Exact {
        if i < 3 && j == i + 3 {
            g[i].clone()
        } else if j < 3 && i == j + 3 {
            -g[j].clone()
        } else {
            q(0, 1)
        }
    };
    for law in [Law::Smooth, Law::NoSlip] {
        for (geometry, nu, pre) in &contact_cases() {
            // Columns of A on (x0, x1, theta, u0, u1, omega); our blocks are (x, u, U_01).
            let mut a = vec![vec![q(0, 1); 6]; 6];
            for col in 0..6 {
                let mut block = vec![q(0, 1); 5];
                let mut dtheta = q(0, 1);
                match col {
                    0 | 1 => block[col] = q(1, 1),
                    2 => dtheta = q(1, 1),
                    3 | 4 => block[col - 1] = q(1, 1),
                    _ => block[4] = q(-1, 1), // d omega = 1 is d U_01 = -1
                }
                let dx = [block[0].clone(), block[1].clone()];
                let dt_c = -dot(nu, &dx) / dot(nu, &pre.velocity);
                let after = boundary_contact(geometry, law, &ball, nu, pre, &mut block);
                let jump = after.spin[0].clone() - pre.spin[0].clone(); // omega - omega'
                let out = [
                    block[0].clone(),
                    block[1].clone(),
                    dtheta + jump * dt_c,
                    block[2].clone(),
                    block[3].clone(),
                    -block[4].clone(),
                ];
                for (row, v) in out.into_iter().enumerate() {
                    a[row][col] = v;
                }
            }
            let form = |i: usize, j: usize| -> Exact {
                let mut s = q(0, 1);
                for k in 0..6 {
                    for l in 0..6 {
                        s += a[k][i].clone() * omega(k, l) * a[l][j].clone();
                    }
                }
                s
            };
            let preserved = (0..6).all(|i| (0..6).all(|j| form(i, j) == omega(i, j)));
            assert_eq!(preserved, law == Law::Smooth, "{geometry:?} {law:?}");
            if law == Law::NoSlip && *geometry == Geometry::Flat {
                assert_eq!(form(0, 3), q(26, 25));
            }
        }
    }
}
