//! The `f32` companions with the bound computed in `f64`
//! (`kernels::dN::certified::{free,fixed}{,_fma}_f32_wide`, `noslip_codegen::certify::wide`)
//! on cases from every regime and the adversarial mix, rounded to `f32`: every output
//! bit-identical to the plain `f32` kernel's (`collide_unchecked`, `collide_unchecked_fma`,
//! with `collide`'s dispatch), every finite bound at least the exact error (exact
//! rationals), and never an infinite bound where the `f32`-evaluated companion's is finite.
//! Returns, per kernel, the infinite bounds of the `f32` companion and of the wide one.

use collision_core::certified::{collide_certified_by, collide_certified_fma_by, Companion};
use collision_core::kernels;
use collision_core::rng::Rng;
use collision_core::{validate, Ball, BodyState, Exact, Generated, Kernel};
use noslip_accuracy::case::{flatten, Case};
use noslip_accuracy::measure::exact_result;
use noslip_accuracy::Regime;
use num_traits::Signed;

type Free<const N: usize, const S: usize> =
    fn(
        &[f32; N],
        &Ball<f32>,
        &Ball<f32>,
        &BodyState<f32, N, S>,
        &BodyState<f32, N, S>,
    ) -> ([BodyState<f32, N, S>; 2], [BodyState<f64, N, S>; 2]);

type Fixed<const N: usize, const S: usize> = fn(
    &[f32; N],
    &f32,
    &Ball<f32>,
    &BodyState<f32, N, S>,
    &BodyState<f32, N, S>,
) -> (BodyState<f32, N, S>, BodyState<f64, N, S>);

/// `collide`'s dispatch over a wide companion pair.
fn dispatch<const N: usize, const S: usize>(
    (free, fixed): (Free<N, S>, Fixed<N, S>),
    c: &Case<f32, N, S>,
) -> ([BodyState<f32, N, S>; 2], [BodyState<f64, N, S>; 2]) {
    let ([b1, b2], [s1, s2]) = (&c.balls, &c.states);
    if b1.is_immovable() {
        let (o, e) = fixed(&c.nu, &b1.radius, b2, s1, s2);
        ([s1.clone(), o], [BodyState::zero(), e])
    } else if b2.is_immovable() {
        let (o, e) = fixed(&c.nu.map(|x| -x), &b2.radius, b1, s2, s1);
        ([o, s2.clone()], [e, BodyState::zero()])
    } else {
        free(&c.nu, b1, b2, s1, s2)
    }
}

/// Check `per_source` cases per source; returns `[[f32 inf, wide inf, wide inf with a
/// finite output]; 2]` (plain, FMA).
pub fn check<const N: usize, const S: usize>(
    per_source: usize,
    kinds: [(Free<N, S>, Fixed<N, S>); 2],
) -> [[usize; 3]; 2]
where
    Generated: Kernel<f32, N, S>
        + Kernel<collision_core::ExactRelaxed, N, S>
        + collision_core::certified::CertifiedKernel<f32, N, S>,
{
    let mut rng = Rng::new(0x1D3 ^ N as u64);
    let mut infinite = [[0; 3]; 2];
    let mut checked = 0;
    for source in 0..=Regime::ALL.len() {
        for _ in 0..per_source {
            let case = match Regime::ALL.get(source) {
                Some(r) => r.sample::<N, S>(&mut rng),
                None => super::adversarial::<N, S>(&mut rng),
            };
            let Ok(c) = case.to_f32() else { continue };
            if validate(&c.nu, c.ball_refs(), c.state_refs()).is_err() {
                continue;
            }
            let exact = flatten(&exact_result(&c.map(|&x| f64::from(x)).to_exact()));
            for (k, kind) in kinds.into_iter().enumerate() {
                let fma = k == 1;
                let (plain, (_, narrow)) = if fma {
                    (
                        collision_core::collide_unchecked_fma(&c.nu, c.ball_refs(), c.state_refs()),
                        collide_certified_fma_by(
                            Companion::Running,
                            &c.nu,
                            c.ball_refs(),
                            c.state_refs(),
                        ),
                    )
                } else {
                    (
                        collision_core::collide_unchecked(&c.nu, c.ball_refs(), c.state_refs()),
                        collide_certified_by(
                            Companion::Running,
                            &c.nu,
                            c.ball_refs(),
                            c.state_refs(),
                        ),
                    )
                };
                let (out, bound) = dispatch(kind, &c);
                let (out, plain, bound, narrow) = (
                    flatten(&out),
                    flatten(&plain),
                    flatten(&bound),
                    flatten(&narrow),
                );
                for i in 0..out.len() {
                    assert!(
                        out[i].to_bits() == plain[i].to_bits()
                            || (out[i].is_nan() && plain[i].is_nan()),
                        "n = {N} fma {fma}: component {i} differs from the plain f32 kernel"
                    );
                    let (e, e32) = (bound[i], f64::from(narrow[i]));
                    assert!(e >= 0.0, "n = {N}: bound {e}");
                    infinite[k][0] += usize::from(e32.is_infinite());
                    if e.is_infinite() {
                        infinite[k][1] += 1;
                        infinite[k][2] += usize::from(out[i].is_finite());
                        assert!(
                            e32.is_infinite(),
                            "n = {N} fma {fma}: component {i} has an infinite wide bound, \
                             a finite f32 one"
                        );
                        continue;
                    }
                    let err =
                        (Exact::from_float(f64::from(out[i])).expect("finite") - &exact[i]).abs();
                    assert!(
                        err <= Exact::from_float(e).expect("finite"),
                        "n = {N} fma {fma}: component {i} error {:e} above its wide bound {e:e} \
                         for {c:?}",
                        err.to_f64()
                    );
                    checked += 1;
                }
            }
        }
    }
    assert!(checked > 0, "n = {N}: no component checked");
    infinite
}

macro_rules! dims {
    ($per_source:expr; $(($m:ident $n:literal $s:literal))*) => {{
        let mut all = Vec::new();
        $({
            use kernels::$m::certified as c;
            all.push(($n, check::<$n, $s>(
                $per_source,
                [(c::free_f32_wide, c::fixed_f32_wide), (c::free_fma_f32_wide, c::fixed_fma_f32_wide)],
            )));
        })*
        all
    }};
}

#[test]
fn the_f32_companions_with_f64_bounds_hold_and_do_not_overflow() {
    let seen = dims!(6; (d2 2 1) (d3 3 3) (d4 4 6) (d5 5 10) (d6 6 15));
    for (n, inf) in seen {
        for [narrow, wide, _] in inf {
            assert!(
                wide <= narrow,
                "n = {n}: {wide} infinite wide bounds, {narrow} in f32"
            );
        }
    }
}

/// The long run: `NOSLIP_WIDE_CASES` (default 2000) cases per source and n; prints the
/// infinite bounds of the `f32` companion and of the wide one.
///
/// ```sh
/// NOSLIP_WIDE_CASES=2000 cargo test --release -p noslip-accuracy --test proven wide -- --ignored --nocapture
/// ```
#[test]
#[ignore = "long: minutes in a release build"]
fn the_f32_companions_with_f64_bounds_long() {
    let per_source = crate::env_count("NOSLIP_WIDE_CASES", 2000);
    let seen = dims!(per_source; (d2 2 1) (d3 3 3) (d4 4 6) (d5 5 10) (d6 6 15));
    for (n, inf) in seen {
        println!(
            "n = {n}: infinite bounds (f32 companion, wide, wide on a finite output): plain {:?}, FMA {:?}",
            inf[0], inf[1]
        );
    }
}
