//! The rough-ball family in the report (issue 27): the generated `rough` kernels (constant
//! `(e, beta)`, `docs/derivation.md` §15) and `walton` kernels (`(e, mu, beta0)`, §15.1)
//! against their exact results, in regimes of the law: typical, at and near the ends of
//! `e` and `beta`, against an immovable body (the `fixed` kernels), near grazing, and
//! near the Walton law's switch between sticking and sliding.
//!
//! A case is a no-slip regime's case ([`Regime::sample`]) with a law drawn beside it. Its
//! truth is the same kernel on the same inputs (the law included) in exact rationals; the
//! Walton kernel's one square root is the exact root of a rational square or else truncated
//! to 256 bits (`collision_core::exact::root`), far below any float's resolution. The
//! figures are the no-slip report's normwise error per movable body ([`crate::measure`]) and
//! the time per collision, beside the no-slip kernel's time on the same cases.

mod render;
mod run;

pub use render::markdown;
pub use run::{
    family_result, FamilyResult, FamilyStability, FamilyVariant, VariantResult, BOUND_EPS,
};

use crate::case::Case;
use crate::regime::{normal_and_slip, Regime};
use collision_core::rng::Rng;
use collision_core::{Restitution, Walton};
use serde::Serialize;

/// A contact law of the family, as a case carries it.
#[derive(Clone, Debug, PartialEq)]
pub enum Law<T> {
    /// Constant restitutions: `dn+ = -e dn`, `t+ = -beta t`.
    Rough(Restitution<T>),
    /// Walton's law: `beta = min(beta0, beta_C)`.
    Walton(Walton<T>),
}

impl Law<f64> {
    /// The same law in `f32` (each parameter rounded once; the rounded law is the one the
    /// `f32` kernel runs and its truth uses).
    pub fn to_f32(&self) -> Law<f32> {
        match self {
            Law::Rough(l) => Law::Rough(Restitution {
                e: l.e as f32,
                beta: l.beta as f32,
            }),
            Law::Walton(l) => Law::Walton(Walton {
                e: l.e as f32,
                mu: l.mu as f32,
                beta0: l.beta0 as f32,
            }),
        }
    }
}

/// A sampled regime of the family: a no-slip regime's inputs and a distribution of the law.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FamilyRegime {
    /// Typical inputs, `e = U(0,1)`, `beta = U(-1,1)`.
    Rough,
    /// Typical inputs, `e` in `{0, 1}` and `beta` in `{-1, 0, 1}`: the ends, the smooth and
    /// no-slip laws among them.
    RoughEnds,
    /// Typical inputs, `e = 10^-k` or `1 - 10^-k`, `beta = +-(1 - 10^-k')`, `k, k' = U(1,15)`.
    RoughNearEnds,
    /// Body 1 immovable (the `fixed` kernel), the typical law.
    RoughImmovable,
    /// Normal relative speed `-1e-12 |t|`, the typical law.
    RoughGrazing,
    /// Typical inputs, `e = U(0,1)`, `mu = 10^U(-2,1)`, `beta0 = U(-1,1)`.
    Walton,
    /// Typical inputs and `e`, `beta0`; `mu` puts `beta_C` within a relative `10^-U(3,15)` of
    /// `beta0` (as `1 + beta_C = (1 + beta0)(1 +- 10^-k)`), on either side.
    WaltonSwitch,
}

impl FamilyRegime {
    /// Every regime, in report order.
    pub const ALL: [FamilyRegime; 7] = [
        FamilyRegime::Rough,
        FamilyRegime::RoughEnds,
        FamilyRegime::RoughNearEnds,
        FamilyRegime::RoughImmovable,
        FamilyRegime::RoughGrazing,
        FamilyRegime::Walton,
        FamilyRegime::WaltonSwitch,
    ];

