//! The limits as sequences: the free map at `m_1 = 10^k` approaches the immovable-body
//! kernel, and at `gamma2_1 = 10^-k` the point-mass limit (`gamma2_1 = 0`), with exact
//! errors that shrink like `1/m_1` and like `gamma2_1`: the map is a rational function of
//! `w_1 = 1/m_1` (of `gamma2_1`), regular at 0, so the error is `c 10^-k + O(10^-2k)` and
//! consecutive errors have ratio -> 10.

use crate::under_test::generated;
use collision_core::rng::Rng;
use collision_core::{Ball, BodyState, Exact, Generated, Kernel, Scalar};
use noslip_codegen::model::Variant;
use num_traits::{Signed, Zero};

fn max_diff<const N: usize, const S: usize>(
    a: &[BodyState<Exact, N, S>; 2],
    b: &[BodyState<Exact, N, S>; 2],
) -> Exact {
    a.iter()
        .zip(b)
        .flat_map(|(x, y)| {
            x.spin
                .iter()
                .zip(&y.spin)
                .chain(x.velocity.iter().zip(&y.velocity))
        })
        .map(|(p, q)| (p - q).abs())
        .fold(Exact::zero(), |m, d| if d > m { d } else { m })
}

/// Which limit.
#[derive(Clone, Copy, Debug)]
pub enum Limit {
    /// `m_1 -> inf`: the free map at `w_1 = 10^-k` against the `fixed` kernel.
    Mass,
    /// `lambda_1 -> 0`: the free map at `gamma2_1 = 10^-k` against the free map at `gamma2_1 = 0`.
    PointMass,
}

/// Errors for `k = 1..=8` and the check that they shrink by a factor in `[9, 11]` per step
/// from `k = 3` on. Returns the errors as f64 for the report.
pub fn check<const N: usize, const S: usize>(limit: Limit, seed: u64) -> Result<Vec<f64>, String>
where
    Generated: Kernel<Exact, N, S> + Kernel<collision_core::ExactRelaxed, N, S>,
{
    let mut rng = Rng::new(seed);
    let mut small =
        |lo: u64, hi: u64| Exact::from_ratio((lo + rng.next_u64() % (hi - lo + 1)) as i64, 4);
    let nu = crate::sample::normal::<N>(&mut Rng::new(seed + 1));
    let mut ball = || Ball {
        inv_mass: small(1, 8),
        radius: small(1, 8),
        gamma2: Exact::from_ratio(1, N as i64),
    };
    let (b1, b2) = (ball(), ball());
    let states = [0, 1].map(|_| BodyState::<Exact, N, S> {
        spin: std::array::from_fn(|_| small(0, 12) - Exact::from_ratio(3, 2)),
        velocity: std::array::from_fn(|_| small(0, 12) - Exact::from_ratio(3, 2)),
    });
    let s = [&states[0], &states[1]];
    let free = generated::<N, S>(Variant::Free);
    let target = match limit {
        Limit::Mass => generated::<N, S>(Variant::Fixed)(
            &nu,
            [
                &Ball {
                    inv_mass: Exact::zero(),
                    ..b1.clone()
                },
                &b2,
            ],
            s,
        ),
        Limit::PointMass => free(
            &nu,
            [
                &Ball {
                    gamma2: Exact::zero(),
                    ..b1.clone()
                },
                &b2,
            ],
            s,
        ),
    };
    let mut errors = Vec::new();
    for k in 1..=8u32 {
        let eps = Exact::from_ratio(1, 10i64.pow(k));
        let b = match limit {
            Limit::Mass => Ball {
                inv_mass: eps,
                ..b1.clone()
            },
            Limit::PointMass => Ball {
                gamma2: eps,
                ..b1.clone()
            },
        };
        errors.push(max_diff(&free(&nu, [&b, &b2], s), &target));
    }
    let as_f64: Vec<f64> = errors.iter().map(|e| e.to_f64()).collect();
    for k in 2..errors.len() - 1 {
        if errors[k + 1].is_zero() {
            return Err(format!(
                "error vanished at k = {}: the sequence does not probe the limit",
                k + 2
            ));
        }
        let ratio = (&errors[k] / &errors[k + 1]).to_f64();
        if !(9.0..=11.0).contains(&ratio) {
            return Err(format!(
                "error ratio {ratio} between k = {} and k = {}, expected ~10 (errors {as_f64:?})",
                k + 1,
                k + 2
            ));
        }
    }
    Ok(as_f64)
}
