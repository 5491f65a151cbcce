//! Fast certified companions: the plain kernel, then a magnitude per value computed on few
//! leaves, and a bound per output that is a constant, fixed when the companion is generated,
//! times the output's magnitude (`docs/accuracy.md`, "Fast certified companions"). The
//! magnitudes take about half the kernel's operations at n = 3 and a sixth at n = 6, against
//! the running companions' five times (`super`), at the price of a looser bound.
//!
//! # The magnitudes
//!
//! Every value `x` of the kernel gets a magnitude `A_x >= 0`: an input `A = max(|x^|, s)`,
//! where the inputs of one vector or skew matrix (`nu`, `u_1`, `u_2`, `U_1`, `U_2`) share one
//! leaf, the largest of their absolute values (`inv_mass`, `radius`, `gamma2` are leaves of
//! their own); a constant `A = max(|c^|, s)`; `A_(a+-b) = A_a + A_b`,
//! `A_(ab) = A_a A_b`, `A_(-a) = A_a`; a quotient `x = a / b` starts a new magnitude
//! `A_x = max(RN(RN(A_a / |b^|) F_a), s)`. Write `A*` for the same recursion in exact
//! arithmetic on the same leaves (inputs, constants, quotients; the proof below needs only
//! `A >= |x^|` at a leaf, so a shared leaf serves all its inputs), and `R_x` for the kernel's
//! polynomial in exact arithmetic on the leaves' floats (`R_x = x^` at an input, `c^` at a
//! constant, `R_a / b^` at a quotient). Then, by induction over the steps,
//!
//! ```text
//! |x^ - R_x| <= cc_x A*_x      (the kernel's roundings)
//! |x  - R_x| <= ce_x A*_x      (the leaves' own errors: rounded constants and quotients)
//! ```
//!
//! with `x` the exact map on the given floats and constants fixed here:
//!
//! ```text
//! leaf          cc = 0                          ce = 0 (input, exact constant), u/(1-u) (rounded constant)
//! a +- b        1 + cc = (1 + u)(1 + max cc)    ce = max ce
//! a * b         1 + cc = (1 + u)(1 + cc_a)(1 + cc_b)    1 + ce = (1 + ce_a)(1 + ce_b)
//! a / b         1 + cc = (1 + u)(1 + cc_a)      ce = (ce_a + k) / (1 - k),  k = (cc_b + ce_b) rho / (1 - u)^KA_b
//! fma(a, b, c)  1 + cc = (1 + u)(1 + max((1 + cc_a)(1 + cc_b) - 1, cc_c))
//!               1 + ce = max((1 + ce_a)(1 + ce_b), 1 + ce_c)
//! ```
//!
//! A fused step `z = a b + c` (or `a b - c`, `c - a b`) has `A_z = A_a A_b + A_c` (two
//! roundings of the magnitude: `KA_z = max(KA_a + KA_b + 1, KA_c) + 1`) and one rounding of
//! the kernel, `fl(w) = w (1 + delta)`, `w = a^ b^ + c^`: with
//! `M = max((1 + cc_a)(1 + cc_b) - 1, cc_c)`, `|w - R_z| <= M A*_z` and
//! `|w| <= (1 + M) A*_z`, so `|z^ - R_z| <= (M + u (1 + M)) A*_z`; below the normal range
//! the rounding is at most `u 2^e_min <= u A*_a A*_b`
//! (the same floor condition as a product's, checked on `A_a A_b`).
//!
//! A product's rounding is off by at most `u max(|a^ b^|, 2^e_min)`, and `A*_a A*_b >=
//! 2^e_min` for every product, which the floor `s` ensures (the least power of two for
//! which the recursion's lower bounds pass, recorded in [`Scheme::Fast`]): so gradual underflow is covered
//! by the same `u`. Sums round only in the normal range. A quotient's rounding is covered by
//! its magnitude's floor `s >= 2^e_min`. At a quotient the divisor must not cancel: the
//! companion checks `A_b <= rho |b^|` (`rho = 1 + 2^-20`), so that `|b - b^| <= k |b^|`; if
//! the check fails the bound is `+inf`.
//!
//! The computed magnitudes only lose to rounding (every term non-negative, every operation
//! monotone, no underflow): `A_x >= (1 - u)^KA_x A*_x`, `KA` the rounding count on a
//! monomial of the magnitude recursion (a sum adds one to the larger count, a product adds
//! both and one; inputs, constants and quotients count 0, since `F_a = (1 - u)^-(KA_a + 2)`
//! rounded up covers the quotient's). The one division of magnitudes, `RN(A_a / |b^|)`,
//! may underflow; then `A*_a / |b^| < (1 - u)^-KA_a 2^e_min <= s` (the floor is at least
//! `2^(e_min + 1)`), so the `max` with `s` still gives `A_x >= A*_a / |b^|`. So an output
//! `y` has
//!
//! ```text
//! |y^ - y| <= (cc_y + ce_y) A*_y <= C_y RN(...)       C_y = (cc_y + ce_y) / (1 - u)^(KA_y + 1), rounded up,
//! bound_y = RN(C_y A_y) + flag
//! ```
//!
//! the extra `1 - u` for the product's own rounding. Every constant is computed in `f64`
//! with each operation rounded up ([`crate::bound::round`]), then rounded up to the format.
//! `flag` is `+inf` if an output is not finite (an overflow anywhere reaches an output as
//! an infinity or a NaN, except through a divisor: `finite / inf = 0`), if a divisor is not
//! finite, or if a divisor check fails; otherwise 0. A magnitude never becomes NaN (`max`
//! keeps `s` when its operand is NaN), so a bound is never NaN. A NaN input can make its
//! group's `max` tree drop the group's other entries (`if x > NaN` keeps the NaN, the next
//! `max` drops it): harmless, since `+ - * /` never absorb a NaN, so it reaches an output
//! and the flag is `+inf`.
//!
//! The magnitudes are hash-consed: `a + b`, `a - b` and `b + a` have one magnitude, `-a`
//! that of `a`, and with shared leaves most of the kernel's values fall together (`n = 3`
//! `free`: 44 magnitudes for 96 kernel values, `n = 6`: 50 for 300; 4 distinct ones at the
//! outputs). Equal keys have equal `cc`, `ce`, `KA` (they follow the key's structure).

