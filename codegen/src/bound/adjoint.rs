//! A second proven bound, by the mean value theorem along the roundings: the first-order
//! error terms with their true propagation factors (adjoints), which [`super::propagate`]'s
//! rules can only bound by magnitudes, path by path.
//!
//! **The parametrisation.** Write each rounded step `k` of the kernel as `v_k = z_k + t_k`:
//! `z_k` the operation applied to the step's operands as computed, `t_k` its rounding. Each
//! input and rounded constant is `v = x + t` likewise (`t` the caller's rounding of the input,
//! or the constant's). The outputs are then a function `y = F(t)` of the vector `t`
//! (for fixed real inputs), `F(0)` is the exact map and `F(t*)` the computed result, `t*`
//! the actual roundings.
//!
//! **The box of roundings.** Evaluate the kernel in interval arithmetic with each rounding
//! widened to `[-rho_k, rho_k]`, `rho_k = rnd(max |[z_k]|)` ([`Format::rounding`]): this gives
//! an interval `[v_k]` holding `v_k` for every `t` of the box `T = prod [-rho_k, rho_k]`. By
//! induction over the steps the actual roundings lie in `T`: the computed operands lie in
//! their intervals, so the exact result of the operation on them lies in `[z_k]`, and
//! `|RN(z) - z| <= rnd(|z|) <= rho_k`.
//!
//! **The bound.** `T` is convex and holds `0` and `t*`, so for every output `y`, by the mean
//! value theorem on the segment from `0` to `t*`,
//!
//! ```text
//! |F(t*) - F(0)| = |sum_k dF/dt_k (theta t*) t*_k| <= sum_k max_T |dF/dt_k| rho_k
//! ```
//!
//! where `dF/dt_k` is the adjoint of value `k` (the derivative of `y` with respect to `v_k`),
//! enclosed over `T` by reverse-mode differentiation in interval arithmetic with the
//! intervals `[v_k]`. `F` must be differentiable on `T`: a divisor's or a square root's
//! interval must exclude 0, and a select's comparison must be decided over `T` (then the
//! exact and the computed kernel take the same branch); otherwise the adjoint's enclosure
//! is unbounded and so is this bound. No term is dropped: this is not the first-order
//! estimate `sum_k |dF/dt_k (0)| rho_k` but its maximum over the box, so the higher-order
//! terms are inside. Every interval is rounded outward and every sum and product of the
//! bound upward ([`super::round`]), as in the rules.
//!
//! For a point box (one call) the intervals are a few roundings wide, and the bound is
//! close to the first-order `sum_k |dF/dt_k| rho_k`, which keeps the cancellation between
//! the paths along which one rounding reaches an output (the forward rules add them in
//! magnitude). [`super::KernelBound::analyse`] takes, per output, the smaller of the two
//! bounds; both hold, so the smaller does.

use super::format::Format;
use super::propagate::{Compiled, Enclosed, FusedSign, Rule};
use super::round::{add_up, down, mul_up, sqrt_down, sqrt_up, up, Interval};

/// The kernel evaluated over the box of roundings: each value's interval, each value's
/// rounding radius `rho` (0 for the exact ones), and each step's pre-rounding interval.
struct Widened {
    value: Vec<Interval>,
    rho: Vec<f64>,
    pre: Vec<Interval>,
}

/// `[x] + [-r, r]`, outward.
fn widen(x: Interval, r: f64) -> Interval {
    if r == 0.0 {
        x
    } else {
        Interval::new(down(x.lo - r), up(x.hi + r))
    }
}

/// `rnd(max |[z]|)`, or `+inf` when the interval is unbounded (or could overflow).
fn radius(format: Format, z: Interval) -> f64 {
    if z.is_bounded() {
        format.rounding(z.mag())
    } else {
        f64::INFINITY
    }
}

/// Whether a select's comparison `x < y` is decided over the box: `Some(true)` for the
/// first operand, `Some(false)` for the second.
fn decided(x: Interval, y: Interval) -> Option<bool> {
    if x.hi < y.lo {
        Some(true)
    } else if x.lo >= y.hi {
        Some(false)
    } else {
        None
    }
}

