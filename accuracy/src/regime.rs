//! The sampled regimes: typical inputs and the stiff and extreme ones.
//!
//! Every regime starts from the typical distribution and changes one thing. Typical: the
//! normal uniform on the sphere (a point uniform in the unit ball, normalised in `f64`);
//! per body `m = 2^U(-2,2)` (`inv_mass = 1/m`), `R = 2^U(-1,1)`, `gamma2 = (2/n) U(0,1]`,
//! every entry of `U_i` and `u_i` uniform in `[-1, 1]`; then `nu` is negated if the bodies
//! separate, so that every case approaches.

use crate::case::Case;
use collision_core::rng::Rng;
use collision_core::{Ball, BodyState};
use serde::Serialize;

/// A sampled input distribution: the typical one, or it with one thing changed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Regime {
    /// O(1) inputs, as in the module docs.
    Typical,
    /// `m_1/m_2 = 10^(+-k)`, `k` uniform in `[3, 15]`.
    MassRatio,
    /// Body 1 or body 2 immovable: `inv_mass = 0`.
    Immovable,
    /// `gamma^2 = (2/n) 10^-k` for both bodies, `k` uniform in `[0, 15]`.
    SmallGamma,
    /// `gamma^2 = 0` exactly for one body.
    PointMass,
    /// `R_1/R_2 = 10^k`, `k` uniform in `[-6, 6]`.
    RadiusRatio,
    /// Velocities and angular velocities times independent `10^k`, `k` uniform in `[-100, 100]`.
    Scale,
    /// Angular velocities times `10^k`, `k` uniform in `[3, 12]`: `|U| R >> |u|`.
    SpinDominated,
    /// Normal relative speed `-1e-12 |t|`, `t` the slip at the contact point.
    Grazing,
}

impl Regime {
    /// Every regime, in report order.
    pub const ALL: [Regime; 9] = [
        Regime::Typical,
        Regime::MassRatio,
        Regime::Immovable,
        Regime::SmallGamma,
        Regime::PointMass,
        Regime::RadiusRatio,
        Regime::Scale,
        Regime::SpinDominated,
        Regime::Grazing,
    ];

    /// The regime's name in the report.
    pub fn name(self) -> &'static str {
        match self {
            Regime::Typical => "typical",
            Regime::MassRatio => "mass ratio",
            Regime::Immovable => "immovable body",
            Regime::SmallGamma => "small gamma^2",
            Regime::PointMass => "point mass",
            Regime::RadiusRatio => "radius ratio",
            Regime::Scale => "extreme scales",
            Regime::SpinDominated => "spin-dominated",
            Regime::Grazing => "near-grazing",
        }
    }

    /// How the regime departs from the typical distribution.
    pub fn about(self) -> &'static str {
        match self {
            Regime::Typical => "O(1) inputs: m = 2^U(-2,2), R = 2^U(-1,1), gamma^2 = (2/n) U(0,1], velocity entries U(-1,1)",
            Regime::MassRatio => "m_1/m_2 = 10^(+-k), k = U(3,15): each body the heavy one half the time",
            Regime::Immovable => "body 1 or body 2 (half the time each) immovable: inv_mass = 0",
            Regime::SmallGamma => "gamma^2 = (2/n) 10^-U(0,15) for both bodies: from a shell down to 1e-15 (mass at the centre)",
            Regime::PointMass => "gamma^2 = 0 exactly for one body (each half the time)",
            Regime::RadiusRatio => "R_1/R_2 = 10^U(-6,6)",
            Regime::Scale => "all velocities times 10^U(-100,100), all angular velocities times an independent 10^U(-100,100)",
            Regime::SpinDominated => "angular velocities times 10^U(3,12): |U| R >> |u|",
            Regime::Grazing => "normal relative speed set to -1e-12 |t| (t the slip at the contact point)",
        }
    }

    /// The normwise error bound of the generated `f64` kernel, in units of `f64::EPSILON`.
    pub fn bound_eps(self) -> f64 {
        match self {
            Regime::Typical => 16.0,
            _ => 64.0,
        }
    }

    /// One sampled case.
    pub fn sample<const N: usize, const S: usize>(self, rng: &mut Rng) -> Case<f64, N, S> {
        let mut case = typical::<N, S>(rng);
        let pow10 = |rng: &mut Rng, lo: f64, hi: f64| 10f64.powf(rng.uniform(lo, hi));
        match self {
            Regime::Typical => {}
            Regime::MassRatio => {
                let ratio = pow10(rng, 3.0, 15.0);
                let heavy = usize::from(rng.coin());
                case.balls[heavy].inv_mass = case.balls[1 - heavy].inv_mass / ratio;
            }
            Regime::Immovable => {
                let b = usize::from(rng.coin());
                case.balls[b] = Ball::immovable(N, case.balls[b].radius);
            }
            Regime::SmallGamma => {
                for b in &mut case.balls {
                    b.gamma2 = 2.0 / N as f64 / pow10(rng, 0.0, 15.0);
                }
            }
            Regime::PointMass => {
                case.balls[usize::from(rng.coin())].gamma2 = 0.0;
            }
            Regime::RadiusRatio => {
                case.balls[0].radius = case.balls[1].radius * pow10(rng, -6.0, 6.0);
            }
            Regime::Scale => {
                let (v, w) = (pow10(rng, -100.0, 100.0), pow10(rng, -100.0, 100.0));
                scale(&mut case.states, v, w);
            }
            Regime::SpinDominated => {
                let w = pow10(rng, 3.0, 12.0);
                scale(&mut case.states, 1.0, w);
            }
            Regime::Grazing => {
                let (dn, slip) = normal_and_slip(&case);
                let target = -1e-12 * slip;
                for k in 0..N {
                    case.states[1].velocity[k] += (target - dn) * case.nu[k];
                }
                return case;
            }
        }
        approach(&mut case);
        case
    }
}

