//! Certified companions of the generated kernels: the same operations, bit for bit, and in
//! the same branch-free pass a running error bound for every output, for the inputs of this
//! one call (`docs/accuracy.md`, "Certified companions").
//!
//! [`Certified::derive`] turns a lowered [`Program`] into a language-neutral list of
//! statements ([`Stmt`]): each kernel step as the plain kernel spells it, followed by the
//! float arithmetic of its bound. [`rust`] and [`c`] spell that list.
//!
//! # The rules (a point input, run in format `F` with unit roundoff `u`)
//!
//! Every value `x` carries the float the kernel computes, `x^`, and a float `e_x` with
//! `|x^ - x| <= e_x`, `x` the exact value (the rational map on the given floats). Inputs have
//! `e = 0` (known when the companion is generated, so their terms are left out); an exactly
//! representable constant too; a rounded one `e = u |c^| + u s`. Write
//! `m_x = RN(|x^| + s) >= max(|x^|, s)` for a fixed power of two `s` (`2^-480` in `f64`,
//! `2^-51` in `f32`). One rounding of a result `z^` is off by at most `u |z^|` in the normal
//! range and `2^(e_min - p)` below it (gradual underflow), so by at most `u m_z` (since
//! `u s` exceeds the subnormal half-spacing); that term is exact (a power-of-two scaling of a
//! normal float). Then, in exact arithmetic on the floats,
//!
//! ```text
//! z = a +- b   e_z = e_a + e_b + u m_z
//! z = a * b    e_z = m_a e_b + (m_b + e_b) e_a + u m_z      (|a^ b^ - a b| <= |a^| e_b + |b| e_a)
//! z = a / b    e_z = (e_a + m_z E_b) / L_b + u m_z   if L_b > 0, else +inf
//! z = -a       e_z = e_a, m_z = m_a
//! z = fma(a, b, c) = a b + c (or a b - c, c - a b), one rounding:
//!              e_z = [m_a e_b + (m_b + e_b) e_a] + e_c + u m_z
//! ```
//!
//! The fused step: the FMA kernels call `fma(a^, b^, c^)` (Rust `mul_add`, C `fma`/`fmaf`),
//! which returns `fl(a^ b^ + c^) = (a^ b^ + c^)(1 + delta)`, `|delta| <= u`, one rounding of
//! the exact `w = a^ b^ + c^` (and, below the normal range, at most the subnormal
//! half-spacing, as for any operation). So `z^ = RN(w)`, `|z^ - w| <= u m_z` as above, and
//! `|w - z| <= |a^ b^ - a b| + |c^ - c|`, the first term bounded as in the product rule: no
//! rounding of the product is charged. `a b - c` and `c - a b` are `fma(a, b, -c)` and
//! `fma(-a, b, c)`, negations being exact: the same bound.
//!
//! For the quotient, `a^/b^ - a/b = ((a^ - a) - (a^/b^)(b^ - b)) / b` and
//! `|a^/b^| <= (1 + u) m_z`; `E_b = RN(e_b F(d_b + 1)) >= (1 + u) |b^ - b|` is the divisor's
//! rigorous bound (below), and `L_b = RN(RN(|b^| - E_b) (1 - 2u)) <= |b^| - E_b <= |b|` its
//! smallest magnitude; so `L_b > 0` also proves the exact divisor nonzero. A divisor read
//! straight from an input has `E_b = 0`, `L_b = |b^|`, and adds `0 b^` to the numerator (NaN
//! when `b^` is infinite or NaN, so the bound too).
//!
//! # The bound's own arithmetic
//!
//! The bounds are evaluated in the same format, rounded to nearest, with no change of
//! rounding mode. Every term is non-negative and every operation monotone, so rounding can
//! only lose a relative `u` per operation: every nonzero `e` is at least `u s` and every
//! `m` at least `s`, so each product `m e` is normal (`s^2 u >= 2^e_min`) and only a
//! quotient can underflow, losing at most `2^(e_min - p)`, below `2^-75 u` of the rule's
//! value (which holds `u m_z >= u s`). So each operation loses at most a factor `1 - 2u`,
//! and a computed bound is at least `(1 - 2u)^d` times the exact rule's value, `d` the
//! number of operations on its longest dependency path (the two factors multiply in the
//! product `e_a e_b`), which the generator counts ([`Bounded::depth`]). Where the exact
//! value is needed (a divisor, an output, or `d` past [`DEPTH_LIMIT`]), the bound is
//! multiplied by `F(d) = 1 + (d + 2) 2u`, an exact float: `(1 - 2u)^d F(d) (1 - u) >= 1`
//! whenever `(d + 1)^2 <= 3 / (4u)` (`d < 8 10^7` in `f64`, `3500` in `f32`), so the result
//! is a rigorous bound. Overflow gives `+inf`, an upper bound, and an infinite or NaN bound
//! stays infinite or NaN through every rule (`m >= s > 0`, `e >= u s > 0`); the outputs map
//! NaN to `+inf`. A non-finite kernel value gives a NaN or infinite `m`, so an infinite
//! bound for every output that depends on it; an output that is an input is bounded by
//! `0 x^` (0, or `+inf` for a non-finite input).
//!
//! Branch-free: the two choices (`L_b > 0`, NaN) are selects (`?:` in C, bit masks in Rust).
//!
//! The depth of a fused step's bound: the product's term has the product rule's depth less
//! the rounding term's sum (`d_a + 1`, `d_b + 1`, or `d_a + d_b + 3`); each of the (at most
//! two) following sums adds one to the larger of its operands' depths.
//!
//! The inputs are exact (`e = 0`) unless the companion takes them as rounded ([`rounded`]:
//! a normal or `gamma2` within a run-time relative `rho` of the intended value).

