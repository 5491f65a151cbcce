//! The certified companions spelled in Rust: `kernels::dN::certified::{free, fixed}` (`f64`)
//! and `{free_f32, fixed_f32}`, monomorphic, returning the plain kernel's outputs and a bound
//! per output component in the same layout.

use super::{Arg, Certified, Expr, Format, Scheme};
use crate::model::{names, skew_pairs, Variant};
use crate::program::Program;
use std::fmt::Write;

/// A literal of the kernel's type in `format`: the float's shortest round-trip decimal,
/// suffixed.
fn literal(format: Format, x: f64) -> String {
    match format {
        Format::F64 => format!("{x:e}f64"),
        Format::F32 | Format::F32Wide => format!("{:e}f32", x as f32),
    }
}

/// A literal of the bound's type in `format`.
fn bound_literal(format: Format, x: f64) -> String {
    if format.bound_in_f64() {
        format!("{x:e}f64")
    } else {
        format!("{:e}f32", x as f32)
    }
}

/// The kernel's type.
fn ty(format: Format) -> &'static str {
    match format {
        Format::F64 => "f64",
        Format::F32 | Format::F32Wide => "f32",
    }
}

/// The bound's type.
fn bound_ty(format: Format) -> &'static str {
    if format.bound_in_f64() {
        "f64"
    } else {
        "f32"
    }
}

/// An argument of a bound statement; a kernel value (`kernel` holds their names) widened to
/// `f64` (exactly) where the bound runs in `f64` and the kernel in `f32`.
fn arg(format: Format, kernel: &std::collections::HashSet<&str>, a: &Arg) -> String {
    match a {
        Arg::Name(n) if format == Format::F32Wide && kernel.contains(n.as_str()) => {
            format!("f64::from({n})")
        }
        Arg::Name(n) => n.clone(),
        Arg::Lit(x) => bound_literal(format, *x),
    }
}

/// The law a rough-family kernel reads from its `law` parameter: `Restitution` (`e`,
/// `beta`: the rough-ball kernels) or `Walton` (`e`, `mu`, `beta0`), told by the inputs it
/// reads; `None` for a no-slip kernel.
pub(crate) fn law_of(p: &Program) -> Option<(&'static str, Vec<String>)> {
    let reads = |x: String| p.inputs.contains(&x);
    if reads(names::friction_mu()) || reads(names::walton_beta0()) {
        Some((
            "Walton",
            vec![
                names::restitution_e(),
                names::friction_mu(),
                names::walton_beta0(),
            ],
        ))
    } else if reads(names::restitution_e()) || reads(names::restitution_beta()) {
        Some((
            "Restitution",
            vec![names::restitution_e(), names::restitution_beta()],
        ))
    } else {
        None
    }
}

#[cfg(test)]
/// Whether `p` is a rough-ball kernel (constant `(e, beta)`, read from `law: &Restitution`).
pub(crate) fn is_rough(p: &Program) -> bool {
    law_of(p).is_some_and(|(t, _)| t == "Restitution")
}

/// How each kernel input is read from the Rust parameters (and, for a rough-ball kernel,
/// `law`'s fields).
pub(crate) fn rust_inputs(n: usize, variant: Variant, law: &[String]) -> Vec<(String, String)> {
    let mut v: Vec<(String, String)> = (0..n).map(|k| (names::nu(k), format!("nu[{k}]"))).collect();
    for x in law {
        v.push((x.clone(), format!("law.{x}")));
    }
    for body in 1..=2 {
        if variant == Variant::Fixed && body == 1 {
            v.push((names::radius(1), "*radius1".into()));
        } else {
            v.push((names::inv_mass(body), format!("ball{body}.inv_mass")));
            v.push((names::radius(body), format!("ball{body}.radius")));
            v.push((names::gamma2(body), format!("ball{body}.gamma2")));
        }
        for (k, (i, j)) in skew_pairs(n).into_iter().enumerate() {
            v.push((names::spin(body, i, j), format!("state{body}.spin[{k}]")));
        }
        for k in 0..n {
            v.push((
                names::velocity(body, k),
                format!("state{body}.velocity[{k}]"),
            ));
        }
    }
    v
}

