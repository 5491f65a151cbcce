//! The rules: how an enclosure of the exact value and bounds on the absolute and relative
//! error pass through one operation of a kernel ([`crate::program::Op`]).
//!
//! Each value `x` of the kernel (an input, a constant, a step) carries an interval `[x]`
//! holding its exact value `x` (the DAG evaluated exactly on the real inputs), a number
//! `e_x >= |x^ - x|`, where `x^` is the value the float kernel computes, and a number
//! `r_x >= |x^ - x| / |x|` (infinite when not known). Write `X = max |[x]|`,
//! `m(x) = min |[x]|`, and `rnd(s)` for the rounding of a real of magnitude at most `s`
//! ([`super::Format::rounding`]: `u 2^floor(log2 s)`, at least `u 2^e_min`; infinite where
//! it could overflow).
//!
//! **Before rounding**, the operation applied to the computed operands differs from the
//! exact one by at most `E` (absolute) and `R` (relative):
//!
//! ```text
//! a +- b        E = e_a + e_b                        R = max(r_a, r_b) if the two terms have one sign
//! a * b         E = A e_b + B e_a + e_a e_b          R = r_a + r_b + r_a r_b
//! a / b         E = (e_a + |[a/b]| e_b) / (m(b) - e_b)   R = (r_a + r_b) / (1 - r_b)
//! fma(a, b, c)  E = A e_b + B e_a + e_a e_b + e_c     R as for the sum of the product and c
//! -a            E = e_a                              R = r_a
//! ```
//!
//! (the division: `a^/b^ - a/b = (eps_a - (a/b) eps_b) / b^`, `|b^| >= |b| - e_b`; `E` is
//! infinite unless `m(b) > e_b`). Each also gives the other: `R <= E / m`, `E <= R X`.
//! **The rounding** of a result of magnitude at most `s = min(X + E, X (1 + R))` adds
//! `rnd(s)` to `E` (nothing for a product by an exact constant `+-2^k`, `k >= 0`), and turns
//! `R` into `R + u + R u` when the result is at least `2^e_min` in magnitude (the standard
//! model `(1 + delta)`, `|delta| <= u`, holds in the normal range), else into the bound
//! derived from `E`. An `s` reaching the largest finite value makes both infinite.
//!
//! The relative bounds keep a box's bound tight through the kernels' quotients (`D`,
//! `p_t`, `rho_i` have relative errors of a few `u` whatever the box), where the absolute
//! rule alone would divide the numerator's largest error by the divisor's smallest value.
//! Every sum and product in the rules is rounded upward ([`super::round`]), and every
//! interval outward, so no rule's own arithmetic underestimates.

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
    /// At least `|computed - exact| / |exact|` (`+inf` when not known).
    pub relative: f64,
}

impl Enclosed {
    /// A value with no error.
    pub fn exact(value: Interval) -> Enclosed {
        Enclosed {
            value,
            error: 0.0,
            relative: 0.0,
        }
    }

    /// A value with absolute error at most `error` and relative error at most `relative`,
    /// each tightened by the other.
    pub fn new(value: Interval, error: f64, relative: f64) -> Enclosed {
        let mut e = Enclosed {
            value,
            error,
            relative,
        };
        e.tighten();
        e
    }