fn typical<const N: usize, const S: usize>(rng: &mut Rng) -> Case<f64, N, S> {
    let nu = loop {
        let v: [f64; N] = std::array::from_fn(|_| rng.uniform(-1.0, 1.0));
        let r2: f64 = v.iter().map(|x| x * x).sum();
        if r2 > 1e-6 && r2 <= 1.0 {
            let r = r2.sqrt();
            break v.map(|x| x / r);
        }
    };
    let mut ball = || Ball {
        inv_mass: 1.0 / 2f64.powf(rng.uniform(-2.0, 2.0)),
        radius: 2f64.powf(rng.uniform(-1.0, 1.0)),
        gamma2: 2.0 / N as f64 * (1.0 - rng.uniform(0.0, 1.0)),
    };
    let balls = [ball(), ball()];
    let mut state = || BodyState {
        spin: std::array::from_fn(|_| rng.uniform(-1.0, 1.0)),
        velocity: std::array::from_fn(|_| rng.uniform(-1.0, 1.0)),
    };
    let states = [state(), state()];
    Case { nu, balls, states }
}

fn scale<const N: usize, const S: usize>(
    states: &mut [BodyState<f64, N, S>; 2],
    velocity: f64,
    spin: f64,
) {
    for s in states {
        s.velocity.iter_mut().for_each(|x| *x *= velocity);
        s.spin.iter_mut().for_each(|x| *x *= spin);
    }
}

/// `(du . nu, |t|)` with `t = du - (du . nu) nu - (R_1 U_1 + R_2 U_2) nu`, in `f64`.
pub(crate) fn normal_and_slip<const N: usize, const S: usize>(
    case: &Case<f64, N, S>,
) -> (f64, f64) {
    let du: Vec<f64> = (0..N)
        .map(|k| case.states[1].velocity[k] - case.states[0].velocity[k])
        .collect();
    let dn: f64 = du.iter().zip(&case.nu).map(|(a, b)| a * b).sum();
    let spin = |b: usize| case.states[b].spin_matrix();
    let (u1, u2) = (spin(0), spin(1));
    let (r1, r2) = (case.balls[0].radius, case.balls[1].radius);
    let slip2: f64 = (0..N)
        .map(|i| {
            let c: f64 = (0..N)
                .map(|j| (r1 * u1[i][j] + r2 * u2[i][j]) * case.nu[j])
                .sum();
            let t = du[i] - dn * case.nu[i] - c;
            t * t
        })
        .sum();
    (dn, slip2.sqrt())
}

/// Negate the normal of a separating case.
fn approach<const N: usize, const S: usize>(case: &mut Case<f64, N, S>) {
    if normal_and_slip(case).0 > 0.0 {
        case.nu = case.nu.map(|x| -x);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use collision_core::validate;

    #[test]
    fn every_regime_samples_valid_approaching_cases() {
        let mut rng = Rng::new(7);
        for regime in Regime::ALL {
            for _ in 0..50 {
                let case = regime.sample::<3, 3>(&mut rng);
                validate(&case.nu, case.ball_refs(), case.state_refs())
                    .unwrap_or_else(|e| panic!("{}: {e}", regime.name()));
                assert!(normal_and_slip(&case).0 <= 0.0, "{}", regime.name());
            }
        }
    }

    #[test]
    fn grazing_cases_graze() {
        let mut rng = Rng::new(8);
        for _ in 0..50 {
            let case = Regime::Grazing.sample::<4, 6>(&mut rng);
            let (dn, slip) = normal_and_slip(&case);
            assert!(
                dn < 0.0 && -dn < 2e-12 * slip && -dn > 0.5e-12 * slip,
                "{dn} {slip}"
            );
        }
    }
}
