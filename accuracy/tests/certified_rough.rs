//! The certified companions of the rough-ball kernels (constant `(e, beta)`;
//! `kernels::dN::certified::rough_{free,fixed}{,_fma}{,_f32}`, running error analysis,
//! `noslip_codegen::certify`) against the exact map, as `proven.rs` checks the no-slip
//! companions: for `f64` and `f32`, plain and FMA, every output bit-identical to the plain
//! rough kernel's (`kernels::dN::rough`, dispatched as `collide_rough_unchecked`), and every
//! finite bound at least the true error `|computed - exact|`, the exact map being the same
//! kernel on the same floats (the law included) in exact rationals, compared in exact
//! rationals.
//!
//! Cases: every regime of the report with a law drawn beside it (`e = U(0,1)`,
//! `beta = U(-1,1)`, or at or near the ends `e in {0, 1}`, `beta in {-1, 0, 1}`,
//! `1 - 10^-k`), the family's rough regimes (`FamilyRegime`), and an adversarial mix (mass
//! ratios to 1e15, radius ratios to 1e6, small or zero `gamma2`, an immovable body, velocities
//! and spins scaled by up to 1e+-30, a law near its ends). `cargo test` runs
//! [`QUICK`] per source and n; the long run is ignored (`NOSLIP_ROUGH_CASES` per n, default
//! 10^5; `NOSLIP_ROUGH_DIMS`, default 2..6):
//!
//! ```sh
//! cargo test --release -p noslip-accuracy --test certified_rough -- --ignored --nocapture
//! ```
//!
//! A control: the zero bound fails on some component of every dimension (the comparison
//! is live).

#[path = "certified_rough/laws.rs"]
mod laws;

use laws::{adversarial, q, Sample};

use collision_core::rng::Rng;
use collision_core::{
    validate, Ball, BodyState, Exact, Generated, Relaxing, RoughKernel, WaltonKernel,
};
use noslip_accuracy::case::{flatten, Case};
use noslip_accuracy::family::FamilyRegime;
use noslip_accuracy::Regime;
use num_traits::Signed;

/// Cases per source and n in the quick test.
const QUICK: usize = 40;

/// A companion of `rough_free` (`L = Restitution<T>`) or `walton_free` (`L = Walton<T>`).
type Free<T, L, const N: usize, const S: usize> =
    fn(
        &[T; N],
        &Ball<T>,
        &Ball<T>,
        &L,
        &BodyState<T, N, S>,
        &BodyState<T, N, S>,
    ) -> ([BodyState<T, N, S>; 2], [BodyState<T, N, S>; 2]);

/// A companion of `rough_fixed` or `walton_fixed`.
type Fixed<T, L, const N: usize, const S: usize> = fn(
    &[T; N],
    &T,
    &Ball<T>,
    &L,
    &BodyState<T, N, S>,
    &BodyState<T, N, S>,
) -> (BodyState<T, N, S>, BodyState<T, N, S>);

/// The plain kernels (`kernels::dN::rough::free`, `walton::fixed`, ...).
type PlainFree<T, L, const N: usize, const S: usize> = fn(
    &[T; N],
    &Ball<T>,
    &Ball<T>,
    &L,
    &BodyState<T, N, S>,
    &BodyState<T, N, S>,
) -> [BodyState<T, N, S>; 2];
type PlainFixed<T, L, const N: usize, const S: usize> =
    fn(&[T; N], &T, &Ball<T>, &L, &BodyState<T, N, S>, &BodyState<T, N, S>) -> BodyState<T, N, S>;

/// One kernel (plain or FMA) in one format: the companions and the plain kernels.
struct Kind<T, L, const N: usize, const S: usize> {
    certified: (Free<T, L, N, S>, Fixed<T, L, N, S>),
    plain: (PlainFree<T, L, N, S>, PlainFixed<T, L, N, S>),
}

/// Per dimension and law family (`Restitution`, `Walton`): `[plain, FMA]` in `f64` and in
/// `f32`.
struct Kinds<L64, L32, const N: usize, const S: usize> {
    f64: [Kind<f64, L64, N, S>; 2],
    f32: [Kind<f32, L32, N, S>; 2],
}

/// The [`Kinds`] of `kernels::$m`'s family `$family` (`rough`, `walton`), companions named
/// `$family_free`, ....
macro_rules! kinds {
    ($m:ident $family:ident) => {{
        use collision_core::kernels::$m::{certified as c, $family as r};
        paste_kinds!(c r $family)
    }};
}

