//! The companions with rounded inputs (`kernels::dN::certified::{free,fixed}{,_fma}_rounded`,
//! `noslip_codegen::certify::rounded`) against the exact map at the *intended* inputs: an
//! exact rational unit normal (inverse stereographic projection of a rational point) and
//! exact rational `gamma2` values that are not floats, each perturbed by a relative `delta`
//! with `|delta| <= rho / 2` and rounded to `f64`; the premise `|x^ - x| <= rho |x|` is
//! checked in exact rationals, then every output must equal the plain kernel's bit for bit
//! and lie within its bound of the exact map at the intended inputs, compared in exact
//! rationals. As a control, the companion on the floats given (`free`, `rho = 0`) must miss
//! the intended truth for some component when `rho` is large: the test can fail.

use collision_core::certified::InputRounding;
use collision_core::kernels;
use collision_core::rng::Rng;
use collision_core::{Ball, BodyState, Exact, Generated, Kernel};
use noslip_accuracy::case::{flatten, Case};
use noslip_accuracy::measure::exact_result;
use noslip_accuracy::Regime;
use num_traits::Signed;

/// `(rho_nu, rho_gamma2)` tried: a normal normalised in `f64` and `gamma2` rounded once;
/// then larger input errors.
fn rhos(n: usize) -> [(f64, f64); 3] {
    let u = f64::EPSILON / 2.0;
    [
        ((n as f64 + 2.0) * f64::EPSILON, u),
        (1e-9, 1e-12),
        (1e-6, 1e-4),
    ]
}

/// An exact rational unit vector: `(2 y, |y|^2 - 1) / (|y|^2 + 1)`, `y` rational.
fn unit_normal<const N: usize>(rng: &mut Rng) -> [Exact; N] {
    let y: Vec<Exact> = (0..N - 1)
        .map(|_| Exact::checked_ratio((rng.uniform(-1.0, 1.0) * 1000.0) as i64, 997).unwrap())
        .collect();
    let one = Exact::from_integer(1);
    let r2 = y.iter().fold(Exact::from_integer(0), |a, x| a + x * x);
    let den = &r2 + &one;
    std::array::from_fn(|k| {
        if k < N - 1 {
            Exact::from_integer(2) * &y[k] / &den
        } else {
            (&r2 - &one) / &den
        }
    })
}

/// `x` perturbed by a relative `delta`, `|delta| <= rho / 2` (0 when `rho < 4u`), rounded
/// to `f64`; asserts the premise `|x^ - x| <= rho |x|` in exact rationals.
fn rounded(rng: &mut Rng, x: &Exact, rho: f64) -> f64 {
    let delta = if rho >= 2.0 * f64::EPSILON {
        Exact::from_float(rng.uniform(-0.5, 0.5) * rho).unwrap()
    } else {
        Exact::from_integer(0)
    };
    let y = (x * (Exact::from_integer(1) + delta)).to_f64();
    let err = (Exact::from_float(y).unwrap() - x).abs();
    assert!(err <= Exact::from_float(rho).unwrap() * x.abs(), "premise");
    y
}

