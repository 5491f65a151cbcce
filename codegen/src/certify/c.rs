//! The certified companions spelled in C99 and in OpenCL C (one emitter, through the
//! [`Language`] hooks of the kernels): `noslip_d{n}_{free|fixed}_certified_{f64|f32}`,
//! `..._certified_fast_...`, and those of the FMA kernels `noslip_d{n}_{free|fixed}_fma_certified_...`
//! (fused steps through `fma`/`fmaf`, contraction off as in the plain kernels); the running
//! companions with rounded inputs `noslip_d{n}_{free|fixed}[_fma]_certified_rounded_{f64|f32}`
//! (two more parameters, `rho_nu` and `rho_gamma2`, after the kernel's; [`super::rounded`]);
//! and the `float` kernels' running companions with the bound in `double`,
//! `noslip_d{n}_{free|fixed}[_fma]_certified_f32_wide` ([`super::wide`]); and the running
//! companions of the rough-ball and Walton kernels,
//! `noslip_d{n}_{rough|walton}_{free|fixed}[_fma]_certified_{f64|f32}` (`law` after `ball2`
//! as in their plain kernels): appended to the C header (`noslip gen --lang c`) and to the
//! OpenCL source (`--lang opencl`, each with its batch kernel `NAME_batch`), with the plain
//! kernels' ABI plus one bound array per output array.

use super::{Arg, Certified, Expr, Format, Scheme};
use crate::backend::{constant_literal, BatchParam, Language, Precision};
use crate::model::{names, skew_pairs, Variant};
use crate::Arith;
use std::collections::HashSet;
use std::fmt::Write;

/// The kernel's precision: `float` for both `f32` formats.
fn precision(f: Format) -> Precision {
    match f {
        Format::F64 => Precision::F64,
        Format::F32 | Format::F32Wide => Precision::F32,
    }
}

/// The bound's C type: `double` but for [`Format::F32`].
fn bound_type(f: Format) -> &'static str {
    if f.bound_in_f64() {
        "double"
    } else {
        "float"
    }
}

/// A C literal of a float of the bound's type: its shortest round-trip decimal (`f`-suffixed
/// in `float`), so a correctly rounding compiler restores the same bits.
fn literal(f: Format, x: f64) -> String {
    if f.bound_in_f64() {
        format!("{x:e}")
    } else {
        format!("{:e}f", x as f32)
    }
}

/// An argument of a bound statement; a kernel value (`kernel` holds their names) converted
/// to `double` (exactly) where the bound runs in `double` and the kernel in `float`.
fn arg(f: Format, kernel: &HashSet<&str>, a: &Arg) -> String {
    match a {
        Arg::Name(n) if f == Format::F32Wide && kernel.contains(n.as_str()) => {
            format!("(double){n}")
        }
        Arg::Name(n) => n.clone(),
        Arg::Lit(x) => literal(f, *x),
    }
}

/// Each parameter array and the kernel inputs its elements hold (`radius1` a scalar); a
/// rough-family kernel's `law` (its fields, [`super::rust::law_of`]) after `ball2`.
fn arrays(
    n: usize,
    variant: Variant,
    law: Option<Vec<String>>,
) -> Vec<(&'static str, Vec<String>)> {
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
    if let Some(fields) = law {
        v.push(("law", fields));
    }
    v.push(("state1", state(1)));
    v.push(("state2", state(2)));
    v
}

/// The name of the C function: `noslip_d3_free_certified_f64`, for the fast scheme
/// `noslip_d3_free_certified_fast_f64`, for the FMA kernel `noslip_d3_free_fma_certified_f64`,
/// with rounded inputs `noslip_d3_free_certified_rounded_f64`, with the bound in `double`
/// `noslip_d3_free_certified_f32_wide`.
pub fn function_name(
    n: usize,
    variant: Variant,
    arith: Arith,
    f: Format,
    scheme: Scheme,
    rounded: bool,
) -> String {
    let kind = match (scheme, rounded) {
        (Scheme::Running, false) => "",
        (Scheme::Running, true) => "rounded_",
        (Scheme::Fast { .. }, _) => "fast_",
    };
    let fma = match arith {
        Arith::Plain => "",
        Arith::Fma => "_fma",
    };
    let format = match f {
        Format::F64 => "f64",
        Format::F32 => "f32",
        Format::F32Wide => "f32_wide",
    };
    format!(
        "noslip_d{n}_{}{fma}_certified_{kind}{format}",
        variant.name()
    )
}