use super::{Arg, Certified, CertifiedOutput, Expr, Format, Scheme, Stmt, Unsupported};
use crate::bound::round::{add_up, div_up, mul_up, sub_down};
use crate::model::Variant;
use crate::program::{Op, Operand, Program};
use num_rational::BigRational;
use std::collections::HashMap;

/// `rho`: a divisor passes its check when `A_b <= rho |b^|`.
pub const RHO: f64 = 1.0 + 1.0 / (1u64 << 20) as f64;

/// The checked divisors' `rho` as emitted: `1 + 2^-21`, below [`RHO`], so that a rounded
/// `rho |b^|` that passes is still at most `RHO |b^|`.
pub const RHO_CHECK: f64 = 1.0 + 1.0 / (1u64 << 21) as f64;

/// What the generator knows of one value.
#[derive(Clone, Copy, Debug)]
struct Tracked {
    /// `cc`: the kernel's roundings, relative to the exact magnitude.
    cc: f64,
    /// `ce`: the leaves' own errors, relative to the exact magnitude.
    ce: f64,
    /// `KA`: roundings of the magnitude recursion on a monomial.
    ka: u32,
    /// `log2` of a lower bound of the exact magnitude (given the floor).
    lo: f64,
}

impl Format {
    /// `e_min`: the exponent of the least normal float.
    fn min_exponent(self) -> i32 {
        match self {
            Format::F64 => -1022,
            Format::F32 | Format::F32Wide => -126,
        }
    }
}

/// `(1 + a)(1 + b) - 1 = a + b + ab`, rounded up.
fn compose(a: f64, b: f64) -> f64 {
    add_up(add_up(a, b), mul_up(a, b))
}

/// `(1 - u)^-k`, rounded up, by repeated upward steps.
fn inverse_power(u: f64, k: u32) -> f64 {
    let shrink = 1.0 - u; // exact
    (0..k).fold(1.0f64, |p, _| div_up(p, shrink))
}

