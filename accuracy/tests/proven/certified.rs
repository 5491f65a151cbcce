//! The certified companions (`collision_core::certified`, `kernels::dN::certified`) on the
//! same cases as the interpreter's bound: for `f64` and `f32`, every output bit-identical to
//! the plain kernel's (`collide_unchecked`), every finite bound at least the true error
//! (exact rationals), and how the companion's bound compares with the interpreter's point
//! bound (`ProvenBound::component_bounds`) and with the measured error.

use collision_core::certified::{
    collide_certified_by, collide_certified_fma_by, energy_error_bound, CertifiedKernel, Companion,
};
use collision_core::{
    collide_unchecked, collide_unchecked_fma, validate, Exact, Generated, Kernel,
};
use collision_core::{Ball, BodyState};
use noslip_accuracy::case::{flatten, Case};
use noslip_accuracy::measure::exact_result;
use noslip_accuracy::proven::ProvenBound;
use num_traits::Signed;

/// What the check saw in one format.
#[derive(Clone, Debug, Default)]
pub struct CertSeen {
    /// Cases checked.
    pub cases: usize,
    /// Components checked against the exact error (finite bound).
    pub components: usize,
    /// Components with an infinite companion bound (and with an infinite interpreter bound).
    pub infinite: usize,
    pub infinite_interpreter: usize,
    /// Per component with both bounds finite and positive: companion / interpreter.
    pub over_interpreter: Vec<f64>,
    /// Per component with a nonzero error: companion bound / measured error.
    pub over_measured: Vec<f64>,
    /// Largest measured / companion bound (must stay <= 1).
    pub worst: f64,
}

impl CertSeen {
    /// `(median, max)` of a list (NaN if empty).
    pub fn median_max(v: &[f64]) -> (f64, f64) {
        if v.is_empty() {
            return (f64::NAN, f64::NAN);
        }
        let mut v = v.to_vec();
        v.sort_by(f64::total_cmp);
        (v[v.len() / 2], v[v.len() - 1])
    }

    pub fn min(v: &[f64]) -> f64 {
        v.iter().copied().fold(f64::INFINITY, f64::min)
    }
}

/// Check both formats' companions of kind `companion` on `case` (`f32`: if the case is one
/// `f32` holds), of the plain kernels or (`fma`) of the FMA kernels; the interpreter's
/// bounds `bound64`, `bound32` (of the same kernel; `None`: none to compare with).
pub fn check<const N: usize, const S: usize>(
    (companion, fma): (Companion, bool),
    bound64: &ProvenBound,
    bound32: Option<&ProvenBound>,
    case: &Case<f64, N, S>,
    exact_case: &Case<Exact, N, S>,
    seen: &mut [CertSeen; 2],
) where
    Generated: Kernel<f64, N, S>
        + Kernel<f32, N, S>
        + Kernel<collision_core::ExactRelaxed, N, S>
        + CertifiedKernel<f64, N, S>
        + CertifiedKernel<f32, N, S>,
{
    // f64
    let (plain, (out, bound)) = if fma {
        (
            collide_unchecked_fma(&case.nu, case.ball_refs(), case.state_refs()),
            collide_certified_fma_by(companion, &case.nu, case.ball_refs(), case.state_refs()),
        )
    } else {
        (
            collide_unchecked(&case.nu, case.ball_refs(), case.state_refs()),
            collide_certified_by(companion, &case.nu, case.ball_refs(), case.state_refs()),
        )
    };
    let values: Vec<f64> = flatten(&out);
    let plain: Vec<f64> = flatten(&plain);
    for (k, (a, b)) in values.iter().zip(&plain).enumerate() {
        assert!(
            a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan()),
            "n = {N} f64: component {k} {a:e} differs from the plain kernel's {b:e} for {case:?}"
        );
    }
    let exact = exact_result(exact_case);
    compare(
        &values,
        &flatten(&bound),
        Some(&bound64.component_bounds(case)),
        &flatten(&exact),
        &mut seen[0],
        &format!("n = {N} f64 {case:?}"),
    );
    energy(&case.balls, &values, &bound, &flatten(&exact), "f64");
    // f32: the inputs as rounded, and their exact result.
    let Ok(c32) = case.to_f32() else { return };
    if validate(&c32.nu, c32.ball_refs(), c32.state_refs()).is_err() {
        return;
    }
    let (plain, (out, bound)) = if fma {
        (
            collide_unchecked_fma(&c32.nu, c32.ball_refs(), c32.state_refs()),
            collide_certified_fma_by(companion, &c32.nu, c32.ball_refs(), c32.state_refs()),
        )
    } else {
        (
            collide_unchecked(&c32.nu, c32.ball_refs(), c32.state_refs()),
            collide_certified_by(companion, &c32.nu, c32.ball_refs(), c32.state_refs()),
        )
    };
    let values: Vec<f32> = flatten(&out);
    let plain: Vec<f32> = flatten(&plain);
    for (k, (a, b)) in values.iter().zip(&plain).enumerate() {
        assert!(
            a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan()),
            "n = {N} f32: component {k} {a:e} differs from the plain kernel's {b:e} for {case:?}"
        );
    }
    let ran_on = c32.map(|&x| f64::from(x));
    let exact = exact_result(&ran_on.to_exact());
    let widen = |v: Vec<f32>| v.into_iter().map(f64::from).collect::<Vec<f64>>();
    let bound64: [BodyState<f64, N, S>; 2] = bound.clone().map(|b| BodyState {
        spin: b.spin.map(f64::from),
        velocity: b.velocity.map(f64::from),
    });
    energy(
        &ran_on.balls,
        &widen(values.clone()),
        &bound64,
        &flatten(&exact),
        "f32",
    );
    compare(
        &widen(values),
        &widen(flatten(&bound)),
        bound32.map(|b| b.component_bounds(&ran_on)).as_deref(),
        &flatten(&exact),
        &mut seen[1],
        &format!("n = {N} f32 {ran_on:?}"),
    );
}

