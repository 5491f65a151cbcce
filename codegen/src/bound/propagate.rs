//! The rules: how an enclosure of the exact value and a bound on the absolute error pass
//! through one operation of a kernel ([`crate::program::Op`]).
//!
//! Each value `x` of the kernel (an input, a constant, a step) carries an interval `[x]`
//! holding its exact value `x` (the DAG evaluated exactly on the real inputs) and a number
//! `e_x >= |x^ - x|`, where `x^` is the value the float kernel computes. Write `X = max |[x]|`,
//! and `r(s)` for the rounding of a real of magnitude at most `s`
//! ([`super::Format::rounding`]: `u 2^floor(log2 s)`, at least `u 2^e_min`, infinite where
//! it could overflow). Then, with `s` the bound on the magnitude of the exact operation on
//! the computed operands:
//!
//! ```text
//! a +- b        e = e_a + e_b + r(s),                 s = |[a +- b]| + e_a + e_b
//! a * b         e = A e_b + B e_a + e_a e_b + r(s),   s = |[a b]| + A e_b + B e_a + e_a e_b
//!               (r = 0 when a or b is an exact constant +-2^k, k >= 0)
//! a / b         e = q + r(s),  q = (e_a + |[a/b]| e_b) / (min |[b]| - e_b),  s = |[a/b]| + q
//!               (infinite unless min |[b]| > e_b)
//! fma(a, b, c)  e = A e_b + B e_a + e_a e_b + e_c + r(s)   (one rounding), likewise
//! -a            e = e_a
//! ```
//!
//! The division rule: `a^/b^ - a/b = (eps_a - (a/b) eps_b) / b^` with `|b^| >= |b| - e_b`.
//! Every sum and product above is rounded upward ([`super::round`]), and every interval
//! outward, so no rule's own arithmetic underestimates.

use super::format::Format;
use super::round::{add_up, div_up, mul_up, sub_down, Interval};
use crate::program::{Op, Operand, Program};
use std::collections::HashMap;

/// A value of the kernel: an enclosure of its exact value and a bound on the absolute error
/// of the computed one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Enclosed {
    /// Holds the exact value.
    pub value: Interval,
    /// At least `|computed - exact|`.
    pub error: f64,
}

impl Enclosed {
    /// A value with no error.
    pub fn exact(value: Interval) -> Enclosed {
        Enclosed { value, error: 0.0 }
    }
}

/// An operation with operands as indices into the value table (inputs, constants, steps).
#[derive(Clone, Copy, Debug)]
pub(crate) enum Rule {
    Add(usize, usize),
    Sub(usize, usize),
    Mul(usize, usize),
    Div(usize, usize),
    Neg(usize),
    /// `a b + c`, `a b - c`, `c - a b`: the sign only matters for the enclosure.
    Fused(usize, usize, usize, FusedSign),
}

/// Which fused form.
#[derive(Clone, Copy, Debug)]
pub(crate) enum FusedSign {
    MulAdd,
    MulSub,
    NegMulAdd,
}

/// A program compiled to [`Rule`]s over one flat table: inputs, then constants, then steps.
#[derive(Clone, Debug)]
pub(crate) struct Compiled {
    pub(crate) inputs: Vec<String>,
    pub(crate) constants: Vec<Enclosed>,
    /// Constants whose multiplication is exact (`+-2^k`, `k >= 0`), by table index.
    pub(crate) exact_scale: Vec<bool>,
    pub(crate) rules: Vec<Rule>,
    pub(crate) outputs: Vec<(usize, Vec<usize>, Vec<usize>)>,
}