/// The C name of `c`'s function ([`function_name`]; a rough-family kernel's with its
/// prefix, `noslip_d3_rough_free_certified_f64`, `noslip_d3_walton_fixed_fma_certified_f32`).
pub fn name_of(c: &Certified) -> String {
    let p = &c.program;
    let name = function_name(
        p.dim,
        p.variant,
        p.arith,
        c.format,
        c.scheme,
        !c.rounded.is_empty(),
    );
    match super::rust::law_of(p) {
        Some(("Walton", _)) => {
            name.replacen("_free", "_walton_free", 1)
                .replacen("_fixed", "_walton_fixed", 1)
        }
        Some(_) => name
            .replacen("_free", "_rough_free", 1)
            .replacen("_fixed", "_rough_fixed", 1),
        None => name,
    }
}

/// The function of `c` in `lang` (C99 or OpenCL C: their qualifiers, prologue and the
/// names of `fma`, `sqrt`, `fabs`), with its comment, and its batch entry point where `lang`
/// has one ([`Language::batch`]).
pub fn function(lang: &dyn Language, c: &Certified) -> String {
    let (p, f) = (&c.program, c.format);
    let n = p.dim;
    let ty = precision(f).c_type();
    let bty = bound_type(f);
    let len = n * (n - 1) / 2 + n;
    let bound_precision = if f.bound_in_f64() {
        Precision::F64
    } else {
        Precision::F32
    };
    let (fabs, bsqrt) = (lang.fabs(bound_precision), lang.sqrt(bound_precision));
    let (fma, ksqrt) = (lang.fma(precision(f)), lang.sqrt(precision(f)));
    let kernel: HashSet<&str> = p
        .inputs
        .iter()
        .map(String::as_str)
        .chain(p.constants.iter().map(|c| c.name.as_str()))
        .chain(p.steps.iter().map(|s| s.name.as_str()))
        .chain(c.rounded.iter().map(|r| r.param.as_str()))
        .collect();
    let arg = |f: Format, a: &Arg| arg(f, &kernel, a);
    let mut s = String::new();
    let fma_suffix = match p.arith {
        Arith::Plain => "",
        Arith::Fma => "_fma",
    };
    let law = super::rust::law_of(p);
    let family = match &law {
        Some(("Walton", _)) => "walton_",
        Some(_) => "rough_",
        None => "",
    };
    let plain = format!(
        "noslip_d{n}_{family}{}{fma_suffix}_{}",
        p.variant.name(),
        precision(f).suffix()
    );
    let against = if c.rounded.is_empty() {
        "the given floats".to_string()
    } else {
        "the intended real inputs: rho_nu and\n\
         // rho_gamma2 bound the relative rounding of each normal component and each gamma2 given\n\
         // (|x^ - x| <= rho |x|, rho < 2^-10), docs/accuracy.md \"Rounded inputs\""
            .to_string()
    };
    let _ = writeln!(
        s,
        "// {plain} (the same operations, bit for bit) and a rigorous bound on the absolute\n\
         // error of every output for these inputs, in the same branch-free pass ({}): bound1/bound2 hold, slot by slot,\n\
         // B >= |out - exact| for the exact map on {against}, or +inf where none holds.\n\
         // Ops: kernel {}; bound {} ops{}.",
        match c.scheme {
            Scheme::Running => "running error\n// analysis, docs/accuracy.md \"Certified companions\"".to_string(),
            Scheme::Fast { floor } => format!("a constant per output times\n// magnitudes from the inputs' largest absolute values, docs/accuracy.md \"Fast certified\n// companions\", magnitude floor {floor:e}"),
        },
        p.ops,
        c.bound_ops,
        if f == Format::F32Wide { " (in double)" } else { "" }
    );
    let arrays = arrays(n, p.variant, law.as_ref().map(|(_, f)| f.clone()));
    let mut batch: Vec<BatchParam> = arrays
        .iter()
        .map(|(a, e)| BatchParam::input(a, ty, Some(e.len())))
        .collect();
    let outs: Vec<usize> = c.outputs.iter().map(|o| o.body).collect();
    if p.variant == Variant::Fixed {
        batch.insert(1, BatchParam::input("radius1", ty, None));
    }
    for r in &c.rounded {
        batch.push(BatchParam::input(&r.param, ty, None));
    }
    for b in &outs {
        batch.push(BatchParam::output(&format!("out{b}"), ty, len));
    }
    for b in &outs {
        batch.push(BatchParam::output(&format!("bound{b}"), bty, len));
    }
    let params: Vec<String> = batch
        .iter()
        .map(|b| match (b.len, b.out) {
            (Some(l), false) => format!("const {} {}[{l}]", b.ty, b.name),
            (Some(l), true) => format!("{} {}[{l}]", b.ty, b.name),
            (None, _) => format!("{} {}", b.ty, b.name),
        })
        .collect();
    let name = name_of(c);
    let _ = writeln!(
        s,
        "{} void {name}({})\n{{",
        lang.qualifiers(),
        params.join(", ")
    );
    if !lang.body_prologue().is_empty() {
        let _ = writeln!(s, "    {}", lang.body_prologue());
    }
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
            Expr::Step(k) => super::step_expr(p, &p.steps[*k].op, fma, ksqrt, false),
            Expr::Sqrt(a) => format!("{bsqrt}({})", arg(f, a)),
            Expr::AtMost(x, y) => {
                let (x, y) = (arg(f, x), arg(f, y));
                format!("{x} < {y} ? {x} : {y}")
            }
            Expr::GreaterOr(a, b, x, y) => format!(
                "{} > {} ? {} : {}",
                arg(f, a),
                arg(f, b),
                arg(f, x),
                arg(f, y)
            ),
            Expr::Abs(a) => format!("{fabs}({})", arg(f, a)),
            Expr::Add(a, b) => format!("{} + {}", arg(f, a), arg(f, b)),
            Expr::Sub(a, b) => format!("{} - {}", arg(f, a), arg(f, b)),
            Expr::Mul(a, b) => format!("{} * {}", arg(f, a), arg(f, b)),
            Expr::Div(a, b) => format!("{} / {}", arg(f, a), arg(f, b)),
            Expr::PositiveOr(x, y) => {
                format!("{} > 0 ? {} : ({bty})INFINITY", arg(f, x), arg(f, y))
            }
            Expr::BoundOrInf(x) => {
                let x = arg(f, x);
                format!("{x} >= 0 ? {x} : ({bty})INFINITY")
            }
            Expr::AtLeast(x, y) => {
                let (x, y) = (arg(f, x), arg(f, y));
                format!("{x} > {y} ? {x} : {y}")
            }
        };
        let st_ty = match st.expr {
            Expr::Const(_) | Expr::Step(_) => ty,
            _ => bty,
        };
        let _ = writeln!(s, "    const {st_ty} {} = {e};", st.name);
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
    s.push_str(&lang.batch(&name, &batch));
    s
}

