//! The static bounds (`noslip_accuracy::static_box`) against the true error, in exact
//! rationals: at n = 2, for the regimes whose boxes are cheap to bound in a debug build
//! (all but small `gamma^2`, whose `gamma2` pieces make it 40 times the typical box; the
//! report checks it on every run) and for the plain and FMA kernels, every output component
//! of every sampled case that lies in the regime's box has `|computed - exact| <= bound`.
//! The boxes must also describe their regimes: most of each regime's cases lie in them.

use collision_core::rng::Rng;
use collision_core::{collide_unchecked, collide_unchecked_fma, validate, Exact};
use noslip_accuracy::case::{flatten, Case};
use noslip_accuracy::measure::exact_result;
use noslip_accuracy::proven::ProvenBound;
use noslip_accuracy::static_box::StaticBox;
use noslip_accuracy::Regime;
use noslip_codegen::bound::Format;
use noslip_codegen::Arith;
use num_traits::Signed;

const CASES: usize = 200;

#[test]
fn every_error_in_a_box_is_within_its_static_bound() {
    let regimes = [
        Regime::Typical,
        Regime::MassRatio,
        Regime::Immovable,
        Regime::PointMass,
        Regime::RadiusRatio,
        Regime::SpinDominated,
        Regime::Grazing,
    ];
    for regime in regimes {
        let boxes = StaticBox::of(regime, 2, Format::F64);
        for arith in [Arith::Plain, Arith::Fma] {
            let proven = ProvenBound::of_kernel(2, arith, Format::F64);
            let bound_eps = proven.static_bound(&boxes);
            assert!(bound_eps.is_finite(), "{}: no finite bound", regime.name());
            // `bound_eps * eps` is exact (a power-of-two scaling, far from underflow).
            let bound = Exact::from_float(bound_eps * f64::EPSILON).expect("finite");
            let mut rng = Rng::new(0x57A7 ^ regime as u64);
            let (mut inside, mut worst) = (0, 0.0f64);
            for _ in 0..CASES {
                let case: Case<f64, 2, 1> = regime.sample(&mut rng);
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
                    for k in b * 3..(b + 1) * 3 {
                        let err =
                            (Exact::from_float(computed[k]).expect("finite") - &exact[k]).abs();
                        assert!(
                            err <= bound,
                            "{} {arith:?}: component {k} off by {} eps, static bound {bound_eps}",
                            regime.name(),
                            num_traits::ToPrimitive::to_f64(&err).unwrap() / f64::EPSILON
                        );
                        worst = worst.max(num_traits::ToPrimitive::to_f64(&err).unwrap());
                    }
                }
            }
            assert!(
                inside > CASES / 2,
                "{}: only {inside} of {CASES} cases in its box",
                regime.name()
            );
            assert!(worst > 0.0, "{}: no error measured", regime.name());
        }
    }
}
