//! The generated kernels' fast exact path: inputs in [`ExactRelaxed`], the straight-line
//! kernel with no GCD per operation, outputs reduced to [`Exact`]. The values are those of
//! the kernel run in [`Exact`] (a field's operations do not depend on how a fraction is
//! written); only the work differs: docs/benchmarks.md, "Exact arithmetic".

use super::{Exact, ExactRelaxed};
use crate::collide::collide_unchecked;
use crate::kernels::{Generated, Kernel, RoughKernel};
use crate::{Ball, BodyState, Restitution};

/// The generated kernels in exact arithmetic, run relaxed and reduced at the end:
/// `Relaxing: Kernel<Exact, N, S>` wherever `Generated: Kernel<ExactRelaxed, N, S>`.
/// The FMA forms are the plain ones (exact arithmetic has no rounding to fuse).
#[derive(Clone, Copy, Debug, Default)]
pub struct Relaxing;

fn ball(b: &Ball<Exact>) -> Ball<ExactRelaxed> {
    Ball {
        inv_mass: b.inv_mass.relax(),
        radius: b.radius.relax(),
        gamma2: b.gamma2.relax(),
    }
}

fn state<const N: usize, const S: usize>(
    s: &BodyState<Exact, N, S>,
) -> BodyState<ExactRelaxed, N, S> {
    BodyState {
        spin: std::array::from_fn(|k| s.spin[k].relax()),
        velocity: std::array::from_fn(|k| s.velocity[k].relax()),
    }
}

fn reduced<const N: usize, const S: usize>(
    s: &BodyState<ExactRelaxed, N, S>,
) -> BodyState<Exact, N, S> {
    BodyState {
        spin: std::array::from_fn(|k| s.spin[k].canonical()),
        velocity: std::array::from_fn(|k| s.velocity[k].canonical()),
    }
}

fn normal<const N: usize>(nu: &[Exact; N]) -> [ExactRelaxed; N] {
    std::array::from_fn(|k| nu[k].relax())
}

impl<const N: usize, const S: usize> Kernel<Exact, N, S> for Relaxing
where
    Generated: Kernel<ExactRelaxed, N, S>,
{
    fn free(
        nu: &[Exact; N],
        ball1: &Ball<Exact>,
        ball2: &Ball<Exact>,
        state1: &BodyState<Exact, N, S>,
        state2: &BodyState<Exact, N, S>,
    ) -> [BodyState<Exact, N, S>; 2] {
        let out = Generated::free(
            &normal(nu),
            &ball(ball1),
            &ball(ball2),
            &state(state1),
            &state(state2),
        );
        [reduced(&out[0]), reduced(&out[1])]
    }

    fn fixed(
        nu: &[Exact; N],
        radius1: &Exact,
        ball2: &Ball<Exact>,
        state1: &BodyState<Exact, N, S>,
        state2: &BodyState<Exact, N, S>,
    ) -> BodyState<Exact, N, S> {
        let out = Generated::fixed(
            &normal(nu),
            &radius1.relax(),
            &ball(ball2),
            &state(state1),
            &state(state2),
        );
        reduced(&out)
    }

    fn free_fma(
        nu: &[Exact; N],
        ball1: &Ball<Exact>,
        ball2: &Ball<Exact>,
        state1: &BodyState<Exact, N, S>,
        state2: &BodyState<Exact, N, S>,
    ) -> [BodyState<Exact, N, S>; 2] {
        Self::free(nu, ball1, ball2, state1, state2)
    }

    fn fixed_fma(
        nu: &[Exact; N],
        radius1: &Exact,
        ball2: &Ball<Exact>,
        state1: &BodyState<Exact, N, S>,
        state2: &BodyState<Exact, N, S>,
    ) -> BodyState<Exact, N, S> {
        Self::fixed(nu, radius1, ball2, state1, state2)
    }
}

fn law(l: &Restitution<Exact>) -> Restitution<ExactRelaxed> {
    Restitution {
        e: l.e.relax(),
        beta: l.beta.relax(),
    }
}

/// The rough-ball kernels the same way: `Relaxing: RoughKernel<Exact, N, S>`.
impl<const N: usize, const S: usize> RoughKernel<Exact, N, S> for Relaxing
where
    Generated: RoughKernel<ExactRelaxed, N, S>,
{
    fn rough_free(
        nu: &[Exact; N],
        ball1: &Ball<Exact>,
        ball2: &Ball<Exact>,
        l: &Restitution<Exact>,
        state1: &BodyState<Exact, N, S>,
        state2: &BodyState<Exact, N, S>,
    ) -> [BodyState<Exact, N, S>; 2] {
        let out = Generated::rough_free(
            &normal(nu),
            &ball(ball1),
            &ball(ball2),
            &law(l),
            &state(state1),
            &state(state2),
        );
        [reduced(&out[0]), reduced(&out[1])]
    }

    fn rough_fixed(
        nu: &[Exact; N],
        radius1: &Exact,
        ball2: &Ball<Exact>,
        l: &Restitution<Exact>,
        state1: &BodyState<Exact, N, S>,
        state2: &BodyState<Exact, N, S>,
    ) -> BodyState<Exact, N, S> {
        let out = Generated::rough_fixed(
            &normal(nu),
            &radius1.relax(),
            &ball(ball2),
            &law(l),
            &state(state1),
            &state(state2),
        );
        reduced(&out)
    }

    fn rough_free_fma(
        nu: &[Exact; N],
        ball1: &Ball<Exact>,
        ball2: &Ball<Exact>,
        l: &Restitution<Exact>,
        state1: &BodyState<Exact, N, S>,
        state2: &BodyState<Exact, N, S>,
    ) -> [BodyState<Exact, N, S>; 2] {
        Self::rough_free(nu, ball1, ball2, l, state1, state2)
    }

    fn rough_fixed_fma(
        nu: &[Exact; N],
        radius1: &Exact,
        ball2: &Ball<Exact>,
        l: &Restitution<Exact>,
        state1: &BodyState<Exact, N, S>,
        state2: &BodyState<Exact, N, S>,
    ) -> BodyState<Exact, N, S> {
        Self::rough_fixed(nu, radius1, ball2, l, state1, state2)
    }
}

/// [`collide_unchecked`] in exact arithmetic through [`Relaxing`]: the same dispatch (body 1
/// immovable: `fixed`; body 2: `fixed` swapped; else `free`), the same reduced outputs.
pub fn collide_exact<const N: usize, const S: usize>(
    nu: &[Exact; N],
    balls: [&Ball<Exact>; 2],
    states: [&BodyState<Exact, N, S>; 2],
) -> [BodyState<Exact, N, S>; 2]
where
    Generated: Kernel<ExactRelaxed, N, S>,
{
    let (b, s) = (
        [ball(balls[0]), ball(balls[1])],
        [state(states[0]), state(states[1])],
    );
    let out = collide_unchecked(&normal(nu), [&b[0], &b[1]], [&s[0], &s[1]]);
    [reduced(&out[0]), reduced(&out[1])]
}
