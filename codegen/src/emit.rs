//! Emission of a built kernel as Rust source: `quote!` token streams, parsed back by `syn`
//! (a malformed emission fails loudly), checked to be straight-line, formatted by
//! `prettyplease`.
//!
//! The emitted functions are generic over the runtime crate's `Scalar` (f32, f64, exact
//! rationals), with every operation on references (`&a * &b`), so the same source serves
//! `Copy` floats and heap-allocated rationals.

use crate::arith::Arith;
use crate::bindings::{const_value, ident, lit, Namer};
use crate::ir::{Id, Node};
use crate::model::{names, skew_pairs, KernelGraph, Law, Variant};
use crate::program::{Op, Operand, Program};
use crate::schedule::OpCount;
use proc_macro2::TokenStream;
use quote::quote;
use std::collections::{BTreeSet, HashMap};

/// One emitted kernel with its cost.
#[derive(Debug)]
pub struct EmittedKernel {
    /// The dimension `n`.
    pub dim: usize,
    /// Which bodies move.
    pub variant: Variant,
    /// Plain or fused arithmetic.
    pub arith: Arith,
    /// Its arithmetic operations (the `fma` count is nonzero only for [`Arith::Fma`]).
    pub ops: OpCount,
    /// Intermediate terms (`let` bindings of computed values).
    pub terms: usize,
    /// The function item (doc comment, attributes, signature and body), not yet formatted.
    pub tokens: TokenStream,
}