/// The function `name` of `c`.
pub fn function(c: &Certified, name: &str) -> String {
    let (p, f) = (&c.program, c.format);
    let (n, t) = (p.dim, ty(f));
    let s = n * (n - 1) / 2;
    let state = format!("BodyState<{t}, {n}, {s}>");
    let mut out = String::new();
    let variant = p.variant;
    let law = law_of(p);
    let family = match &law {
        Some(("Walton", _)) => "walton::",
        Some(_) => "rough::",
        None => "",
    };
    let how = match c.scheme {
        Scheme::Running if f == Format::F32Wide => "(running error analysis, the bound in `f64`:\n\
             /// tighter than `f32`'s and without its overflow, `noslip_codegen::certify::wide`)"
            .to_string(),
        Scheme::Running => "(running error analysis, `noslip_codegen::certify`)".to_string(),
        Scheme::Fast { floor } => format!(
            "(a constant fixed at generation times a magnitude of each output computed from the\n\
             /// inputs' largest absolute values, `noslip_codegen::certify::fast`; looser than\n\
             /// the running companions where the kernel cancels; magnitude floor `{floor:e}`)"
        ),
    };
    let _ = writeln!(
        out,
        "/// [`super::{}{}`] in `{t}` (the same operations, bit for bit) with a rigorous bound on the\n\
         /// absolute error of every output for these inputs, computed in the same branch-free pass\n\
         /// {how}: returns `(outputs, bounds)`, each\n\
         /// bound in its output's slot, `|computed - exact| <= bound` for the exact map on {}; `+inf` where no bound holds (a divisor not provably nonzero, overflow, a\n\
         /// non-finite input).\n\
         ///\n\
         /// Ops: {} of the kernel, {} of the bound.",
        family,
        match p.arith {
            crate::Arith::Plain => variant.name().to_string(),
            crate::Arith::Fma => format!("{}_fma", variant.name()),
        },
        if c.rounded.is_empty() {
            "the given\n/// floats".to_string()
        } else {
            "the intended real inputs:\n\
             /// `rho.nu` and `rho.gamma2` bound the relative rounding of each normal component and\n\
             /// each `gamma2` given (`|x^ - x| <= rho |x|`, `rho < 2^-10`; `noslip_codegen::certify::rounded`)".to_string()
        },
        p.ops,
        c.bound_ops
    );
    // The FMA companions, like the FMA kernels, are always inlined: compiled with their
    // caller's target features (`collide_certified_fma_by`), so `mul_add` is an instruction.
    let inline = match p.arith {
        crate::Arith::Plain => "#[inline]",
        crate::Arith::Fma => "#[inline(always)]",
    };
    let bt = bound_ty(f);
    let bstate = format!("BodyState<{bt}, {n}, {s}>");
    let (params, ret) = match variant {
        Variant::Free => (
            format!("nu: &[{t}; {n}], ball1: &Ball<{t}>, ball2: &Ball<{t}>, state1: &{state}, state2: &{state}"),
            format!("([{state}; 2], [{bstate}; 2])"),
        ),
        Variant::Fixed => (
            format!("nu: &[{t}; {n}], radius1: &{t}, ball2: &Ball<{t}>, state1: &{state}, state2: &{state}"),
            format!("({state}, {bstate})"),
        ),
    };
    let kernel: std::collections::HashSet<&str> = p
        .inputs
        .iter()
        .map(String::as_str)
        .chain(p.constants.iter().map(|c| c.name.as_str()))
        .chain(p.steps.iter().map(|s| s.name.as_str()))
        .collect();
    let arg = |f: Format, a: &Arg| arg(f, &kernel, a);
    let mut params = params;
    if let Some((law_ty, _)) = &law {
        params = params.replace(", state1:", &format!(", law: &{law_ty}<{t}>, state1:"));
    }
    if !c.rounded.is_empty() {
        params.push_str(&format!(", rho: &InputRounding<{t}>"));
    }
    let _ = writeln!(
        out,
        "{inline}\n#[allow(non_snake_case, unused_variables, clippy::too_many_arguments, clippy::neg_multiply)]\n\
         pub fn {name}({params}) -> {ret} {{"
    );
    let fields = law.map(|(_, f)| f).unwrap_or_default();
    for (input, access) in rust_inputs(n, variant, &fields) {
        if p.inputs.contains(&input) {
            let _ = writeln!(out, "let {input}: {t} = {access};");
        }
    }
    for r in &c.rounded {
        let field = r.param.trim_start_matches("rho_");
        let _ = writeln!(out, "let {}: {t} = rho.{field};", r.param);
    }
    for st in &c.stmts {
        let e = match &st.expr {
            Expr::Const(k) => literal(f, f_round(f, &p.constants[*k].value)),
            Expr::Step(k) => super::step_expr(
                p,
                &p.steps[*k].op,
                &format!("{t}::mul_add"),
                &format!("{t}::sqrt"),
                true,
            ),
            Expr::Sqrt(a) => format!("{bt}::sqrt({})", arg(f, a)),
            Expr::AtMost(x, y) => {
                let (x, y) = (arg(f, x), arg(f, y));
                format!("if {x} < {y} {{ {x} }} else {{ {y} }}")
            }
            Expr::GreaterOr(a, b, x, y) => format!(
                "if {} > {} {{ {} }} else {{ {} }}",
                arg(f, a),
                arg(f, b),
                arg(f, x),
                arg(f, y)
            ),
            Expr::Abs(a) => format!("{bt}::abs({})", arg(f, a)),
            Expr::Add(a, b) => format!("{} + {}", arg(f, a), arg(f, b)),
            Expr::Sub(a, b) => format!("{} - {}", arg(f, a), arg(f, b)),
            Expr::Mul(a, b) => format!("{} * {}", arg(f, a), arg(f, b)),
            Expr::Div(a, b) => format!("{} / {}", arg(f, a), arg(f, b)),
            Expr::PositiveOr(x, y) => {
                format!("{bt}::positive_or_inf({}, {})", arg(f, x), arg(f, y))
            }
            Expr::BoundOrInf(x) => format!("{bt}::bound_or_inf({})", arg(f, x)),
            Expr::AtLeast(x, y) => {
                let (x, y) = (arg(f, x), arg(f, y));
                format!("if {x} > {y} {{ {x} }} else {{ {y} }}")
            }
        };
        let st_ty = match st.expr {
            Expr::Const(_) | Expr::Step(_) => t,
            _ => bt,
        };
        let _ = writeln!(out, "let {}: {st_ty} = {e};", st.name);
    }
    let body = |o: &super::CertifiedOutput, values: bool| {
        let items: Vec<String> = if values {
            o.values.iter().map(|x| p.name(x).to_string()).collect()
        } else {
            o.bounds.iter().map(|b| arg(f, b)).collect()
        };
        format!(
            "BodyState {{ spin: [{}], velocity: [{}] }}",
            items[..s].join(", "),
            items[s..].join(", ")
        )
    };
    let all = |values: bool| -> Vec<String> { c.outputs.iter().map(|o| body(o, values)).collect() };
    let _ = match variant {
        Variant::Free => writeln!(
            out,
            "([{}], [{}])",
            all(true).join(", "),
            all(false).join(", ")
        ),
        Variant::Fixed => writeln!(out, "({}, {})", all(true).join(", "), all(false).join(", ")),
    };
    out.push_str("}\n");
    out
}

