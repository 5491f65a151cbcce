//! The Walton kernels' switch and square root in the running companions
//! (`docs/accuracy.md`, "Walton companions"): the clamped quotient
//!
//! ```text
//! rho = select(C < L, C, 1) / select(C < L, L, 1) = min(1, C / L)      (L > 0)
//! ```
//!
//! and `sqrt(rho)` ([`crate::walton`]).
//!
//! # What is proved
//!
//! The bound covers the exact map whichever branch it takes: `|rho^ - min(1, C/L)|`, `C`,
//! `L` the exact sides. `min(1, .)` is 1-Lipschitz, so with `q = C^ / L^` (real):
//!
//! - the float slid (`C^ < L^`): `rho^ = fl(q)`, `min(1, q) = q`, so
//!   `|rho^ - min(1, C/L)| <= |fl(q) - q| + |q - C/L|`;
//! - the float stuck (`C^ >= L^`): `rho^ = 1 = min(1, q)`, so the error is at most
//!   `|q - C/L|`, the same bound without the rounding of `q`.
//!
//! `|q - C/L|` is bounded by the quotient rule of [`super`]: `(e_C + m_q E_L) / L_low`,
//! with `m_q = RN(|RN(C^ / L^)| + s)` computed in the bound's arithmetic (the kernel has not
//! computed `q` when it stuck); `L_low > 0` also proves `L > 0`, so the exact map's `rho` is
//! `min(1, C/L)` (it slides iff `C < L`). Both `rho^` and the exact `rho` lie in `[0, 1]`
//! (`C^ >= 0` and `C >= 0` are products of squares, `L >= 0` likewise; sliding needs
//! `C < L`), so the bound is also at most 1: where `L` is not provably positive (`L = 0`
//! exactly when both `gamma2` or `t` vanish, or `mu = 0` makes `C = 0` beside a tiny `L`)
//! it is 1, not `+inf`. And where the sticking branch is decided, `C^ - L^ > e_C + e_L` (checked as
//! `RN(RN(C^ - L^)(1 - 2u)) > RN(e_C F + e_L F)`, each side rounded the safe way), the
//! exact map sticks too and `rho^ = 1` exactly: the bound is 0. So a different branch near
//! the switch is covered, not excluded: both branches' values lie within the bound of the
//! exact one.
//!
//! The square root: the exact `rho = min(1, C/L)` is at least 0 (`C` is a product of
//! squares, `L > 0`), and for `a, b >= 0`, `|sqrt a - sqrt b| <= min(|a - b| / sqrt a,
//! sqrt |a - b|)`; so
//!
//! ```text
//! e_z = min(e_rho / RN(sqrt rho^), RN(sqrt e_rho)) + u m_z      z = sqrt(rho)
//! ```
//!
//! (`e_rho / 0` is `+inf` or NaN, and the `min` then takes the root's term). Each term loses
//! at most `(1 - 2u)` per operation as the other rules' do (`RN(sqrt x)` is within a relative
//! `u`, and the root of a computed bound at least `(1 - 2u)^d` of its rule's value is at least
//! `(1 - 2u)^d` of the rule's root): depth `d + 3`. A square root or select anywhere else is
//! refused ([`super::Unsupported`]).

use super::builder::Builder;
use super::{Arg, Bounded, Expr};
use crate::program::{Op, Operand};

/// The clamped quotient `rho = num / den`: `(C, L)` if `num = select(C < L, C, 1)` and
/// `den = select(C < L, L, 1)`.
pub(crate) fn clamp(b: &Builder<'_>, num: &Operand, den: &Operand) -> Option<(Operand, Operand)> {
    let select = |x: &Operand| match x {
        Operand::Step(k) => match &b.program.steps[*k].op {
            Op::SelectLt(s) => Some(s.clone()),
            _ => None,
        },
        _ => None,
    };
    let one = |x: &Operand| match x {
        Operand::Const(k) => {
            b.program.constants[*k].value == num_rational::BigRational::from_integer(1.into())
        }
        _ => false,
    };
    let [c, l, x, y] = select(num)?;
    let [c2, l2, x2, y2] = select(den)?;
    (c == c2 && l == l2 && x == c && x2 == l && one(&y) && one(&y2)).then_some((c, l))
}

