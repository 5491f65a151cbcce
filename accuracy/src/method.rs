//! The methods the report compares (its "variants": each kernel in each arithmetic, the
//! reference, the dense matrix, the literal closed form, the batch): what each computes and
//! how it is timed.

use crate::batched::Batched;
use crate::case::{flatten, Case};
use crate::dense;
use crate::timing::{pass_over, time, Timing};
use collision_core::batch::{BatchKernel, Exec};
use collision_core::{
    collide_unchecked, collide_unchecked_fma, literal, reference, BodyState, Exact, Generated,
    Kernel, Scalar,
};
use serde::Serialize;

/// A way of computing the collision that the report compares (a "variant" in the report).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Method {
    /// The generated kernels in `f64`.
    F64,
    /// The generated FMA kernels in `f64`.
    F64Fma,
    /// The generated kernels in `f32` (inputs rounded to `f32`).
    F32,
    /// The generated kernels in exact rationals: the ground truth, at its real cost.
    Exact,
    /// The general-n nalgebra reference (impulse basis, Gram solve) in `f64`.
    Reference,
    /// The notes' dense `N x N` matrix, built per collision, times the state, in `f64`.
    Dense,
    /// The closed form of `docs/derivation.md` §7 written literally (`k_i = w_i / gamma_i^2`), in `f64`: the
    /// form before the generator's reformulation.
    Literal,
    /// The generated batch kernels (blocks of 8 contacts) in `f64`, at the widest
    /// instruction set the CPU has (`collision_core::batch::Exec::auto`), dispatched like
    /// `collide` ([`crate::batched`]): the scalar kernels' results, bit for bit.
    Batch,
}

/// What a variant returned on one case.
pub enum Outcome {
    /// The flattened result (`f32` results widened exactly).
    Done(Vec<f64>),
    /// A NaN or an infinity in the result: a stability failure.
    NonFinite,
    /// The variant refuses these inputs (the reference needs `lambda > 0`).
    Unsupported(String),
}

impl Method {
    /// Every method, in report order.
    pub const ALL: [Method; 8] = [
        Method::F64,
        Method::F64Fma,
        Method::F32,
        Method::Exact,
        Method::Reference,
        Method::Dense,
        Method::Literal,
        Method::Batch,
    ];