fn f_round(f: Format, v: &num_rational::BigRational) -> f64 {
    f.round(v)
}

/// The Rust name of a companion: `free`, `fixed_fast`, `free_fma`, `fixed_fma_fast_f32`, ...
pub fn function_name(variant: Variant, arith: crate::Arith, fast: bool, format: Format) -> String {
    let fma = match arith {
        crate::Arith::Plain => "",
        crate::Arith::Fma => "_fma",
    };
    let fast = if fast { "_fast" } else { "" };
    let f32 = match format {
        Format::F64 => "",
        Format::F32 => "_f32",
        Format::F32Wide => "_f32_wide",
    };
    format!("{}{fma}{fast}{f32}", variant.name())
}

/// The Rust name of a running companion with rounded inputs: `free_rounded`,
/// `fixed_fma_rounded_f32`, ...
pub fn rounded_name(variant: Variant, arith: crate::Arith, format: Format) -> String {
    let fma = match arith {
        crate::Arith::Plain => "",
        crate::Arith::Fma => "_fma",
    };
    let f32 = match format {
        Format::F64 => "",
        Format::F32 => "_f32",
        Format::F32Wide => "_f32_wide",
    };
    format!("{}{fma}_rounded{f32}", variant.name())
}

/// The file name of dimension `dim`'s companions: `certified_{dim}.rs`.
pub fn file_name(dim: usize) -> String {
    format!("certified_{dim}.rs")
}

