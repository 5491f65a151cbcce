//! `Exec::rough_fixed_rows` against the scalar family `fixed` kernels on each row, bit for
//! bit, with one law shared and one per row, at every instruction-set level, serial and
//! split, across chunks; the elastic end `(1, 1)` against the no-slip `fixed` kernel; and the
//! laws' checks: every refused value and shape names its field (and row), nothing written.

use super::rough_fixed::CHUNK_ROWS;
use super::tests::{arrays, by_hand, physical, Arrays};
use super::*;
use crate::batch::each::tests::{restitutions, waltons};
use crate::batch::lanes::Contact;
use crate::batch::{Exec, Isa};
use crate::error::Field;
use crate::kernels::{RoughKernel, WaltonKernel};
use crate::{skew_pairs, Ball, BodyState, Generated, Kernel, Restitution, Walton};

/// The arrays as fixed rows: body 1's radius `R_1` (its other parameters unused), body 2's
/// parameters.
fn fixed_rows(a: &Arrays) -> FixedRows<'_, f64> {
    FixedRows {
        nu: &a.nu,
        states: [0, 1].map(|b| StateRows {
            spin: &a.spin[b],
            velocity: &a.velocity[b],
        }),
        radius1: &a.params[0][1],
        ball2: BallRows {
            inv_mass: &a.params[1][0],
            radius: &a.params[1][1],
            gamma2: &a.params[1][2],
        },
    }
}

/// Body 2's states after, as rows written by hand: the full skew matrix (`+0` on the
/// diagonal, `U_rc` above it, `0 - U_rc` below it) and the velocity.
fn by_hand_rows<const N: usize, const S: usize>(states: &[BodyState<f64, N, S>]) -> [Vec<f64>; 2] {
    let (mut spin, mut velocity) = (vec![f64::NAN; states.len() * N * N], Vec::new());
    for (i, s) in states.iter().enumerate() {
        let m = &mut spin[i * N * N..(i + 1) * N * N];
        for r in 0..N {
            m[r * N + r] = 0.0;
        }
        for (x, (r, c)) in s.spin.iter().zip(skew_pairs(N)) {
            m[r * N + c] = *x;
            m[c * N + r] = 0.0 - x;
        }
        velocity.extend(s.velocity);
    }
    [spin, velocity]
}

/// A scalar `fixed` kernel on row `i`: `(i, contact, R_1, ball_2)` to body 2's state after.
type RowKernel<'a, const N: usize, const S: usize> =
    dyn Fn(usize, &Contact<f64, N, S>, f64, &Ball<f64>) -> BodyState<f64, N, S> + 'a;

fn bits(o: &[Vec<f64>; 2]) -> Vec<u64> {
    o.iter().flatten().map(|x| x.to_bits()).collect()
}

/// `Exec::rough_fixed_rows` on `laws` at every level, serial and split, against `want`.
fn every_level<R: LawRows<f64>, const N: usize, const S: usize>(
    a: &Arrays,
    laws: &R,
    want: &[Vec<f64>; 2],
    what: &str,
) where
    Generated: crate::batch::RoughBatchKernel<R::Law, f64, N, S>
        + crate::batch::EachLawBatchKernel<<R::Law as crate::batch::FamilyLaw>::Lanes, f64, N, S>,
    <R::Law as crate::batch::FamilyLaw>::Lanes: 'static,
{
    let len = a.nu.len() / N;
    for isa in Isa::available() {
        let serial = Exec::auto().with_isa(isa).expect("available").serial();
        #[cfg(feature = "parallel")]
        let execs = [serial, serial.parallel_from(0)];
        #[cfg(not(feature = "parallel"))]
        let execs = [serial];
        for exec in execs {
            let mut got = [vec![f64::NAN; len * N * N], vec![f64::NAN; len * N]];
            let [spin, velocity] = &mut got;
            exec.rough_fixed_rows::<R, f64, N, S>(
                laws,
                &fixed_rows(a),
                StateRowsMut { spin, velocity },
            )
            .expect("valid laws");
            assert_eq!(
                bits(&got),
                bits(want),
                "n = {N}, {isa}, {exec:?}, {len} rows, {what}"
            );
        }
    }
}