impl Builder<'_> {
    /// The bound of `rho = min(1, C/L)` computed as `z` (module docs).
    pub(crate) fn clamped_quotient(&mut self, c: &Operand, l: &Operand, z: &Operand) -> Bounded {
        let (bc, bl) = (self.bounded(c), self.bounded(l));
        let u = self.format.unit_roundoff();
        let shrink = Arg::Lit(1.0 - 2.0 * u);
        let mz = self.mag(z);
        let r = self.bind(Expr::Mul(self.u(), mz));
        // q = C^ / L^ in the bound's arithmetic, and its magnitude.
        let q = self.bind(Expr::Div(self.value(c), self.value(l)));
        let aq = self.bind(Expr::Abs(q));
        let mq = self.bind(Expr::Add(aq, Arg::Lit(self.format.floor())));
        let el = self.rigorous(&bl, 1);
        let abs_l = self.bind(Expr::Abs(self.value(l)));
        let (low, term) = match el {
            Some(el) => {
                let d = self.bind(Expr::Sub(abs_l, el.clone()));
                let low = self.bind(Expr::Mul(d, shrink.clone()));
                (low, self.bind(Expr::Mul(mq, el)))
            }
            None => (abs_l, self.bind(Expr::Mul(Arg::Lit(0.0), self.value(l)))),
        };
        let num = match bc.error.clone() {
            Some(ec) => self.bind(Expr::Add(ec, term)),
            None => term,
        };
        let quotient = self.bind(Expr::Div(num, low.clone()));
        let quotient = self.bind(Expr::PositiveOr(low, quotient));
        let quotient = self.bind(Expr::Add(quotient, r));
        // Both rho^ and the exact rho lie in [0, 1]: never more than 1 apart.
        let quotient = self.bind(Expr::AtMost(quotient, Arg::Lit(1.0)));
        // Decided sticking: RN(RN(C^ - L^)(1 - 2u)) > RN(e_C F + e_L F) gives 0.
        let gap = self.bind(Expr::Sub(self.value(c), self.value(l)));
        let gap = self.bind(Expr::Mul(gap, shrink));
        let margins: Vec<Arg> = [self.rigorous(&bc, 2), self.rigorous(&bl, 2)]
            .into_iter()
            .flatten()
            .collect();
        let margin = match margins.as_slice() {
            [] => Arg::Lit(0.0),
            [m] => m.clone(),
            [a, b] => self.bind(Expr::Add(a.clone(), b.clone())),
            _ => unreachable!("two sides"),
        };
        let error = self.bind(Expr::GreaterOr(gap, margin, Arg::Lit(0.0), quotient));
        self.clamped.insert(z.clone());
        Bounded {
            error: Some(error),
            depth: bc.depth.max(bl.depth + 1) + 4,
        }
    }

    /// The bound of `z = sqrt(x)`, `x` a clamped quotient (module docs).
    pub(crate) fn root(&mut self, x: &Operand, z: &Operand) -> Bounded {
        let bx = self.bounded(x);
        let mz = self.mag(z);
        let r = self.bind(Expr::Mul(self.u(), mz));
        let Some(ex) = bx.error else {
            return Bounded {
                error: Some(r),
                depth: 0,
            };
        };
        let s = self.bind(Expr::Sqrt(self.value(x)));
        let t1 = self.bind(Expr::Div(ex.clone(), s));
        let t2 = self.bind(Expr::Sqrt(ex));
        let t = self.bind(Expr::AtMost(t1, t2));
        Bounded {
            error: Some(self.bind(Expr::Add(t, r))),
            depth: bx.depth + 3,
        }
    }
}