    /// The regime's name in the report.
    pub fn name(self) -> &'static str {
        match self {
            FamilyRegime::Rough => "rough, typical",
            FamilyRegime::RoughEnds => "rough, at the ends",
            FamilyRegime::RoughNearEnds => "rough, near the ends",
            FamilyRegime::RoughImmovable => "rough, immovable body",
            FamilyRegime::RoughGrazing => "rough, near-grazing",
            FamilyRegime::Walton => "Walton, typical",
            FamilyRegime::WaltonSwitch => "Walton, near the switch",
        }
    }

    /// The law and inputs it samples.
    pub fn about(self) -> &'static str {
        match self {
            FamilyRegime::Rough => "typical inputs; e = U(0,1), beta = U(-1,1)",
            FamilyRegime::RoughEnds => "typical inputs; e in {0, 1}, beta in {-1, 0, 1} (smooth and no-slip among them)",
            FamilyRegime::RoughNearEnds => "typical inputs; e = 10^-k or 1 - 10^-k, beta = +-(1 - 10^-k'), k, k' = U(1,15)",
            FamilyRegime::RoughImmovable => "body 1 immovable (the fixed kernel); e = U(0,1), beta = U(-1,1)",
            FamilyRegime::RoughGrazing => "normal relative speed -1e-12 |t|; e = U(0,1), beta = U(-1,1)",
            FamilyRegime::Walton => "typical inputs; e = U(0,1), mu = 10^U(-2,1), beta0 = U(-1,1)",
            FamilyRegime::WaltonSwitch => "typical inputs; e = U(0,1), beta0 = U(-1,1), mu such that 1 + beta_C = (1 + beta0)(1 +- 10^-U(3,15))",
        }
    }

    /// The generated kernels it measures: `"rough"` or `"walton"`.
    pub fn kernel(self) -> &'static str {
        match self {
            FamilyRegime::Walton | FamilyRegime::WaltonSwitch => "walton",
            _ => "rough",
        }
    }

    /// One sampled case and its law.
    pub fn sample<const N: usize, const S: usize>(
        self,
        rng: &mut Rng,
    ) -> (Case<f64, N, S>, Law<f64>) {
        let base = match self {
            FamilyRegime::RoughImmovable => {
                let mut case = Regime::Typical.sample::<N, S>(rng);
                case.balls[0] = collision_core::Ball::immovable(N, case.balls[0].radius);
                case
            }
            FamilyRegime::RoughGrazing => Regime::Grazing.sample::<N, S>(rng),
            _ => Regime::Typical.sample::<N, S>(rng),
        };
        let pow10 = |rng: &mut Rng, lo: f64, hi: f64| 10f64.powf(rng.uniform(lo, hi));
        let sign = |rng: &mut Rng| if rng.coin() { 1.0 } else { -1.0 };
        let rough = |e: f64, beta: f64| {
            Law::Rough(Restitution::new(e, beta).expect("sampled laws are in range"))
        };
        let law = match self {
            FamilyRegime::Rough | FamilyRegime::RoughImmovable | FamilyRegime::RoughGrazing => {
                rough(rng.uniform(0.0, 1.0), rng.uniform(-1.0, 1.0))
            }
            FamilyRegime::RoughEnds => {
                let e = rng.integer(0..=1) as f64;
                rough(e, rng.integer(0..=2) as f64 - 1.0)
            }
            FamilyRegime::RoughNearEnds => {
                let small = pow10(rng, -15.0, -1.0);
                let e = if rng.coin() { small } else { 1.0 - small };
                rough(e, sign(rng) * (1.0 - pow10(rng, -15.0, -1.0)))
            }
            FamilyRegime::Walton => {
                let (e, mu) = (rng.uniform(0.0, 1.0), pow10(rng, -2.0, 1.0));
                walton(e, mu, rng.uniform(-1.0, 1.0))
            }
            FamilyRegime::WaltonSwitch => {
                let (e, beta0) = (rng.uniform(0.0, 1.0), rng.uniform(-1.0, 1.0));
                let side = 1.0 + sign(rng) * pow10(rng, -15.0, -3.0);
                walton(e, (1.0 + beta0) * side / coulomb_slope(&base, e), beta0)
            }
        };
        (base, law)
    }
}

fn walton(e: f64, mu: f64, beta0: f64) -> Law<f64> {
    Law::Walton(Walton::new(e, mu, beta0).expect("sampled laws are in range"))
}

