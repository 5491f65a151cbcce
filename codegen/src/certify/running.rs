//! The running companions: [`Certified::derive`] and its rounded-input form walk the lowered
//! program step by step and bind, after each step, the float arithmetic of its bound by the
//! rules of [`super`] ("The rules").

use super::builder::Builder;
use super::rounded;
use super::DEPTH_LIMIT;
use super::{Arg, Bounded, Certified, CertifiedOutput, Expr, Format, Scheme, Stmt, Unsupported};
use crate::bound::round::up;
use crate::model::Variant;
use crate::program::{Op, Operand, Program};
use std::collections::HashMap;

impl Builder<'_> {
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
        // A select's value is bounded only as part of a clamped quotient.
        let clamp = match &s.op {
            Op::Div(a, b) => super::clamp::clamp(self, a, b),
            _ => None,
        };
        if clamp.is_none() {
            if let Some(x) = operands(&s.op)
                .into_iter()
                .find(|x| !self.bounds.contains_key(x))
            {
                return Err(Unsupported(format!(
                    "the select {} outside a clamped quotient",
                    program.name(&x)
                )));
            }
        }
        let bounded = match &s.op {
            Op::Div(..) if clamp.is_some() => {
                let (c, l) = clamp.expect("matched");
                self.clamped_quotient(&c, &l, &z)
            }
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
            Op::Sqrt(a) if self.clamped.contains(a) => self.root(a, &z),
            Op::Sqrt(_) => return Err(Unsupported(format!("the square root {}", s.name))),
            // Bound where it is used, by the clamped quotient's rule.
            Op::SelectLt(_) => return Ok(()),
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
    /// bound's statements, then the bound of every output. Refuses a program with square
    /// roots or selects other than the Walton kernels' clamped quotient and its root
    /// ([`super::clamp`]; the no-slip and rough kernels have none).
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
            clamped: Default::default(),
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
        if let Some(x) = program
            .outputs
            .iter()
            .flat_map(|o| o.spin.iter().chain(&o.velocity))
            .find(|x| !b.bounds.contains_key(x))
        {
            return Err(Unsupported(format!(
                "the select {} as an output",
                program.name(x)
            )));
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

    /// The running companion of the Walton kernel `variant` (`(e, mu, beta0)`,
    /// [`crate::walton::build_walton`]) in dimension `dim`, plain or FMA: its switch and
    /// square root bounded by [`super::clamp`]'s rules.
    pub fn of_walton(
        dim: usize,
        variant: Variant,
        arith: crate::Arith,
        format: Format,
    ) -> Certified {
        let program = Program::lower(&crate::walton::build_walton(dim, variant), arith);
        Certified::derive(&program, format)
            .expect("the Walton kernels' selects and root form a clamped quotient")
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

/// The operands of a kernel step.
fn operands(op: &Op) -> Vec<Operand> {
    match op {
        Op::Neg(a) | Op::Sqrt(a) => vec![a.clone()],
        Op::Add(a, b) | Op::Sub(a, b) | Op::Mul(a, b) | Op::Div(a, b) => vec![a.clone(), b.clone()],
        Op::MulAdd(a, b, c) | Op::MulSub(a, b, c) | Op::NegMulAdd(a, b, c) => {
            vec![a.clone(), b.clone(), c.clone()]
        }
        Op::SelectLt(ids) => ids.to_vec(),
    }
}