pub(crate) fn doc_lines(lines: &[String]) -> TokenStream {
    lines
        .iter()
        .map(|l| {
            let l = format!(" {l}");
            quote!(#[doc = #l])
        })
        .collect()
}

/// An array pattern binding the live names and `_` for the rest.
pub(crate) fn array_pattern(
    names: impl IntoIterator<Item = String>,
    live: &BTreeSet<String>,
) -> TokenStream {
    let elems = names.into_iter().map(|n| {
        if live.contains(&n) {
            let i = ident(&n);
            quote!(#i)
        } else {
            quote!(_)
        }
    });
    quote!([#(#elems),*])
}

pub(crate) fn state_pattern(n: usize, body: usize, live: &BTreeSet<String>) -> TokenStream {
    let spin = array_pattern(
        skew_pairs(n)
            .into_iter()
            .map(|(i, j)| names::spin(body, i, j)),
        live,
    );
    let velocity = array_pattern((0..n).map(|k| names::velocity(body, k)), live);
    quote!(BodyState { spin: #spin, velocity: #velocity })
}

fn ball_pattern(body: usize, live: &BTreeSet<String>) -> TokenStream {
    let fields = [
        ("inv_mass", names::inv_mass(body)),
        ("radius", names::radius(body)),
        ("gamma2", names::gamma2(body)),
    ];
    let bound: Vec<TokenStream> = fields
        .iter()
        .filter(|(_, n)| live.contains(n))
        .map(|(f, n)| {
            let (f, n) = (ident(f), ident(n));
            quote!(#f: #n)
        })
        .collect();
    let rest = (bound.len() < fields.len()).then(|| quote!(..));
    quote!(Ball { #(#bound,)* #rest })
}

/// `Restitution { e, beta }`, binding the live ones.
fn restitution_pattern(live: &BTreeSet<String>) -> TokenStream {
    let fields = [names::restitution_e(), names::restitution_beta()];
    let bound: Vec<TokenStream> = fields
        .iter()
        .filter(|n| live.contains(*n))
        .map(|n| {
            // The input names are the field names: shorthand patterns.
            let n = ident(n);
            quote!(#n)
        })
        .collect();
    let rest = (bound.len() < fields.len()).then(|| quote!(..));
    quote!(Restitution { #(#bound,)* #rest })
}

/// `Walton { e, mu, beta0 }`, binding the live ones.
fn walton_pattern(live: &BTreeSet<String>) -> TokenStream {
    let fields = [
        names::restitution_e(),
        names::friction_mu(),
        names::walton_beta0(),
    ];
    let bound: Vec<TokenStream> = fields
        .iter()
        .filter(|n| live.contains(*n))
        .map(|n| {
            let n = ident(n);
            quote!(#n)
        })
        .collect();
    let rest = (bound.len() < fields.len()).then(|| quote!(..));
    quote!(Walton { #(#bound,)* #rest })
}

/// A formula file as a Markdown text block (split into doc lines by [`description`]).
fn text_block(formulas: &str) -> String {
    format!("```text\n{formulas}```")
}

pub(crate) fn description(kernel: &KernelGraph) -> Vec<String> {
    let n = kernel.dim;
    let mut lines = match (kernel.law, kernel.variant) {
        (Law::Rough, Variant::Free) => vec![
            format!("Rough-ball collision of two free balls in R^{n} with normal restitution `e` and"),
            "tangential restitution `beta` (`docs/derivation.md` §15): returns `[body 1, body 2]`.".into(),
            String::new(),
            text_block(Law::Rough.closed_form(Variant::Free)),
            String::new(),
            "`w_i` = `inv_mass` (0: immovable), `g_i` = `gamma2` = 2 lambda_i / R_i^2;".into(),
            "`e` in `[0, 1]`, `beta` in `[-1, 1]`: `(1, 1)` is the no-slip map [`super::free`]".into(),
            "(the same values, bit for bit, also in floats), `(1, -1)` the smooth one. Energy change".into(),
            "`-(1 - e^2) dn^2 / (2 (w_1 + w_2)) - (1 - beta^2) g_1 g_2 |t|^2 / (2 D)`.".into(),
            "Requires `D > 0` and `w_1 + w_2 > 0`, as [`super::free`].".into(),
        ],
        (Law::Rough, Variant::Fixed) => vec![
            format!("Rough-ball collision in R^{n} of a free ball (body 2) with an immovable one (body 1),"),
            "normal restitution `e`, tangential restitution `beta`: returns body 2 after contact.".into(),
            "The `w_1 -> 0` limit of [`free`]; body 2's mass drops out.".into(),
            String::new(),
            text_block(Law::Rough.closed_form(Variant::Fixed)),
            String::new(),
            "Finite for every `gamma2` in `[0, 2/n]`; `(e, beta) = (1, 1)` is [`super::fixed`].".into(),
        ],
        (Law::Walton, Variant::Free) => vec![
            format!("Walton-law collision of two free balls in R^{n}: normal restitution `e`, friction"),
            "coefficient `mu`, tangential restitution `beta = min(beta0, beta_C)`, where `beta_C` makes".into(),
            "the tangential impulse `mu` times the normal one (`docs/derivation.md` §15.1): returns".into(),
            "`[body 1, body 2]`.".into(),
            String::new(),
            text_block(Law::Walton.closed_form(Variant::Free)),
            String::new(),
            "While sticking (`C >= L`, including `t = 0`) the outputs are [`super::rough::free`]'s at".into(),
            "`beta = beta0`, bit for bit. Requires `D > 0` and `w_1 + w_2 > 0`, as [`super::free`], and".into(),
            "`L` and `C` finite (floats: `|t|`, `|dn|` far below the square root of the largest value).".into(),
        ],
        (Law::Walton, Variant::Fixed) => vec![
            format!("Walton-law collision in R^{n} of a free ball (body 2) with an immovable one (body 1):"),
            "returns body 2 after contact. The `w_1 -> 0` limit of [`free`].".into(),
            String::new(),
            text_block(Law::Walton.closed_form(Variant::Fixed)),
            String::new(),
            "While sticking the outputs are [`super::rough::fixed`]'s at `beta = beta0`, bit for bit.".into(),
        ],
        (Law::NoSlip, Variant::Free) => vec![
            format!("No-slip collision of two free balls in R^{n}: returns `[body 1, body 2]` after contact."),
            String::new(),
            text_block(Law::NoSlip.closed_form(Variant::Free)),
            String::new(),
            "`w_i` = `inv_mass` (0: immovable), `g_i` = `gamma2` = 2 lambda_i / R_i^2.".into(),
            "Finite for an immovable body with `gamma2 > 0` and for one point mass (`gamma2 = 0`)".into(),
            "on a movable body; requires `D > 0` and `w_1 + w_2 > 0` (the checked `collide` ensures it).".into(),
        ],
        (Law::NoSlip, Variant::Fixed) => vec![
            format!("No-slip collision in R^{n} of a free ball (body 2) with an immovable one (body 1):"),
            "returns body 2 after contact. The `w_1 -> 0` limit of [`free`]; body 2's mass drops out.".into(),
            String::new(),
            text_block(Law::NoSlip.closed_form(Variant::Fixed)),
            String::new(),
            "Finite for every `gamma2` in `[0, 2/n]`, including a point mass (`gamma2 = 0`).".into(),
            String::new(),
            "The spin coefficient is `2 (1 - p) / R_2` of the rounded `p = g_2 / (1 + g_2)`, with".into(),
            "`2 (1 - p)` carried as `head + tail` and `y_k = (head t_k + tail t_k) / R_2`, so the".into(),
            "rounded map has no energy bias from its constants (`noslip_codegen::unbiased`).".into(),
        ],
    };
    lines.push(String::new());
    lines.push(format!(
        "Skew storage: entries `(i, j)`, `i < j`, in the order {:?}.",
        skew_pairs(n)
    ));
    lines.push("Straight-line: no branches, loops or calls; all operations on references.".into());
    lines
        .iter()
        .flat_map(|l| l.split('\n').map(String::from))
        .collect()
}

/// The statements and outputs of a kernel, shared by the generic kernels and the
/// specialised ones (`crate::specialise`), which differ only in their signatures.
#[derive(Debug)]
pub struct EmittedBody {
    /// Input names the body reads (the patterns bind these and `_` for the rest).
    pub live: BTreeSet<String>,
    /// The constant and intermediate `let` bindings, in schedule order.
    pub statements: TokenStream,
    /// One `BodyState { .. }` expression per output body, in the kernel's output order.
    pub outputs: Vec<TokenStream>,
    /// Its arithmetic operations.
    pub ops: OpCount,
    /// Intermediate terms (`let` bindings of computed values).
    pub terms: usize,
}

/// Schedule a kernel and emit its bindings and output expressions, plain arithmetic.
pub fn emit_body(kernel: &KernelGraph) -> EmittedBody {
    emit_body_as(kernel, Arith::Plain)
}

/// Schedule a kernel and emit its bindings and output expressions with `arith`: the
/// [`Program`] every back end emits from, spelled in Rust.
pub fn emit_body_as(kernel: &KernelGraph, arith: Arith) -> EmittedBody {
    let program = Program::lower(kernel, arith);
    let operand = |x: &Operand| {
        let i = ident(program.name(x));
        match x {
            Operand::Input(_) => quote!(#i),
            _ => quote!(&#i),
        }
    };
    let constants = program.constants.iter().map(|c| {
        let name = ident(&c.name);
        let value = const_value(&c.value);
        quote!(let #name: T = #value;)
    });
    let step_tokens = program.steps.iter().map(|s| {
        let name = ident(&s.name);
        let expr = match &s.op {
            Op::Add(a, b) => {
                let (a, b) = (operand(a), operand(b));
                quote!(#a + #b)
            }
            Op::Sub(a, b) => {
                let (a, b) = (operand(a), operand(b));
                quote!(#a - #b)
            }
            Op::Mul(a, b) => {
                let (a, b) = (operand(a), operand(b));
                quote!(#a * #b)
            }
            Op::Div(a, b) => {
                let (a, b) = (operand(a), operand(b));
                quote!(#a / #b)
            }
            Op::Neg(a) => {
                let a = operand(a);
                quote!(-#a)
            }
            Op::MulAdd(a, b, c) => fused_call(quote!(mul_add), [a, b, c].map(operand)),
            Op::MulSub(a, b, c) => fused_call(quote!(mul_sub), [a, b, c].map(operand)),
            Op::NegMulAdd(a, b, c) => fused_call(quote!(neg_mul_add), [a, b, c].map(operand)),
            Op::Sqrt(a) => {
                let a = operand(a);
                quote!(T::sqrt(#a))
            }
            Op::SelectLt(ids) => {
                let [x, y, a, b] = ids.each_ref().map(operand);
                quote!(T::select_lt(#x, #y, #a, #b))
            }
        };
        quote!(let #name: T = #expr;)
    });
    let statements = quote!(#(#constants)* #(#step_tokens)*);

    let output_uses = program.output_uses();
    let output = |x: &Operand| {
        let i = ident(program.name(x));
        match x {
            Operand::Input(_) => quote!(#i.clone()),
            Operand::Const(k) => const_value(&program.constants[*k].value),
            Operand::Step(_) if output_uses[x] > 1 => quote!(#i.clone()),
            Operand::Step(_) => quote!(#i),
        }
    };
    let outputs = program
        .outputs
        .iter()
        .map(|o| {
            let spin = o.spin.iter().map(output);
            let velocity = o.velocity.iter().map(output);
            quote!(BodyState { spin: [#(#spin),*], velocity: [#(#velocity),*] })
        })
        .collect();
    EmittedBody {
        live: program.inputs.clone(),
        statements,
        outputs,
        ops: program.ops,
        terms: program.terms(),
    }
}

/// Emit one kernel as a generic function with plain arithmetic.
pub fn emit_kernel(kernel: &KernelGraph) -> EmittedKernel {
    emit_kernel_as(kernel, Arith::Plain)
}

/// Emit one kernel as a generic function, with the arithmetic `arith`.
pub fn emit_kernel_as(kernel: &KernelGraph, arith: Arith) -> EmittedKernel {
    let n = kernel.dim;
    let s = n * (n - 1) / 2;
    let EmittedBody {
        live,
        statements,
        outputs: bodies,
        ops,
        terms,
    } = emit_body_as(kernel, arith);
    let live = &live;

    let nu_pattern = array_pattern((0..n).map(names::nu), live);
    let state1 = state_pattern(n, 1, live);
    let state2 = state_pattern(n, 2, live);
    let ball2 = ball_pattern(2, live);
    let (nl, sl) = (lit(n), lit(s));
    let state_ty = quote!(BodyState<T, #nl, #sl>);
    let fn_name = ident(&arith.function_name(kernel.variant));

    let mut doc = match arith {
        Arith::Plain => description(kernel),
        Arith::Fma => vec![
            format!(
                "[`{}`] with every single-use product fused into the addition that consumes it",
                kernel.variant.name()
            ),
            "(`T::mul_add`, `T::mul_sub`, `T::neg_mul_add`: one rounding for `a b + c` in floats;"
                .into(),
            "exact in rationals). Same formula, same operation order otherwise.".into(),
            String::new(),
            "Always inlined, so it is compiled with its caller's target features:".into(),
            match kernel.law {
                Law::NoSlip => "`collision_core::collide_unchecked_fma` calls it from a function compiled with",
                Law::Rough | Law::Walton => "call it from a function compiled with (as `collision_core::collide_unchecked_fma` does)",
            }
            .into(),
            "`#[target_feature(enable = \"fma\")]` when the CPU has FMA (run-time detection)."
                .into(),
            "Called from code compiled without FMA, `f64::mul_add` is a libm call: the same".into(),
            "bits (both round once, correctly), several times slower.".into(),
        ],
    };
    // The FMA forms are inlined into the caller, whose target features decide whether
    // `mul_add` is an instruction; the plain forms are left to LLVM's inliner.
    let inline = match arith {
        Arith::Plain => quote!(#[inline]),
        Arith::Fma => quote!(#[inline(always)]),
    };
    doc.push(String::new());
    doc.push(format!("Ops: {ops}; {terms} intermediate terms."));
    let doc = doc_lines(&doc);

    // The rough law's parameters follow the balls: `law: &Restitution<T>`.
    let (law_param, law_prologue) = match kernel.law {
        Law::NoSlip => (quote!(), quote!()),
        Law::Rough => {
            let pattern = restitution_pattern(live);
            (quote!(law: &Restitution<T>,), quote!(let #pattern = law;))
        }
        Law::Walton => {
            let pattern = walton_pattern(live);
            (quote!(law: &Walton<T>,), quote!(let #pattern = law;))
        }
    };
    // The Walton kernels take a square root and select: `T: ScalarRoot`.
    let scalar = match kernel.law {
        Law::Walton => quote!(ScalarRoot),
        Law::NoSlip | Law::Rough => quote!(Scalar),
    };
    let (params, prologue, ret_ty, ret) = match kernel.variant {
        Variant::Free => {
            let ball1 = ball_pattern(1, live);
            (
                quote!(nu: &[T; #nl], ball1: &Ball<T>, ball2: &Ball<T>, #law_param state1: &#state_ty, state2: &#state_ty),
                quote!(let #ball1 = ball1; let #ball2 = ball2; #law_prologue),
                quote!([#state_ty; 2]),
                quote!([#(#bodies),*]),
            )
        }
        Variant::Fixed => (
            quote!(nu: &[T; #nl], radius1: &T, ball2: &Ball<T>, #law_param state1: &#state_ty, state2: &#state_ty),
            quote!(let #ball2 = ball2; #law_prologue),
            quote!(#state_ty),
            quote!(#(#bodies)*),
        ),
    };

    let tokens = quote! {
        #doc
        #inline
        #[allow(non_snake_case, clippy::too_many_arguments)]
        pub fn #fn_name<T: #scalar>(#params) -> #ret_ty
        where
            for<'a> &'a T: RefArith<T>,
        {
            let #nu_pattern = nu;
            #prologue
            let #state1 = state1;
            let #state2 = state2;
            #statements
            #ret
        }
    };
    EmittedKernel {
        dim: n,
        variant: kernel.variant,
        arith,
        ops,
        terms,
        tokens,
    }
}

fn fused_call(f: TokenStream, [a, b, c]: [TokenStream; 3]) -> TokenStream {
    quote!(T::#f(#a, #b, #c))
}

/// The `let` binding of one scheduled step: `let name: T = a op b;`.
pub(crate) fn step(namer: &Namer<'_>, id: Id) -> TokenStream {
    let name = namer.binding(id);
    let expr = match namer.kernel.graph.node(id) {
        Node::Add(a, b) => binary(namer, *a, quote!(+), *b),
        Node::Sub(a, b) => binary(namer, *a, quote!(-), *b),
        Node::Mul(a, b) => binary(namer, *a, quote!(*), *b),
        Node::Div(a, b) => binary(namer, *a, quote!(/), *b),
        Node::Neg(a) => {
            let a = namer.operand(*a);
            quote!(-#a)
        }
        Node::Sqrt(a) => {
            let a = namer.operand(*a);
            quote!(T::sqrt(#a))
        }
        Node::SelectLt(ids) => {
            let [x, y, a, b] = ids.map(|id| namer.operand(id));
            quote!(T::select_lt(#x, #y, #a, #b))
        }
        Node::Input(_) | Node::Const(_) => unreachable!("not a step"),
    };
    quote!(let #name: T = #expr;)
}

/// How many output slots each node fills (a temporary used once is moved, not cloned).
pub(crate) fn output_uses(kernel: &KernelGraph) -> HashMap<Id, usize> {
    let mut uses: HashMap<Id, usize> = HashMap::new();
    for o in &kernel.outputs {
        for &id in o.spin.iter().chain(&o.velocity) {
            *uses.entry(id).or_default() += 1;
        }
    }
    uses
}

fn binary(namer: &Namer<'_>, a: Id, op: TokenStream, b: Id) -> TokenStream {
    let (a, b) = (namer.operand(a), namer.operand(b));
    quote!(#a #op #b)
}

/// The header of a generated file: provenance, and the cost of every kernel in it.
pub fn header(dim: usize, kernels: &[EmittedKernel]) -> String {
    titled_header(
        &format!("No-slip collision kernels for n = {dim}."),
        kernels,
    )
}

/// The header of a generated rough-ball file (`rough_{dim}.rs`): provenance and costs.
pub fn rough_header(dim: usize, kernels: &[EmittedKernel]) -> String {
    titled_header(
        &format!("Rough-ball (e, beta) collision kernels for n = {dim}."),
        kernels,
    )
}

/// The header of a generated Walton file (`walton_{dim}.rs`): provenance and costs.
pub fn walton_header(dim: usize, kernels: &[EmittedKernel]) -> String {
    titled_header(
        &format!("Walton (e, mu, beta0) collision kernels for n = {dim}."),
        kernels,
    )
}

/// Provenance, the file's `title`, and a line per kernel: its name, operation count and
/// intermediate terms.
fn titled_header(title: &str, kernels: &[EmittedKernel]) -> String {
    let mut h = format!(
        "// @generated by noslip-codegen from the general SO(n) formulas (codegen/src/model.rs).\n\
         // Do not edit: it is rewritten by collision-core's build.rs.\n\
         // {title}\n"
    );
    for k in kernels {
        h.push_str(&format!(
            "// {}: {}; {} intermediate terms.\n",
            k.arith.function_name(k.variant),
            k.ops,
            k.terms
        ));
    }
    h
}

/// The `use` line of a rough-ball module: the runtime types and `Restitution`.
pub fn rough_imports(crate_path: &str) -> TokenStream {
    let path: syn::Path = syn::parse_str(crate_path).expect("crate path is a Rust path");
    quote!(use #path::{Ball, BodyState, RefArith, Restitution, Scalar};)
}

/// The `use` line of a Walton module: the runtime types, `ScalarRoot` and `Walton`.
pub fn walton_imports(crate_path: &str) -> TokenStream {
    let path: syn::Path = syn::parse_str(crate_path).expect("crate path is a Rust path");
    quote!(use #path::{Ball, BodyState, RefArith, ScalarRoot, Walton};)
}

/// Parse emitted items into a `syn::File`. Panics with the offending source when the
/// emission is not valid Rust: that is a generator bug, and the build must stop.
pub fn parse(tokens: TokenStream) -> syn::File {
    match syn::parse2::<syn::File>(tokens.clone()) {
        Ok(file) => file,
        Err(e) => panic!("noslip-codegen emitted invalid Rust ({e}):\n{tokens}"),
    }
}

/// The `use` line that brings the runtime types into a generated module.
pub fn runtime_imports(crate_path: &str) -> TokenStream {
    let path: syn::Path = syn::parse_str(crate_path).expect("crate path is a Rust path");
    quote!(use #path::{Ball, BodyState, RefArith, Scalar};)
}
