//! What a companion's derivation holds as it walks the program ([`Builder`]): the statements
//! bound so far, each value's bound and magnitude, and the primitives every rule binds with
//! (the running steps, `running.rs`; the clamped quotients, `clamp.rs`; the rounded inputs,
//! `rounded.rs`).

use super::{Arg, Bounded, Expr, Format, Stmt};
use crate::bound::round::up;
use crate::program::{Operand, Program};
use std::collections::HashMap;

/// A companion's derivation in progress.
pub(crate) struct Builder<'a> {
    pub(crate) program: &'a Program,
    pub(crate) format: Format,
    pub(crate) stmts: Vec<Stmt>,
    pub(crate) bounds: HashMap<Operand, Bounded>,
    pub(crate) mags: HashMap<Operand, Arg>,
    pub(crate) temp: usize,
    pub(crate) ops: usize,
    /// The clamped quotients ([`super::clamp`]), whose square roots are bounded.
    pub(crate) clamped: std::collections::HashSet<Operand>,
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

    pub(crate) fn value(&self, x: &Operand) -> Arg {
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

    pub(crate) fn bounded(&self, x: &Operand) -> Bounded {
        self.bounds[x].clone()
    }

    /// `e_x F(d)`, rigorous, with the factor `extra` more operations deep.
    pub(crate) fn rigorous(&mut self, b: &Bounded, extra: u32) -> Option<Arg> {
        let e = b.error.clone()?;
        if b.depth == 0 && extra == 0 {
            return Some(e);
        }
        let f = Arg::Lit(self.format.inflation(b.depth + extra));
        Some(self.bind(Expr::Mul(e, f)))
    }
}