pub mod c;
pub mod fast;
pub mod rounded;
pub mod rust;
#[cfg(test)]
mod tests;
pub mod wide;

use crate::bound::round::up;
use crate::model::Variant;
use crate::program::{Op, Operand, Program};
use std::collections::HashMap;

/// Past this many operations on a dependency path, a bound is made rigorous (multiplied by
/// `F(d)`) and its count restarts: it keeps every `F(d)` small and within the proof's range.
pub const DEPTH_LIMIT: u32 = 1000;

/// The float format a companion runs in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Format {
    /// IEEE binary64.
    F64,
    /// IEEE binary32.
    F32,
    /// The kernel in IEEE binary32, its bound in binary64 ([`wide`]): the kernel's `u` and
    /// rounding rules, the bound's own arithmetic in `f64` (which loses less per operation
    /// than the proof allows for `u = 2^-24`, and cannot overflow where `f32` would).
    F32Wide,
}

impl Format {
    /// `log2 u`: `-53`, `-24`.
    fn roundoff_exponent(self) -> i32 {
        match self {
            Format::F64 => -53,
            Format::F32 | Format::F32Wide => -24,
        }
    }

    /// The unit roundoff `u`.
    pub fn unit_roundoff(self) -> f64 {
        2f64.powi(self.roundoff_exponent())
    }

    /// The magnitude floor `s`: `2^-480` (`f64`), `2^-51` (`f32`), so that `s^2 u` is normal
    /// and `u s` is above the subnormal half-spacing; `2^-126` for [`Format::F32Wide`]
    /// (`u s = 2^-150`, the `f32` subnormal half-spacing; `s^2 u` is normal in `f64`).
    pub fn floor(self) -> f64 {
        match self {
            Format::F64 => 2f64.powi(-480),
            Format::F32 => 2f64.powi(-51),
            Format::F32Wide => 2f64.powi(-126),
        }
    }

    /// Whether the bound is evaluated in `f64` (every format but [`Format::F32`]).
    pub fn bound_in_f64(self) -> bool {
        !matches!(self, Format::F32)
    }

    /// `F(d) = 1 + (d + 2) 2u`, exact in the format for `d < 2^22`.
    pub fn inflation(self, depth: u32) -> f64 {
        assert!(depth < 1 << 22, "depth {depth} out of range");
        1.0 + f64::from(depth + 2) * 2.0 * self.unit_roundoff()
    }

    /// The smallest float of the format at least `x` (`x` an `f64` upper bound).
    fn up(self, x: f64) -> f64 {
        match self {
            Format::F64 | Format::F32Wide => x,
            Format::F32 => {
                let y = x as f32;
                if f64::from(y) >= x {
                    f64::from(y)
                } else {
                    f64::from(f32::from_bits(y.to_bits() + 1))
                }
            }
        }
    }

    /// The float the kernel holds for an exact constant.
    pub(crate) fn round(self, value: &num_rational::BigRational) -> f64 {
        let (x64, x32) = crate::literal::nearest_floats(value);
        match self {
            Format::F64 => x64,
            Format::F32 | Format::F32Wide => f64::from(x32),
        }
    }
}

