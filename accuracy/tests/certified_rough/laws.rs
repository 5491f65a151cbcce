//! The laws of `certified_rough.rs`: how each family's law is drawn beside a case, rounded
//! to `f32`, and run exactly (the truth), and the adversarial mix of inputs.

use collision_core::rng::Rng;
use collision_core::{
    Ball, BodyState, Exact, Generated, Relaxing, Restitution, RoughKernel, Walton, WaltonKernel,
};
use noslip_accuracy::case::{flatten, Case};
use noslip_accuracy::family::{coulomb_slope, Law};
use noslip_accuracy::Regime;

/// The exact map on the same floats (the law included): the rough kernels through the
/// fast exact path ([`Relaxing`]), the Walton kernels in [`Exact`] (their one square root
/// exact where `rho` is a rational square, else truncated to 256 bits,
/// `collision_core::exact::root`: a relative `2^-256`, far below any bound here).
pub trait Family: Clone + std::fmt::Debug {
    /// The law in `f32` (each parameter rounded once), if `f32` holds it.
    type F32: Clone + std::fmt::Debug;
    fn to_f32(&self) -> Option<Self::F32>;
    fn widen(l: &Self::F32) -> Self;
    fn exact<const N: usize, const S: usize>(&self, c: &Case<f64, N, S>) -> Vec<Exact>
    where
        Relaxing: RoughKernel<Exact, N, S>,
        Generated: WaltonKernel<Exact, N, S>;
}

/// `collide_rough_unchecked`'s dispatch on exact inputs, with `free` and `fixed`.
fn exact_dispatch<L, const N: usize, const S: usize>(
    c: &Case<Exact, N, S>,
    law: &L,
    free: impl Fn(
        &[Exact; N],
        &Ball<Exact>,
        &Ball<Exact>,
        &L,
        &BodyState<Exact, N, S>,
        &BodyState<Exact, N, S>,
    ) -> [BodyState<Exact, N, S>; 2],
    fixed: impl Fn(
        &[Exact; N],
        &Exact,
        &Ball<Exact>,
        &L,
        &BodyState<Exact, N, S>,
        &BodyState<Exact, N, S>,
    ) -> BodyState<Exact, N, S>,
) -> Vec<Exact> {
    let ([b1, b2], [s1, s2]) = (&c.balls, &c.states);
    let out = if b1.is_immovable() {
        [s1.clone(), fixed(&c.nu, &b1.radius, b2, law, s1, s2)]
    } else if b2.is_immovable() {
        let minus = c.nu.clone().map(|v| -v);
        [fixed(&minus, &b2.radius, b1, law, s2, s1), s2.clone()]
    } else {
        free(&c.nu, b1, b2, law, s1, s2)
    };
    flatten(&out)
}

pub fn q(v: f64) -> Exact {
    Exact::from_float(v).expect("finite")
}

impl Family for Restitution<f64> {
    type F32 = Restitution<f32>;
    fn to_f32(&self) -> Option<Restitution<f32>> {
        Restitution::new(self.e as f32, self.beta as f32).ok()
    }
    fn widen(l: &Restitution<f32>) -> Self {
        Restitution {
            e: f64::from(l.e),
            beta: f64::from(l.beta),
        }
    }
    fn exact<const N: usize, const S: usize>(&self, c: &Case<f64, N, S>) -> Vec<Exact>
    where
        Relaxing: RoughKernel<Exact, N, S>,
        Generated: WaltonKernel<Exact, N, S>,
    {
        let law = Restitution {
            e: q(self.e),
            beta: q(self.beta),
        };
        exact_dispatch(
            &c.to_exact(),
            &law,
            Relaxing::rough_free,
            Relaxing::rough_fixed,
        )
    }
}

impl Family for Walton<f64> {
    type F32 = Walton<f32>;
    fn to_f32(&self) -> Option<Walton<f32>> {
        Walton::new(self.e as f32, self.mu as f32, self.beta0 as f32).ok()
    }
    fn widen(l: &Walton<f32>) -> Self {
        Walton {
            e: f64::from(l.e),
            mu: f64::from(l.mu),
            beta0: f64::from(l.beta0),
        }
    }
    fn exact<const N: usize, const S: usize>(&self, c: &Case<f64, N, S>) -> Vec<Exact>
    where
        Relaxing: RoughKernel<Exact, N, S>,
        Generated: WaltonKernel<Exact, N, S>,
    {
        let law = Walton {
            e: q(self.e),
            mu: q(self.mu),
            beta0: q(self.beta0),
        };
        exact_dispatch(
            &c.to_exact(),
            &law,
            Generated::walton_free,
            Generated::walton_fixed,
        )
    }
}