macro_rules! paste_kinds {
    ($c:ident $r:ident rough) => {
        crate::Kinds {
            f64: [
                crate::Kind {
                    certified: ($c::rough_free, $c::rough_fixed),
                    plain: ($r::free, $r::fixed),
                },
                crate::Kind {
                    certified: ($c::rough_free_fma, $c::rough_fixed_fma),
                    plain: ($r::free_fma, $r::fixed_fma),
                },
            ],
            f32: [
                crate::Kind {
                    certified: ($c::rough_free_f32, $c::rough_fixed_f32),
                    plain: ($r::free, $r::fixed),
                },
                crate::Kind {
                    certified: ($c::rough_free_fma_f32, $c::rough_fixed_fma_f32),
                    plain: ($r::free_fma, $r::fixed_fma),
                },
            ],
        }
    };
    ($c:ident $r:ident walton) => {
        crate::Kinds {
            f64: [
                crate::Kind {
                    certified: ($c::walton_free, $c::walton_fixed),
                    plain: ($r::free, $r::fixed),
                },
                crate::Kind {
                    certified: ($c::walton_free_fma, $c::walton_fixed_fma),
                    plain: ($r::free_fma, $r::fixed_fma),
                },
            ],
            f32: [
                crate::Kind {
                    certified: ($c::walton_free_f32, $c::walton_fixed_f32),
                    plain: ($r::free, $r::fixed),
                },
                crate::Kind {
                    certified: ($c::walton_free_fma_f32, $c::walton_fixed_fma_f32),
                    plain: ($r::free_fma, $r::fixed_fma),
                },
            ],
        }
    };
}

/// `collide_rough_unchecked`'s dispatch: body 1 immovable, `fixed`; body 2 immovable,
/// `fixed` with the bodies swapped and `-nu`; else `free`. Returns the outputs and bounds
/// (an immovable body unchanged, bound 0).
#[allow(clippy::type_complexity)]
fn dispatch<
    T: collision_core::Scalar + Copy + Default + std::ops::Neg<Output = T>,
    L,
    const N: usize,
    const S: usize,
>(
    (free, fixed): (Free<T, L, N, S>, Fixed<T, L, N, S>),
    c: &Case<T, N, S>,
    law: &L,
) -> ([BodyState<T, N, S>; 2], [BodyState<T, N, S>; 2]) {
    let ([b1, b2], [s1, s2]) = (&c.balls, &c.states);
    let zero = BodyState {
        spin: [T::default(); S],
        velocity: [T::default(); N],
    };
    if b1.is_immovable() {
        let (o, e) = fixed(&c.nu, &b1.radius, b2, law, s1, s2);
        ([s1.clone(), o], [zero, e])
    } else if b2.is_immovable() {
        let (o, e) = fixed(&c.nu.map(|x| -x), &b2.radius, b1, law, s2, s1);
        ([o, s2.clone()], [e, zero])
    } else {
        free(&c.nu, b1, b2, law, s1, s2)
    }
}

/// The plain kernels under the same dispatch.
fn plain<
    T: collision_core::Scalar + Copy + std::ops::Neg<Output = T>,
    L,
    const N: usize,
    const S: usize,
>(
    (free, fixed): (PlainFree<T, L, N, S>, PlainFixed<T, L, N, S>),
    c: &Case<T, N, S>,
    law: &L,
) -> [BodyState<T, N, S>; 2] {
    let ([b1, b2], [s1, s2]) = (&c.balls, &c.states);
    if b1.is_immovable() {
        [s1.clone(), fixed(&c.nu, &b1.radius, b2, law, s1, s2)]
    } else if b2.is_immovable() {
        [
            fixed(&c.nu.map(|x| -x), &b2.radius, b1, law, s2, s1),
            s2.clone(),
        ]
    } else {
        free(&c.nu, b1, b2, law, s1, s2)
    }
}

/// What one kind saw in one format.
#[derive(Clone, Debug, Default)]
struct Seen {
    cases: usize,
    /// Components checked against the exact error (finite bound).
    components: usize,
    /// Components with an infinite bound.
    infinite: usize,
    /// Components whose exact error is nonzero: the zero bound would fail them.
    nonzero: usize,
    /// Per component with a nonzero error: bound / measured.
    over_measured: Vec<f64>,
    /// Largest measured / bound (must stay <= 1).
    worst: f64,
}