/// The leaf an input's magnitude reads: its vector's or matrix's (`nu`, `u1`, `U2`, ...), or
/// its own.
pub fn leaf_group(input: &str) -> String {
    match input.split_once('_') {
        Some((g @ ("nu" | "u1" | "u2" | "U1" | "U2"), _)) => g.to_string(),
        _ => input.to_string(),
    }
}

/// Whether the constant `k` is exact in `format`.
fn exact_constant(program: &Program, format: Format, k: usize) -> bool {
    let c = format.round(&program.constants[k].value);
    BigRational::from_float(c).as_ref() == Some(&program.constants[k].value)
}

/// The recursion over `program` with floor `2^floor_log2`, or `Err` if a product's
/// magnitude could fall below `2^(e_min + 1)`.
fn track(program: &Program, format: Format, floor_log2: i32) -> Result<Vec<Tracked>, ()> {
    let u = format.unit_roundoff();
    let threshold = f64::from(format.min_exponent() + 1);
    let floor = f64::from(floor_log2);
    let leaf = |x: &Operand, steps: &[Tracked]| -> Tracked {
        match x {
            Operand::Input(_) => Tracked {
                cc: 0.0,
                ce: 0.0,
                ka: 0,
                lo: floor,
            },
            Operand::Const(k) => {
                let c = format.round(&program.constants[*k].value);
                Tracked {
                    cc: 0.0,
                    ce: if exact_constant(program, format, *k) {
                        0.0
                    } else {
                        div_up(u, 1.0 - u)
                    },
                    ka: 0,
                    lo: if c == 0.0 {
                        floor
                    } else {
                        c.abs().log2().floor().max(floor)
                    },
                }
            }
            Operand::Step(k) => steps[*k],
        }
    };
    let mut steps: Vec<Tracked> = Vec::with_capacity(program.steps.len());
    for s in &program.steps {
        let t = match &s.op {
            Op::Neg(a) => leaf(a, &steps),
            Op::Add(a, b) | Op::Sub(a, b) => {
                let (a, b) = (leaf(a, &steps), leaf(b, &steps));
                Tracked {
                    cc: compose(u, a.cc.max(b.cc)),
                    ce: a.ce.max(b.ce),
                    ka: a.ka.max(b.ka) + 1,
                    lo: a.lo.max(b.lo),
                }
            }
            Op::Mul(a, b) => {
                let (a, b) = (leaf(a, &steps), leaf(b, &steps));
                let t = Tracked {
                    cc: compose(u, compose(a.cc, b.cc)),
                    ce: compose(a.ce, b.ce),
                    ka: a.ka + b.ka + 1,
                    lo: a.lo + b.lo,
                };
                if t.lo < threshold {
                    return Err(());
                }
                t
            }
            Op::Div(a, b) => {
                let (a, b) = (leaf(a, &steps), leaf(b, &steps));
                let kappa = mul_up(mul_up(add_up(b.cc, b.ce), RHO), inverse_power(u, b.ka));
                assert!(kappa < 0.5, "a divisor's error bound {kappa} is not small");
                Tracked {
                    cc: compose(u, a.cc),
                    ce: div_up(add_up(a.ce, kappa), sub_down(1.0, kappa)),
                    ka: 0,
                    lo: floor,
                }
            }
            Op::MulAdd(a, b, c) | Op::MulSub(a, b, c) | Op::NegMulAdd(a, b, c) => {
                let (a, b, c) = (leaf(a, &steps), leaf(b, &steps), leaf(c, &steps));
                let t = Tracked {
                    cc: compose(u, compose(a.cc, b.cc).max(c.cc)),
                    ce: compose(a.ce, b.ce).max(c.ce),
                    ka: (a.ka + b.ka + 1).max(c.ka) + 1,
                    lo: (a.lo + b.lo).max(c.lo),
                };
                // The product's magnitude `A_a A_b` is rounded on its own: it stays normal.
                if a.lo + b.lo < threshold {
                    return Err(());
                }
                t
            }
            _ => unreachable!("derive_fast refuses it first"),
        };
        steps.push(t);
    }
    Ok(steps)
}