impl Widened {
    fn new(c: &Compiled, format: Format, inputs: &[Enclosed]) -> Widened {
        let total = c.exact_scale.len();
        let (mut value, mut rho) = (Vec::with_capacity(total), Vec::with_capacity(total));
        // The inputs as given (their rounding `t` within `error`), then the constants.
        for e in inputs.iter().chain(&c.constants) {
            value.push(widen(e.value, e.error));
            rho.push(e.error);
        }
        let mut pre = Vec::with_capacity(c.rules.len());
        for rule in &c.rules {
            let v = |i: usize| value[i];
            let (z, rounds) = match *rule {
                Rule::Add(a, b) => (v(a) + v(b), true),
                Rule::Sub(a, b) => (v(a) - v(b), true),
                Rule::Mul(a, b) => (v(a) * v(b), !(c.exact_scale[a] || c.exact_scale[b])),
                Rule::Div(a, b) => (v(a) / v(b), true),
                Rule::Neg(a) => (-v(a), false),
                Rule::Fused(a, b, d, sign) => {
                    let p = v(a) * v(b);
                    let z = match sign {
                        FusedSign::MulAdd => p + v(d),
                        FusedSign::MulSub => p - v(d),
                        FusedSign::NegMulAdd => v(d) - p,
                    };
                    (z, true)
                }
                Rule::Sqrt(a) => {
                    let x = v(a);
                    let z = if x.hi < 0.0 || !x.is_bounded() {
                        Interval::ENTIRE
                    } else {
                        Interval::new(sqrt_down(x.lo.max(0.0)), sqrt_up(x.hi))
                    };
                    (z, true)
                }
                Rule::SelectLt([x, y, a, b]) => {
                    let z = match decided(v(x), v(y)) {
                        Some(true) => v(a),
                        Some(false) => v(b),
                        None => Interval::new(v(a).lo.min(v(b).lo), v(a).hi.max(v(b).hi)),
                    };
                    (z, false)
                }
            };
            // An exact step (a product by a power of two, a negation, a select) adds no
            // rounding, but a product by 2^k can still overflow.
            let r = if rounds || !(z.is_bounded() && z.mag() < format.max()) {
                radius(format, z)
            } else {
                0.0
            };
            pre.push(z);
            value.push(widen(z, r));
            rho.push(r);
        }
        Widened { value, rho, pre }
    }
}

/// `acc + x`, where `acc` starts as the exact 0.
fn accumulate(acc: &mut Interval, x: Interval) {
    *acc = if acc.lo == 0.0 && acc.hi == 0.0 {
        x
    } else {
        *acc + x
    };
}

/// The bound of this module for each output of `c` (table indices `outputs`), over the box
/// `inputs` (each input's enclosure and the error of the float passed, as the rules take
/// them): `sum_k max |[dy/dv_k]| rho_k`, rounded upward (`+inf` where `F` may not be
/// differentiable on the box of roundings, or a rounding may overflow).
pub(crate) fn bounds(
    c: &Compiled,
    format: Format,
    inputs: &[Enclosed],
    outputs: &[usize],
) -> Vec<f64> {
    let w = Widened::new(c, format, inputs);
    let first_step = c.inputs.len() + c.constants.len();
    let zero = Interval::point(0.0);
    let mut adjoint = vec![zero; w.value.len()];
    outputs
        .iter()
        .map(|&o| {
            adjoint.fill(zero);
            adjoint[o] = Interval::point(1.0);
            // A select undecided over the box may switch branches between 0 and t*.
            let mut smooth = true;
            for (s, rule) in c.rules.iter().enumerate().rev() {
                let k = first_step + s;
                let a = adjoint[k];
                if a.lo == 0.0 && a.hi == 0.0 {
                    continue;
                }
                let v = |i: usize| w.value[i];
                match *rule {
                    Rule::Add(x, y) => {
                        accumulate(&mut adjoint[x], a);
                        accumulate(&mut adjoint[y], a);
                    }
                    Rule::Sub(x, y) => {
                        accumulate(&mut adjoint[x], a);
                        accumulate(&mut adjoint[y], -a);
                    }
                    Rule::Neg(x) => accumulate(&mut adjoint[x], -a),
                    Rule::Mul(x, y) => {
                        accumulate(&mut adjoint[x], a * v(y));
                        accumulate(&mut adjoint[y], a * v(x));
                    }
                    Rule::Div(x, y) => {
                        // d(x/y)/dx = 1/y, d(x/y)/dy = -(x/y)/y.
                        accumulate(&mut adjoint[x], a / v(y));
                        accumulate(&mut adjoint[y], -((a * w.pre[s]) / v(y)));
                    }
                    Rule::Fused(x, y, d, sign) => {
                        let (p, q) = match sign {
                            FusedSign::MulAdd => (a, a),
                            FusedSign::MulSub => (a, -a),
                            FusedSign::NegMulAdd => (-a, a),
                        };
                        accumulate(&mut adjoint[x], p * v(y));
                        accumulate(&mut adjoint[y], p * v(x));
                        accumulate(&mut adjoint[d], q);
                    }
                    Rule::Sqrt(x) => {
                        // d sqrt(x)/dx = 1 / (2 sqrt(x)), unbounded where x may vanish.
                        let twice = Interval::point(2.0) * w.pre[s];
                        accumulate(&mut adjoint[x], a / twice);
                    }
                    Rule::SelectLt([x, y, p, q]) => match decided(v(x), v(y)) {
                        Some(true) => accumulate(&mut adjoint[p], a),
                        Some(false) => accumulate(&mut adjoint[q], a),
                        None => smooth = false,
                    },
                }
            }
            if !smooth {
                return f64::INFINITY;
            }
            adjoint
                .iter()
                .zip(&w.rho)
                .filter(|(a, &r)| r > 0.0 && !(a.lo == 0.0 && a.hi == 0.0))
                .fold(0.0, |sum, (a, &r)| add_up(sum, mul_up(a.mag(), r)))
        })
        .collect()
}
