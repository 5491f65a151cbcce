//! The contact law at every kind of boundary, against first principles: exactly, the state
//! after a contact with a wall, a container and a sphere obstacle touching the ball at the
//! same point is the `fixed` kernel at the local normal (the same for all three: curvature
//! does not enter), the mean of the states before and after has no slip at the contact
//! point, and the energy is kept; and in f64, the engine applies exactly that map at the
//! normal its geometry gives.

use crate::table::{Boundary, ContactKind, Shape, Table};
use crate::{Body, Contact, GenericKernels, Setup, Simulation, Step};
use collision_core::{Ball, BodyState, Exact, Generated, Kernel};
use num_traits::{One, Signed, Zero};

fn q(p: i64, d: i64) -> Exact {
    Exact::checked_ratio(p, d).expect("nonzero denominator")
}

/// `sqrt(x)` of a rational square.
fn sqrt_exact(x: &Exact) -> Exact {
    x.exact_sqrt().expect("a rational square")
}

fn dot<const N: usize>(a: &[Exact; N], b: &[Exact; N]) -> Exact {
    (0..N).map(|k| &a[k] * &b[k]).sum()
}

/// The compact skew entries `U_ij`, `i < j`, as a matrix.
fn skew<const N: usize>(spin: &[Exact]) -> [[Exact; N]; N] {
    let pairs: Vec<(usize, usize)> = (0..N)
        .flat_map(|i| (i + 1..N).map(move |j| (i, j)))
        .collect();
    std::array::from_fn(|i| {
        std::array::from_fn(
            |j| match pairs.iter().position(|&p| p == (i.min(j), i.max(j))) {
                Some(k) if i < j => spin[k].clone(),
                Some(k) => -spin[k].clone(),
                None => Exact::zero(),
            },
        )
    })
}

/// The velocity of the ball's material point at `Q = a - R nu`: `u + U (Q - a)`.
fn contact_velocity<const N: usize, const S: usize>(
    s: &BodyState<Exact, N, S>,
    nu: &[Exact; N],
    r: &Exact,
) -> [Exact; N] {
    let u = skew::<N>(&s.spin);
    std::array::from_fn(|i| {
        let turn: Exact = (0..N).map(|j| &u[i][j] * &(-(r * &nu[j]))).sum();
        &s.velocity[i] + &turn
    })
}

/// `|u|^2 + 2 lambda |U|^2` (twice the energy over the mass), `|U|^2` the compact entries'.
fn energy<const N: usize, const S: usize>(s: &BodyState<Exact, N, S>, ball: &Ball<Exact>) -> Exact {
    let lambda = &ball.gamma2 * &ball.radius * &ball.radius / q(2, 1);
    let spin2: Exact = s.spin.iter().map(|x| x * x).sum();
    dot(&s.velocity, &s.velocity) + q(2, 1) * lambda * spin2
}

/// The exact local normal of a shape at a ball's centre `a` (the f64 [`Shape::normal`] in
/// exact rationals, for geometry whose distances are rational).
enum ExactShape<const N: usize> {
    Wall { normal: [Exact; N] },
    Container { centre: [Exact; N] },
    Sphere { centre: [Exact; N] },
}

impl<const N: usize> ExactShape<N> {
    fn normal(&self, a: &[Exact; N]) -> [Exact; N] {
        let unit = |d: [Exact; N]| {
            let len = sqrt_exact(&dot(&d, &d));
            d.map(|x| x / &len)
        };
        match self {
            ExactShape::Wall { normal } => unit(normal.clone()),
            ExactShape::Container { centre } => unit(std::array::from_fn(|k| &centre[k] - &a[k])),
            ExactShape::Sphere { centre } => unit(std::array::from_fn(|k| &a[k] - &centre[k])),
        }
    }
}

fn curvature_does_not_enter<const N: usize, const S: usize>(nu: [Exact; N], spin: [Exact; S])
where
    Generated: Kernel<Exact, N, S>,
{
    assert_eq!(dot(&nu, &nu), Exact::one(), "a unit rational normal");
    let ball = Ball {
        inv_mass: q(2, 3),
        radius: q(1, 2),
        gamma2: q(2, 5),
    };
    let a: [Exact; N] = std::array::from_fn(|k| q(k as i64 + 1, 3));
    // Moving into each boundary: u . nu < 0.
    let pre = BodyState::<Exact, N, S> {
        spin,
        velocity: std::array::from_fn(|k| &q(k as i64 - 2, 5) - &(q(3, 1) * &nu[k])),
    };
    assert!(dot(&pre.velocity, &nu).is_negative());
    let r = &ball.radius;
    // The three boundaries touch the ball at Q = a - R nu: a wall with a non-unit normal
    // 5 nu, a container of radius 3 (centre a + (3 - R) nu), a sphere of radius 7/4 (centre
    // a - (7/4 + R) nu).
    let shapes = [
        ExactShape::Wall {
            normal: nu.clone().map(|x| x * q(5, 1)),
        },
        ExactShape::Container {
            centre: std::array::from_fn(|k| &a[k] + &(&(q(3, 1) - r) * &nu[k])),
        },
        ExactShape::Sphere {
            centre: std::array::from_fn(|k| &a[k] - &(&(q(7, 4) + r) * &nu[k])),
        },
    ];
    let zero = BodyState::zero();
    let post: Vec<BodyState<Exact, N, S>> = shapes
        .iter()
        .map(|s| {
            let local = s.normal(&a);
            assert_eq!(local, nu);
            Generated::fixed(&local, &Exact::one(), &ball, &zero, &pre)
        })
        .collect();
    assert!(
        post.iter().all(|p| p == &post[0]),
        "the same map at every shape"
    );
    let post = &post[0];
    // The mean state has no slip at Q: v_Q(post) = -v_Q(pre), every component.
    let (before, after) = (
        contact_velocity(&pre, &nu, r),
        contact_velocity(post, &nu, r),
    );
    for k in 0..N {
        assert_eq!(&before[k] + &after[k], Exact::zero(), "slip component {k}");
    }
    assert_eq!(energy(post, &ball), energy(&pre, &ball));
    assert_eq!(dot(&post.velocity, &nu), -dot(&pre.velocity, &nu));
    assert_ne!(post.velocity, crate::smooth::fixed(&nu, &pre).velocity);
}