struct Builder<'a> {
    program: &'a Program,
    format: Format,
    floor: Arg,
    stmts: Vec<Stmt>,
    ops: usize,
    /// The magnitude binding of each key.
    keys: HashMap<String, Arg>,
    /// Each kernel step's magnitude key.
    step_keys: Vec<String>,
}

impl Builder<'_> {
    fn bind(&mut self, expr: Expr) -> Arg {
        self.ops += 1;
        let name = format!("mag{}", self.stmts.len());
        self.stmts.push(Stmt {
            name: name.clone(),
            expr,
        });
        Arg::Name(name)
    }

    fn value(&self, x: &Operand) -> Arg {
        Arg::Name(self.program.name(x).to_string())
    }

    /// The key of an operand's magnitude.
    fn key(&self, x: &Operand) -> String {
        match x {
            Operand::Input(name) => leaf_group(name),
            Operand::Const(k) => self.program.constants[*k].name.clone(),
            Operand::Step(k) => self.step_keys[*k].clone(),
        }
    }

    /// The magnitude of an operand (bound already).
    fn mag(&self, x: &Operand) -> Arg {
        self.keys[&self.key(x)].clone()
    }

    /// `args` combined pairwise by `op` as a balanced tree (`max`, a sum).
    fn tree(&mut self, mut args: Vec<Arg>, op: fn(Arg, Arg) -> Expr) -> Arg {
        while args.len() > 1 {
            let mut next = Vec::with_capacity(args.len().div_ceil(2));
            let mut it = args.into_iter();
            while let Some(a) = it.next() {
                match it.next() {
                    Some(b) => next.push(self.bind(op(a, b))),
                    None => next.push(a),
                }
            }
            args = next;
        }
        args.pop().expect("at least one")
    }

    /// The leaves: one magnitude per group of inputs, `max(|x_1^|, ..., |x_k^|, s)` (a
    /// tree), one per constant (`max(|c^|, s)`, a literal).
    fn leaves(&mut self) {
        let mut groups: Vec<(String, Vec<String>)> = Vec::new();
        for input in &self.program.inputs {
            let g = leaf_group(input);
            match groups.iter_mut().find(|(k, _)| *k == g) {
                Some((_, v)) => v.push(input.clone()),
                None => groups.push((g, vec![input.clone()])),
            }
        }
        for (g, inputs) in groups {
            let abs: Vec<Arg> = inputs
                .iter()
                .map(|x| self.bind(Expr::Abs(Arg::Name(x.clone()))))
                .collect();
            let m = self.tree(abs, Expr::AtLeast);
            let m = self.bind(Expr::AtLeast(m, self.floor.clone()));
            self.keys.insert(g, m);
        }
        let s = match self.floor {
            Arg::Lit(s) => s,
            Arg::Name(_) => unreachable!("the floor is a literal"),
        };
        for c in &self.program.constants {
            let v = self.format.round(&c.value).abs();
            self.keys
                .insert(c.name.clone(), Arg::Lit(if v > s { v } else { s }));
        }
    }
}