    fn tighten(&mut self) {
        let (mag, mig) = (self.value.mag(), self.value.mig());
        if self.error.is_nan() || self.relative.is_nan() {
            self.error = f64::INFINITY;
            self.relative = f64::INFINITY;
            return;
        }
        if self.relative.is_finite() {
            self.error = self.error.min(mul_up(self.relative, mag));
        }
        if mig > 0.0 && self.error.is_finite() {
            self.relative = self.relative.min(div_up(self.error, mig));
        }
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
    /// `sqrt(a)`.
    Sqrt(usize),
    /// `if x < y { a } else { b }`.
    SelectLt([usize; 4]),
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
                    Enclosed::new(value, format.rounding(value.mag()), f64::INFINITY)
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
                Op::Sqrt(a) => Rule::Sqrt(at(a)),
                Op::SelectLt(ids) => Rule::SelectLt(ids.each_ref().map(&at)),
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

    /// The table indices of the outputs, body by body (spin entries, then velocity).
    pub(crate) fn output_indices(&self) -> Vec<usize> {
        self.outputs
            .iter()
            .flat_map(|(_, spin, velocity)| spin.iter().chain(velocity))
            .copied()
            .collect()
    }

    /// Every value of the table for the given inputs (in [`Compiled::inputs`] order).
    pub(crate) fn run(&self, format: Format, inputs: &[Enclosed]) -> Vec<Enclosed> {
        assert_eq!(inputs.len(), self.inputs.len(), "one range per input");
        let mut v: Vec<Enclosed> = Vec::with_capacity(self.exact_scale.len());
        v.extend_from_slice(inputs);
        v.extend_from_slice(&self.constants);
        for rule in &self.rules {
            let next = match *rule {
                Rule::Add(a, b) => {
                    let value = v[a].value + v[b].value;
                    let same = one_sign(v[a].value, v[b].value);
                    sum(format, v[a], v[b], value, same)
                }
                Rule::Sub(a, b) => {
                    let value = v[a].value - v[b].value;
                    let same = one_sign(v[a].value, -v[b].value);
                    sum(format, v[a], v[b], value, same)
                }
                Rule::Neg(a) => Enclosed {
                    value: -v[a].value,
                    ..v[a]
                },
                Rule::Mul(a, b) => {
                    let value = v[a].value * v[b].value;
                    let exact = self.exact_scale[a] || self.exact_scale[b];
                    let (e, r) = product_error(v[a], v[b]);
                    rounded(format, value, e, r, exact)
                }
                Rule::Div(a, b) => quotient(format, v[a], v[b]),
                Rule::Fused(a, b, c, sign) => {
                    let p = v[a].value * v[b].value;
                    let (value, same) = match sign {
                        FusedSign::MulAdd => (p + v[c].value, one_sign(p, v[c].value)),
                        FusedSign::MulSub => (p - v[c].value, one_sign(p, -v[c].value)),
                        FusedSign::NegMulAdd => (v[c].value - p, one_sign(-p, v[c].value)),
                    };
                    let (pe, pr) = product_error(v[a], v[b]);
                    let e = add_up(pe, v[c].error);
                    let r = if same {
                        pr.max(v[c].relative)
                    } else {
                        f64::INFINITY
                    };
                    rounded(format, value, e, r, false)
                }
                Rule::Sqrt(a) => root(format, v[a]),
                Rule::SelectLt([x, y, a, b]) => select(v[x], v[y], v[a], v[b]),
            };
            v.push(next);
        }
        v
    }
}

/// Whether every element of `a` and of `b` has one sign (so `|a + b| = |a| + |b|`).
fn one_sign(a: Interval, b: Interval) -> bool {
    (a.lo >= 0.0 && b.lo >= 0.0) || (a.hi <= 0.0 && b.hi <= 0.0)
}

/// The result of an operation with error `e` (absolute) and `r` (relative) before its
/// rounding, rounded once (or not at all when `exact`): see the module docs.
fn rounded(format: Format, value: Interval, e: f64, r: f64, exact: bool) -> Enclosed {
    let pre = Enclosed::new(value, e, r);
    let (mag, mig) = (value.mag(), value.mig());
    let s = add_up(mag, pre.error).min(mul_up(mag, add_up(1.0, pre.relative)));
    if s.is_nan() || s >= format.max() {
        return Enclosed::new(value, f64::INFINITY, f64::INFINITY);
    }
    if exact {
        return pre;
    }
    let error = add_up(pre.error, format.rounding(s));
    // The smallest magnitude the rounded operand can have.
    let low = sub_down(mig, pre.error).max(mul_down_nonneg(mig, sub_down(1.0, pre.relative)));
    let u = format.unit_roundoff();
    let relative = if low >= 2f64.powi(format.min_exponent) {
        add_up(add_up(pre.relative, u), mul_up(pre.relative, u))
    } else {
        f64::INFINITY
    };
    Enclosed::new(value, error, relative)
}

/// Lower bound of `a b` for `a >= 0`, or 0 when `b < 0`.
fn mul_down_nonneg(a: f64, b: f64) -> f64 {
    if b <= 0.0 {
        0.0
    } else {
        super::round::down(a * b).max(0.0)
    }
}

/// `a +- b` (the enclosure given), `same`: whether the two terms have one sign.
fn sum(format: Format, a: Enclosed, b: Enclosed, value: Interval, same: bool) -> Enclosed {
    let e = add_up(a.error, b.error);
    let r = if same {
        a.relative.max(b.relative)
    } else {
        f64::INFINITY
    };
    rounded(format, value, e, r, false)
}

/// `|a^ b^ - a b| <= A e_b + B e_a + e_a e_b`, relative `r_a + r_b + r_a r_b`.
fn product_error(a: Enclosed, b: Enclosed) -> (f64, f64) {
    let r = add_up(
        add_up(a.relative, b.relative),
        mul_up(a.relative, b.relative),
    );
    if a.error == 0.0 && b.error == 0.0 {
        return (0.0, r);
    }
    let cross = add_up(
        mul_up(a.value.mag(), b.error),
        mul_up(b.value.mag(), a.error),
    );
    (add_up(cross, mul_up(a.error, b.error)), r)
}

/// `sqrt(a)`: `sqrt(a (1 + d)) = sqrt(a) sqrt(1 + d)` and `|sqrt(1 + d) - 1| <= |d|` for
/// `|d| <= 1`, so `R = r_a` before the rounding (infinite unless `r_a <= 1`); and
/// `|sqrt(x) - sqrt(y)| <= sqrt(|x - y|)`, so `E = sqrt(e_a)`. The exact argument is taken to
/// be `>= 0` (the Walton kernels' one root is of a ratio of squares), so an enclosure's lower
/// end below 0 (outward rounding around 0) is raised to 0; an enclosure wholly below 0 gives
/// no bound.
fn root(format: Format, a: Enclosed) -> Enclosed {
    if a.value.hi < 0.0 || !a.value.is_bounded() {
        return Enclosed::new(a.value, f64::INFINITY, f64::INFINITY);
    }
    let value = Interval::new(
        super::round::sqrt_down(a.value.lo.max(0.0)),
        super::round::sqrt_up(a.value.hi),
    );
    let r = if a.relative <= 1.0 {
        a.relative
    } else {
        f64::INFINITY
    };
    rounded(format, value, super::round::sqrt_up(a.error), r, false)
}

/// `if x < y { a } else { b }` (no rounding): when the enclosures and errors of `x` and `y`
/// decide the comparison for the computed and the exact values alike, the chosen operand;
/// otherwise either may be computed and either be exact, so the value is the hull and the
/// error at most the larger operand error plus the hull's width.
fn select(x: Enclosed, y: Enclosed, a: Enclosed, b: Enclosed) -> Enclosed {
    let below = add_up(add_up(x.value.hi, x.error), y.error) < y.value.lo;
    let above = sub_down(sub_down(x.value.lo, x.error), y.error) >= y.value.hi;
    if below {
        return a;
    }
    if above {
        return b;
    }
    let hull = Interval::new(a.value.lo.min(b.value.lo), a.value.hi.max(b.value.hi));
    let width = super::round::up(hull.hi - hull.lo);
    Enclosed::new(hull, add_up(a.error.max(b.error), width), f64::INFINITY)
}

/// `a / b`: see the module docs.
fn quotient(format: Format, a: Enclosed, b: Enclosed) -> Enclosed {
    let value = a.value / b.value;
    if !value.is_bounded() {
        return Enclosed::new(value, f64::INFINITY, f64::INFINITY);
    }
    let room = sub_down(b.value.mig(), b.error);
    let e = if room > 0.0 {
        div_up(add_up(a.error, mul_up(value.mag(), b.error)), room)
    } else {
        f64::INFINITY
    };
    let below = sub_down(1.0, b.relative);
    let r = if below > 0.0 {
        div_up(add_up(a.relative, b.relative), below)
    } else {
        f64::INFINITY
    };
    rounded(format, value, e, r, false)
}