/// A rough law beside a no-slip regime's case: typical (`e = U(0,1)`, `beta = U(-1,1)`)
/// half the time, else at or near the ends.
fn rough_law(rng: &mut Rng) -> Restitution<f64> {
    let near = |rng: &mut Rng| 1.0 - 10f64.powf(rng.uniform(-15.0, -1.0));
    let sign = |rng: &mut Rng| if rng.coin() { 1.0 } else { -1.0 };
    let (e, beta) = match rng.integer(0..=3) {
        0 | 1 => (rng.uniform(0.0, 1.0), rng.uniform(-1.0, 1.0)),
        2 => (rng.integer(0..=1) as f64, rng.integer(0..=2) as f64 - 1.0),
        _ => (near(rng), sign(rng) * near(rng)),
    };
    Restitution::new(e, beta).expect("in range")
}

/// A Walton law beside a case: `e = U(0,1)`, `beta0 = U(-1,1)`, and `mu = 10^U(-2,1)` half
/// the time, else `mu` putting the case within a relative `10^-U(3,15)` of the switch (as
/// the family's `WaltonSwitch`), or `mu = 0`.
fn walton_law<const N: usize, const S: usize>(
    rng: &mut Rng,
    case: &Case<f64, N, S>,
) -> Walton<f64> {
    let (e, beta0) = (rng.uniform(0.0, 1.0), rng.uniform(-1.0, 1.0));
    let mu = match rng.integer(0..=3) {
        0 | 1 => 10f64.powf(rng.uniform(-2.0, 1.0)),
        2 => {
            let sign = if rng.coin() { 1.0 } else { -1.0 };
            let side = 1.0 + sign * 10f64.powf(rng.uniform(-15.0, -3.0));
            let mu = (1.0 + beta0) * side / coulomb_slope(case, e);
            if mu.is_finite() && mu >= 0.0 {
                mu
            } else {
                1.0
            }
        }
        _ => 0.0,
    };
    Walton::new(e, mu, beta0).expect("in range")
}

/// A typical case with several extremes at once (as `proven.rs`'s adversarial mix).
pub fn adversarial<const N: usize, const S: usize>(rng: &mut Rng) -> Case<f64, N, S> {
    let mut case = Regime::Typical.sample::<N, S>(rng);
    let pow10 = |rng: &mut Rng, lo: f64, hi: f64| 10f64.powf(rng.uniform(lo, hi));
    if rng.coin() {
        case.balls[0].inv_mass = case.balls[1].inv_mass * pow10(rng, -15.0, 15.0);
    }
    if rng.coin() {
        case.balls[0].radius = case.balls[1].radius * pow10(rng, -6.0, 6.0);
    }
    if rng.coin() {
        for b in &mut case.balls {
            b.gamma2 /= pow10(rng, 0.0, 15.0);
        }
    }
    if rng.coin() && rng.coin() {
        case.balls[usize::from(rng.coin())].gamma2 = 0.0;
    }
    if rng.coin() && rng.coin() {
        case.balls[usize::from(rng.coin())].inv_mass = 0.0;
    }
    if rng.coin() {
        let (v, w) = (pow10(rng, -30.0, 30.0), pow10(rng, -30.0, 30.0));
        for s in &mut case.states {
            s.velocity.iter_mut().for_each(|x| *x *= v);
            s.spin.iter_mut().for_each(|x| *x *= w);
        }
    }
    case
}

/// One sampled case of source `source` of the family `kernel`, and its law.
pub trait Sample: Family {
    const KERNEL: &'static str;
    fn beside<const N: usize, const S: usize>(rng: &mut Rng, case: &Case<f64, N, S>) -> Self;
    fn of(law: Law<f64>) -> Self;
}

impl Sample for Restitution<f64> {
    const KERNEL: &'static str = "rough";
    fn beside<const N: usize, const S: usize>(rng: &mut Rng, _: &Case<f64, N, S>) -> Self {
        rough_law(rng)
    }
    fn of(law: Law<f64>) -> Self {
        match law {
            Law::Rough(l) => l,
            Law::Walton(_) => unreachable!("a rough regime"),
        }
    }
}

impl Sample for Walton<f64> {
    const KERNEL: &'static str = "walton";
    fn beside<const N: usize, const S: usize>(rng: &mut Rng, case: &Case<f64, N, S>) -> Self {
        walton_law(rng, case)
    }
    fn of(law: Law<f64>) -> Self {
        match law {
            Law::Walton(l) => l,
            Law::Rough(_) => unreachable!("a Walton regime"),
        }
    }
}