impl Certified {
    /// The fast companion of `program` in `format` (see the module's docs). Refuses fused
    /// steps, square roots and selects, as [`Certified::derive`] does.
    pub fn derive_fast(program: &Program, format: Format) -> Result<Certified, Unsupported> {
        for s in &program.steps {
            match s.op {
                Op::Add(..)
                | Op::Sub(..)
                | Op::Mul(..)
                | Op::Div(..)
                | Op::Neg(..)
                | Op::MulAdd(..)
                | Op::MulSub(..)
                | Op::NegMulAdd(..) => {}
                _ => return Err(Unsupported(format!("the step {}", s.name))),
            }
        }
        let u = format.unit_roundoff();
        // The least floor for which no product's magnitude can fall below 2^(e_min + 1).
        let mut floor_log2 = format.min_exponent();
        let tracked = loop {
            if let Ok(t) = track(program, format, floor_log2) {
                break t;
            }
            floor_log2 += 1;
            assert!(floor_log2 < 0, "no floor below 1 keeps the products normal");
        };
        let floor = 2f64.powi(floor_log2);
        let mut b = Builder {
            program,
            format,
            floor: Arg::Lit(floor),
            stmts: Vec::new(),
            ops: 0,
            keys: HashMap::new(),
            step_keys: Vec::new(),
        };
        // The plain kernel, as it is.
        for (k, c) in program.constants.iter().enumerate() {
            b.stmts.push(Stmt {
                name: c.name.clone(),
                expr: Expr::Const(k),
            });
        }
        for (k, s) in program.steps.iter().enumerate() {
            b.stmts.push(Stmt {
                name: s.name.clone(),
                expr: Expr::Step(k),
            });
        }
        b.leaves();
        // The magnitudes, one per key; the flag's terms from the divisors.
        let mut checks: Vec<Arg> = Vec::new();
        // The first step's constants per key: every later step with that key must agree, or
        // the shared magnitude would carry another value's `cc`, `ce`, `KA` or floor.
        let mut of_key: HashMap<String, Tracked> = HashMap::new();
        for (k, s) in program.steps.iter().enumerate() {
            let key = match &s.op {
                Op::Neg(a) => b.key(a),
                Op::Add(x, y) | Op::Sub(x, y) | Op::Mul(x, y) => {
                    let mut v = [b.key(x), b.key(y)];
                    v.sort();
                    let sym = if matches!(s.op, Op::Mul(..)) {
                        '*'
                    } else {
                        '+'
                    };
                    let key = format!("({sym} {} {})", v[0], v[1]);
                    if !b.keys.contains_key(&key) {
                        let (ma, mb) = (b.mag(x), b.mag(y));
                        let m = match s.op {
                            Op::Mul(..) => b.bind(Expr::Mul(ma, mb)),
                            _ => b.bind(Expr::Add(ma, mb)),
                        };
                        b.keys.insert(key.clone(), m);
                    }
                    key
                }
                Op::MulAdd(x, y, w) | Op::MulSub(x, y, w) | Op::NegMulAdd(x, y, w) => {
                    let mut v = [b.key(x), b.key(y)];
                    v.sort();
                    let product = format!("(* {} {})", v[0], v[1]);
                    let key = format!("(fma {} {} {})", v[0], v[1], b.key(w));
                    if !b.keys.contains_key(&key) {
                        // `A_a A_b` shares the product's key: the same magnitude.
                        let p = match b.keys.get(&product) {
                            Some(p) => p.clone(),
                            None => {
                                let (ma, mb) = (b.mag(x), b.mag(y));
                                let p = b.bind(Expr::Mul(ma, mb));
                                b.keys.insert(product, p.clone());
                                p
                            }
                        };
                        let mw = b.mag(w);
                        let m = b.bind(Expr::Add(p, mw));
                        b.keys.insert(key.clone(), m);
                    }
                    key
                }
                Op::Div(x, y) => {
                    let key = format!("(/ {} {})", b.key(x), program.name(y));
                    if !b.keys.contains_key(&key) {
                        let ka = match x {
                            Operand::Step(j) => tracked[*j].ka,
                            _ => 0,
                        };
                        let widen = format.up(inverse_power(u, ka + 2));
                        let abs_b = b.bind(Expr::Abs(b.value(y)));
                        let ma = b.mag(x);
                        let q = b.bind(Expr::Div(ma, abs_b.clone()));
                        let q = b.bind(Expr::Mul(q, Arg::Lit(widen)));
                        let m = b.bind(Expr::AtLeast(q, b.floor.clone()));
                        b.keys.insert(key.clone(), m);
                        // The divisor: `0 b^` (NaN if it is not finite), and unless it is an
                        // input, the check that it does not cancel, `A_b < rho |b^|`.
                        let guard = b.bind(Expr::Mul(Arg::Lit(0.0), b.value(y)));
                        checks.push(if matches!(y, Operand::Input(_)) {
                            guard
                        } else {
                            let mb = b.mag(y);
                            let r = b.bind(Expr::Mul(Arg::Lit(RHO_CHECK), abs_b));
                            let c = b.bind(Expr::Sub(r, mb));
                            b.bind(Expr::PositiveOr(c, guard))
                        });
                    }
                    key
                }
                _ => unreachable!("refused above"),
            };
            let (t, first) = (tracked[k], *of_key.entry(key.clone()).or_insert(tracked[k]));
            assert!(
                t.cc == first.cc && t.ce == first.ce && t.ka == first.ka && t.lo == first.lo,
                "the step {} shares the magnitude {key} but not its constants: {t:?}, {first:?}",
                s.name
            );
            b.step_keys.push(key);
        }
        // The flag: 0 times the sum of the outputs (a tree), plus the divisors' terms; NaN
        // to +inf. It is 0, or +inf if an output or a divisor is not finite or a divisor
        // cancels.
        let values: Vec<Arg> = program
            .outputs
            .iter()
            .flat_map(|o| o.spin.iter().chain(&o.velocity))
            .map(|x| b.value(x))
            .collect();
        let sum = b.tree(values, Expr::Add);
        let mut flag = b.bind(Expr::Mul(Arg::Lit(0.0), sum));
        for t in checks {
            flag = b.bind(Expr::Add(flag, t));
        }
        let flag = b.bind(Expr::BoundOrInf(flag));
        // Each output: C_y A_y + flag, one binding per distinct (C_y, A_y).
        let mut bounds: HashMap<(String, u64), Arg> = HashMap::new();
        let outputs = program
            .outputs
            .iter()
            .map(|o| {
                let values: Vec<Operand> = o.spin.iter().chain(&o.velocity).cloned().collect();
                let bounds = values
                    .iter()
                    .map(|x| match x {
                        Operand::Step(k) => {
                            let t = tracked[*k];
                            let c =
                                format.up(mul_up(add_up(t.cc, t.ce), inverse_power(u, t.ka + 1)));
                            // `C_y A_y >= C_y s` stays normal: its rounding is relative.
                            assert!(
                                c * floor >= 2f64.powi(format.min_exponent() + 1),
                                "C_y s = {c:e} {floor:e} is not normal"
                            );
                            let key = (b.step_keys[*k].clone(), c.to_bits());
                            if let Some(a) = bounds.get(&key) {
                                return a.clone();
                            }
                            let m = b.mag(x);
                            let p = b.bind(Expr::Mul(Arg::Lit(c), m));
                            let e = b.bind(Expr::Add(p, flag.clone()));
                            bounds.insert(key, e.clone());
                            e
                        }
                        // An input returned as it is: exact.
                        Operand::Input(_) => flag.clone(),
                        Operand::Const(_) => unreachable!("an output is never a bare constant"),
                    })
                    .collect();
                CertifiedOutput {
                    body: o.body,
                    values,
                    bounds,
                }
            })
            .collect();
        Ok(Certified {
            program: program.clone(),
            format,
            stmts: b.stmts,
            outputs,
            bound_ops: b.ops,
            scheme: Scheme::Fast { floor },
            rounded: Vec::new(),
        })
    }

    /// The fast companion of the no-slip kernel `variant` in dimension `dim`, plain or FMA
    /// (`arith`).
    pub fn of_fast(dim: usize, variant: Variant, arith: crate::Arith, format: Format) -> Certified {
        let kernel = crate::model::build(dim, variant);
        let program = Program::lower(&kernel, arith);
        Certified::derive_fast(&program, format)
            .expect("the no-slip kernels have + - * / and FMA only")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Hash-consing is sound only if equal keys have equal `cc`, `ce`, `KA` and floor:
    /// [`Certified::derive_fast`] asserts it per step; here on every plain kernel and format.
    #[test]
    fn equal_magnitude_keys_have_equal_constants() {
        for dim in 2..=6 {
            for variant in Variant::ALL {
                for format in [Format::F64, Format::F32] {
                    for arith in [crate::Arith::Plain, crate::Arith::Fma] {
                        let c = Certified::of_fast(dim, variant, arith, format);
                        assert!(matches!(c.scheme, Scheme::Fast { .. }));
                    }
                }
            }
        }
    }
}
