use super::*;
use crate::model::Variant;

#[test]
fn every_plain_no_slip_kernel_has_a_companion_with_every_step_in_order() {
    for n in crate::DIMS {
        for v in Variant::ALL {
            for (f, arith) in [Format::F64, Format::F32, Format::F32Wide]
                .into_iter()
                .flat_map(|f| crate::Arith::ALL.map(|a| (f, a)))
            {
                let c = Certified::of(n, v, arith, f);
                let steps: Vec<usize> = c
                    .stmts
                    .iter()
                    .filter_map(|s| match s.expr {
                        Expr::Step(k) => Some(k),
                        _ => None,
                    })
                    .collect();
                assert_eq!(steps, (0..c.program.steps.len()).collect::<Vec<_>>());
                let outputs: usize = c.outputs.iter().map(|o| o.bounds.len()).sum();
                assert_eq!(outputs, c.outputs.len() * (n * (n - 1) / 2 + n));
                // Every statement reads only inputs and earlier bindings.
                let mut bound: std::collections::HashSet<String> =
                    c.program.inputs.iter().cloned().collect();
                for s in &c.stmts {
                    let args: Vec<&Arg> = match &s.expr {
                        Expr::Abs(a) | Expr::BoundOrInf(a) | Expr::Sqrt(a) => vec![a],
                        Expr::Add(a, b)
                        | Expr::Sub(a, b)
                        | Expr::Mul(a, b)
                        | Expr::Div(a, b)
                        | Expr::PositiveOr(a, b)
                        | Expr::AtLeast(a, b)
                        | Expr::AtMost(a, b) => vec![a, b],
                        Expr::GreaterOr(a, b, x, y) => vec![a, b, x, y],
                        Expr::Const(_) | Expr::Step(_) => vec![],
                    };
                    for a in args {
                        if let Arg::Name(x) = a {
                            assert!(bound.contains(x), "n = {n} {v:?}: {} reads {x}", s.name);
                        }
                    }
                    bound.insert(s.name.clone());
                }
            }
        }
    }
}

#[test]
fn the_inflation_factor_covers_the_lost_roundings() {
    // (1 - 2u)^d F(d) (1 - u) >= 1 for every depth the generator can reach (d <= DEPTH_LIMIT
    // + the deepest rule, 2 DEPTH_LIMIT + 4), through Bernoulli's (1 - 2u)^d >= 1 - 2du, in
    // exact rationals.
    use num_rational::BigRational;
    use num_traits::One;
    for f in [Format::F64, Format::F32] {
        let u = BigRational::from_float(f.unit_roundoff()).unwrap();
        let one = BigRational::one();
        let two = &one + &one;
        for d in [0u32, 1, 2, 7, 100, DEPTH_LIMIT, 2 * DEPTH_LIMIT + 4] {
            let factor = BigRational::from_float(f.inflation(d)).unwrap();
            let bernoulli = &one - &two * &u * BigRational::from_integer(d.into());
            assert!(bernoulli > BigRational::from_integer(0.into()));
            let p = &factor * (&one - &u) * bernoulli;
            assert!(p >= one, "{f:?} d = {d}");
        }
    }
}

/// `F32Wide`: the kernel's roundings in `f32` (`u s` at least the `f32` subnormal
/// half-spacing `2^-150`), the bound's products normal in `f64`.
#[test]
fn the_wide_floor_covers_f32_underflow_and_keeps_f64_products_normal() {
    let f = Format::F32Wide;
    let (u, s) = (f.unit_roundoff(), f.floor());
    assert_eq!(u, 2f64.powi(-24));
    assert!(u * s >= 2f64.powi(-150));
    assert!(s * s * u >= 2f64.powi(-1022));
    assert!(f.bound_in_f64() && !Format::F32.bound_in_f64());
}