/// An argument of a bound statement.
#[derive(Clone, Debug, PartialEq)]
pub enum Arg {
    /// A binding: a kernel input, constant or step, or a bound statement.
    Name(String),
    /// A float of the format, exactly.
    Lit(f64),
}

/// What a statement computes. All arithmetic rounds to nearest in the format.
#[derive(Clone, Debug, PartialEq)]
pub enum Expr {
    /// The kernel's constant `constants[k]`, as the plain kernel rounds it.
    Const(usize),
    /// The kernel's step `steps[k]`, spelled as in the plain kernel.
    Step(usize),
    /// `|a|`.
    Abs(Arg),
    /// `a + b`.
    Add(Arg, Arg),
    /// `a - b`.
    Sub(Arg, Arg),
    /// `a * b`.
    Mul(Arg, Arg),
    /// `a / b`.
    Div(Arg, Arg),
    /// `x` if `c > 0`, else `+inf` (a NaN `c` gives `+inf`).
    PositiveOr(Arg, Arg),
    /// `x` if `x >= 0`, else `+inf` (NaN becomes `+inf`).
    BoundOrInf(Arg),
    /// `x` if `x > y`, else `y` (a NaN `x` gives `y`): `max` as x86's `maxsd`.
    AtLeast(Arg, Arg),
}

/// How a companion bounds its outputs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Scheme {
    /// Running error analysis: a bound carried with every value.
    Running,
    /// A magnitude per value and a constant per output ([`fast`]), with the magnitudes'
    /// floor.
    Fast {
        /// The floor `s`.
        floor: f64,
    },
}

/// One binding `name = expr`.
#[derive(Clone, Debug, PartialEq)]
pub struct Stmt {
    /// The binding's name.
    pub name: String,
    /// What it computes.
    pub expr: Expr,
}

/// One returned body: its values and their bounds, spin entries then velocity components.
#[derive(Clone, Debug, PartialEq)]
pub struct CertifiedOutput {
    /// 1 or 2.
    pub body: usize,
    /// The kernel's outputs (as the plain kernel returns them).
    pub values: Vec<Operand>,
    /// The bound of each.
    pub bounds: Vec<Arg>,
}

/// A value's bound as the generator tracks it.
#[derive(Clone, Debug)]
pub struct Bounded {
    /// The binding holding `e_x`; `None` when the value is exact (`e_x = 0`).
    pub error: Option<Arg>,
    /// Operations on the longest path behind `e_x` since it was last made rigorous.
    pub depth: u32,
}

/// A kernel and its bound, as one straight-line list of statements.
#[derive(Clone, Debug)]
pub struct Certified {
    /// The kernel.
    pub program: Program,
    /// The format it runs in.
    pub format: Format,
    /// The statements, operands before their uses.
    pub stmts: Vec<Stmt>,
    /// The bodies returned, in the kernel's output order.
    pub outputs: Vec<CertifiedOutput>,
    /// Operations of the bound (beyond the kernel's own).
    pub bound_ops: usize,
    /// How the bound is computed.
    pub scheme: Scheme,
    /// The run-time parameters of the inputs' rounding ([`rounded`]): each `rho` parameter
    /// and the inputs it covers; empty for a companion of the map on the floats given.
    pub rounded: Vec<rounded::Rounding>,
}

/// A kernel step as the plain kernels spell it in Rust and C alike: one IEEE operation
/// (`a + b`, `a - b`, `a * b`, `a / b`, `-a`), or a fused one through `fma` (`f64::mul_add`,
/// `fma`, ...) as the FMA kernels call it: `fma(a, b, c)`, `fma(a, b, -c)`, `fma(-a, b, c)`.
pub(crate) fn step_expr(program: &Program, op: &Op, fma: &str) -> String {
    let o = |x: &Operand| program.name(x).to_string();
    match op {
        Op::Add(a, b) => format!("{} + {}", o(a), o(b)),
        Op::Sub(a, b) => format!("{} - {}", o(a), o(b)),
        Op::Mul(a, b) => format!("{} * {}", o(a), o(b)),
        Op::Div(a, b) => format!("{} / {}", o(a), o(b)),
        Op::Neg(a) => format!("-{}", o(a)),
        Op::MulAdd(a, b, c) => format!("{fma}({}, {}, {})", o(a), o(b), o(c)),
        Op::MulSub(a, b, c) => format!("{fma}({}, {}, -{})", o(a), o(b), o(c)),
        Op::NegMulAdd(a, b, c) => format!("{fma}(-{}, {}, {})", o(a), o(b), o(c)),
        _ => unreachable!("Certified::derive and derive_fast refuse it"),
    }
}