/// Whether `c` computes in `double` (its kernel or its bound): in OpenCL it needs
/// `cl_khr_fp64`.
fn uses_double(c: &Certified) -> bool {
    c.format.bound_in_f64()
}

/// The companions of `dims` in the order of the emitted files: per format (`f64`, then
/// `f32`), dimension, kernel (plain, FMA) and variant, the running, fast and rounded-input
/// companions; then the `float` kernels' running companions with the bound in `double`; then
/// the rough-ball and Walton kernels' running companions, `f64` then `f32`.
pub fn companions(dims: &[usize]) -> Vec<Certified> {
    let mut all = Vec::new();
    for f in [Format::F64, Format::F32] {
        for &n in dims {
            for arith in Arith::ALL {
                for v in Variant::ALL {
                    all.push(Certified::of(n, v, arith, f));
                    all.push(Certified::of_fast(n, v, arith, f));
                    all.push(Certified::of_rounded(n, v, arith, f));
                }
            }
        }
    }
    for &n in dims {
        for arith in Arith::ALL {
            for v in Variant::ALL {
                all.push(Certified::of(n, v, arith, Format::F32Wide));
            }
        }
    }
    // The rough-ball and Walton kernels' running companions.
    for f in [Format::F64, Format::F32] {
        for &n in dims {
            for arith in Arith::ALL {
                for v in Variant::ALL {
                    all.push(Certified::of_rough(n, v, arith, f));
                    all.push(Certified::of_walton(n, v, arith, f));
                }
            }
        }
    }
    all
}

/// The functions of `companions` in `lang`, in order, after a comment on their ABI; each
/// run of companions computing in `double` wrapped in `lang`'s `double` guard
/// ([`Language::begin`], [`Language::end`]; OpenCL's `cl_khr_fp64`, nothing in C).
pub fn functions_of(lang: &dyn Language, companions: &[Certified]) -> String {
    let mut s = String::from(
        "\n/* Certified companions: the plain kernels' parameters (and rho_nu, rho_gamma2 for the\n \
         * rounded-input ones), then out arrays, then one bound array per out array (the same\n \
         * layout; double for the _f32_wide ones). */\n",
    );
    let guard = |d: bool| if d { Precision::F64 } else { Precision::F32 };
    let mut open: Option<bool> = None;
    for c in companions {
        let d = uses_double(c);
        if open != Some(d) {
            if let Some(o) = open {
                s.push_str(&lang.end(guard(o)));
            }
            s.push_str(&lang.begin(guard(d)));
            open = Some(d);
        }
        s.push('\n');
        s.push_str(&function(lang, c));
    }
    if let Some(o) = open {
        s.push_str(&lang.end(guard(o)));
    }
    s
}

/// Every companion of `dims` ([`companions`]) in `lang` ([`functions_of`]): what the C
/// header and the OpenCL source append to the kernels.
pub fn functions(lang: &dyn Language, dims: &[usize]) -> String {
    functions_of(lang, &companions(dims))
}