#[test]
fn the_floor_makes_every_product_of_the_bound_normal() {
    for (f, e_min) in [(Format::F64, -1022), (Format::F32, -126)] {
        let (u, s) = (f.unit_roundoff(), f.floor());
        // m e >= s * u s is normal; u s is above the subnormal half-spacing 2^(e_min - p).
        assert!(s * s * u >= 2f64.powi(e_min));
        let p = -f.roundoff_exponent() - 1; // precision - 1
        assert!(u * s >= 2f64.powi(e_min - p - 1));
    }
}

#[test]
fn square_roots_are_refused_with_their_name() {
    let kernel = crate::model::build(3, Variant::Free);
    let mut program = Program::lower(&kernel, crate::Arith::Plain);
    let x = Operand::Input(program.inputs.iter().next().expect("inputs").clone());
    program.steps[0].op = Op::Sqrt(x);
    let err = Certified::derive(&program, Format::F64).unwrap_err();
    assert!(err.to_string().contains("square root"), "{err}");
}

/// The FMA kernels' companions bound every fused step with one rounding: a fused step's
/// bound reads the three operands' bounds and a single `u m_z`, and every fused step of the
/// program is there.
#[test]
fn the_fma_companions_bound_every_fused_step() {
    for v in Variant::ALL {
        let c = Certified::of(3, v, crate::Arith::Fma, Format::F64);
        let fused = c
            .program
            .steps
            .iter()
            .filter(|s| matches!(s.op, Op::MulAdd(..) | Op::MulSub(..) | Op::NegMulAdd(..)))
            .count();
        assert!(fused > 0, "{v:?}: no fused step");
        let plain = Certified::of(3, v, crate::Arith::Plain, Format::F64);
        // Fewer roundings, so fewer `u m_z` terms: fewer bound operations than the plain
        // companion, which has one more product per fused step.
        assert!(
            c.bound_ops < plain.bound_ops,
            "{} {}",
            c.bound_ops,
            plain.bound_ops
        );
    }
}

/// The rough-ball kernels (constant `(e, beta)`) have running companions in every
/// dimension, format and arithmetic, reading `e` and `beta`; so do the Walton kernels, their
/// selects bound through the clamped quotient (a decided-sticking test in the bound).
#[test]
fn the_rough_and_walton_kernels_have_companions() {
    for n in crate::DIMS {
        for v in Variant::ALL {
            for arith in crate::Arith::ALL {
                for f in [Format::F64, Format::F32] {
                    let c = Certified::of_rough(n, v, arith, f);
                    assert!(rust::is_rough(&c.program), "n = {n} {v:?}");
                    let steps = c
                        .stmts
                        .iter()
                        .filter(|s| matches!(s.expr, Expr::Step(_)))
                        .count();
                    assert_eq!(steps, c.program.steps.len());
                }
                let walton = Program::lower(&crate::walton::build_walton(n, v), arith);
                assert!(!rust::is_rough(&walton));
                for f in [Format::F64, Format::F32] {
                    let c = Certified::derive(&walton, f).expect("a clamped quotient");
                    // The two selects are bound through their quotient, not on their own.
                    let steps = c
                        .stmts
                        .iter()
                        .filter(|s| matches!(s.expr, Expr::Step(_)))
                        .count();
                    assert_eq!(steps, walton.steps.len());
                    assert!(c
                        .stmts
                        .iter()
                        .any(|s| matches!(s.expr, Expr::GreaterOr(..))));
                }
            }
        }
    }
}

/// A select used anywhere but in a clamped quotient is refused by name.
#[test]
fn a_select_outside_a_clamped_quotient_is_refused() {
    let mut program = Program::lower(
        &crate::walton::build_walton(2, Variant::Fixed),
        crate::Arith::Plain,
    );
    let k = program
        .steps
        .iter()
        .position(|s| matches!(s.op, Op::SelectLt(_)))
        .expect("a select");
    let user = program
        .steps
        .iter()
        .position(|s| matches!(s.op, Op::Div(..)) && s.name == "rho")
        .expect("the quotient rho");
    program.steps[user].op = Op::Add(Operand::Step(k), Operand::Step(k));
    let err = Certified::derive(&program, Format::F64).unwrap_err();
    assert!(err.0.contains("outside a clamped quotient"), "{err}");
}