/// `(1 + e) (b / a) |dn| / |t|`, in `f64`: the slope of `1 + beta_C = mu (1 + e) (b/a) |dn| / |t|`
/// in `mu` (`docs/derivation.md` §15.1), `a = w_1 + w_2`, `b = a + w_1/g_1 + w_2/g_2`
/// the inverse effective masses (`w = inv_mass`, `g = gamma2 > 0`).
pub fn coulomb_slope<const N: usize, const S: usize>(case: &Case<f64, N, S>, e: f64) -> f64 {
    let [b1, b2] = &case.balls;
    let a = b1.inv_mass + b2.inv_mass;
    let b = a + b1.inv_mass / b1.gamma2 + b2.inv_mass / b2.gamma2;
    let (dn, slip) = normal_and_slip(case);
    (1.0 + e) * (b / a) * dn.abs() / slip
}

/// Whether a Walton case slides (`beta_C < beta0`, estimated in `f64`; a case within
/// rounding of the switch may be counted on either side); `false` for a rough law.
pub fn slides<const N: usize, const S: usize>(case: &Case<f64, N, S>, law: &Law<f64>) -> bool {
    match law {
        Law::Walton(l) => l.mu * coulomb_slope(case, l.e) - 1.0 < l.beta0,
        Law::Rough(_) => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use collision_core::{kernels::d3, validate};

    #[test]
    fn every_regime_samples_valid_cases_and_laws() {
        let mut rng = Rng::new(27);
        for regime in FamilyRegime::ALL {
            for _ in 0..50 {
                let (case, law) = regime.sample::<3, 3>(&mut rng);
                validate(&case.nu, case.ball_refs(), case.state_refs())
                    .unwrap_or_else(|e| panic!("{}: {e}", regime.name()));
                match (&law, regime.kernel()) {
                    (Law::Rough(l), "rough") => Restitution::new(l.e, l.beta).map(|_| ()),
                    (Law::Walton(l), "walton") => Walton::new(l.e, l.mu, l.beta0).map(|_| ()),
                    _ => panic!("{}: the law is not the regime's kernel's", regime.name()),
                }
                .unwrap();
            }
        }
    }

    /// The switch regime's `mu` lands on both sides of the switch, and on the side it
    /// chose: the kernel's tangential restitution, read off its output slip, is `beta0`
    /// when it sticks and below it when it slides (the exact kernel decides).
    #[test]
    fn the_switch_regime_straddles_the_switch() {
        let mut rng = Rng::new(28);
        let (mut stick, mut slide, mut compared) = (0, 0, 0);
        for _ in 0..200 {
            let (case, law) = FamilyRegime::WaltonSwitch.sample::<3, 3>(&mut rng);
            let Law::Walton(l) = &law else { unreachable!() };
            let beta_c = l.mu * coulomb_slope(&case, l.e) - 1.0;
            let gap = (beta_c - l.beta0) / (1.0 + l.beta0);
            assert!(gap.abs() <= 1.01e-3, "{gap}");
            if gap.abs() < 1e-12 {
                continue; // within the f64 estimate's rounding of the switch
            }
            if slides(&case, &law) {
                slide += 1;
            } else {
                stick += 1;
            }
            let [s1, s2] = case.state_refs();
            let [b1, b2] = case.ball_refs();
            let out = d3::walton::free(&case.nu, b1, b2, l, s1, s2);
            let slip = |s: [&collision_core::State3<f64>; 2]| {
                let mut c = case.clone();
                c.states = [s[0].clone(), s[1].clone()];
                normal_and_slip(&c).1
            };
            let beta = slip([&out[0], &out[1]]) / slip([s1, s2]);
            // `t+ = -beta t`: |t+| / |t| = |beta|; compare where beta has one sign.
            if l.beta0 > 0.01 && beta_c > 0.01 {
                let expected = l.beta0.min(beta_c);
                assert!((beta - expected).abs() < 1e-9, "{beta} {expected}");
                compared += 1;
            }
        }
        assert!(stick > 50 && slide > 50, "{stick} stick, {slide} slide");
        assert!(compared > 40, "{compared} cases compared");
    }
}
