//! The certified companions spelled in C99: `noslip_d{n}_{free|fixed}_certified_{f64|f32}`,
//! `..._certified_fast_...`, and those of the FMA kernels `noslip_d{n}_{free|fixed}_fma_certified_...`
//! (fused steps through `fma`/`fmaf`, contraction off as in the plain kernels), appended to
//! the C header (`noslip gen --lang c`), with the plain kernels' ABI plus one bound array per
//! output array.

use super::{Arg, Certified, Expr, Format, Scheme};
use crate::backend::{constant_literal, Precision};
use crate::model::{names, skew_pairs, Variant};
use crate::Arith;
use std::fmt::Write;

fn precision(f: Format) -> Precision {
    match f {
        Format::F64 => Precision::F64,
        Format::F32 => Precision::F32,
        Format::F32Wide => unreachable!("the f32 companions with f64 bounds are Rust only"),
    }
}

/// A C literal of a float of `format`: its shortest round-trip decimal (`f`-suffixed in
/// `float`), so a correctly rounding compiler restores the same bits.
fn literal(f: Format, x: f64) -> String {
    match f {
        Format::F64 => format!("{x:e}"),
        Format::F32 => format!("{:e}f", x as f32),
        Format::F32Wide => unreachable!("the f32 companions with f64 bounds are Rust only"),
    }
}

fn arg(f: Format, a: &Arg) -> String {
    match a {
        Arg::Name(n) => n.clone(),
        Arg::Lit(x) => literal(f, *x),
    }
}

/// Each parameter array and the kernel inputs its elements hold (`radius1` a scalar).
fn arrays(n: usize, variant: Variant) -> Vec<(&'static str, Vec<String>)> {
    let ball = |b: usize| vec![names::inv_mass(b), names::radius(b), names::gamma2(b)];
    let state = |b: usize| -> Vec<String> {
        skew_pairs(n)
            .into_iter()
            .map(|(i, j)| names::spin(b, i, j))
            .chain((0..n).map(|k| names::velocity(b, k)))
            .collect()
    };
    let mut v = vec![("nu", (0..n).map(names::nu).collect::<Vec<_>>())];
    if variant == Variant::Free {
        v.push(("ball1", ball(1)));
    }
    v.push(("ball2", ball(2)));
    v.push(("state1", state(1)));
    v.push(("state2", state(2)));
    v
}

/// The name of the C function: `noslip_d3_free_certified_f64`, for the fast scheme
/// `noslip_d3_free_certified_fast_f64`, for the FMA kernel `noslip_d3_free_fma_certified_f64`.
pub fn function_name(
    n: usize,
    variant: Variant,
    arith: Arith,
    f: Format,
    scheme: Scheme,
) -> String {
    let fast = match scheme {
        Scheme::Running => "",
        Scheme::Fast { .. } => "fast_",
    };
    let fma = match arith {
        Arith::Plain => "",
        Arith::Fma => "_fma",
    };
    format!(
        "noslip_d{n}_{}{fma}_certified_{fast}{}",
        variant.name(),
        precision(f).suffix()
    )
}