/// A kernel operation the companions do not bound (`sqrt`, selects).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Unsupported(pub String);

impl std::fmt::Display for Unsupported {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "certified companions do not bound {}", self.0)
    }
}

pub(crate) struct Builder<'a> {
    program: &'a Program,
    format: Format,
    stmts: Vec<Stmt>,
    bounds: HashMap<Operand, Bounded>,
    mags: HashMap<Operand, Arg>,
    temp: usize,
    ops: usize,
}

impl Builder<'_> {
    pub(crate) fn u(&self) -> Arg {
        Arg::Lit(self.format.unit_roundoff())
    }

    pub(crate) fn bind(&mut self, expr: Expr) -> Arg {
        if !matches!(expr, Expr::Const(_) | Expr::Step(_)) {
            self.ops += 1;
        }
        let name = format!("cert{}", self.temp);
        self.temp += 1;
        self.stmts.push(Stmt {
            name: name.clone(),
            expr,
        });
        Arg::Name(name)
    }

    fn value(&self, x: &Operand) -> Arg {
        Arg::Name(self.program.name(x).to_string())
    }

    /// `m_x = RN(|x^| + s)`, bound once per value.
    pub(crate) fn mag(&mut self, x: &Operand) -> Arg {
        if let Some(m) = self.mags.get(x) {
            return m.clone();
        }
        let m = match x {
            Operand::Const(k) => {
                let c = self.format.round(&self.program.constants[*k].value);
                Arg::Lit(self.format.up(up(c.abs() + self.format.floor())))
            }
            _ => {
                let a = self.bind(Expr::Abs(self.value(x)));
                self.bind(Expr::Add(a, Arg::Lit(self.format.floor())))
            }
        };
        self.mags.insert(x.clone(), m.clone());
        m
    }

    fn bounded(&self, x: &Operand) -> Bounded {
        self.bounds[x].clone()
    }

    /// `e_x F(d)`, rigorous, with the factor `extra` more operations deep.
    fn rigorous(&mut self, b: &Bounded, extra: u32) -> Option<Arg> {
        let e = b.error.clone()?;
        if b.depth == 0 && extra == 0 {
            return Some(e);
        }
        let f = Arg::Lit(self.format.inflation(b.depth + extra));
        Some(self.bind(Expr::Mul(e, f)))
    }

    fn sum(&mut self, terms: Vec<Arg>) -> Arg {
        let mut it = terms.into_iter();
        let first = it.next().expect("at least one term");
        it.fold(first, |acc, t| self.bind(Expr::Add(acc, t)))
    }

    fn step(&mut self, k: usize) -> Result<(), Unsupported> {
        let program = self.program;
        let s = &program.steps[k];
        self.stmts.push(Stmt {
            name: s.name.clone(),
            expr: Expr::Step(k),
        });
        let z = Operand::Step(k);
        let bounded = match &s.op {
            Op::Neg(a) => {
                let b = self.bounded(a);
                if let Some(m) = self.mags.get(a).cloned() {
                    self.mags.insert(z.clone(), m);
                }
                b
            }
            Op::Add(a, b) | Op::Sub(a, b) => {
                let (ba, bb) = (self.bounded(a), self.bounded(b));
                let mz = self.mag(&z);
                let r = self.bind(Expr::Mul(self.u(), mz));
                let mut terms: Vec<Arg> = [ba.error, bb.error].into_iter().flatten().collect();
                let depth = ba.depth.max(bb.depth) + terms.len() as u32;
                terms.push(r);
                Bounded {
                    error: Some(self.sum(terms)),
                    depth,
                }
            }
            Op::Mul(a, b) => {
                let (ba, bb) = (self.bounded(a), self.bounded(b));
                let mz = self.mag(&z);
                let r = self.bind(Expr::Mul(self.u(), mz));
                let (error, depth) = match (ba.error.clone(), bb.error.clone()) {
                    (None, None) => (r, 0),
                    (Some(ea), None) => {
                        let mb = self.mag(b);
                        let p = self.bind(Expr::Mul(mb, ea));
                        (self.bind(Expr::Add(p, r)), ba.depth + 2)
                    }
                    (None, Some(eb)) => {
                        let ma = self.mag(a);
                        let p = self.bind(Expr::Mul(ma, eb));
                        (self.bind(Expr::Add(p, r)), bb.depth + 2)
                    }
                    (Some(ea), Some(eb)) => {
                        let (ma, mb) = (self.mag(a), self.mag(b));
                        let p1 = self.bind(Expr::Mul(ma, eb.clone()));
                        let sb = self.bind(Expr::Add(mb, eb));
                        let p2 = self.bind(Expr::Mul(sb, ea));
                        let t = self.bind(Expr::Add(p1, p2));
                        (self.bind(Expr::Add(t, r)), ba.depth + bb.depth + 4)
                    }
                };
                Bounded {
                    error: Some(error),
                    depth,
                }
            }
            Op::Div(a, b) => {
                let (ba, bb) = (self.bounded(a), self.bounded(b));
                let mz = self.mag(&z);
                let r = self.bind(Expr::Mul(self.u(), mz.clone()));
                let eb = self.rigorous(&bb, 1);
                let abs_b = self.bind(Expr::Abs(self.value(b)));
                let (low, term) = match eb {
                    Some(eb) => {
                        let d = self.bind(Expr::Sub(abs_b, eb.clone()));
                        let shrink = Arg::Lit(1.0 - 2.0 * self.format.unit_roundoff());
                        let low = self.bind(Expr::Mul(d, shrink));
                        (low, self.bind(Expr::Mul(mz, eb)))
                    }
                    // An exact divisor: `0 b^` is 0, or NaN when `b^` is not finite.
                    None => (abs_b, self.bind(Expr::Mul(Arg::Lit(0.0), self.value(b)))),
                };
                let num = match ba.error.clone() {
                    Some(ea) => self.bind(Expr::Add(ea, term)),
                    None => term,
                };
                let q = self.bind(Expr::Div(num, low.clone()));
                let q = self.bind(Expr::PositiveOr(low, q));
                Bounded {
                    error: Some(self.bind(Expr::Add(q, r))),
                    depth: ba.depth + 4,
                }
            }
            Op::MulAdd(a, b, c) | Op::MulSub(a, b, c) | Op::NegMulAdd(a, b, c) => {
                self.fused(a, b, c, &z)
            }
            Op::Sqrt(_) => return Err(Unsupported(format!("the square root {}", s.name))),
            Op::SelectLt(_) => return Err(Unsupported(format!("the select {}", s.name))),
        };
        let bounded = if bounded.depth > DEPTH_LIMIT {
            Bounded {
                error: self.rigorous(&bounded, 0),
                depth: 0,
            }
        } else {
            bounded
        };
        self.bounds.insert(z, bounded);
        Ok(())
    }

    /// The fused step `z = a b + c` (or `a b - c`, `c - a b`), one rounding:
    /// `e_z = [m_a e_b + (m_b + e_b) e_a] + e_c + u m_z`, the product's term as in the
    /// product rule without its own rounding.
    fn fused(&mut self, a: &Operand, b: &Operand, c: &Operand, z: &Operand) -> Bounded {
        let (ba, bb, bc) = (self.bounded(a), self.bounded(b), self.bounded(c));
        let mz = self.mag(z);
        let r = self.bind(Expr::Mul(self.u(), mz));
        let product = match (ba.error.clone(), bb.error.clone()) {
            (None, None) => None,
            (Some(ea), None) => {
                let mb = self.mag(b);
                Some((self.bind(Expr::Mul(mb, ea)), ba.depth + 1))
            }
            (None, Some(eb)) => {
                let ma = self.mag(a);
                Some((self.bind(Expr::Mul(ma, eb)), bb.depth + 1))
            }
            (Some(ea), Some(eb)) => {
                let (ma, mb) = (self.mag(a), self.mag(b));
                let p1 = self.bind(Expr::Mul(ma, eb.clone()));
                let sb = self.bind(Expr::Add(mb, eb));
                let p2 = self.bind(Expr::Mul(sb, ea));
                Some((self.bind(Expr::Add(p1, p2)), ba.depth + bb.depth + 3))
            }
        };
        let terms = product
            .into_iter()
            .chain(bc.error.map(|e| (e, bc.depth)))
            .chain(std::iter::once((r, 0)));
        // A sum loses one rounding on top of the deeper of its two operands.
        let (error, depth) = terms
            .reduce(|(acc, da), (t, dt)| (self.bind(Expr::Add(acc, t)), da.max(dt) + 1))
            .expect("the rounding term");
        Bounded {
            error: Some(error),
            depth,
        }
    }

    fn output(&mut self, x: &Operand) -> Arg {
        match x {
            Operand::Input(_) => {
                let z = self.bind(Expr::Mul(Arg::Lit(0.0), self.value(x)));
                self.bind(Expr::BoundOrInf(z))
            }
            _ => {
                let b = self.bounded(x);
                match self.rigorous(&b, 0) {
                    Some(e) => self.bind(Expr::BoundOrInf(e)),
                    None => Arg::Lit(0.0),
                }
            }
        }
    }
}