    /// The method's name in the report.
    pub fn name(self) -> &'static str {
        match self {
            Method::F64 => "generated f64",
            Method::F64Fma => "generated f64 FMA",
            Method::F32 => "generated f32",
            Method::Exact => "generated exact",
            Method::Reference => "nalgebra reference f64",
            Method::Dense => "dense matrix f64",
            Method::Literal => "literal closed form f64 (before)",
            Method::Batch => "generated f64 batch (x8 lanes)",
        }
    }

    /// The epsilon of the variant's format (`0` for exact).
    pub fn epsilon(self) -> f64 {
        match self {
            Method::F32 => f32::EPSILON as f64,
            Method::Exact => 0.0,
            _ => f64::EPSILON,
        }
    }

    /// The name of the generated kernel pair it runs (`free`/`fixed` or the FMA forms).
    pub fn generated(self) -> Option<noslip_codegen::Arith> {
        match self {
            Method::F64 | Method::F32 | Method::Exact | Method::Batch => {
                Some(noslip_codegen::Arith::Plain)
            }
            Method::F64Fma => Some(noslip_codegen::Arith::Fma),
            Method::Reference | Method::Dense | Method::Literal => None,
        }
    }

    /// Run on one case (`f32` on the rounded inputs, or refused with the reason they are
    /// not usable).
    pub fn run<const N: usize, const S: usize>(
        self,
        case: &Case<f64, N, S>,
        case32: Result<&Case<f32, N, S>, &str>,
    ) -> Outcome
    where
        Generated: Kernel<f64, N, S> + Kernel<f32, N, S> + BatchKernel<f64, N, S>,
    {
        let (nu, balls, states) = (&case.nu, case.ball_refs(), case.state_refs());
        match self {
            Method::F64 => done(&collide_unchecked(nu, balls, states)),
            Method::F64Fma => done(&collide_unchecked_fma(nu, balls, states)),
            Method::F32 => match case32 {
                Ok(c) => done(&collide_unchecked(&c.nu, c.ball_refs(), c.state_refs())),
                Err(why) => Outcome::Unsupported(why.into()),
            },
            Method::Exact => unreachable!("the exact variant is the ground truth"),
            Method::Reference => match reference::collide(nu, balls, states) {
                Ok(r) => done(&r),
                Err(e) => Outcome::Unsupported(e.message),
            },
            Method::Dense => done(&dense::collide(nu, balls, states)),
            Method::Literal => done(&literal::free(nu, balls[0], balls[1], states[0], states[1])),
            Method::Batch => {
                let cases = std::slice::from_ref(case);
                let mut batched = Batched::new(cases);
                batched.run(&Exec::auto().serial());
                match batched.result(0, cases) {
                    Some(r) => done(&r),
                    None => Outcome::Unsupported("empty batch".into()),
                }
            }
        }
    }

    /// Median time per collision over `samples` timed samples of passes over the batch.
    pub fn time<const N: usize, const S: usize>(
        self,
        cases: &[Case<f64, N, S>],
        cases32: &[Case<f32, N, S>],
        exact: &[Case<Exact, N, S>],
        samples: usize,
    ) -> Option<Timing>
    where
        Generated: Kernel<f64, N, S>
            + Kernel<f32, N, S>
            + Kernel<Exact, N, S>
            + Kernel<collision_core::ExactRelaxed, N, S>
            + BatchKernel<f64, N, S>,
    {
        let run64 = |c: &Case<f64, N, S>| collide_unchecked(&c.nu, c.ball_refs(), c.state_refs());
        Some(match self {
            Method::F64 => time(cases.len(), samples, || pass_over(cases, run64)),
            // The public entry point, with its run-time choice of FMA instructions: what a
            // caller gets.
            Method::F64Fma => time(cases.len(), samples, || {
                pass_over(cases, |c| {
                    collide_unchecked_fma(&c.nu, c.ball_refs(), c.state_refs())
                })
            }),
            Method::F32 if cases32.is_empty() => return None,
            Method::F32 => time(cases32.len(), samples, || {
                pass_over(cases32, |c| {
                    collide_unchecked(&c.nu, c.ball_refs(), c.state_refs())
                })
            }),
            Method::Exact => time(exact.len(), samples.min(5), || {
                pass_over(exact, |c| {
                    collide_unchecked(&c.nu, c.ball_refs(), c.state_refs())
                })
            }),
            Method::Reference => time(cases.len(), samples, || {
                pass_over(cases, |c| {
                    reference::collide(&c.nu, c.ball_refs(), c.state_refs())
                })
            }),
            Method::Dense => time(cases.len(), samples, || {
                pass_over(cases, |c| {
                    dense::collide(&c.nu, c.ball_refs(), c.state_refs())
                })
            }),
            Method::Batch => {
                let (exec, mut batched) = (Exec::auto().serial(), Batched::new(cases));
                time(cases.len(), samples, || {
                    batched.run(std::hint::black_box(&exec));
                    std::hint::black_box(&batched);
                })
            }
            Method::Literal => time(cases.len(), samples, || {
                pass_over(cases, |c| {
                    let ([b1, b2], [s1, s2]) = (c.ball_refs(), c.state_refs());
                    literal::free(&c.nu, b1, b2, s1, s2)
                })
            }),
        })
    }
}

fn done<T: Scalar, const N: usize, const S: usize>(states: &[BodyState<T, N, S>; 2]) -> Outcome {
    let flat: Vec<f64> = flatten(states).iter().map(Scalar::to_f64).collect();
    if flat.iter().all(|x| x.is_finite()) {
        Outcome::Done(flat)
    } else {
        Outcome::NonFinite
    }
}

/// Whether this CPU runs the FMA kernels with FMA instructions
/// ([`collision_core::fma_in_hardware`]).
pub fn has_fma() -> bool {
    collision_core::fma_in_hardware()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::regime::Regime;
    use collision_core::rng::Rng;

    fn bits(outcome: Outcome) -> Option<Vec<u64>> {
        match outcome {
            Outcome::Done(v) => Some(v.iter().map(|x| x.to_bits()).collect()),
            _ => None,
        }
    }

    /// The batch variant's result is `collide_unchecked`'s (the `f64` variant), bit for bit,
    /// on 40 cases of every regime: an immovable body goes through `fixed` there too.
    fn batch_is_the_scalar_path<const N: usize, const S: usize>()
    where
        Generated: Kernel<f64, N, S> + Kernel<f32, N, S> + BatchKernel<f64, N, S>,
    {
        for regime in Regime::ALL {
            let mut rng = Rng::new(0xba7c ^ N as u64);
            for k in 0..40 {
                let case = regime.sample::<N, S>(&mut rng);
                let scalar = bits(Method::F64.run(&case, Err("f32 not needed")));
                let batch = bits(Method::Batch.run(&case, Err("f32 not needed")));
                assert!(scalar.is_some(), "n = {N}, {}, case {k}", regime.name());
                assert_eq!(batch, scalar, "n = {N}, {}, case {k}", regime.name());
            }
        }
    }

    #[test]
    fn the_batch_variant_gives_the_scalar_results_bit_for_bit() {
        batch_is_the_scalar_path::<2, 1>();
        batch_is_the_scalar_path::<3, 3>();
        batch_is_the_scalar_path::<4, 6>();
        batch_is_the_scalar_path::<5, 10>();
        batch_is_the_scalar_path::<6, 15>();
    }
}
