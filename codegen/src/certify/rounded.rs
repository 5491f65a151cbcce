//! Rounded inputs: companions whose bound covers the rounding of inputs the caller computed
//! (a normal normalised in floats, a `gamma2` rounded from its real value), against the
//! exact map on the intended real inputs (`docs/accuracy.md`, "Rounded inputs").
//!
//! # The rule
//!
//! The caller passes, per group of inputs (`nu`, `gamma2`), a relative bound `rho`: each
//! float input `x^` of the group is within `rho |x|` of the intended real `x`. So
//! `|x^ - x| <= rho (|x^| + |x^ - x|)`, `|x^ - x| <= rho / (1 - rho) |x^|`, and for
//! `rho <= 2^-10`, `rho / (1 - rho) <= rho (1 + 2^-9)`. The input then enters the running
//! rules ([`super`]) with
//!
//! ```text
//! e_x = RN(k m_x),   k = RN(RN(|rho| (1 + 2^-9)) + u)   if |rho| < 2^-10, else +inf
//! ```
//!
//! `m_x = RN(|x^| + s) >= |x^|`. The running rules are exact inequalities for any real `x`
//! within `e_x` of `x^` (they never use that `x` is the float's value), so with these input
//! bounds each output's bound covers `|y^ - y|`, `y` the exact map at the intended inputs:
//! the inputs' rounding propagated through the whole kernel, every higher-order term
//! included (no first-order truncation, no remainder left to bound).
//!
//! The added `u` keeps `k >= u`, so `e_x >= u s` and the rules' products stay normal (the
//! proof in [`super`] needs every nonzero `e` at least `u s`); it charges each rounded input
//! one more unit roundoff than `rho`, harmless beside a `rho` of a few `u`. The bound's own
//! arithmetic: `RN(|rho| (1 + 2^-9))` may underflow, by at most `2^(e_min - p)`, far below
//! `u^2`; so `k >= (1 - 2u)^2 (|rho| (1 + 2^-9) + u)` and `e_x >= (1 - 2u)^3` times its
//! rule's value: depth 3 in the running count. A NaN `rho` or one at least `2^-10` gives
//! `+inf` (a select), and so does every output depending on that input.

use super::builder::Builder;
use super::{Arg, Bounded, Expr};
use crate::program::Operand;

/// The largest `rho` the rule takes: `2^-10`.
pub const RHO_LIMIT: f64 = 1.0 / 1024.0;

/// One run-time `rho` and the inputs it covers.
#[derive(Clone, Debug, PartialEq)]
pub struct Rounding {
    /// The parameter's binding name (`rho_nu`, `rho_gamma2`).
    pub param: String,
    /// The kernel inputs it covers (`nu_0`, ..., `gamma2_1`, `gamma2_2`).
    pub inputs: Vec<String>,
}

impl Rounding {
    /// The no-slip kernels' two: the normal's components (`rho_nu`) and each body's
    /// `gamma2` (`rho_gamma2`), of the inputs `inputs` the kernel reads.
    pub fn no_slip(dim: usize, inputs: &std::collections::BTreeSet<String>) -> Vec<Rounding> {
        use crate::model::names;
        let read = |v: Vec<String>| v.into_iter().filter(|x| inputs.contains(x)).collect();
        vec![
            Rounding {
                param: "rho_nu".into(),
                inputs: read((0..dim).map(names::nu).collect()),
            },
            Rounding {
                param: "rho_gamma2".into(),
                inputs: read(vec![names::gamma2(1), names::gamma2(2)]),
            },
        ]
    }

    /// Bind `k` from the parameter and each covered input's `e_x = RN(k m_x)`, depth 3.
    pub(super) fn bind_inputs(&self, b: &mut Builder<'_>) {
        if self.inputs.is_empty() {
            return;
        }
        let a = b.bind(Expr::Abs(Arg::Name(self.param.clone())));
        let room = b.bind(Expr::Sub(Arg::Lit(RHO_LIMIT), a.clone()));
        let k0 = b.bind(Expr::Mul(a, Arg::Lit(1.0 + 2f64.powi(-9))));
        let k = b.bind(Expr::Add(k0, b.u()));
        let k = b.bind(Expr::PositiveOr(room, k));
        for x in &self.inputs {
            let x = Operand::Input(x.clone());
            let m = b.mag(&x);
            let e = b.bind(Expr::Mul(k.clone(), m));
            b.bounds.insert(
                x,
                Bounded {
                    error: Some(e),
                    depth: 3,
                },
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::certify::{Certified, Format};
    use crate::model::Variant;
    use crate::program::Program;

    /// Every no-slip kernel's companion with rounded inputs reads both parameters, binds
    /// each covered input's bound before any step, and costs more bound operations than the
    /// companion on the floats given (the inputs' errors now propagate).
    #[test]
    fn the_rounded_companions_bound_the_covered_inputs() {
        for v in Variant::ALL {
            for arith in crate::Arith::ALL {
                let program = Program::lower(&crate::model::build(3, v), arith);
                let rounded = Rounding::no_slip(3, &program.inputs);
                assert_eq!(rounded[0].inputs.len(), 3, "{v:?}: the normal");
                let gammas = match v {
                    Variant::Free => 2,
                    Variant::Fixed => 1,
                };
                assert_eq!(rounded[1].inputs.len(), gammas, "{v:?}: gamma2");
                let c = Certified::derive_rounded(&program, Format::F64, &rounded).unwrap();
                let plain = Certified::derive(&program, Format::F64).unwrap();
                assert!(c.bound_ops > plain.bound_ops);
                let first_step = c
                    .stmts
                    .iter()
                    .position(|s| matches!(s.expr, Expr::Step(_)))
                    .unwrap();
                let reads = |p: &str| {
                    c.stmts[..first_step]
                        .iter()
                        .any(|s| s.expr == Expr::Abs(Arg::Name(p.into())))
                };
                assert!(reads("rho_nu") && reads("rho_gamma2"));
            }
        }
    }
}