impl Compiled {
    pub(crate) fn new(program: &Program, format: Format) -> Compiled {
        let inputs: Vec<String> = program.inputs.iter().cloned().collect();
        let index: HashMap<&str, usize> = inputs
            .iter()
            .enumerate()
            .map(|(k, s)| (s.as_str(), k))
            .collect();
        let (ni, nc) = (inputs.len(), program.constants.len());
        let at = |x: &Operand| match x {
            Operand::Input(name) => index[name.as_str()],
            Operand::Const(k) => ni + k,
            Operand::Step(k) => ni + nc + k,
        };
        let mut exact_scale = vec![false; ni + nc + program.steps.len()];
        let constants = program
            .constants
            .iter()
            .enumerate()
            .map(|(k, c)| {
                let (f, exact) = format.round_constant(&c.value);
                exact_scale[ni + k] = exact && Format::scales_exactly(&c.value);
                if exact {
                    Enclosed::exact(Interval::point(f))
                } else {
                    let value = Interval::new(super::round::down(f), super::round::up(f));
                    Enclosed {
                        value,
                        error: format.rounding(value.mag()),
                    }
                }
            })
            .collect();
        let rules = program
            .steps
            .iter()
            .map(|s| match &s.op {
                Op::Add(a, b) => Rule::Add(at(a), at(b)),
                Op::Sub(a, b) => Rule::Sub(at(a), at(b)),
                Op::Mul(a, b) => Rule::Mul(at(a), at(b)),
                Op::Div(a, b) => Rule::Div(at(a), at(b)),
                Op::Neg(a) => Rule::Neg(at(a)),
                Op::MulAdd(a, b, c) => Rule::Fused(at(a), at(b), at(c), FusedSign::MulAdd),
                Op::MulSub(a, b, c) => Rule::Fused(at(a), at(b), at(c), FusedSign::MulSub),
                Op::NegMulAdd(a, b, c) => Rule::Fused(at(a), at(b), at(c), FusedSign::NegMulAdd),
            })
            .collect();
        let outputs = program
            .outputs
            .iter()
            .map(|o| {
                (
                    o.body,
                    o.spin.iter().map(at).collect(),
                    o.velocity.iter().map(at).collect(),
                )
            })
            .collect();
        Compiled {
            inputs,
            constants,
            exact_scale,
            rules,
            outputs,
        }
    }

    /// Every value of the table for the given inputs (in [`Compiled::inputs`] order).
    pub(crate) fn run(&self, format: Format, inputs: &[Enclosed]) -> Vec<Enclosed> {
        assert_eq!(inputs.len(), self.inputs.len(), "one range per input");
        let mut v: Vec<Enclosed> = Vec::with_capacity(self.exact_scale.len());
        v.extend_from_slice(inputs);
        v.extend_from_slice(&self.constants);
        for rule in &self.rules {
            let next = match *rule {
                Rule::Add(a, b) => sum(format, v[a], v[b], v[a].value.add(v[b].value)),
                Rule::Sub(a, b) => sum(format, v[a], v[b], v[a].value.sub(v[b].value)),
                Rule::Neg(a) => Enclosed {
                    value: v[a].value.neg(),
                    error: v[a].error,
                },
                Rule::Mul(a, b) => {
                    let value = v[a].value.mul(v[b].value);
                    let e = product_error(v[a], v[b]);
                    let s = add_up(value.mag(), e);
                    let exact = self.exact_scale[a] || self.exact_scale[b];
                    // An exact scaling rounds only if it overflows.
                    let r = match (exact, s < format.max()) {
                        (true, true) => 0.0,
                        (true, false) => f64::INFINITY,
                        (false, _) => format.rounding(s),
                    };
                    Enclosed {
                        value,
                        error: add_up(e, r),
                    }
                }
                Rule::Div(a, b) => quotient(format, v[a], v[b]),
                Rule::Fused(a, b, c, sign) => {
                    let p = v[a].value.mul(v[b].value);
                    let value = match sign {
                        FusedSign::MulAdd => p.add(v[c].value),
                        FusedSign::MulSub => p.sub(v[c].value),
                        FusedSign::NegMulAdd => v[c].value.sub(p),
                    };
                    let e = add_up(product_error(v[a], v[b]), v[c].error);
                    let s = add_up(value.mag(), e);
                    Enclosed {
                        value,
                        error: add_up(e, format.rounding(s)),
                    }
                }
            };
            v.push(next);
        }
        v
    }
}

/// `a +- b`, given the enclosure of the exact result.
fn sum(format: Format, a: Enclosed, b: Enclosed, value: Interval) -> Enclosed {
    let e = add_up(a.error, b.error);
    let s = add_up(value.mag(), e);
    Enclosed {
        value,
        error: add_up(e, format.rounding(s)),
    }
}

/// `|a^ b^ - a b| <= A e_b + B e_a + e_a e_b`.
fn product_error(a: Enclosed, b: Enclosed) -> f64 {
    if a.error == 0.0 && b.error == 0.0 {
        return 0.0;
    }
    let cross = add_up(
        mul_up(a.value.mag(), b.error),
        mul_up(b.value.mag(), a.error),
    );
    add_up(cross, mul_up(a.error, b.error))
}

/// `a / b`: see the module docs.
fn quotient(format: Format, a: Enclosed, b: Enclosed) -> Enclosed {
    let value = a.value.div(b.value);
    let room = sub_down(b.value.mig(), b.error);
    if !(room > 0.0) || !value.is_bounded() {
        return Enclosed {
            value,
            error: f64::INFINITY,
        };
    }
    let q = div_up(add_up(a.error, mul_up(value.mag(), b.error)), room);
    let s = add_up(value.mag(), q);
    Enclosed {
        value,
        error: add_up(q, format.rounding(s)),
    }
}