/// Per body, `energy_error_bound` at least the body's error in its energy norm,
/// `|x^ - x|_E^2 = 2 lambda sum dU^2 + sum du^2` (`2 lambda = gamma2 R^2`), compared squared in
/// exact rationals.
fn energy<const N: usize, const S: usize>(
    balls: &[Ball<f64>; 2],
    values: &[f64],
    bound: &[BodyState<f64, N, S>; 2],
    exact: &[Exact],
    what: &str,
) {
    for b in 0..2 {
        let e = energy_error_bound(&balls[b], &bound[b]);
        if !e.is_finite() {
            continue;
        }
        let x = |v: f64| Exact::from_float(v).expect("finite");
        let two_lambda = x(balls[b].gamma2) * x(balls[b].radius) * x(balls[b].radius);
        let mut sq = x(0.0);
        for k in 0..S + N {
            let i = b * (S + N) + k;
            let d = x(values[i]) - &exact[i];
            let d2 = &d * &d;
            sq = if k < S {
                sq + &two_lambda * &d2
            } else {
                sq + d2
            };
        }
        assert!(
            sq <= x(e) * x(e),
            "n = {N} {what}: body {} energy-norm error above energy_error_bound {e:e}",
            b + 1
        );
    }
}

fn compare(
    values: &[f64],
    bounds: &[f64],
    interpreter: Option<&[f64]>,
    exact: &[Exact],
    seen: &mut CertSeen,
    what: &str,
) {
    seen.cases += 1;
    for k in 0..values.len() {
        // No interpreter bound to compare with: NaN, counted nowhere.
        let (e, i) = (bounds[k], interpreter.map_or(f64::NAN, |b| b[k]));
        assert!(e >= 0.0, "{what}: component {k} has a bound {e}");
        if i.is_infinite() {
            seen.infinite_interpreter += 1;
        }
        if e.is_infinite() {
            seen.infinite += 1;
            continue;
        }
        assert!(
            values[k].is_finite(),
            "{what}: component {k} is {} with a finite bound {e:e}",
            values[k]
        );
        seen.components += 1;
        let err = (Exact::from_float(values[k]).expect("finite") - &exact[k]).abs();
        assert!(
            err <= Exact::from_float(e).expect("finite"),
            "{what}: component {k} computed {:e}, exact {:e}, error above the companion's bound {e:e}",
            values[k],
            exact[k].to_f64()
        );
        let measured = err.to_f64();
        if measured > 0.0 {
            seen.over_measured.push(e / measured);
            seen.worst = seen.worst.max(measured / e);
        }
        if i.is_finite() && i > 0.0 && e > 0.0 {
            seen.over_interpreter.push(e / i);
        }
    }
}