fn fixed_rows_are_the_scalar_kernels<const N: usize, const S: usize>()
where
    Generated: crate::batch::RoughBatchKernel<Restitution<f64>, f64, N, S>
        + crate::batch::RoughBatchKernel<Walton<f64>, f64, N, S>
        + crate::batch::EachLawBatchKernel<crate::batch::RestitutionLanes<f64>, f64, N, S>
        + crate::batch::EachLawBatchKernel<crate::batch::WaltonLanes<f64>, f64, N, S>
        + RoughKernel<f64, N, S>
        + WaltonKernel<f64, N, S>
        + Kernel<f64, N, S>,
{
    // Empty, one, a ragged block, and across a chunk's end.
    for len in [0, 1, 9, CHUNK_ROWS + 13] {
        let seed = len as u64 * 5 + N as u64;
        let a = physical(arrays::<N>(seed, len, [len % 2 == 1, false]));
        let r = restitutions(seed, len.max(1));
        let (e, beta): (Vec<f64>, Vec<f64>) = r.iter().map(|l| (l.e, l.beta)).unzip();
        let w = waltons(seed, len.max(1));
        let (we, (mu, beta0)): (Vec<f64>, (Vec<f64>, Vec<f64>)) =
            w.iter().map(|l| (l.e, (l.mu, l.beta0))).unzip();
        // Row i by the scalar kernel `kernel(nu, R_1, ball_2, s1, s2)`.
        let scalar = |kernel: &RowKernel<'_, N, S>| {
            let states: Vec<BodyState<f64, N, S>> = (0..len)
                .map(|i| {
                    let (c, [b1, b2]) = by_hand::<N, S>(&a, i);
                    kernel(i, &c, b1.radius, &b2)
                })
                .collect();
            by_hand_rows(&states)
        };
        let rough = |law: &dyn Fn(usize) -> Restitution<f64>| {
            scalar(&|i, c, r1, b2| {
                let [s1, s2] = &c.states;
                Generated::rough_fixed(&c.nu, &r1, b2, &law(i), s1, s2)
            })
        };
        let walton = |law: &dyn Fn(usize) -> Walton<f64>| {
            scalar(&|i, c, r1, b2| {
                let [s1, s2] = &c.states;
                Generated::walton_fixed(&c.nu, &r1, b2, &law(i), s1, s2)
            })
        };
        if len > 0 {
            let each = RestitutionRows { e: &e, beta: &beta };
            every_level::<_, N, S>(&a, &each, &rough(&|i| r[i].clone()), "(e, beta) per row");
            let half = RestitutionRows {
                e: &e,
                beta: &beta[..1],
            };
            let want = rough(&|i| Restitution::new(e[i], beta[0]).unwrap());
            every_level::<_, N, S>(&a, &half, &want, "e per row, beta shared");
            let each = WaltonRows {
                e: &we,
                mu: &mu,
                beta0: &beta0,
            };
            every_level::<_, N, S>(&a, &each, &walton(&|i| w[i].clone()), "Walton per row");
        }
        let shared = RestitutionRows {
            e: &[0.9],
            beta: &[0.4],
        };
        let law = Restitution::new(0.9, 0.4).unwrap();
        every_level::<_, N, S>(&a, &shared, &rough(&|_| law.clone()), "(0.9, 0.4) shared");
        let shared = WaltonRows {
            e: &[0.9],
            mu: &[0.2],
            beta0: &[0.4],
        };
        let law = Walton::new(0.9, 0.2, 0.4).unwrap();
        every_level::<_, N, S>(&a, &shared, &walton(&|_| law.clone()), "Walton shared");
        // The elastic end (1, 1): the no-slip `fixed` kernel's bits.
        let no_slip = scalar(&|_, c, r1, b2| {
            let [s1, s2] = &c.states;
            Generated::fixed(&c.nu, &r1, b2, s1, s2)
        });
        let ends = RestitutionRows {
            e: &[1.0],
            beta: &[1.0],
        };
        every_level::<_, N, S>(&a, &ends, &no_slip, "(1, 1): no-slip");
    }
}