/// The companions of dimension `dim` (`free`, `fixed` in `f64`; `free_f32`, `fixed_f32`;
/// the fast ones `free_fast`, `fixed_fast`, `free_fast_f32`, `fixed_fast_f32`; those of
/// the FMA kernels, `free_fma`, `free_fma_fast`, `free_fma_f32`, ...: [`function_name`];
/// the rounded-input ones [`rounded_name`]; the wide ones `free_f32_wide`, ...; and the
/// rough-ball and Walton kernels' running companions `rough_free`, `walton_fixed_fma_f32`,
/// ...)
/// as one formatted file; `crate_path` as for [`crate::generate`].
pub fn generate(dim: usize, crate_path: &str) -> String {
    // One companion: its line in the header (op counts) and its function.
    fn push(header: &mut String, src: &mut String, c: &Certified, name: &str, unit: &str) {
        let _ = writeln!(
            header,
            "// {name}: kernel {}; bound {} ops{unit}.",
            c.program.ops, c.bound_ops
        );
        src.push_str(&function(c, name));
    }
    let mut src = format!(
        "use {crate_path}::{{Ball, BodyState, Restitution, Walton}};\nuse {crate_path}::certified::{{Certify, InputRounding}};\n"
    );
    let mut header = format!(
        "// @generated by noslip-codegen (codegen/src/certify): certified companions for n = {dim}.\n\
         // Do not edit: it is rewritten by collision-core's build.rs.\n"
    );
    for format in [Format::F64, Format::F32] {
        for arith in crate::Arith::ALL {
            for variant in Variant::ALL {
                for fast in [false, true] {
                    let c = match fast {
                        false => Certified::of(dim, variant, arith, format),
                        true => Certified::of_fast(dim, variant, arith, format),
                    };
                    let name = function_name(variant, arith, fast, format);
                    push(&mut header, &mut src, &c, &name, "");
                }
                // The running companion with the normal and gamma2 taken as rounded.
                let c = Certified::of_rounded(dim, variant, arith, format);
                let name = rounded_name(variant, arith, format);
                push(&mut header, &mut src, &c, &name, "");
            }
        }
    }
    // The rough-ball kernels' running companions (constant `(e, beta)`).
    for format in [Format::F64, Format::F32] {
        for arith in crate::Arith::ALL {
            for variant in Variant::ALL {
                let c = Certified::of_rough(dim, variant, arith, format);
                let name = format!("rough_{}", function_name(variant, arith, false, format));
                push(&mut header, &mut src, &c, &name, "");
            }
        }
    }
    // The Walton kernels' running companions (`(e, mu, beta0)`: the switch and the root
    // bounded by `certify::clamp`).
    for format in [Format::F64, Format::F32] {
        for arith in crate::Arith::ALL {
            for variant in Variant::ALL {
                let c = Certified::of_walton(dim, variant, arith, format);
                let name = format!("walton_{}", function_name(variant, arith, false, format));
                push(&mut header, &mut src, &c, &name, "");
            }
        }
    }
    // The f32 kernels' running companions with the bound computed in f64.
    for arith in crate::Arith::ALL {
        for variant in Variant::ALL {
            let c = Certified::of(dim, variant, arith, Format::F32Wide);
            let name = function_name(variant, arith, false, Format::F32Wide);
            push(&mut header, &mut src, &c, &name, " (in f64)");
        }
    }
    src.push_str(
        "/// The `f64` companions under the names generic code uses.\n\
         pub mod in_f64 {\n\
         pub use super::{fixed, fixed_fast, free, free_fast};\n\
         pub use super::{fixed_fma, fixed_fma_fast, free_fma, free_fma_fast};\n\
         pub use super::{fixed_fma_rounded, fixed_rounded, free_fma_rounded, free_rounded};\n\
         pub use super::{rough_fixed, rough_fixed_fma, rough_free, rough_free_fma};\n\
         pub use super::{walton_fixed, walton_fixed_fma, walton_free, walton_free_fma};\n\
         }\n\
         /// The `f32` companions under the names generic code uses.\n\
         pub mod in_f32 {\n\
         pub use super::{fixed_f32 as fixed, fixed_fast_f32 as fixed_fast, free_f32 as free, free_fast_f32 as free_fast};\n\
         pub use super::{fixed_fma_f32 as fixed_fma, fixed_fma_fast_f32 as fixed_fma_fast, free_fma_f32 as free_fma, free_fma_fast_f32 as free_fma_fast};\n\
         pub use super::{fixed_fma_rounded_f32 as fixed_fma_rounded, fixed_rounded_f32 as fixed_rounded, free_fma_rounded_f32 as free_fma_rounded, free_rounded_f32 as free_rounded};\n\
         pub use super::{rough_fixed_f32 as rough_fixed, rough_fixed_fma_f32 as rough_fixed_fma, rough_free_f32 as rough_free, rough_free_fma_f32 as rough_free_fma};\n\
         pub use super::{walton_fixed_f32 as walton_fixed, walton_fixed_fma_f32 as walton_fixed_fma, walton_free_f32 as walton_free, walton_free_fma_f32 as walton_free_fma};\n\
         }\n",
    );
    let file = crate::emit::parse(src.parse().expect("certified source tokenizes"));
    format!("{header}\n{}", prettyplease::unparse(&file))
}
