//! The exact kernels side by side on every exact representation measured for issue 15:
//! median µs per collision, `free` and `fixed`, n = 2, 3, 6, on the accuracy report's inputs
//! (`Regime::Typical` for `free`, `Regime::Immovable` for `fixed`, the same seed for all).
//!
//! - `num-rational`: `Rational<num_rational::BigRational>`, the former `Exact`;
//! - `dashu RBig`: [`Exact`], dashu's rationals reduced after every operation;
//! - `dashu Relaxed`: the kernel run in [`ExactRelaxed`] (only common powers of 2 removed
//!   between operations), inputs converted and outputs reduced inside the timed region: the
//!   cost of the whole exact path, not only of the kernel.
//!
//! Before timing, the outputs of every representation are checked equal, as reduced
//! fractions, to num-rational's: a speed-up of a wrong kernel is worthless.
//!
//! Run: `cargo run --release -p noslip-accuracy --example exact_backends [-- CASES SAMPLES]`
//! (defaults 32 cases, 7 samples; docs/benchmarks.md quotes its output).

use collision_core::{
    collide_unchecked, rng::Rng, BodyState, Exact, ExactNumRational, ExactRelaxed, Generated,
    Kernel, Scalar,
};
use noslip_accuracy::{case::Case, timing, Regime};

/// The seed of the sampled cases (the report's default is 1; any fixed seed will do).
const SEED: u64 = 1;

/// Outputs as reduced `(numerator, denominator)` decimal strings, for comparing types.
fn digits<T: Scalar, const N: usize, const S: usize>(
    out: &[BodyState<T, N, S>; 2],
    parts: impl Fn(&T) -> (String, String),
) -> Vec<(String, String)> {
    out.iter()
        .flat_map(|b| b.spin.iter().chain(&b.velocity))
        .map(parts)
        .collect()
}

fn median_us(cases: usize, samples: usize, pass: impl FnMut()) -> f64 {
    timing::time(cases, samples, pass).median_ns / 1e3
}

fn row<const N: usize, const S: usize>(variant: &str, regime: Regime, cases: usize, samples: usize)
where
    Generated: Kernel<Exact, N, S> + Kernel<ExactNumRational, N, S> + Kernel<ExactRelaxed, N, S>,
{
    let mut rng = Rng::new(SEED);
    let exact: Vec<Case<Exact, N, S>> = (0..cases)
        .map(|_| regime.sample::<N, S>(&mut rng).to_exact())
        .collect();
    let old: Vec<Case<ExactNumRational, N, S>> =
        exact.iter().map(|c| c.map(|x| x.convert())).collect();
    let run = |c: &Case<Exact, N, S>| collide_unchecked(&c.nu, c.ball_refs(), c.state_refs());
    let run_old =
        |c: &Case<ExactNumRational, N, S>| collide_unchecked(&c.nu, c.ball_refs(), c.state_refs());
    let run_relaxed = |c: &Case<Exact, N, S>| {
        let r = c.map(Exact::relax);
        collide_unchecked(&r.nu, r.ball_refs(), r.state_refs()).map(|b| BodyState {
            spin: b.spin.map(|x| x.canonical()),
            velocity: b.velocity.map(|x| x.canonical()),
        })
    };
    for (c, o) in exact.iter().zip(&old) {
        let want = digits(&run_old(o), ExactNumRational::parts);
        assert_eq!(digits(&run(c), Exact::parts), want, "dashu RBig differs");
        assert_eq!(
            digits(&run_relaxed(c), Exact::parts),
            want,
            "relaxed differs"
        );
    }
    let t_old = median_us(cases, samples, || timing::pass_over(&old, run_old));
    let t_new = median_us(cases, samples, || timing::pass_over(&exact, run));
    let t_relaxed = median_us(cases, samples, || timing::pass_over(&exact, run_relaxed));
    println!(
        "| {N} | {variant} | {t_old:.1} | {t_new:.1} | {t_relaxed:.1} | {:.1} | {:.1} |",
        t_old / t_new,
        t_old / t_relaxed
    );
}

fn main() {
    let mut args = std::env::args().skip(1).map(|a| a.parse::<usize>());
    let cases = args.next().map_or(Ok(32), |a| a).expect("CASES: a count");
    let samples = args.next().map_or(Ok(7), |a| a).expect("SAMPLES: a count");
    println!("{cases} cases, {samples} samples; median µs per collision");
    println!("| n | kernel | num-rational | dashu RBig | dashu Relaxed | RBig speed-up | Relaxed speed-up |");
    println!("|---|---|---:|---:|---:|---:|---:|");
    row::<2, 1>("free", Regime::Typical, cases, samples);
    row::<2, 1>("fixed", Regime::Immovable, cases, samples);
    row::<3, 3>("free", Regime::Typical, cases, samples);
    row::<3, 3>("fixed", Regime::Immovable, cases, samples);
    row::<6, 15>("free", Regime::Typical, cases, samples);
    row::<6, 15>("fixed", Regime::Immovable, cases, samples);
}