#[test]
fn every_boundary_applies_the_fixed_kernel_at_its_local_normal_exactly() {
    curvature_does_not_enter::<2, 1>([q(3, 5), q(4, 5)], [q(7, 3)]);
    curvature_does_not_enter::<3, 3>([q(2, 7), q(3, 7), q(6, 7)], [q(1, 2), q(-2, 1), q(5, 3)]);
    curvature_does_not_enter::<4, 6>(
        [q(1, 2), q(1, 2), q(1, 2), q(-1, 2)],
        [q(1, 1), q(0, 1), q(-3, 2), q(2, 5), q(1, 3), q(-1, 1)],
    );
}

const DISK: Ball<f64> = Ball {
    inv_mass: 1.0,
    radius: 0.25,
    gamma2: 0.5,
};

/// One disk at `a` with velocity `v` and spin 1, and one boundary; its first contact.
fn first_contact(
    shape: Shape<2>,
    contact: ContactKind,
    a: [f64; 2],
    v: [f64; 2],
) -> crate::Event<2, 1> {
    let table = Table {
        boxed: false,
        boundaries: vec![Boundary {
            shape,
            contact,
            arc: 0.0,
        }],
        ..Table::boxed()
    };
    let setup = Setup {
        size: [4.0, 4.0],
        periodic: [false; 2],
        species: vec![DISK],
        obstacles: vec![],
        bodies: vec![Body {
            species: 0,
            position: a,
            state: BodyState {
                spin: [1.0],
                velocity: v,
            },
        }],
        orientation: false,
        table,
    };
    let mut sim = Simulation::new(
        setup,
        GenericKernels {
            species: vec![DISK],
        },
    )
    .unwrap();
    match sim.step(f64::INFINITY) {
        Step::Contact(e) => {
            assert_eq!(e.contact, Contact::Boundary { i: 0, boundary: 0 });
            e
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn the_engine_applies_the_fixed_map_at_the_normal_of_the_geometry() {
    let s = std::f64::consts::FRAC_1_SQRT_2;
    let cases = [
        // A wall below, a container around, a sphere ahead, a polygon edge below.
        (
            Shape::Wall {
                point: [0.0, -1.0],
                normal: [0.0, 1.0],
            },
            [0.0, -1.0],
        ),
        (
            Shape::Container {
                centre: [0.0, 0.0],
                radius: 2.0,
            },
            [s, s],
        ),
        (
            Shape::Sphere {
                centre: [3.0, 0.0],
                radius: 1.0,
            },
            [1.0, 0.0],
        ),
        (
            Shape::Edge {
                from: [-2.0, -1.0],
                to: [2.0, -1.0],
                normal: [0.0, 1.0],
            },
            [0.0, -1.0],
        ),
    ];
    for (shape, v) in cases {
        let rough = ContactKind::Rough { e: 0.5, beta: 0.25 };
        let walton = ContactKind::Walton {
            e: 0.5,
            mu: 0.1,
            beta0: 0.25,
        };
        for contact in [ContactKind::NoSlip, ContactKind::Smooth, rough, walton] {
            let e = first_contact(shape.clone(), contact, [0.0, 0.0], v);
            // The contact is at the contact distance, and nu is the geometry's unit normal.
            assert!(
                shape.gap(&e.position[0], DISK.radius).abs() < 1e-15,
                "{shape:?}"
            );
            assert_eq!(e.nu, shape.normal(&e.position[0]));
            let expected = match contact {
                ContactKind::NoSlip => {
                    Generated::fixed(&e.nu, &1.0, &DISK, &BodyState::zero(), &e.pre[0])
                }
                ContactKind::Smooth => crate::smooth::fixed(&e.nu, &e.pre[0]),
                ContactKind::Rough {
                    e: restitution,
                    beta,
                } => {
                    let law = crate::rough::RoughLaw::Constant(collision_core::Restitution {
                        e: restitution,
                        beta,
                    });
                    crate::rough::fixed(&e.nu, &DISK, &law, &e.pre[0])
                }
                ContactKind::Walton {
                    e: restitution,
                    mu,
                    beta0,
                } => {
                    let law = crate::rough::RoughLaw::Walton(collision_core::Walton {
                        e: restitution,
                        mu,
                        beta0,
                    });
                    crate::rough::fixed(&e.nu, &DISK, &law, &e.pre[0])
                }
            };
            assert_eq!(e.post[0], expected, "{shape:?} {contact:?}");
        }
    }
}