/// Check one dimension: `cases` cases per `rho` pair, `free` and `fixed`, plain and FMA.
/// Returns how many components the control (the companion on the floats given) missed.
#[allow(clippy::type_complexity)]
fn check<const N: usize, const S: usize>(
    cases: usize,
    free: [fn(
        &[f64; N],
        &Ball<f64>,
        &Ball<f64>,
        &BodyState<f64, N, S>,
        &BodyState<f64, N, S>,
        &InputRounding<f64>,
    ) -> ([BodyState<f64, N, S>; 2], [BodyState<f64, N, S>; 2]); 2],
    fixed: [fn(
        &[f64; N],
        &f64,
        &Ball<f64>,
        &BodyState<f64, N, S>,
        &BodyState<f64, N, S>,
        &InputRounding<f64>,
    ) -> (BodyState<f64, N, S>, BodyState<f64, N, S>); 2],
    control: fn(
        &[f64; N],
        &Ball<f64>,
        &Ball<f64>,
        &BodyState<f64, N, S>,
        &BodyState<f64, N, S>,
    ) -> ([BodyState<f64, N, S>; 2], [BodyState<f64, N, S>; 2]),
) -> usize
where
    Generated: Kernel<f64, N, S> + Kernel<collision_core::ExactRelaxed, N, S>,
{
    let mut rng = Rng::new(0x5EED ^ N as u64);
    let mut missed = 0;
    for (rho_nu, rho_g) in rhos(N) {
        let rho = InputRounding {
            nu: rho_nu,
            gamma2: rho_g,
        };
        for _ in 0..cases {
            let floats = Regime::Typical.sample::<N, S>(&mut rng);
            // The intended inputs: exact, the normal unit, each gamma2 a non-float rational.
            let mut intended: Case<Exact, N, S> = floats.to_exact();
            intended.nu = unit_normal::<N>(&mut rng);
            for b in &mut intended.balls {
                b.gamma2 =
                    Exact::checked_ratio((rng.uniform(0.01, 1.0) * 1e6) as i64, 1_000_003).unwrap();
            }
            let mut given = floats.clone();
            given.nu = std::array::from_fn(|k| rounded(&mut rng, &intended.nu[k], rho_nu));
            for b in 0..2 {
                given.balls[b].gamma2 = rounded(&mut rng, &intended.balls[b].gamma2, rho_g);
            }
            for fixed_kernel in [false, true] {
                let (mut given, mut intended) = (given.clone(), intended.clone());
                if fixed_kernel {
                    given.balls[0].inv_mass = 0.0;
                    intended.balls[0].inv_mass = Exact::from_integer(0);
                }
                let truth = flatten(&exact_result(&intended));
                let ([b1, b2], [s1, s2]) = (given.ball_refs(), given.state_refs());
                for fma in [0, 1] {
                    let plain = match fma {
                        0 => flatten(&kernels_plain(&given, false)),
                        _ => flatten(&kernels_plain(&given, true)),
                    };
                    let (out, bound): (Vec<f64>, Vec<f64>) = if fixed_kernel {
                        let (o, e) = fixed[fma](&given.nu, &b1.radius, b2, s1, s2, &rho);
                        (flatten(&[s1.clone(), o]), flatten(&[BodyState::zero(), e]))
                    } else {
                        let (o, e) = free[fma](&given.nu, b1, b2, s1, s2, &rho);
                        (flatten(&o), flatten(&e))
                    };
                    for k in 0..out.len() {
                        assert_eq!(out[k].to_bits(), plain[k].to_bits(), "n = {N}: bits");
                        let e = bound[k];
                        assert!(
                            e.is_finite(),
                            "n = {N}: an infinite bound on a typical case"
                        );
                        let err = (Exact::from_float(out[k]).unwrap() - &truth[k]).abs();
                        assert!(
                            err <= Exact::from_float(e).unwrap(),
                            "n = {N} fixed {fixed_kernel} fma {fma} rho {rho:?}: component {k} \
                             error {:e} above its bound {e:e}",
                            err.to_f64()
                        );
                    }
                }
                if !fixed_kernel {
                    let (out, bound) = control(&given.nu, b1, b2, s1, s2);
                    let (out, bound) = (flatten(&out), flatten(&bound));
                    missed += (0..out.len())
                        .filter(|&k| {
                            (Exact::from_float(out[k]).unwrap() - &truth[k]).abs()
                                > Exact::from_float(bound[k]).unwrap()
                        })
                        .count();
                }
            }
        }
    }
    missed
}

/// The plain kernels on `case` as `collide_unchecked(_fma)` dispatches them.
fn kernels_plain<const N: usize, const S: usize>(
    case: &Case<f64, N, S>,
    fma: bool,
) -> [BodyState<f64, N, S>; 2]
where
    Generated: Kernel<f64, N, S>,
{
    if fma {
        collision_core::collide_unchecked_fma(&case.nu, case.ball_refs(), case.state_refs())
    } else {
        collision_core::collide_unchecked(&case.nu, case.ball_refs(), case.state_refs())
    }
}

macro_rules! dims {
    ($(($m:ident $n:literal $s:literal))*) => {$({
        use kernels::$m::certified as c;
        let missed = check::<$n, $s>(
            4,
            [c::free_rounded, c::free_fma_rounded],
            [c::fixed_rounded, c::fixed_fma_rounded],
            c::free,
        );
        assert!(missed > 0, "n = {}: the control never missed the intended truth", $n);
    })*};
}

#[test]
fn the_rounded_companions_bound_the_error_against_the_intended_inputs() {
    dims!((d2 2 1) (d3 3 3) (d4 4 6) (d5 5 10) (d6 6 15));
}
