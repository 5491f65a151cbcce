//! `Exec::rough_free_rows` against the scalar family kernels on each row, bit for bit, with
//! one law shared and one per row, at every level (serial, split; passes in both orders); and the laws'
//! checks: every refused value and shape names its field (and row).

use super::tests::{arrays, bits, by_hand, nan_rows, physical, row_execs, rows, rows_mut};
use super::*;
use crate::batch::each::tests::{restitutions, waltons};
use crate::batch::{Exec, Isa, PairBatch};
use crate::error::Field;
use crate::kernels::{RoughKernel, WaltonKernel};
use crate::{Generated, Restitution, Walton};

/// The lengths: empty, one, a ragged block, and across passes (in cache) and splits.
fn lengths<const N: usize, const S: usize>() -> [usize; 5] {
    let pass = super::exec::pass_rows::<
        crate::batch::WithLaw<crate::batch::FreeLanes<f64, N, S>, crate::batch::WaltonLanes<f64>>,
        [crate::batch::StateLanes<f64, N, S>; 2],
    >(super::ROWS_PASS_BYTES);
    [0, 1, 9, pass + 3, 2 * pass + 17]
}

/// `Exec::rough_free_rows` on `laws` at every level, against `want`, bit for bit.
fn every_level<R: LawRows<f64>, const N: usize, const S: usize>(
    a: &super::tests::Arrays,
    laws: &R,
    want: &[[Vec<f64>; 2]; 2],
    what: &str,
) where
    Generated: crate::batch::RoughBatchKernel<R::Law, f64, N, S>
        + crate::batch::EachLawBatchKernel<<R::Law as crate::batch::FamilyLaw>::Lanes, f64, N, S>,
    <R::Law as crate::batch::FamilyLaw>::Lanes: 'static,
{
    let len = a.nu.len() / N;
    for isa in Isa::available() {
        for exec in row_execs(isa) {
            let mut got = nan_rows::<N>(len);
            exec.rough_free_rows::<R, f64, N, S>(laws, &rows(a), rows_mut(&mut got))
                .expect("valid laws");
            assert_eq!(
                bits(&got),
                bits(want),
                "n = {N}, {isa}, {exec:?}, {len} rows, {what}"
            );
        }
    }
}

