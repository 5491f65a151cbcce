//! A whitelist check that a generated kernel is straight-line code.
//!
//! Allowed in a kernel body: `let` bindings whose patterns are identifiers, `_`, arrays and
//! struct destructurings; the expressions `a + b`, `a - b`, `a * b`, `a / b`, `-a`, `&a`,
//! paths, integer literals, array and struct literals, `T::from_ratio(p, q)` with literal
//! arguments, `T::from_literal(x64, x32, "p", "q")` with literal arguments, and `x.clone()`. Anything else (`if`, `match`, loops, closures, other calls or
//! methods, macros, blocks, `return`, indexing) is a violation. Allowed at the top level of a
//! generated file: `use` items and such functions.

use syn::visit::{self, Visit};
use syn::{BinOp, Expr, Item, Pat, Stmt, UnOp};

/// A construct a straight-line kernel must not contain.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Violation {
    /// The function it is in (empty at the top level).
    pub function: String,
    /// The offending construct, as a message (e.g. "`if`", "a loop").
    pub what: String,
}

impl std::fmt::Display for Violation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "in `{}`: {}", self.function, self.what)
    }
}

struct Checker {
    function: String,
    violations: Vec<Violation>,
}

impl Checker {
    fn flag(&mut self, what: impl Into<String>) {
        self.violations.push(Violation {
            function: self.function.clone(),
            what: what.into(),
        });
    }
}

/// The segments of a call's path (`["T", "from_ratio"]`), empty for any other callee.
fn call_path(call: &syn::ExprCall) -> Vec<String> {
    match &*call.func {
        Expr::Path(p) => p
            .path
            .segments
            .iter()
            .map(|s| s.ident.to_string())
            .collect(),
        _ => Vec::new(),
    }
}

/// `T::mul_add(a, b, c)`, `T::mul_sub(..)` or `T::neg_mul_add(..)`: one fused operation.
fn is_fused_call(call: &syn::ExprCall) -> bool {
    matches!(
        call_path(call)
            .iter()
            .map(String::as_str)
            .collect::<Vec<_>>()[..],
        ["T", "mul_add" | "mul_sub" | "neg_mul_add"]
    ) && call.args.len() == 3
}

/// `T::sqrt(a)` or `T::select_lt(x, y, a, b)`: the Walton kernels' root and branch-free
/// select (`collision_core::ScalarRoot`).
fn is_root_or_select_call(call: &syn::ExprCall) -> bool {
    let path = call_path(call);
    match path.iter().map(String::as_str).collect::<Vec<_>>()[..] {
        ["T", "sqrt"] => call.args.len() == 1,
        ["T", "select_lt"] => call.args.len() == 4,
        _ => false,
    }
}

fn is_from_ratio_call(call: &syn::ExprCall) -> bool {
    let segments = call_path(call);
    let literal_int = |e: &Expr| match e {
        Expr::Lit(l) => matches!(l.lit, syn::Lit::Int(_)),
        Expr::Unary(u) => {
            matches!(u.op, UnOp::Neg(_))
                && matches!(&*u.expr, Expr::Lit(l) if matches!(l.lit, syn::Lit::Int(_)))
        }
        _ => false,
    };
    let literal = |e: &Expr, ok: fn(&syn::Lit) -> bool| match e {
        Expr::Lit(l) => ok(&l.lit),
        Expr::Unary(u) => {
            matches!(u.op, UnOp::Neg(_)) && matches!(&*u.expr, Expr::Lit(l) if ok(&l.lit))
        }
        _ => false,
    };
    let float = |l: &syn::Lit| matches!(l, syn::Lit::Float(_));
    let string = |l: &syn::Lit| matches!(l, syn::Lit::Str(_));
    let args: Vec<&Expr> = call.args.iter().collect();
    match segments.iter().map(String::as_str).collect::<Vec<_>>()[..] {
        ["T", "from_ratio"] => args.len() == 2 && args.iter().all(|e| literal_int(e)),
        ["T", "from_literal"] => {
            args.len() == 4
                && literal(args[0], float)
                && literal(args[1], float)
                && matches!(args[2], Expr::Lit(l) if string(&l.lit))
                && matches!(args[3], Expr::Lit(l) if string(&l.lit))
        }
        _ => false,
    }
}

impl<'ast> Visit<'ast> for Checker {
    fn visit_item(&mut self, item: &'ast Item) {
        match item {
            Item::Use(_) => {}
            Item::Fn(f) => {
                self.function = f.sig.ident.to_string();
                for stmt in &f.block.stmts {
                    self.visit_stmt(stmt);
                }
                self.function.clear();
            }
            _ => self.flag("an item other than `use` or `fn`"),
        }
    }

    fn visit_stmt(&mut self, stmt: &'ast Stmt) {
        match stmt {
            Stmt::Local(local) => {
                self.visit_pat(&local.pat);
                match &local.init {
                    Some(init) if init.diverge.is_none() => self.visit_expr(&init.expr),
                    Some(_) => self.flag("`let ... else`"),
                    None => self.flag("`let` without a value"),
                }
            }
            Stmt::Expr(e, _) => self.visit_expr(e),
            Stmt::Item(_) => self.flag("a nested item"),
            Stmt::Macro(_) => self.flag("a macro"),
        }
    }

    fn visit_pat(&mut self, pat: &'ast Pat) {
        match pat {
            Pat::Ident(p) if p.by_ref.is_none() && p.subpat.is_none() => {}
            Pat::Wild(_) | Pat::Rest(_) => {}
            Pat::Type(_) | Pat::Slice(_) | Pat::Struct(_) => visit::visit_pat(self, pat),
            _ => self.flag("a refutable or unusual pattern"),
        }
    }