impl Certified {
    /// The companion of `program` in `format`: its steps in order, each followed by its
    /// bound's statements, then the bound of every output. Refuses a program with fused
    /// square roots or selects (the no-slip and rough kernels have none).
    pub fn derive(program: &Program, format: Format) -> Result<Certified, Unsupported> {
        Certified::derive_rounded(program, format, &[])
    }

    /// [`Certified::derive`] with the inputs of each [`rounded::Rounding`] taken as rounded:
    /// their bound `e_x` is the run-time `rho`'s ([`rounded`]), and the outputs are bounded
    /// against the exact map on the intended real inputs.
    pub fn derive_rounded(
        program: &Program,
        format: Format,
        rounded: &[rounded::Rounding],
    ) -> Result<Certified, Unsupported> {
        let mut b = Builder {
            program,
            format,
            stmts: Vec::new(),
            bounds: HashMap::new(),
            mags: HashMap::new(),
            temp: 0,
            ops: 0,
        };
        for name in &program.inputs {
            b.bounds.insert(
                Operand::Input(name.clone()),
                Bounded {
                    error: None,
                    depth: 0,
                },
            );
        }
        for r in rounded {
            r.bind_inputs(&mut b);
        }
        for (k, c) in program.constants.iter().enumerate() {
            b.stmts.push(Stmt {
                name: c.name.clone(),
                expr: Expr::Const(k),
            });
            let f = format.round(&c.value);
            let exact = num_rational::BigRational::from_float(f).as_ref() == Some(&c.value);
            let error = (!exact).then(|| {
                let u = format.unit_roundoff();
                Arg::Lit(format.up(up(up(u * f.abs()) + u * format.floor())))
            });
            b.bounds
                .insert(Operand::Const(k), Bounded { error, depth: 0 });
        }
        for k in 0..program.steps.len() {
            b.step(k)?;
        }
        let outputs = program
            .outputs
            .iter()
            .map(|o| {
                let values: Vec<Operand> = o.spin.iter().chain(&o.velocity).cloned().collect();
                let bounds = values.iter().map(|x| b.output(x)).collect();
                CertifiedOutput {
                    body: o.body,
                    values,
                    bounds,
                }
            })
            .collect();
        let bound_ops = b.ops;
        Ok(Certified {
            program: program.clone(),
            format,
            stmts: b.stmts,
            outputs,
            bound_ops,
            scheme: Scheme::Running,
            rounded: rounded.to_vec(),
        })
    }