/// Check one kind on one case (inputs and law in the kind's format `T`, `wide` widening
/// them exactly; `truth` the exact map on the widened inputs).
fn check<T, L, const N: usize, const S: usize>(
    kind: &Kind<T, L, N, S>,
    (case, law): (&Case<T, N, S>, &L),
    truth: &[Exact],
    wide: fn(T) -> f64,
    seen: &mut Seen,
    what: &dyn Fn() -> String,
) where
    T: collision_core::Scalar + Copy + Default + std::ops::Neg<Output = T>,
{
    let (out, bound) = dispatch(kind.certified, case, law);
    let reference = plain(kind.plain, case, law);
    let values: Vec<f64> = flatten(&out).into_iter().map(wide).collect();
    let expected: Vec<f64> = flatten(&reference).into_iter().map(wide).collect();
    for (k, (a, b)) in values.iter().zip(&expected).enumerate() {
        assert!(
            a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan()),
            "{}: component {k} {a:e} differs from the plain kernel's {b:e}",
            what()
        );
    }
    let bounds: Vec<f64> = flatten(&bound).into_iter().map(wide).collect();
    seen.cases += 1;
    for k in 0..values.len() {
        let e = bounds[k];
        assert!(e >= 0.0, "{}: component {k} has a bound {e}", what());
        if e.is_infinite() {
            seen.infinite += 1;
            continue;
        }
        let v = Exact::from_float(values[k]).expect("a finite bound has a finite output");
        let err = (v - &truth[k]).abs();
        assert!(
            err <= q(e),
            "{}: component {k} error {:e} above its bound {e:e}",
            what(),
            err.to_f64()
        );
        seen.components += 1;
        let m = err.to_f64();
        if m > 0.0 {
            seen.nonzero += 1;
            seen.over_measured.push(e / m);
            seen.worst = seen.worst.max(m / e);
        }
    }
}

/// The sources of one family: the report's regimes (a law drawn beside), the family's
/// regimes of that kernel, the adversarial mix.
fn sources(kernel: &str) -> Vec<String> {
    Regime::ALL
        .iter()
        .map(|r| r.name().to_string())
        .chain(
            FamilyRegime::ALL
                .iter()
                .filter(|r| r.kernel() == kernel)
                .map(|r| r.name().to_string()),
        )
        .chain(std::iter::once("adversarial".to_string()))
        .collect()
}

/// `per_source` cases from every source of the family `L`; per source, `[[f64 plain, f64
/// FMA], [f32 plain, f32 FMA]]`.
fn run<L: Sample, const N: usize, const S: usize>(
    kinds: &Kinds<L, L::F32, N, S>,
    per_source: usize,
    seed: u64,
) -> Vec<[[Seen; 2]; 2]>
where
    Relaxing: RoughKernel<Exact, N, S>,
    Generated: WaltonKernel<Exact, N, S>,
{
    let mut rng = Rng::new(seed ^ ((N as u64) << 40));
    let family: Vec<FamilyRegime> = FamilyRegime::ALL
        .into_iter()
        .filter(|r| r.kernel() == L::KERNEL)
        .collect();
    let names = sources(L::KERNEL);
    let mut seen: Vec<[[Seen; 2]; 2]> = vec![Default::default(); names.len()];
    for (source, name) in names.iter().enumerate() {
        for _ in 0..per_source {
            let (case, law) = if let Some(r) = Regime::ALL.get(source) {
                let case = r.sample::<N, S>(&mut rng);
                let law = L::beside(&mut rng, &case);
                (case, law)
            } else if let Some(f) = family.get(source - Regime::ALL.len()) {
                let (case, law) = f.sample::<N, S>(&mut rng);
                (case, L::of(law))
            } else {
                let case = adversarial::<N, S>(&mut rng);
                let law = L::beside(&mut rng, &case);
                (case, law)
            };
            if validate(&case.nu, case.ball_refs(), case.state_refs()).is_err() {
                continue;
            }
            let truth = law.exact(&case);
            for (k, kind) in kinds.f64.iter().enumerate() {
                let what = || format!("n = {N} {name} f64 kind {k} {case:?} {law:?}");
                check(
                    kind,
                    (&case, &law),
                    &truth,
                    |x| x,
                    &mut seen[source][0][k],
                    &what,
                );
            }
            let Ok(c32) = case.to_f32() else { continue };
            if validate(&c32.nu, c32.ball_refs(), c32.state_refs()).is_err() {
                continue;
            }
            let Some(l32) = law.to_f32() else { continue };
            let truth = L::widen(&l32).exact(&c32.map(|&x| f64::from(x)));
            for (k, kind) in kinds.f32.iter().enumerate() {
                let what = || format!("n = {N} {name} f32 kind {k} {c32:?} {l32:?}");
                check(
                    kind,
                    (&c32, &l32),
                    &truth,
                    f64::from,
                    &mut seen[source][1][k],
                    &what,
                );
            }
        }
    }
    seen
}