    fn visit_expr(&mut self, expr: &'ast Expr) {
        match expr {
            Expr::Binary(b) => {
                if !matches!(
                    b.op,
                    BinOp::Add(_) | BinOp::Sub(_) | BinOp::Mul(_) | BinOp::Div(_)
                ) {
                    self.flag("a binary operator other than + - * /");
                }
                visit::visit_expr(self, expr)
            }
            Expr::Unary(u) if matches!(u.op, UnOp::Neg(_)) => visit::visit_expr(self, expr),
            Expr::Reference(r) if r.mutability.is_none() => visit::visit_expr(self, expr),
            Expr::Path(_) | Expr::Lit(_) | Expr::Paren(_) => visit::visit_expr(self, expr),
            Expr::Array(_) | Expr::Struct(_) => visit::visit_expr(self, expr),
            Expr::Call(c) if is_from_ratio_call(c) => {}
            Expr::Call(c) if is_fused_call(c) => visit::visit_expr_call(self, c),
            Expr::Call(c) if is_root_or_select_call(c) => visit::visit_expr_call(self, c),
            Expr::MethodCall(m) if m.method == "clone" && m.args.is_empty() => {
                self.visit_expr(&m.receiver)
            }
            Expr::If(_) => self.flag("`if`"),
            Expr::Match(_) => self.flag("`match`"),
            Expr::Loop(_) | Expr::While(_) | Expr::ForLoop(_) => self.flag("a loop"),
            Expr::Call(_) => self.flag(
                "a call other than `T::from_ratio(int, int)`, `T::from_literal(float, float, str, str)` or a fused `T::mul_add(a, b, c)`",
            ),
            Expr::MethodCall(_) => self.flag("a method call other than `.clone()`"),
            Expr::Closure(_) => self.flag("a closure"),
            Expr::Macro(_) => self.flag("a macro"),
            Expr::Index(_) => self.flag("indexing"),
            _ => self.flag(format!("a disallowed expression `{}`", kind(expr))),
        }
    }
}

fn kind(expr: &Expr) -> String {
    let text = quote::ToTokens::to_token_stream(expr).to_string();
    text.chars().take(40).collect()
}

/// Every violation of straight-line form in a generated file.
pub fn check(file: &syn::File) -> Vec<Violation> {
    let mut checker = Checker {
        function: String::new(),
        violations: Vec::new(),
    };
    for item in &file.items {
        checker.visit_item(item);
    }
    checker.violations
}

#[cfg(test)]
mod tests {
    use super::*;

    fn violations(src: &str) -> Vec<String> {
        check(&syn::parse_file(src).unwrap())
            .into_iter()
            .map(|v| v.what)
            .collect()
    }

    #[test]
    fn accepts_arithmetic_and_destructuring() {
        let src = "fn k<T>(nu: &[T; 2]) -> [T; 2] {
            let [a, _] = nu; let c_2: T = T::from_ratio(2, 1);
            let x: T = &c_2 * a; let y: T = -&x; let z: T = T::mul_add(&x, a, &y);
            [x, z.clone()] }";
        assert_eq!(violations(src), Vec::<String>::new());
    }

    #[test]
    fn rejects_control_flow_and_calls() {
        let cases = [
            (
                "fn k(a: f64) -> f64 { if a > 0.0 { a } else { -a } }",
                "`if`",
            ),
            ("fn k(a: f64) -> f64 { match a { _ => a } }", "`match`"),
            (
                "fn k(a: f64) -> f64 { let mut s = a; for _ in 0..2 { s = s + a; } s }",
                "a loop",
            ),
            (
                "fn k(a: f64) -> f64 { a.sqrt() }",
                "a method call other than `.clone()`",
            ),
            (
                "fn k(a: f64) -> f64 { f(a) }",
                "a call other than `T::from_ratio(int, int)`, `T::from_literal(float, float, str, str)` or a fused `T::mul_add(a, b, c)`",
            ),
            (
                "fn k(a: f64) -> f64 { T::mul_add(a, a) }",
                "a call other than `T::from_ratio(int, int)`, `T::from_literal(float, float, str, str)` or a fused `T::mul_add(a, b, c)`",
            ),
            (
                "fn k(a: f64) -> f64 { T::mul_add(a, a, if a > 0.0 { a } else { a }) }",
                "`if`",
            ),
            (
                "fn k(a: f64) -> f64 { g(a) }",
                "a call other than `T::from_ratio(int, int)`, `T::from_literal(float, float, str, str)` or a fused `T::mul_add(a, b, c)`",
            ),
            (
                "fn k(a: f64) -> f64 { T::from_literal(a, 0.1f32, \"1\", \"10\") }",
                "a call other than `T::from_ratio(int, int)`, `T::from_literal(float, float, str, str)` or a fused `T::mul_add(a, b, c)`",
            ),
            ("fn k(a: [f64; 2]) -> f64 { a[0] }", "indexing"),
            (
                "fn k(a: f64) -> bool { a < 1.0 }",
                "a binary operator other than + - * /",
            ),
        ];
        for (src, expected) in cases {
            let v = violations(src);
            assert!(v.iter().any(|w| w == expected), "{src}: {v:?}");
        }
        let literal =
            "fn k() -> f64 { let x: T = T::from_literal(-0.1f64, -0.1f32, \"-1\", \"10\"); x }";
        assert!(violations(literal).is_empty(), "{:?}", violations(literal));
    }
}
