//! The bounds against the programs they bound: each lowered program is run in `f64` or `f32`
//! (the same operations in the same order as the emitted kernels, `fma` correctly rounded)
//! and in exact rationals, and every output's error is compared with its bound exactly.

use super::*;
use crate::program::{Op, Operand};
use num_rational::BigRational;
use num_traits::{FromPrimitive, Signed, Zero};

/// A deterministic generator (SplitMix64), so that the test needs no dependency.
struct Mix(u64);

impl Mix {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A float format's arithmetic, for running a [`Program`].
trait Arithmetic: Copy {
    fn of(x: f64) -> Self;
    fn to(self) -> f64;
    fn op(op: &Op, at: &dyn Fn(&Operand) -> Self) -> Self;
}

macro_rules! arithmetic {
    ($t:ty) => {
        impl Arithmetic for $t {
            fn of(x: f64) -> Self {
                x as $t
            }
            fn to(self) -> f64 {
                self as f64
            }
            fn op(op: &Op, at: &dyn Fn(&Operand) -> Self) -> Self {
                match op {
                    Op::Add(a, b) => at(a) + at(b),
                    Op::Sub(a, b) => at(a) - at(b),
                    Op::Mul(a, b) => at(a) * at(b),
                    Op::Div(a, b) => at(a) / at(b),
                    Op::Neg(a) => -at(a),
                    Op::MulAdd(a, b, c) => at(a).mul_add(at(b), at(c)),
                    Op::MulSub(a, b, c) => at(a).mul_add(at(b), -at(c)),
                    Op::NegMulAdd(a, b, c) => (-at(a)).mul_add(at(b), at(c)),
                    Op::Sqrt(a) => at(a).sqrt(),
                    Op::SelectLt([x, y, a, b]) => {
                        if at(x) < at(y) {
                            at(a)
                        } else {
                            at(b)
                        }
                    }
                }
            }
        }
    };
}
arithmetic!(f64);
arithmetic!(f32);

/// The program's outputs in the float type `F`, flattened body by body (spin, velocity).
fn run_float<F: Arithmetic>(p: &Program, input: &dyn Fn(&str) -> f64) -> Vec<f64> {
    let consts: Vec<F> = p
        .constants
        .iter()
        .map(|c| F::of(num_traits::ToPrimitive::to_f64(&c.value).unwrap()))
        .collect();
    let mut steps: Vec<F> = Vec::with_capacity(p.steps.len());
    for s in &p.steps {
        let at = |x: &Operand| match x {
            Operand::Input(name) => F::of(input(name)),
            Operand::Const(k) => consts[*k],
            Operand::Step(k) => steps[*k],
        };
        let v = F::op(&s.op, &at);
        steps.push(v);
    }
    let at = |x: &Operand| match x {
        Operand::Input(name) => F::of(input(name)).to(),
        Operand::Const(k) => consts[*k].to(),
        Operand::Step(k) => steps[*k].to(),
    };
    p.outputs
        .iter()
        .flat_map(|o| o.spin.iter().chain(&o.velocity).map(at).collect::<Vec<_>>())
        .collect()
}

/// The program's outputs in exact rationals.
fn run_exact(p: &Program, input: &dyn Fn(&str) -> f64) -> Vec<BigRational> {
    let q = |x: f64| BigRational::from_f64(x).expect("finite input");
    let mut steps: Vec<BigRational> = Vec::with_capacity(p.steps.len());
    for s in &p.steps {
        let at = |x: &Operand| match x {
            Operand::Input(name) => q(input(name)),
            Operand::Const(k) => p.constants[*k].value.clone(),
            Operand::Step(k) => steps[*k].clone(),
        };
        let v = match &s.op {
            Op::Add(a, b) => at(a) + at(b),
            Op::Sub(a, b) => at(a) - at(b),
            Op::Mul(a, b) => at(a) * at(b),
            Op::Div(a, b) => at(a) / at(b),
            Op::Neg(a) => -at(a),
            Op::MulAdd(a, b, c) => at(a) * at(b) + at(c),
            Op::MulSub(a, b, c) => at(a) * at(b) - at(c),
            Op::NegMulAdd(a, b, c) => at(c) - at(a) * at(b),
            Op::Sqrt(a) => crate::ir::rational_sqrt(&at(a)).expect("a rational root"),
            Op::SelectLt([x, y, a, b]) => {
                if at(x) < at(y) {
                    at(a)
                } else {
                    at(b)
                }
            }
        };
        steps.push(v);
    }
    let at = |x: &Operand| match x {
        Operand::Input(name) => q(input(name)),
        Operand::Const(k) => p.constants[*k].value.clone(),
        Operand::Step(k) => steps[*k].clone(),
    };
    p.outputs
        .iter()
        .flat_map(|o| o.spin.iter().chain(&o.velocity).map(at).collect::<Vec<_>>())
        .collect()
}

/// A typical input of the report (`m = 2^U(-2,2)`, `R = 2^U(-1,1)`, `gamma2 = (2/n) U(0,1]`,
/// states `U(-1,1)`, a unit normal), scaled by `scale` for the states.
fn sample(n: usize, rng: &mut Mix, scale: f64, name: &str) -> f64 {
    match name {
        // The Walton law's parameters: `mu` is set by the caller ([`check_with`]).
        "e" | "beta0" => rng.uniform(-1.0, 1.0).abs(),
        _ if name.starts_with("inv_mass") => 2f64.powf(rng.uniform(-2.0, 2.0)),
        _ if name.starts_with("radius") => 2f64.powf(rng.uniform(-1.0, 1.0)),
        _ if name.starts_with("gamma2") => 2.0 / n as f64 * (1.0 - rng.uniform(0.0, 1.0)),
        _ => scale * rng.uniform(-1.0, 1.0),
    }
}

/// Check every output of `program` in `format` at `cases` random points against the bound
/// of the point box and of the enclosing `box_of` box; returns the largest ratio
/// error / point bound seen.
fn check(program: &Program, format: Format, cases: usize, seed: u64, scale: f64) -> f64 {
    check_with(program, format, cases, seed, scale, &[])
}

/// A random input point of `kb` ([`sample`], a rounded unit normal, in `format`), with the
/// inputs `fixed` set to the values given.
fn draw_point(
    kb: &KernelBound,
    format: Format,
    rng: &mut Mix,
    scale: f64,
    fixed: &[(&str, f64)],
) -> std::collections::HashMap<String, f64> {
    let n = kb.dim;
    let mut values: std::collections::HashMap<String, f64> = kb
        .inputs()
        .iter()
        .map(|name| (name.clone(), sample(n, rng, scale, name)))
        .collect();
    for &(name, x) in fixed {
        values.insert(name.to_string(), x);
    }
    // A unit normal (rounded): normalise the nu components.
    let norm = (0..n)
        .map(|k| values[&format!("nu_{k}")].powi(2))
        .sum::<f64>()
        .sqrt();
    for k in 0..n {
        let x = values.get_mut(&format!("nu_{k}")).unwrap();
        *x /= norm;
    }
    if format == Format::F32 {
        values.values_mut().for_each(|x| *x = f64::from(*x as f32));
    }
    values
}

/// Every output's computed value in `format` and its exact value at the point `values`.
fn computed_and_exact(
    program: &Program,
    format: Format,
    values: &std::collections::HashMap<String, f64>,
) -> (Vec<f64>, Vec<BigRational>) {
    let input = |name: &str| values[name];
    let computed = match format.precision {
        24 => run_float::<f32>(program, &input),
        _ => run_float::<f64>(program, &input),
    };
    (computed, run_exact(program, &input))
}

/// [`check`] with the inputs `fixed` set to the values given.
fn check_with(
    program: &Program,
    format: Format,
    cases: usize,
    seed: u64,
    scale: f64,
    fixed: &[(&str, f64)],
) -> f64 {
    let kb = KernelBound::new(program, format);
    let mut rng = Mix(seed);
    let mut worst: f64 = 0.0;
    for _ in 0..cases {
        let values = draw_point(&kb, format, &mut rng, scale, fixed);
        let (computed, exact) = computed_and_exact(program, format, &values);
        let bounds = kb.analyse_named(|name| InputRange::point(values[name]));
        let flat: Vec<&Enclosed> = bounds.bodies.iter().flat_map(|b| b.components()).collect();
        assert_eq!(flat.len(), exact.len());
        for ((c, y), e) in computed.iter().zip(&exact).zip(&flat) {
            let err = (BigRational::from_f64(*c).unwrap() - y).abs();
            let bound = BigRational::from_f64(e.error)
                .unwrap_or_else(|| panic!("no bound: {:?} at {values:?}", e));
            assert!(err <= bound, "error {c} vs {y}: bound {}", e.error);
            let lo = BigRational::from_f64(e.value.lo).unwrap();
            let hi = BigRational::from_f64(e.value.hi).unwrap();
            assert!(&lo <= y && y <= &hi, "enclosure");
            if !err.is_zero() {
                let r = num_traits::ToPrimitive::to_f64(&(err / bound)).unwrap();
                worst = worst.max(r);
            }
        }
    }
    worst
}

/// The mean-value bound (`adjoint.rs`) on its own, not through the smaller of the two that
/// [`KernelBound::analyse`] takes: at random points of three scales, for n = 2, 3, every
/// variant, plain and FMA, f64 and f32, every output's error is within it (exactly), it is
/// finite everywhere (these points have no vanishing divisor), and it is below the rules'
/// bound for most outputs (else it would add nothing).
#[test]
fn the_mean_value_bound_holds_on_its_own_and_is_mostly_the_tighter() {
    let (mut outputs, mut tighter) = (0, 0);
    for n in [2, 3] {
        for v in Variant::ALL {
            for arith in Arith::ALL {
                let p = Program::lower(&model::build(n, v), arith);
                for format in [Format::F64, Format::F32] {
                    let kb = KernelBound::new(&p, format);
                    let indices = kb.compiled.output_indices();
                    for (seed, scale) in [(11, 1.0), (12, 1e-30), (13, 1e30)] {
                        let mut rng = Mix(seed);
                        for _ in 0..10 {
                            let values = draw_point(&kb, format, &mut rng, scale, &[]);
                            let (computed, exact) = computed_and_exact(&p, format, &values);
                            let given: Vec<Enclosed> = kb
                                .inputs()
                                .iter()
                                .map(|name| Enclosed::exact(Interval::point(values[name])))
                                .collect();
                            let rules = kb.compiled.run(format, &given);
                            let second = adjoint::bounds(&kb.compiled, format, &given, &indices);
                            for (j, (c, y)) in computed.iter().zip(&exact).enumerate() {
                                let bound = BigRational::from_f64(second[j]).unwrap_or_else(|| {
                                    panic!("n = {n} {v:?} {arith:?}: no bound at {values:?}")
                                });
                                let err = (BigRational::from_f64(*c).unwrap() - y).abs();
                                assert!(
                                    err <= bound,
                                    "n = {n} {v:?} {arith:?} {format:?}: error {c} vs {y}, \
                                     mean-value bound {}",
                                    second[j]
                                );
                                outputs += 1;
                                tighter += usize::from(second[j] < rules[indices[j]].error);
                            }
                        }
                    }
                }
            }
        }
    }
    assert!(
        2 * tighter > outputs,
        "tighter on {tighter} of {outputs} outputs"
    );
}

#[test]
fn point_bounds_hold_for_every_small_kernel_and_format() {
    for n in [2, 3] {
        for v in Variant::ALL {
            for arith in Arith::ALL {
                let p = Program::lower(&model::build(n, v), arith);
                for format in [Format::F64, Format::F32] {
                    for (seed, scale) in [(1, 1.0), (2, 1e-30), (3, 1e30)] {
                        let worst = check(&p, format, 20, seed, scale);
                        // The bound is attained to within a modest factor somewhere.
                        assert!(worst > 0.0 && worst <= 1.0, "{n} {v:?} {arith:?} {worst}");
                    }
                }
            }
        }
    }
}

/// The rules of the Walton kernels' root and select hold where the exact root is rational:
/// `mu = 0` (a sliding contact has `rho = 0/L = 0`, a sticking one `1/1`) and `mu = 10^6`
/// (every contact sticks, `rho = 1`), both selects decided by the inputs' enclosures.
#[test]
fn point_bounds_hold_for_the_walton_kernels_where_the_root_is_rational() {
    for v in Variant::ALL {
        for arith in Arith::ALL {
            let p = Program::lower(&crate::walton::build_walton(3, v), arith);
            for format in [Format::F64, Format::F32] {
                for mu in [0.0, 1e6] {
                    let worst = check_with(&p, format, 20, 5, 1.0, &[("mu", mu)]);
                    assert!(
                        worst > 0.0 && worst <= 1.0,
                        "{v:?} {arith:?} mu = {mu}: {worst}"
                    );
                }
            }
        }
    }
}

#[test]
fn a_box_bound_covers_every_point_in_it() {
    let p = Program::lower(&model::build(2, Variant::Free), Arith::Plain);
    let kb = KernelBound::new(&p, Format::F64);
    let range = |name: &str| match name {
        _ if name.starts_with("inv_mass") => InputRange::range(0.25, 4.0),
        _ if name.starts_with("radius") => InputRange::range(0.5, 2.0),
        _ if name.starts_with("gamma2") => InputRange::range(0.01, 1.0),
        _ => InputRange::range(-1.0, 1.0),
    };
    let boxed = kb.analyse_named(range);
    let mut rng = Mix(9);
    for _ in 0..200 {
        let values: std::collections::HashMap<String, f64> = kb
            .inputs()
            .iter()
            .map(|name| {
                let r = range(name).value;
                (name.clone(), rng.uniform(r.lo, r.hi))
            })
            .collect();
        let point = kb.analyse_named(|name| InputRange::point(values[name]));
        for (b, q) in boxed.bodies.iter().zip(&point.bodies) {
            for (x, y) in b.components().zip(q.components()) {
                assert!(y.error <= x.error, "box bound below a point bound");
                assert!(x.value.lo <= y.value.lo && y.value.hi <= x.value.hi);
            }
        }
    }
}

#[test]
fn inputs_given_rounded_raise_the_bound() {
    let kb = KernelBound::of(2, Variant::Fixed, Arith::Plain, Format::F64);
    let exact = kb.analyse_named(|_| InputRange::point(0.5));
    let rounded = kb.analyse_named(|name| {
        let r = InputRange::point(0.5);
        if name.starts_with("nu") || name.starts_with("gamma2") {
            r.rounded(Format::F64.unit_roundoff())
        } else {
            r
        }
    });
    for (a, b) in exact.bodies[0]
        .components()
        .zip(rounded.bodies[0].components())
    {
        assert!(b.error > a.error);
    }
}

#[test]
fn possible_overflow_or_a_vanishing_divisor_gives_no_bound() {
    let kb = KernelBound::of(2, Variant::Free, Arith::Plain, Format::F32);
    // u_2 - u_1 = -6e38 is beyond f32's 3.4e38.
    let huge = kb.analyse_named(|name| {
        InputRange::point(match name {
            _ if name.starts_with("u1") => 3e38,
            _ if name.starts_with("u2") => -3e38,
            _ => 0.5,
        })
    });
    assert!(huge.bodies[0].velocity[0].error.is_infinite());
    // Both gamma2 ranges reaching 0: D = w_1 g_2 (1 + g_1) + w_2 g_1 (1 + g_2) can vanish.
    let kb = KernelBound::of(2, Variant::Free, Arith::Plain, Format::F64);
    let zero_d = kb.analyse_named(|name| {
        if name.starts_with("gamma2") {
            InputRange::range(0.0, 1.0)
        } else {
            InputRange::point(0.5)
        }
    });
    assert!(zero_d.bodies[0].spin[0].error.is_infinite());
}

#[test]
fn the_energy_norm_bound_is_the_componentwise_one_weighted() {
    let e = |error: f64, x: f64| Enclosed::new(Interval::point(x), error, f64::INFINITY);
    let b = BodyBound {
        body: 2,
        spin: vec![e(3.0, 1.0)],
        velocity: vec![e(4.0, 0.0), e(0.0, 2.0)],
    };
    // lambda = 1/2: weight 1 on the spin; |E| = 5, |x| = sqrt(1 + 4).
    assert!((b.energy_error(0.5) - 5.0).abs() < 1e-14 && b.energy_error(0.5) >= 5.0);
    let r = b.relative_energy_error(0.5);
    assert!(r >= 5.0 / 5f64.sqrt() && r < 5.0 / 5f64.sqrt() * (1.0 + 1e-14));
    let zero = BodyBound {
        body: 2,
        spin: vec![e(1.0, 0.0)],
        velocity: vec![],
    };
    assert!(zero.relative_energy_error(0.5).is_infinite());
}