/// `(median, max)` of a list (`None` if empty).
fn median_max(v: &[f64]) -> Option<(f64, f64)> {
    let mut v = v.to_vec();
    v.sort_by(f64::total_cmp);
    Some((*v.get(v.len() / 2)?, *v.last()?))
}

fn quick<L: Sample, const N: usize, const S: usize>(kinds: Kinds<L, L::F32, N, S>)
where
    Relaxing: RoughKernel<Exact, N, S>,
    Generated: WaltonKernel<Exact, N, S>,
{
    let seen = run(&kinds, QUICK, 0xB0D);
    let names = sources(L::KERNEL);
    for (source, s) in seen.iter().enumerate() {
        for (k, s) in s[0].iter().enumerate() {
            assert!(
                s.components > 0,
                "n = {N} {} f64 kind {k}: no component checked",
                names[source]
            );
        }
    }
    for f in 0..2 {
        for k in 0..2 {
            let nonzero: usize = seen.iter().map(|s| s[f][k].nonzero).sum();
            // The control: the zero bound would fail these components.
            assert!(nonzero > 0, "n = {N} format {f} kind {k}: no nonzero error");
        }
    }
}

macro_rules! per_dim {
    ($(($m:ident $n:literal $s:literal))*) => {$(
        mod $m {
            #[test]
            fn the_rough_companions_bound_the_error_in_every_regime() {
                super::quick::<collision_core::Restitution<f64>, $n, $s>(kinds!($m rough));
            }

            #[test]
            fn the_walton_companions_bound_the_error_in_every_regime() {
                super::quick::<collision_core::Walton<f64>, $n, $s>(kinds!($m walton));
            }
        }
    )*};
}

per_dim!((d2 2 1) (d3 3 3) (d4 4 6) (d5 5 10) (d6 6 15));

/// Print one family's run.
fn print(n: usize, kernel: &str, seen: &[[[Seen; 2]; 2]], start: std::time::Instant) {
    for (source, name) in sources(kernel).iter().enumerate() {
        for (f, format) in ["f64", "f32"].iter().enumerate() {
            for (k, kind) in ["plain", "fma"].iter().enumerate() {
                let s = &seen[source][f][k];
                let (med, max) = median_max(&s.over_measured).unwrap_or((f64::NAN, f64::NAN));
                println!(
                    "n = {n} {kernel} {kind} {format} {name:<24} cases {:>7} components {:>8} inf {:>6}; bound/measured median {med:.1} max {max:.3e}; worst measured/bound {:.4} ({:.0} s)",
                    s.cases,
                    s.components,
                    s.infinite,
                    s.worst,
                    start.elapsed().as_secs_f64()
                );
                assert!(s.worst <= 1.0);
            }
        }
    }
}

/// The long run: prints, per family, source, format and kind, the bound over the measured
/// error (median and max), the infinite bounds and the worst measured / bound.
#[test]
#[ignore = "long: NOSLIP_ROUGH_CASES (default 10^5) cases per n and family in a release build"]
fn the_rough_and_walton_companions_long() {
    let total: usize = std::env::var("NOSLIP_ROUGH_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(100_000);
    let dims: Vec<usize> = std::env::var("NOSLIP_ROUGH_DIMS")
        .ok()
        .map(|s| s.split(',').filter_map(|d| d.parse().ok()).collect())
        .unwrap_or_else(|| (2..=6).collect());
    let rough = total.div_ceil(sources("rough").len());
    let walton = total.div_ceil(sources("walton").len());
    macro_rules! both {
        ($m:ident $n:literal) => {{
            let start = std::time::Instant::now();
            let s = run(&kinds!($m rough), rough, 0x1E6);
            print($n, "rough", &s, start);
            let s = run(&kinds!($m walton), walton, 0x1E6);
            print($n, "walton", &s, start);
        }};
    }
    for n in dims {
        match n {
            2 => both!(d2 2),
            3 => both!(d3 3),
            4 => both!(d4 4),
            5 => both!(d5 5),
            6 => both!(d6 6),
            _ => panic!("n = {n} has no kernels"),
        }
    }
}