#[test]
fn rough_fixed_rows_gives_the_scalar_family_kernels_bits_at_every_level() {
    fixed_rows_are_the_scalar_kernels::<2, 1>();
    fixed_rows_are_the_scalar_kernels::<3, 3>();
    fixed_rows_are_the_scalar_kernels::<4, 6>();
    fixed_rows_are_the_scalar_kernels::<5, 10>();
    fixed_rows_are_the_scalar_kernels::<6, 15>();
}

#[test]
fn refused_fixed_laws_name_the_field_and_the_row() {
    let a = &physical(arrays::<3>(5, 6, [false, false]));
    let run = |laws: &dyn Fn(StateRowsMut<'_, f64>) -> Result<(), LawRowError>| {
        let mut out = [vec![f64::NAN; 6 * 9], vec![f64::NAN; 6 * 3]];
        let [spin, velocity] = &mut out;
        let err = laws(StateRowsMut { spin, velocity }).unwrap_err();
        // Nothing was written.
        assert!(out.iter().flatten().all(|x| x.is_nan()));
        err
    };
    let exec = Exec::auto();
    let rough = |e: &[f64], beta: &[f64]| {
        run(&|out| {
            exec.rough_fixed_rows::<_, f64, 3, 3>(&RestitutionRows { e, beta }, &fixed_rows(a), out)
        })
    };
    let ok = [0.5; 6];
    for (e, beta, field, row) in [
        (
            &[0.5, 0.5, 1.5, 0.5, 0.5, 0.5][..],
            &ok[..],
            Field::RestitutionE,
            Some(2),
        ),
        (
            &ok[..],
            &[0.0, 0.0, 0.0, 0.0, 0.0, -1.01][..],
            Field::RestitutionBeta,
            Some(5),
        ),
        (&[f64::NAN][..], &ok[..], Field::RestitutionE, None),
        (&ok[..5], &ok[..], Field::RestitutionE, None),
        (&ok[..], &[][..], Field::RestitutionBeta, None),
    ] {
        let err = rough(e, beta);
        assert_eq!((err.error.field, err.row), (field, row), "{err}");
    }
    assert_eq!(
        rough(&[0.5, 0.5, 1.5, 0.5, 0.5, 0.5], &ok).to_string(),
        "row 2: restitution e: must be in [0, 1], got 1.5"
    );
    assert_eq!(
        rough(&ok[..5], &ok).to_string(),
        "restitution e: 5 values for 6 contacts (give one per contact, or one shared)"
    );
    let walton = |e: &[f64], mu: &[f64], beta0: &[f64]| {
        run(&|out| {
            let laws = WaltonRows { e, mu, beta0 };
            exec.rough_fixed_rows::<_, f64, 3, 3>(&laws, &fixed_rows(a), out)
        })
    };
    for (e, mu, beta0, field, row) in [
        (
            &[1.01][..],
            &[0.1][..],
            &[0.0][..],
            Field::RestitutionE,
            None,
        ),
        (
            &[1.0][..],
            &[0.1, 0.1, 0.1, -0.1, 0.1, 0.1][..],
            &[0.0][..],
            Field::FrictionMu,
            Some(3),
        ),
        (
            &[1.0][..],
            &[0.1][..],
            &[0.0, 0.0, 0.0, 0.0, 2.0, 0.0][..],
            Field::WaltonBeta0,
            Some(4),
        ),
        (
            &[1.0][..],
            &[0.1; 7][..],
            &[0.0][..],
            Field::FrictionMu,
            None,
        ),
    ] {
        let err = walton(e, mu, beta0);
        assert_eq!((err.error.field, err.row), (field, row), "{err}");
    }
}

#[test]
#[should_panic(expected = "body 1: velocity: n per contact")]
fn fixed_rows_of_the_wrong_length_panic() {
    let mut a = arrays::<3>(1, 4, [false, false]);
    a.velocity[1].pop();
    fixed_rows(&a).len::<3>();
}