/// No bound where none holds: a non-finite input (an infinite velocity, a NaN radius read as
/// a divisor) gives `+inf` for every output that reads it, and so does a vanishing divisor
/// (two movable point masses: `D = 0`); a finite case gives finite bounds.
#[test]
fn non_finite_inputs_and_a_zero_divisor_give_infinite_bounds() {
    use collision_core::kernels::d3;
    use collision_core::{Ball, BodyState};
    let ball = |w: f64, r: f64, g: f64| Ball {
        inv_mass: w,
        radius: r,
        gamma2: g,
    };
    let state = BodyState::<f64, 3, 3> {
        spin: [0.3, -0.2, 0.1],
        velocity: [0.5, 0.25, -1.0],
    };
    let rest = BodyState::<f64, 3, 3> {
        spin: [0.0; 3],
        velocity: [0.0; 3],
    };
    let nu = [0.0, 0.0, 1.0];
    let all = |b: &[BodyState<f64, 3, 3>; 2]| flatten(b);
    let (b1, b2) = (ball(1.0, 1.0, 0.4), ball(0.5, 2.0, 0.3));
    let (_, bound) = d3::certified::free(&nu, &b1, &b2, &state, &rest);
    assert!(all(&bound).iter().all(|e| e.is_finite() && *e > 0.0));
    let mut fast = state.clone();
    fast.velocity[0] = f64::INFINITY;
    let (_, bound) = d3::certified::free(&nu, &b1, &b2, &fast, &rest);
    assert!(all(&bound).iter().all(|e| *e == f64::INFINITY), "{bound:?}");
    let (_, bound) = d3::certified::fixed(&nu, &1.0, &ball(0.5, f64::NAN, 0.3), &state, &rest);
    let e: Vec<f64> = bound.spin.iter().chain(&bound.velocity).copied().collect();
    assert!(e.iter().all(|e| *e == f64::INFINITY), "{bound:?}");
    let (p1, p2) = (ball(1.0, 1.0, 0.0), ball(0.5, 2.0, 0.0));
    let (_, bound) = d3::certified::free(&nu, &p1, &p2, &state, &rest);
    assert!(all(&bound).contains(&f64::INFINITY), "{bound:?}");
    // The fast companions: the same cases.
    let (_, bound) = d3::certified::free_fast(&nu, &b1, &b2, &state, &rest);
    assert!(all(&bound).iter().all(|e| e.is_finite() && *e > 0.0));
    let (_, bound) = d3::certified::free_fast(&nu, &b1, &b2, &fast, &rest);
    assert!(all(&bound).iter().all(|e| *e == f64::INFINITY), "{bound:?}");
    let (_, bound) = d3::certified::fixed_fast(&nu, &1.0, &ball(0.5, f64::NAN, 0.3), &state, &rest);
    let e: Vec<f64> = bound.spin.iter().chain(&bound.velocity).copied().collect();
    assert!(e.iter().all(|e| *e == f64::INFINITY), "{bound:?}");
    let (_, bound) = d3::certified::free_fast(&nu, &p1, &p2, &state, &rest);
    assert!(all(&bound).contains(&f64::INFINITY), "{bound:?}");
    // The FMA kernels' companions, both kinds: the same cases.
    type Free3 = fn(
        &[f64; 3],
        &Ball<f64>,
        &Ball<f64>,
        &BodyState<f64, 3, 3>,
        &BodyState<f64, 3, 3>,
    ) -> ([BodyState<f64, 3, 3>; 2], [BodyState<f64, 3, 3>; 2]);
    let fma: [Free3; 2] = [d3::certified::free_fma, d3::certified::free_fma_fast];
    for f in fma {
        let (_, bound) = f(&nu, &b1, &b2, &state, &rest);
        assert!(all(&bound).iter().all(|e| e.is_finite() && *e > 0.0));
        let (_, bound) = f(&nu, &b1, &b2, &fast, &rest);
        assert!(all(&bound).iter().all(|e| *e == f64::INFINITY), "{bound:?}");
        let (_, bound) = f(&nu, &p1, &p2, &state, &rest);
        assert!(all(&bound).contains(&f64::INFINITY), "{bound:?}");
    }
    for f in [d3::certified::fixed_fma, d3::certified::fixed_fma_fast] {
        let (_, bound) = f(&nu, &1.0, &ball(0.5, f64::NAN, 0.3), &state, &rest);
        let e: Vec<f64> = bound.spin.iter().chain(&bound.velocity).copied().collect();
        assert!(e.iter().all(|e| *e == f64::INFINITY), "{bound:?}");
    }
    // A rho at or above 2^-10, or NaN, gives +inf bounds on the rounded-input companions.
    use collision_core::certified::InputRounding;
    for rho in [
        InputRounding::normalised(3),
        InputRounding {
            nu: 1.0 / 1024.0,
            gamma2: 0.0,
        },
        InputRounding {
            nu: 0.0,
            gamma2: f64::NAN,
        },
    ] {
        let (_, bound) = d3::certified::free_rounded(&nu, &b1, &b2, &state, &rest, &rho);
        let finite = rho == InputRounding::normalised(3);
        assert_eq!(
            all(&bound).iter().all(|e| e.is_finite()),
            finite,
            "{rho:?}: {bound:?}"
        );
    }
    // A divisor that cancels (a negative inverse mass, which `collide` refuses): `+inf`.
    let (_, bound) = d3::certified::free_fast(&nu, &b1, &ball(-0.999, 2.0, 0.3), &state, &rest);
    assert!(all(&bound).contains(&f64::INFINITY), "{bound:?}");
}
