//! Certified companions of the generated kernels: the same operations, bit for bit, and in
//! the same branch-free pass a running error bound for every output, for the inputs of this
//! one call (`docs/accuracy.md`, "Certified companions").
//!
//! [`Certified::derive`] turns a lowered [`Program`] into a language-neutral list of
//! statements ([`Stmt`]): each kernel step as the plain kernel spells it, followed by the
//! float arithmetic of its bound. [`rust`] and [`c`] spell that list. The Walton kernels'
//! switch and square root have their own rules ([`clamp`]).
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

mod builder;
pub mod c;
pub mod clamp;
pub mod fast;
mod format;
pub mod rounded;
mod running;
pub mod rust;
#[cfg(test)]
mod tests;
pub mod wide;

pub use format::Format;

use crate::program::{Op, Operand, Program};

/// Past this many operations on a dependency path, a bound is made rigorous (multiplied by
/// `F(d)`) and its count restarts: it keeps every `F(d)` small and within the proof's range.
pub const DEPTH_LIMIT: u32 = 1000;

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
    /// `x` if `x < y`, else `y` (a NaN `x` gives `y`): `min`.
    AtMost(Arg, Arg),
    /// `sqrt(a)`, correctly rounded.
    Sqrt(Arg),
    /// `x` if `a > b`, else `y` (a NaN comparison gives `y`).
    GreaterOr(Arg, Arg, Arg, Arg),
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
/// A square root is `{sqrt}(a)`; a select `if x < y { a } else { b }` in Rust
/// (`select_rust`), `x < y ? a : b` in C, as the plain kernels spell them (the C and OpenCL
/// back end spells its kernels' steps with it: `crate::backend`).
pub(crate) fn step_expr(
    program: &Program,
    op: &Op,
    fma: &str,
    sqrt: &str,
    select_rust: bool,
) -> String {
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
        Op::Sqrt(a) => format!("{sqrt}({})", o(a)),
        Op::SelectLt([x, y, a, b]) if select_rust => {
            format!("if {} < {} {{ {} }} else {{ {} }}", o(x), o(y), o(a), o(b))
        }
        Op::SelectLt([x, y, a, b]) => format!("{} < {} ? {} : {}", o(x), o(y), o(a), o(b)),
    }
}

/// A kernel operation the companions do not bound (a square root or select outside the
/// Walton kernels' clamped quotient, [`clamp`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Unsupported(pub String);

impl std::fmt::Display for Unsupported {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "certified companions do not bound {}", self.0)
    }
}
