//! Property test: the generated f64 kernels against the general-n reference in f64.
//!
//! Tolerance: `|kernel - reference|_inf <= 1e-9 * S`, `S` the largest magnitude among the
//! state's components before and after. Both sides evaluate the same rational map: the
//! kernel with at most ~600 roundings along any output's dependency chain (n = 6), the
//! reference with a Gram solve of size n. On this sample (mass ratio <= 16, radius ratio
//! <= 16, gamma2 >= 1/(10 n)) the Gram matrix's condition number stays below ~1e4, so each
//! side is within about `1e3 * 1e4 * 2^-53 * S ~ 1e-9 S` of the exact map in the worst case;
//! typical differences are far smaller. The exact suite (`kernels_exact.rs`) is the strong
//! check; this one shows the float instantiation runs the same map.

#![allow(clippy::needless_range_loop)] // components of paired states are indexed together

use collision_core::{collide, reference, Ball, BodyState, Generated, Kernel, Wide};
use proptest::prelude::*;

fn unit(v: Vec<f64>) -> Option<Vec<f64>> {
    let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    (norm > 1e-3).then(|| v.iter().map(|x| x / norm).collect())
}

fn ball(n: usize) -> impl Strategy<Value = Ball<f64>> {
    (0.25f64..4.0, 0.25f64..4.0, 0.1f64..1.0).prop_map(move |(m, r, g)| Ball {
        inv_mass: 1.0 / m,
        radius: r,
        gamma2: g * 2.0 / n as f64,
    })
}

fn check<const N: usize, const S: usize>(
    nu: Vec<f64>,
    mut balls: [Ball<f64>; 2],
    xi: Vec<f64>,
    fixed: bool,
) -> Result<(), TestCaseError>
where
    Generated: Kernel<Wide<f64>, N, S>,
{
    let Some(nu) = unit(nu) else { return Ok(()) };
    let nu: [f64; N] = nu.try_into().unwrap();
    if fixed {
        balls[0].inv_mass = 0.0;
    }
    let mut states: [BodyState<f64, N, S>; 2] = reference::from_coords(&xi.into());
    let dn: f64 = (0..N)
        .map(|k| (states[1].velocity[k] - states[0].velocity[k]) * nu[k])
        .sum();
    if dn > 0.0 {
        for k in 0..N {
            states[1].velocity[k] -= 2.0 * dn * nu[k];
        }
    }
    let b = [&balls[0], &balls[1]];
    let s = [&states[0], &states[1]];
    let kernel = collide(&nu, b, s).unwrap();
    let reference = reference::collide(&nu, b, s).unwrap();
    let before = reference::coords(s);
    let (k, r) = (
        reference::coords([&kernel[0], &kernel[1]]),
        reference::coords([&reference[0], &reference[1]]),
    );
    let scale = before
        .iter()
        .chain(r.iter())
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let err = (k - r).amax();
    prop_assert!(
        err <= 1e-9 * scale,
        "n = {N}, fixed = {fixed}: error {err:e}, scale {scale:e}"
    );
    Ok(())
}

/// 200 cases per dimension; failures are saved beside this crate, in
/// `tests/proptest-regressions/`, and replayed first.
fn config() -> ProptestConfig {
    ProptestConfig {
        cases: 200,
        failure_persistence: Some(Box::new(
            proptest::test_runner::FileFailurePersistence::Direct(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/proptest-regressions/kernels_f64.txt"
            )),
        )),
        ..ProptestConfig::default()
    }
}

macro_rules! per_dim {
    ($(($name:ident $n:literal $s:literal))*) => {$(
        proptest! {
            #![proptest_config(config())]
            #[test]
            fn $name(
                nu in proptest::collection::vec(-1.0f64..1.0, $n),
                b1 in ball($n),
                b2 in ball($n),
                xi in proptest::collection::vec(-3.0f64..3.0, $n * ($n - 1) + 2 * $n),
                fixed in any::<bool>(),
            ) {
                check::<$n, $s>(nu, [b1, b2], xi, fixed)?;
            }
        }
    )*};
}

collision_core::for_each_dim!(per_dim);
