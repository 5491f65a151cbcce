//! The static bounds (`noslip_accuracy::static_box`) against the true error, in exact
//! rationals: for the plain and FMA kernels, every output component of every sampled case
//! that lies in its regime's box has `|computed - exact| <= bound`; and the boxes describe
//! their regimes (most of each regime's cases lie in them). `cargo test` runs n = 2 for the
//! regimes whose boxes are cheap to bound in a debug build (all but small `gamma^2`, whose
//! `gamma2` pieces make it a few typical boxes; the report checks it on every run); the
//! ignored test runs every regime at n = 2..6 (`NOSLIP_STATIC_CASES` per regime, n and
//! kernel, default 1000):
//!
//! ```sh
//! cargo test --release -p noslip-accuracy --test proven static_bound -- --ignored --nocapture
//! ```

use collision_core::rng::Rng;
use collision_core::{
    collide_unchecked, collide_unchecked_fma, validate, Exact, Generated, Kernel,
};
use noslip_accuracy::case::{flatten, Case};
use noslip_accuracy::measure::exact_result;
use noslip_accuracy::proven::ProvenBound;
use noslip_accuracy::static_box::StaticBox;
use noslip_accuracy::Regime;
use noslip_codegen::bound::Format;
use noslip_codegen::Arith;
use num_traits::Signed;

/// `cases` cases of `regime` per kernel (plain, FMA): every in-box error within the static
/// bound (panics otherwise), more than half of them in the box. Returns the bounds in eps
/// and the largest error over bound.
fn check<const N: usize, const S: usize>(regime: Regime, cases: usize) -> ([f64; 2], f64)
where
    Generated: Kernel<f64, N, S> + Kernel<collision_core::ExactRelaxed, N, S>,
{
    let boxes = StaticBox::of(regime, N, Format::F64);
    let (mut bounds, mut worst_ratio) = ([0.0; 2], 0.0f64);
    for (a, arith) in [Arith::Plain, Arith::Fma].into_iter().enumerate() {
        let proven = ProvenBound::of_kernel(N, arith, Format::F64);
        let bound_eps = proven.static_bound(&boxes);
        assert!(bound_eps.is_finite(), "{}: no finite bound", regime.name());
        bounds[a] = bound_eps;
        // `bound_eps * eps` is exact (a power-of-two scaling, far from underflow).
        let bound = Exact::from_float(bound_eps * f64::EPSILON).expect("finite");
        let mut rng = Rng::new(0x57A7 ^ regime as u64 ^ ((N as u64) << 8));
        let (mut inside, mut worst) = (0, 0.0f64);
        for _ in 0..cases {
            let case: Case<f64, N, S> = regime.sample(&mut rng);
            if validate(&case.nu, case.ball_refs(), case.state_refs()).is_err()
                || !proven.in_box(&case, &boxes)
            {
                continue;
            }
            inside += 1;
            let (nu, balls, states) = (&case.nu, case.ball_refs(), case.state_refs());
            let computed = flatten(&match arith {
                Arith::Plain => collide_unchecked(nu, balls, states),
                Arith::Fma => collide_unchecked_fma(nu, balls, states),
            });
            let exact = flatten(&exact_result(&case.to_exact()));
            for b in (0..2).filter(|&b| case.balls[b].inv_mass != 0.0) {
                for k in b * (S + N)..(b + 1) * (S + N) {
                    let err = (Exact::from_float(computed[k]).expect("finite") - &exact[k]).abs();
                    let eps = err.to_f64() / f64::EPSILON;
                    assert!(
                        err <= bound,
                        "n = {N}, {} {arith:?}: component {k} off by {eps} eps, static bound {bound_eps}",
                        regime.name(),
                    );
                    worst = worst.max(eps);
                }
            }
        }
        assert!(
            inside > cases / 2,
            "n = {N}, {}: only {inside} of {cases} cases in its box",
            regime.name()
        );
        assert!(worst > 0.0, "n = {N}, {}: no error measured", regime.name());
        worst_ratio = worst_ratio.max(worst / bound_eps);
    }
    (bounds, worst_ratio)
}

#[test]
fn every_error_in_a_box_is_within_its_static_bound() {
    for regime in [
        Regime::Typical,
        Regime::MassRatio,
        Regime::Immovable,
        Regime::PointMass,
        Regime::RadiusRatio,
        Regime::SpinDominated,
        Regime::Grazing,
    ] {
        check::<2, 1>(regime, 200);
    }
}

#[test]
#[ignore = "every regime at n = 2..6: run with --release"]
fn every_regime_at_every_n() {
    let cases = crate::env_count("NOSLIP_STATIC_CASES", 1000);
    for n in 2..=6 {
        for regime in Regime::ALL {
            let (bounds, ratio) =
                collision_core::with_dim!(n, |N, S| check::<N, S>(regime, cases), unreachable!());
            eprintln!(
                "n = {n} {:<15} static bound {:.4e} (FMA {:.4e}) eps, largest error / bound {ratio:.2e}",
                regime.name(),
                bounds[0],
                bounds[1]
            );
        }
    }
}
