//! One unit spelled as a function of a C-family language, the same for every language but
//! for its hooks: the comment, the signature, the live inputs loaded from their arrays (an
//! array with none is cast to `void`), each constant as the correctly rounded literal of its
//! exact value, one `const` per step in schedule order, the outputs stored last.

use super::language::Language;
use super::precision::Precision;
use super::unit::{Param, Unit};
use crate::certify::step_expr;
use crate::program::{Operand, Program};
use num_rational::BigRational;
use std::fmt::Write;

/// A C literal of a finite float: the shortest decimal that reads back as exactly `x` in
/// its format (Rust's `{:e}`), so a correctly rounding compiler restores the same bits. Hex
/// floats would be exact by construction but are not C++ before C++17.
fn decimal_literal(x: impl std::fmt::LowerExp, finite: bool) -> String {
    assert!(finite, "a literal must be finite");
    format!("{x:e}")
}

/// The correctly rounded literal of an exact constant in precision `p`, exactly as the Rust
/// kernels round it (`T::from_ratio`, `T::from_literal`: [`crate::literal::nearest_floats`]).
pub fn constant_literal(value: &BigRational, p: Precision) -> String {
    let (x64, x32) = crate::literal::nearest_floats(value);
    match p {
        Precision::F64 => decimal_literal(x64, x64.is_finite()),
        Precision::F32 => format!("{}f", decimal_literal(x32, x32.is_finite())),
    }
}

fn operand(program: &Program, x: &Operand) -> String {
    program.name(x).to_string()
}

/// The length of an output array for dimension `n`: `S + N`.
fn state_len(n: usize) -> usize {
    n * (n - 1) / 2 + n
}

/// The function of `unit` in precision `p`, with its comment.
pub fn function(lang: &dyn Language, unit: &Unit, p: Precision) -> String {
    let ty = p.c_type();
    let program = &unit.program;
    let n = program.dim;
    let mut f = String::new();
    for line in &unit.doc {
        f.push_str(format!("// {line}").trim_end());
        f.push('\n');
    }
    let params: Vec<String> = unit
        .params
        .iter()
        .map(|param| match param {
            Param::Array(name, elems) => format!("const {ty} {name}[{}]", elems.len()),
            Param::Scalar(name) => format!("{ty} {name}"),
            Param::Out(name, _) => format!("{ty} {name}[{}]", state_len(n)),
        })
        .collect();
    let _ = writeln!(
        f,
        "{} void {}({})\n{{",
        lang.qualifiers(),
        unit.function_name(p),
        params.join(", ")
    );
    if !lang.body_prologue().is_empty() {
        let _ = writeln!(f, "    {}", lang.body_prologue());
    }
    for param in &unit.params {
        match param {
            Param::Array(name, elems) => {
                let mut any = false;
                for (k, e) in elems.iter().enumerate() {
                    if program.inputs.contains(e) {
                        any = true;
                        let _ = writeln!(f, "    const {ty} {e} = {name}[{k}];");
                    }
                }
                if !any {
                    let _ = writeln!(f, "    (void){name};");
                }
            }
            Param::Scalar(name) if !program.inputs.contains(name) => {
                let _ = writeln!(f, "    (void){name};");
            }
            Param::Scalar(_) | Param::Out(..) => {}
        }
    }
    for c in &program.constants {
        let _ = writeln!(
            f,
            "    const {ty} {} = {};",
            c.name,
            constant_literal(&c.value, p)
        );
    }
    for s in &program.steps {
        let _ = writeln!(
            f,
            "    const {ty} {} = {};",
            s.name,
            step_expr(program, &s.op, lang.fma(p), lang.sqrt(p), false)
        );
    }
    for param in &unit.params {
        if let Param::Out(name, body) = param {
            let out = program
                .outputs
                .iter()
                .find(|o| o.body == *body)
                .expect("the program returns this body");
            for (k, x) in out.spin.iter().chain(&out.velocity).enumerate() {
                let _ = writeln!(f, "    {name}[{k}] = {};", operand(program, x));
            }
        }
    }
    f.push_str("}\n");
    f
}

#[cfg(test)]
mod tests {
    use super::super::{c::C, units::generic_units};
    use super::*;

    #[test]
    fn literals_read_back_exactly() {
        let r = |p: i64, q: i64| BigRational::new(p.into(), q.into());
        assert_eq!(constant_literal(&r(2, 1), Precision::F64), "2e0");
        assert_eq!(constant_literal(&r(-1, 2), Precision::F32), "-5e-1f");
        for x in [r(1, 3), r(1, 10), r(-7, 3), r(1, 1 << 40)] {
            let (x64, x32) = crate::literal::nearest_floats(&x);
            let l64 = constant_literal(&x, Precision::F64);
            assert_eq!(
                l64.parse::<f64>().unwrap().to_bits(),
                x64.to_bits(),
                "{l64}"
            );
            let l32 = constant_literal(&x, Precision::F32);
            let l32 = l32.trim_end_matches('f');
            assert_eq!(
                l32.parse::<f32>().unwrap().to_bits(),
                x32.to_bits(),
                "{l32}"
            );
        }
    }

    #[test]
    fn every_step_is_one_statement_in_schedule_order() {
        for unit in generic_units(3) {
            let text = function(&C, &unit, Precision::F64);
            let mut at = 0;
            for s in &unit.program.steps {
                let line = format!("    const double {} = ", s.name);
                let found = text[at..]
                    .find(&line)
                    .unwrap_or_else(|| panic!("{}: {} missing or out of order", unit.name, s.name));
                at += found + line.len();
            }
            assert_eq!(
                text.matches(" fma(").count(),
                unit.program.ops.fma,
                "{}",
                unit.name
            );
        }
    }
}