    /// The companion of the no-slip kernel `variant` in dimension `dim`, plain or FMA
    /// (`arith`).
    pub fn of(dim: usize, variant: Variant, arith: crate::Arith, format: Format) -> Certified {
        let kernel = crate::model::build(dim, variant);
        let program = Program::lower(&kernel, arith);
        Certified::derive(&program, format).expect("the no-slip kernels have + - * / and FMA only")
    }

    /// The running companion of the rough-ball kernel `variant` (constant `(e, beta)`,
    /// [`crate::model::build_rough`]) in dimension `dim`, plain or FMA: its inputs `e` and
    /// `beta` are floats given, exact like the others.
    pub fn of_rough(
        dim: usize,
        variant: Variant,
        arith: crate::Arith,
        format: Format,
    ) -> Certified {
        let program = Program::lower(&crate::model::build_rough(dim, variant), arith);
        Certified::derive(&program, format)
            .expect("the rough-ball kernels have + - * / and FMA only")
    }

    /// The running companion of the no-slip kernel `variant` in dimension `dim` with the
    /// normal and `gamma2` taken as rounded ([`rounded::Rounding::no_slip`]).
    pub fn of_rounded(
        dim: usize,
        variant: Variant,
        arith: crate::Arith,
        format: Format,
    ) -> Certified {
        let program = Program::lower(&crate::model::build(dim, variant), arith);
        let rounded = rounded::Rounding::no_slip(dim, &program.inputs);
        Certified::derive_rounded(&program, format, &rounded)
            .expect("the no-slip kernels have + - * / and FMA only")
    }
}