/// The C function of `c`, with its comment.
pub fn function(c: &Certified) -> String {
    let (p, f) = (&c.program, c.format);
    let n = p.dim;
    let ty = precision(f).c_type();
    let len = n * (n - 1) / 2 + n;
    let (fabs, fma) = match f {
        Format::F64 => ("fabs", "fma"),
        Format::F32 => ("fabsf", "fmaf"),
        Format::F32Wide => unreachable!("the f32 companions with f64 bounds are Rust only"),
    };
    let mut s = String::new();
    let fma_suffix = match p.arith {
        Arith::Plain => "",
        Arith::Fma => "_fma",
    };
    let plain = format!(
        "noslip_d{n}_{}{fma_suffix}_{}",
        p.variant.name(),
        precision(f).suffix()
    );
    let _ = writeln!(
        s,
        "// {plain} (the same operations, bit for bit) and a rigorous bound on the absolute\n\
         // error of every output for these inputs, in the same branch-free pass ({}): bound1/bound2 hold, slot by slot,\n\
         // B >= |out - exact| for the exact map on the given floats, or +inf where none holds.\n\
         // Ops: kernel {}; bound {} ops.",
        match c.scheme {
            Scheme::Running => "running error\n// analysis, docs/accuracy.md \"Certified companions\"".to_string(),
            Scheme::Fast { floor } => format!("a constant per output times\n// magnitudes from the inputs' largest absolute values, docs/accuracy.md \"Fast certified\n// companions\", magnitude floor {floor:e}"),
        },
        p.ops, c.bound_ops
    );
    let arrays = arrays(n, p.variant);
    let mut params: Vec<String> = arrays
        .iter()
        .map(|(a, e)| format!("const {ty} {a}[{}]", e.len()))
        .collect();
    let outs: Vec<usize> = c.outputs.iter().map(|o| o.body).collect();
    if p.variant == Variant::Fixed {
        params.insert(1, format!("{ty} radius1"));
    }
    for b in &outs {
        params.push(format!("{ty} out{b}[{len}]"));
    }
    for b in &outs {
        params.push(format!("{ty} bound{b}[{len}]"));
    }
    let _ = writeln!(
        s,
        "static inline NOSLIP_NO_CONTRACT void {}({})\n{{\n    NOSLIP_FP_CONTRACT_OFF",
        function_name(n, p.variant, p.arith, f, c.scheme),
        params.join(", ")
    );
    for (a, elems) in &arrays {
        let mut any = false;
        for (k, e) in elems.iter().enumerate() {
            if p.inputs.contains(e) {
                any = true;
                let _ = writeln!(s, "    const {ty} {e} = {a}[{k}];");
            }
        }
        if !any {
            let _ = writeln!(s, "    (void){a};");
        }
    }
    if p.variant == Variant::Fixed && !p.inputs.contains(&names::radius(1)) {
        let _ = writeln!(s, "    (void)radius1;");
    }
    for st in &c.stmts {
        let e = match &st.expr {
            Expr::Const(k) => constant_literal(&p.constants[*k].value, precision(f)),
            Expr::Step(k) => super::step_expr(p, &p.steps[*k].op, fma),
            Expr::Abs(a) => format!("{fabs}({})", arg(f, a)),
            Expr::Add(a, b) => format!("{} + {}", arg(f, a), arg(f, b)),
            Expr::Sub(a, b) => format!("{} - {}", arg(f, a), arg(f, b)),
            Expr::Mul(a, b) => format!("{} * {}", arg(f, a), arg(f, b)),
            Expr::Div(a, b) => format!("{} / {}", arg(f, a), arg(f, b)),
            Expr::PositiveOr(x, y) => {
                format!("{} > 0 ? {} : ({ty})INFINITY", arg(f, x), arg(f, y))
            }
            Expr::BoundOrInf(x) => {
                let x = arg(f, x);
                format!("{x} >= 0 ? {x} : ({ty})INFINITY")
            }
            Expr::AtLeast(x, y) => {
                let (x, y) = (arg(f, x), arg(f, y));
                format!("{x} > {y} ? {x} : {y}")
            }
        };
        let _ = writeln!(s, "    const {ty} {} = {e};", st.name);
    }
    for o in &c.outputs {
        for (k, x) in o.values.iter().enumerate() {
            let _ = writeln!(s, "    out{}[{k}] = {};", o.body, p.name(x));
        }
        for (k, b) in o.bounds.iter().enumerate() {
            let _ = writeln!(s, "    bound{}[{k}] = {};", o.body, arg(f, b));
        }
    }
    s.push_str("}\n");
    s
}

/// The companions of `dims` in both formats (`f64` first), for the C header.
pub fn functions(dims: &[usize]) -> String {
    let mut s = String::from(
        "\n/* Certified companions: the plain kernels' parameters, then out arrays, then one\n \
         * bound array per out array (the same layout). */\n",
    );
    for f in [Format::F64, Format::F32] {
        for &n in dims {
            for arith in Arith::ALL {
                for v in Variant::ALL {
                    s.push('\n');
                    s.push_str(&function(&Certified::of(n, v, arith, f)));
                    s.push('\n');
                    s.push_str(&function(&Certified::of_fast(n, v, arith, f)));
                }
            }
        }
    }
    s
}