fn rough_rows_are_the_scalar_kernels<const N: usize, const S: usize>()
where
    Generated: crate::batch::RoughBatchKernel<Restitution<f64>, f64, N, S>
        + crate::batch::RoughBatchKernel<Walton<f64>, f64, N, S>
        + crate::batch::EachLawBatchKernel<crate::batch::RestitutionLanes<f64>, f64, N, S>
        + crate::batch::EachLawBatchKernel<crate::batch::WaltonLanes<f64>, f64, N, S>
        + crate::batch::BatchKernel<f64, N, S>
        + RoughKernel<f64, N, S>
        + WaltonKernel<f64, N, S>,
{
    for len in lengths::<N, S>() {
        let seed = len as u64 * 3 + N as u64;
        let a = physical(arrays::<N>(seed, len, [false, len % 2 == 1]));
        let contact = |i: usize| by_hand::<N, S>(&a, i);
        // Per row: each row its own law; shared: one law (a column of one value) for all.
        let r = restitutions(seed, len.max(1));
        let (e, beta): (Vec<f64>, Vec<f64>) = r.iter().map(|l| (l.e, l.beta)).unzip();
        let w = waltons(seed, len.max(1));
        let (we, (mu, beta0)): (Vec<f64>, (Vec<f64>, Vec<f64>)) =
            w.iter().map(|l| (l.e, (l.mu, l.beta0))).unzip();
        let rough = |laws: &dyn Fn(usize) -> Restitution<f64>| {
            let pairs: PairBatch<f64, N, S> = (0..len)
                .map(|i| {
                    let (c, [b1, b2]) = contact(i);
                    let [s1, s2] = &c.states;
                    Generated::rough_free(&c.nu, &b1, &b2, &laws(i), s1, s2)
                })
                .collect();
            let mut want = nan_rows::<N>(len);
            pairs.write_rows_on(Isa::Baseline, rows_mut(&mut want));
            want
        };
        let walton = |laws: &dyn Fn(usize) -> Walton<f64>| {
            let pairs: PairBatch<f64, N, S> = (0..len)
                .map(|i| {
                    let (c, [b1, b2]) = contact(i);
                    let [s1, s2] = &c.states;
                    Generated::walton_free(&c.nu, &b1, &b2, &laws(i), s1, s2)
                })
                .collect();
            let mut want = nan_rows::<N>(len);
            pairs.write_rows_on(Isa::Baseline, rows_mut(&mut want));
            want
        };
        if len > 0 {
            let each = RestitutionRows { e: &e, beta: &beta };
            every_level::<_, N, S>(&a, &each, &rough(&|i| r[i].clone()), "(e, beta) per row");
            // One column per row, the other shared: the per-row kernel too.
            let half = RestitutionRows {
                e: &e[..1],
                beta: &beta,
            };
            let want = rough(&|i| Restitution::new(e[0], beta[i]).unwrap());
            every_level::<_, N, S>(&a, &half, &want, "e shared, beta per row");
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
        // The elastic ends shared: the no-slip path's bits.
        let mut no_slip = nan_rows::<N>(len);
        Exec::auto().free_rows::<f64, N, S>(&rows(&a), rows_mut(&mut no_slip));
        let ends = RestitutionRows {
            e: &[1.0],
            beta: &[1.0],
        };
        every_level::<_, N, S>(&a, &ends, &no_slip, "(1, 1): no-slip");
    }
}

#[test]
fn rough_free_rows_gives_the_scalar_family_kernels_bits_at_every_level() {
    rough_rows_are_the_scalar_kernels::<2, 1>();
    rough_rows_are_the_scalar_kernels::<3, 3>();
    rough_rows_are_the_scalar_kernels::<4, 6>();
    rough_rows_are_the_scalar_kernels::<5, 10>();
    rough_rows_are_the_scalar_kernels::<6, 15>();
}

/// Row-major outputs of both bodies (`nan_rows`).
type Out = [[Vec<f64>; 2]; 2];

#[test]
fn refused_laws_name_the_field_and_the_row() {
    let a = &physical(arrays::<3>(5, 6, [false, false]));
    let run = |laws: &dyn Fn(&mut Out) -> Result<(), LawRowError>| {
        let mut out = nan_rows::<3>(6);
        let err = laws(&mut out).unwrap_err();
        // Nothing was written.
        assert!(out.iter().flatten().flatten().all(|x| x.is_nan()));
        err
    };
    let exec = Exec::auto();
    let rough = |e: &[f64], beta: &[f64]| {
        let (e, beta) = (e.to_vec(), beta.to_vec());
        run(&move |out| {
            exec.rough_free_rows::<_, f64, 3, 3>(
                &RestitutionRows { e: &e, beta: &beta },
                &rows(a),
                rows_mut(out),
            )
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
        (&[-0.0001][..], &[0.0][..], Field::RestitutionE, None),
        (
            &ok[..],
            &[0.0, f64::NAN, 0.0, 0.0, 0.0, 0.0][..],
            Field::RestitutionBeta,
            Some(1),
        ),
        (&ok[..5], &ok[..], Field::RestitutionE, None),
        (&ok[..], &[][..], Field::RestitutionBeta, None),
    ] {
        let err = rough(e, beta);
        assert_eq!((err.error.field, err.row), (field, row), "{err}");
    }
    let err = rough(&[0.5, 0.5, 1.5, 0.5, 0.5, 0.5], &ok);
    assert_eq!(
        err.to_string(),
        "row 2: restitution e: must be in [0, 1], got 1.5"
    );
    // A value every row shares names no row.
    let err = rough(&[1.5], &ok);
    assert_eq!(err.to_string(), "restitution e: must be in [0, 1], got 1.5");
    let err = rough(&ok[..5], &ok);
    assert_eq!(
        err.to_string(),
        "restitution e: 5 values for 6 contacts (give one per contact, or one shared)"
    );
    let walton = |e: &[f64], mu: &[f64], beta0: &[f64]| {
        let (e, mu, beta0) = (e.to_vec(), mu.to_vec(), beta0.to_vec());
        run(&move |out| {
            let laws = WaltonRows {
                e: &e,
                mu: &mu,
                beta0: &beta0,
            };
            exec.rough_free_rows::<_, f64, 3, 3>(&laws, &rows(a), rows_mut(out))
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
            &[f64::INFINITY][..],
            &[0.0][..],
            Field::FrictionMu,
            None,
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
fn no_contacts_take_a_valid_law_column_of_one_value() {
    let a = arrays::<2>(1, 0, [false, false]);
    let mut out = nan_rows::<2>(0);
    let laws = RestitutionRows {
        e: &[0.5],
        beta: &[0.5],
    };
    Exec::auto()
        .rough_free_rows::<_, f64, 2, 1>(&laws, &rows(&a), rows_mut(&mut out))
        .expect("no rows");
    // A shared law is checked even for no contacts.
    let laws = RestitutionRows {
        e: &[0.5],
        beta: &[1.5],
    };
    let err = Exec::auto()
        .rough_free_rows::<_, f64, 2, 1>(&laws, &rows(&a), rows_mut(&mut out))
        .unwrap_err();
    assert_eq!((err.error.field, err.row), (Field::RestitutionBeta, None));
}
