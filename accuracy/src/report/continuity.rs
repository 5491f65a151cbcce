//! The generated `f64` kernel across the two limits it reaches without branches (a body a
//! million billion times heavier against an immovable one, a `gamma2` of `1e-15` against
//! zero): the largest differences of the computed results, of the exact ones, and of their
//! rounding errors, in eps in the body's energy norm.

use crate::case::Case;
use crate::measure::exact_result;
use crate::regime::Regime;
use collision_core::rng::Rng;
use collision_core::{Exact, Generated, Kernel};
use serde::Serialize;

/// Agreement of the generated `f64` kernel across the limits it reaches without branches,
/// `m_1 = 1e15 m_2` against an immovable body 1 (body 2's result) and `gamma2_1 = 1e-15`
/// against `gamma2_1 = 0` (both bodies), over typical cases: the largest normwise
/// difference of the two `f64` results, of the two exact results (the model's own
/// difference at these parameters), and of the two (the rounding part, which must stay
/// within the bound: no jump at the limit). In eps, in the body's energy norm.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct Limit {
    /// The largest normwise difference of the two `f64` results.
    pub computed_eps: f64,
    /// The largest normwise difference of the two exact results (the model's own).
    pub exact_eps: f64,
    /// The largest normwise difference of the two rounding errors (`f64` minus exact).
    pub rounding_eps: f64,
}

/// The generated `f64` kernel across its two branch-free limits, over typical cases.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Continuity {
    /// Typical cases compared.
    pub cases: usize,
    /// `m_1 = 1e15 m_2` against an immovable body 1 (body 2's result).
    pub mass_1e15_vs_immovable: Limit,
    /// `gamma2_1 = 1e-15` against `gamma2_1 = 0` (both bodies).
    pub gamma2_1e15_vs_zero: Limit,
}

/// [`Continuity`] over `cases` typical cases.
pub fn continuity<const N: usize, const S: usize>(cases: usize, seed: u64) -> Continuity
where
    Generated: Kernel<f64, N, S> + Kernel<collision_core::ExactRelaxed, N, S>,
{
    use crate::measure::relative_norm;
    let mut rng = Rng::new(seed ^ 0xC0 ^ ((N as u64) << 32));
    let (mut mass, mut gamma) = (Limit::default(), Limit::default());
    let compare = |a: &Case<f64, N, S>, b: &Case<f64, N, S>, body: usize, limit: &mut Limit| {
        let run = |c: &Case<f64, N, S>| {
            let computed = crate::case::flatten(&collision_core::collide_unchecked(
                &c.nu,
                c.ball_refs(),
                c.state_refs(),
            ));
            let exact = crate::case::flatten(&exact_result(&c.to_exact()));
            (computed, exact)
        };
        let ((ca, ea), (cb, eb)) = (run(a), run(b));
        let to_f64 = |x: &Exact| num_traits::ToPrimitive::to_f64(x).unwrap_or(f64::INFINITY);
        let computed: Vec<f64> = ca.iter().zip(&cb).map(|(x, y)| x - y).collect();
        let exact: Vec<f64> = ea.iter().zip(&eb).map(|(x, y)| to_f64(&(x - y))).collect();
        let rounding: Vec<f64> = ca
            .iter()
            .zip(&cb)
            .zip(ea.iter().zip(&eb))
            .map(|((x, y), (ex, ey))| {
                let (dx, dy) = (Exact::from_float(*x), Exact::from_float(*y));
                let (dx, dy) = (dx.expect("finite"), dy.expect("finite"));
                to_f64(&((dx - ex) - (dy - ey)))
            })
            .collect();
        let reference: Vec<f64> = eb.iter().map(to_f64).collect();
        let lambda = b.balls[body].lambda();
        let rel = |d: &[f64]| relative_norm(lambda, S, N, body, d, &reference) / f64::EPSILON;
        limit.computed_eps = limit.computed_eps.max(rel(&computed));
        limit.exact_eps = limit.exact_eps.max(rel(&exact));
        limit.rounding_eps = limit.rounding_eps.max(rel(&rounding));
    };
    for _ in 0..cases {
        let case = Regime::Typical.sample::<N, S>(&mut rng);
        let mut heavy = case.clone();
        heavy.balls[0].inv_mass = heavy.balls[1].inv_mass * 1e-15;
        let mut wall = case.clone();
        wall.balls[0].inv_mass = 0.0;
        compare(&heavy, &wall, 1, &mut mass);
        let (mut small, mut point) = (case.clone(), case);
        small.balls[0].gamma2 = 1e-15;
        point.balls[0].gamma2 = 0.0;
        compare(&small, &point, 0, &mut gamma);
        compare(&small, &point, 1, &mut gamma);
    }
    Continuity {
        cases,
        mass_1e15_vs_immovable: mass,
        gamma2_1e15_vs_zero: gamma,
    }
}
