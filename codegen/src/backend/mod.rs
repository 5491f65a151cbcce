//! Back ends for languages other than Rust: the same [`Program`]s, spelled in C99
//! ([`C`]) and OpenCL C ([`OpenCl`]).
//!
//! There is one generator: a kernel is built as a DAG ([`crate::model`]), scheduled, fused
//! and named once ([`Program::lower`]); the Rust emitter ([`crate::emit`]) and these back ends
//! only spell its steps, in the same order. What differs between languages is the
//! [`Language`] trait: scalar types, the fused multiply-add's name, function qualifiers, the
//! file's prelude and epilogue, and what follows each function (OpenCL's batch `__kernel`).
//! The body of every function (load the live inputs, bind the constants, one `const` per
//! step, store the outputs) is written once, here, for every C-family language.
//!
//! Adding a language: implement [`Language`] (see [`OpenCl`], about 100 lines), add it to
//! [`Lang`], and give it a faithfulness test that compiles the emitted source and compares
//! its results with the Rust kernels bit for bit (`tests/c_backend.rs`).
//!
//! # ABI
//!
//! Each kernel is a `void` function over arrays of its scalar type (`double` or `float`):
//!
//! ```text
//! free : (nu[N], ball1[3], ball2[3], state1[S+N], state2[S+N], out1[S+N], out2[S+N])
//! fixed: (nu[N], radius1,  ball2[3], state1[S+N], state2[S+N], out2[S+N])
//! rough_free, rough_fixed: the same with law[2] = {e, beta} after ball2
//! ball = {inv_mass, radius, gamma2}; state = {U_01, U_02, .., U_(n-2)(n-1), u_0, .., u_(n-1)}
//! ```
//!
//! mirroring the Rust kernels (`Ball`, `BodyState` with the strict upper triangle of `U` in
//! row-major order, then `u`). Every input is read before any output is written, so an
//! output may alias an input. No allocation, no global state.

mod c;
mod conserve;

pub use c::{OpenCl, C};

use crate::arith::Arith;
use crate::model::{names, skew_pairs, Law, Variant};
use crate::program::{Op, Operand, Program};
use crate::schedule::OpCount;
use crate::DIMS;
use noslip_scene::{Pair, PairSet};
use num_rational::BigRational;
use std::fmt::Write;

/// A float format of the emitted kernels.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Precision {
    /// IEEE binary64 (`double`).
    F64,
    /// IEEE binary32 (`float`).
    F32,
}

impl Precision {
    /// Both, in emission order.
    pub const ALL: [Precision; 2] = [Precision::F64, Precision::F32];

    /// The suffix of the function names: `f64`, `f32`.
    pub fn suffix(self) -> &'static str {
        match self {
            Precision::F64 => "f64",
            Precision::F32 => "f32",
        }
    }

    /// The C type: `double`, `float`.
    pub fn c_type(self) -> &'static str {
        match self {
            Precision::F64 => "double",
            Precision::F32 => "float",
        }
    }
}

/// The languages with a back end, as `noslip gen --lang` names them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lang {
    /// C99 header, usable from C++ ([`C`]).
    C,
    /// OpenCL C source: device functions and batch kernels ([`OpenCl`]).
    OpenCl,
}

impl Lang {
    /// Every language, in the order `--help` lists them.
    pub const ALL: [Lang; 2] = [Lang::C, Lang::OpenCl];

    /// The name on the command line: `c`, `opencl`.
    pub fn name(self) -> &'static str {
        match self {
            Lang::C => "c",
            Lang::OpenCl => "opencl",
        }
    }

    /// The back end.
    pub fn language(self) -> &'static dyn Language {
        match self {
            Lang::C => &C,
            Lang::OpenCl => &OpenCl,
        }
    }
}

/// One parameter of an emitted function.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Param {
    /// An input array: its name and the kernel input each element holds.
    Array(&'static str, Vec<String>),
    /// One input scalar (`fixed`'s `radius1`), named as the input.
    Scalar(String),
    /// The output array of body `body` (1 or 2): `S + N` elements, spin then velocity.
    Out(&'static str, usize),
}

/// One parameter of a batch entry point ([`Language::batch`]): the scalar function's
/// parameter `name` of C type `ty`, an array of `len` elements (`None`: one scalar), read
/// (`out == false`) or written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BatchParam {
    /// The parameter's name.
    pub name: String,
    /// Its element type: `double`, `float`.
    pub ty: &'static str,
    /// The array's length, or `None` for a scalar.
    pub len: Option<usize>,
    /// Whether the function writes it.
    pub out: bool,
}

impl BatchParam {
    /// An input array (`len` given) or scalar.
    pub fn input(name: &str, ty: &'static str, len: Option<usize>) -> Self {
        BatchParam {
            name: name.to_string(),
            ty,
            len,
            out: false,
        }
    }

    /// An output array of `len` elements.
    pub fn output(name: &str, ty: &'static str, len: usize) -> Self {
        BatchParam {
            name: name.to_string(),
            ty,
            len: Some(len),
            out: true,
        }
    }
}

/// A kernel ready to be spelled: its name (without the precision suffix), its program, its
/// parameters and the comment above it.
#[derive(Clone, Debug)]
pub struct Unit {
    /// The function name without the precision suffix (`noslip_d3_free`).
    pub name: String,
    /// The straight-line program.
    pub program: Program,
    /// The parameters, in order.
    pub params: Vec<Param>,
    /// The comment lines above the function (without comment markers).
    pub doc: Vec<String>,
}

impl Unit {
    /// The function name in precision `p`: `noslip_d3_free_f64`.
    pub fn function_name(&self, p: Precision) -> String {
        format!("{}_{}", self.name, p.suffix())
    }
}

/// The hooks of one C-family language. The shared driver ([`source`]) writes the file:
/// [`Language::prelude`], then per precision [`Language::begin`], each unit's function and
/// [`Language::after_function`], [`Language::end`]; then [`Language::epilogue`].
pub trait Language {
    /// The language's name in comments: `C99`, `OpenCL C`.
    fn title(&self) -> &'static str;
    /// The file extension: `h`, `cl`.
    fn extension(&self) -> &'static str;
    /// The qualifiers before `void` of a kernel function: `static inline`.
    fn qualifiers(&self) -> &'static str;
    /// The correctly rounded fused multiply-add of precision `p`: `fma`, `fmaf`.
    fn fma(&self, p: Precision) -> &'static str;
    /// The correctly rounded square root of precision `p`: `sqrt`, `sqrtf`.
    fn sqrt(&self, p: Precision) -> &'static str;
    /// The absolute value of precision `p`: `fabs`, `fabsf`.
    fn fabs(&self, p: Precision) -> &'static str;
    /// The first line of every function body (a pragma or macro), or `""`.
    fn body_prologue(&self) -> &'static str;
    /// The file's start after the common header comment: include guard, includes, pragmas.
    fn prelude(&self, guard: &str) -> String;
    /// The file's end.
    fn epilogue(&self, guard: &str) -> String;
    /// Before the functions of precision `p` (an extension guard), or `""`.
    fn begin(&self, p: Precision) -> String;
    /// After the functions of precision `p`.
    fn end(&self, p: Precision) -> String;
    /// What follows each function (OpenCL: its batch kernel, [`Language::batch`]), or `""`.
    fn after_function(&self, unit: &Unit, p: Precision) -> String;
    /// The batch entry point `{function}_batch(count, arrays..)` of the scalar function
    /// `function` with parameters `params` (OpenCL: a `__kernel`, one record per work item), or
    /// `""`.
    fn batch(&self, function: &str, params: &[BatchParam]) -> String;
    /// Lines describing the language-specific rules, for the header comment.
    fn notes(&self) -> Vec<String>;
}

/// A C literal of a finite float: the shortest decimal that reads back as exactly `x` in
/// its format (Rust's `{:e}`), so a correctly rounding compiler restores the same bits. Hex
/// floats would be exact by construction but are not C++ before C++17.
fn decimal_literal(x: impl std::fmt::LowerExp, finite: bool) -> String {
    assert!(finite, "a literal must be finite");
    format!("{x:e}")
}

/// The correctly rounded literal of an exact constant in precision `p`, exactly as the Rust
/// kernels round it (`T::from_ratio`, `T::from_literal`: [`crate::literal::nearest_floats`]).
pub fn constant_literal(value: &BigRational, p: Precision) -> String {
    let (x64, x32) = crate::literal::nearest_floats(value);
    match p {
        Precision::F64 => decimal_literal(x64, x64.is_finite()),
        Precision::F32 => format!("{}f", decimal_literal(x32, x32.is_finite())),
    }
}

fn operand(program: &Program, x: &Operand) -> String {
    program.name(x).to_string()
}

fn expression(lang: &dyn Language, program: &Program, op: &Op, p: Precision) -> String {
    let o = |x: &Operand| operand(program, x);
    let fma = lang.fma(p);
    match op {
        Op::Add(a, b) => format!("{} + {}", o(a), o(b)),
        Op::Sub(a, b) => format!("{} - {}", o(a), o(b)),
        Op::Mul(a, b) => format!("{} * {}", o(a), o(b)),
        Op::Div(a, b) => format!("{} / {}", o(a), o(b)),
        Op::Neg(a) => format!("-{}", o(a)),
        Op::MulAdd(a, b, c) => format!("{fma}({}, {}, {})", o(a), o(b), o(c)),
        Op::MulSub(a, b, c) => format!("{fma}({}, {}, -{})", o(a), o(b), o(c)),
        Op::NegMulAdd(a, b, c) => format!("{fma}(-{}, {}, {})", o(a), o(b), o(c)),
        Op::Sqrt(a) => format!("{}({})", lang.sqrt(p), o(a)),
        Op::SelectLt([x, y, a, b]) => format!("{} < {} ? {} : {}", o(x), o(y), o(a), o(b)),
    }
}

/// The length of an output array for dimension `n`: `S + N`.
fn state_len(n: usize) -> usize {
    n * (n - 1) / 2 + n
}

/// The function of `unit` in precision `p`, with its comment.
pub fn function(lang: &dyn Language, unit: &Unit, p: Precision) -> String {
    let ty = p.c_type();
    let program = &unit.program;
    let n = program.dim;
    let mut f = String::new();
    for line in &unit.doc {
        f.push_str(format!("// {line}").trim_end());
        f.push('\n');
    }
    let params: Vec<String> = unit
        .params
        .iter()
        .map(|param| match param {
            Param::Array(name, elems) => format!("const {ty} {name}[{}]", elems.len()),
            Param::Scalar(name) => format!("{ty} {name}"),
            Param::Out(name, _) => format!("{ty} {name}[{}]", state_len(n)),
        })
        .collect();
    let _ = writeln!(
        f,
        "{} void {}({})\n{{",
        lang.qualifiers(),
        unit.function_name(p),
        params.join(", ")
    );
    if !lang.body_prologue().is_empty() {
        let _ = writeln!(f, "    {}", lang.body_prologue());
    }
    for param in &unit.params {
        match param {
            Param::Array(name, elems) => {
                let mut any = false;
                for (k, e) in elems.iter().enumerate() {
                    if program.inputs.contains(e) {
                        any = true;
                        let _ = writeln!(f, "    const {ty} {e} = {name}[{k}];");
                    }
                }
                if !any {
                    let _ = writeln!(f, "    (void){name};");
                }
            }
            Param::Scalar(name) if !program.inputs.contains(name) => {
                let _ = writeln!(f, "    (void){name};");
            }
            Param::Scalar(_) | Param::Out(..) => {}
        }
    }
    for c in &program.constants {
        let _ = writeln!(
            f,
            "    const {ty} {} = {};",
            c.name,
            constant_literal(&c.value, p)
        );
    }
    for s in &program.steps {
        let _ = writeln!(
            f,
            "    const {ty} {} = {};",
            s.name,
            expression(lang, program, &s.op, p)
        );
    }
    for param in &unit.params {
        if let Param::Out(name, body) = param {
            let out = program
                .outputs
                .iter()
                .find(|o| o.body == *body)
                .expect("the program returns this body");
            for (k, x) in out.spin.iter().chain(&out.velocity).enumerate() {
                let _ = writeln!(f, "    {name}[{k}] = {};", operand(program, x));
            }
        }
    }
    f.push_str("}\n");
    f
}

/// The kernel inputs of one body's `{inv_mass, radius, gamma2}`.
fn ball_elems(body: usize) -> Vec<String> {
    vec![
        names::inv_mass(body),
        names::radius(body),
        names::gamma2(body),
    ]
}

/// The kernel inputs of one body's state: spin, then velocity.
fn state_elems(n: usize, body: usize) -> Vec<String> {
    skew_pairs(n)
        .into_iter()
        .map(|(i, j)| names::spin(body, i, j))
        .chain((0..n).map(|k| names::velocity(body, k)))
        .collect()
}

fn nu_elems(n: usize) -> Vec<String> {
    (0..n).map(names::nu).collect()
}

/// The comment of a generic kernel: the formula, the parameters, the preconditions, the
/// storage order and the op counts.
fn generic_doc(
    n: usize,
    (law, variant): (Law, Variant),
    arith: Arith,
    ops: OpCount,
    terms: usize,
) -> Vec<String> {
    let mut doc = match (law, variant) {
        (Law::NoSlip, Variant::Free) => vec![
            format!("No-slip collision of two free balls in R^{n}: writes body 1 to out1, body 2 to out2."),
            String::new(),
        ],
        (Law::NoSlip, Variant::Fixed) => vec![
            format!("No-slip collision in R^{n} of a free ball (body 2) with an immovable one (body 1):"),
            "writes body 2 to out2 (body 1 is unchanged). Reads radius1 and ball2's radius, gamma2.".into(),
            String::new(),
        ],
        (Law::Rough, Variant::Free) => vec![
            format!("Rough-ball collision of two free balls in R^{n}, law = {{e, beta}} (docs/derivation.md §15):"),
            "writes body 1 to out1, body 2 to out2. (e, beta) = (1, 1) is the no-slip kernel, (1, -1) the smooth map.".into(),
            String::new(),
        ],
        (Law::Rough, Variant::Fixed) => vec![
            format!("Rough-ball collision in R^{n} of a free ball (body 2) with an immovable one (body 1),"),
            "law = {e, beta}: writes body 2 to out2 (body 1 is unchanged).".into(),
            String::new(),
        ],
        (Law::Walton, Variant::Free) => vec![
            format!("Walton-law collision of two free balls in R^{n}, law = {{e, mu, beta0}} (docs/derivation.md §15.1):"),
            "writes body 1 to out1, body 2 to out2. beta = min(beta0, beta_C); while sticking the rough kernel at beta0.".into(),
            String::new(),
        ],
        (Law::Walton, Variant::Fixed) => vec![
            format!("Walton-law collision in R^{n} of a free ball (body 2) with an immovable one (body 1),"),
            "law = {e, mu, beta0}: writes body 2 to out2 (body 1 is unchanged).".into(),
            String::new(),
        ],
    };
    doc.extend(law.closed_form(variant).lines().map(|l| format!("    {l}")));
    doc.push(String::new());
    doc.push("w_i = inv_mass, g_i = gamma2 = 2 lambda_i / R_i^2 in [0, 2/n]; ball = {inv_mass, radius, gamma2}.".into());
    doc.push(format!(
        "state = spin U_ij (i < j) in the order {:?}, then velocity u_0..u_{}.",
        skew_pairs(n),
        n - 1
    ));
    doc.push(
        "Preconditions (what the checked Rust `collide` validates): every input finite, |nu| = 1,"
            .into(),
    );
    doc.push(
        "0 <= gamma2 <= 2/n, radius > 0, inv_mass >= 0, (u_2 - u_1) . nu <= 0 (approach or graze);"
            .into(),
    );
    if law == Law::Rough {
        doc.push("0 <= e <= 1, -1 <= beta <= 1 (collision_core::Restitution::new);".into());
    }
    if law == Law::Walton {
        doc.push("0 <= e <= 1, mu >= 0, -1 <= beta0 <= 1 (collision_core::Walton::new);".into());
    }
    if variant == Variant::Free {
        doc.push(
            "w_1 + w_2 > 0 and D > 0 (not both immovable, not both movable point masses).".into(),
        );
    } else {
        doc.push("its denominator 1 + g_2 is at least 1.".into());
    }
    if arith == Arith::Fma {
        doc.push("FMA form: every single-use product fused into the addition that consumes it (one rounding).".into());
    }
    doc.push(format!("Ops: {ops}; {terms} intermediate terms."));
    doc
}

/// The generic kernels of dimension `n`: each variant in each arithmetic, as in the Rust
/// module `kernels::dN` (`free`, `fixed`, `free_fma`, `fixed_fma`).
pub fn generic_units(n: usize) -> Vec<Unit> {
    law_units(n, Law::NoSlip)
}

/// The rough-ball kernels of dimension `n` (`noslip_dN_rough_free`, ...), as in the Rust
/// module `kernels::dN::rough`: the generic kernels' parameters with `law = {e, beta}` after
/// the balls.
pub fn rough_units(n: usize) -> Vec<Unit> {
    law_units(n, Law::Rough)
}

/// The Walton kernels of dimension `n` (`noslip_dN_walton_free`, ...), as in the Rust
/// module `kernels::dN::walton`: the generic kernels' parameters with
/// `law = {e, mu, beta0}` after the balls.
pub fn walton_units(n: usize) -> Vec<Unit> {
    law_units(n, Law::Walton)
}

fn law_units(n: usize, law: Law) -> Vec<Unit> {
    let law_param = || {
        let fields = match law {
            Law::Walton => vec![
                names::restitution_e(),
                names::friction_mu(),
                names::walton_beta0(),
            ],
            Law::NoSlip | Law::Rough => {
                vec![names::restitution_e(), names::restitution_beta()]
            }
        };
        Param::Array("law", fields)
    };
    Arith::ALL
        .iter()
        .flat_map(|&arith| {
            Variant::ALL.iter().map(move |&variant| {
                let program = Program::lower(&crate::laws::build_law(n, variant, law), arith);
                let mut params = match variant {
                    Variant::Free => vec![
                        Param::Array("nu", nu_elems(n)),
                        Param::Array("ball1", ball_elems(1)),
                        Param::Array("ball2", ball_elems(2)),
                        Param::Array("state1", state_elems(n, 1)),
                        Param::Array("state2", state_elems(n, 2)),
                        Param::Out("out1", 1),
                        Param::Out("out2", 2),
                    ],
                    Variant::Fixed => vec![
                        Param::Array("nu", nu_elems(n)),
                        Param::Scalar(names::radius(1)),
                        Param::Array("ball2", ball_elems(2)),
                        Param::Array("state1", state_elems(n, 1)),
                        Param::Array("state2", state_elems(n, 2)),
                        Param::Out("out2", 2),
                    ],
                };
                let prefix = match law {
                    Law::NoSlip => "",
                    Law::Rough => {
                        params.insert(3, law_param());
                        "rough_"
                    }
                    Law::Walton => {
                        params.insert(3, law_param());
                        "walton_"
                    }
                };
                let doc = generic_doc(n, (law, variant), arith, program.ops, program.terms());
                Unit {
                    name: format!("noslip_d{n}_{prefix}{}", arith.function_name(variant)),
                    program,
                    params,
                    doc,
                }
            })
        })
        .collect()
}

/// The kernels specialised to a scene's pairs ([`crate::specialise`]), plain arithmetic as
/// in Rust: `noslip_{scene}_{pair}`, e.g. `noslip_gas2d_ball_ball_0_0`.
pub fn scene_units(set: &PairSet) -> Vec<Unit> {
    let n = set.dim;
    set.all()
        .into_iter()
        .map(|pair| {
            let kernel = crate::specialise::build(set, pair);
            let program = Program::lower(&kernel, Arith::Plain);
            let params = match pair {
                Pair::BallBall(..) => vec![
                    Param::Array("nu", nu_elems(n)),
                    Param::Array("state1", state_elems(n, 1)),
                    Param::Array("state2", state_elems(n, 2)),
                    Param::Out("out1", 1),
                    Param::Out("out2", 2),
                ],
                Pair::BallWall(..) => vec![
                    Param::Array("state", state_elems(n, 2)),
                    Param::Out("out", 2),
                ],
                Pair::BallObstacle(..) => vec![
                    Param::Array("nu", nu_elems(n)),
                    Param::Array("state", state_elems(n, 2)),
                    Param::Out("out", 2),
                ],
            };
            let mut doc = vec![format!(
                "Scene `{}`, {} kernel `{}` (the `{}` {} map with the species constants and the law folded in).",
                set.name,
                pair.kind(),
                pair.fn_name(),
                crate::specialise::variant(pair).name(),
                crate::specialise::law_name(set, pair)
            )];
            doc.push(format!(
                "Ops: {}; {} intermediate terms.",
                program.ops,
                program.terms()
            ));
            Unit {
                name: format!("noslip_{}_{}", set.name, pair.fn_name()),
                program,
                params,
                doc,
            }
        })
        .collect()
}

/// A whole source file: the header comment (provenance, ABI, op counts), the language's
/// prelude, every unit in every precision, the epilogue.
pub fn source(lang: &dyn Language, guard: &str, about: &str, units: &[Unit]) -> String {
    source_with(lang, guard, about, units, "")
}

/// [`source`] with `extra` functions before the epilogue (the certified companions,
/// [`crate::certify::c`]).
pub fn source_with(
    lang: &dyn Language,
    guard: &str,
    about: &str,
    units: &[Unit],
    extra: &str,
) -> String {
    let mut s = format!(
        "// @generated by noslip-codegen {} from the general SO(n) formulas (codegen/src/model.rs).\n\
         // Do not edit: rewrite it with `noslip gen --lang ...` (docs/backends.md).\n\
         // {about} in {}.\n",
        env!("CARGO_PKG_VERSION"),
        lang.title()
    );
    let abi = [
        "",
        "ABI: void functions over arrays of double (suffix _f64) or float (_f32):",
        "  free : (nu[N], ball1[3], ball2[3], state1[S+N], state2[S+N], out1[S+N], out2[S+N])",
        "  fixed: (nu[N], radius1, ball2[3], state1[S+N], state2[S+N], out2[S+N])",
        "  ball = {inv_mass, radius, gamma2}; state = {U_ij for i < j in row-major order, then u_0..u_(N-1)};",
        "  S = N (N - 1) / 2. All inputs are read before any output is written (outputs may alias inputs).",
        "Same operations in the same order as the Rust kernels (collision_core::kernels): bit-identical",
        "results under IEEE arithmetic without contraction (tests/c_backend.rs).",
    ];
    // The rough-ball kernels' parameters, where the file has them.
    let has_law = |fields: usize| {
        units.iter().any(|u| {
            u.params
                .iter()
                .any(|p| matches!(p, Param::Array("law", f) if f.len() == fields))
        })
    };
    let rough = has_law(2).then_some(
        "  rough_*: the same, with law[2] = {e, beta} after ball2 (docs/derivation.md §15).",
    );
    let walton = has_law(3).then_some(
        "  walton_*: the same, with law[3] = {e, mu, beta0} after ball2 (docs/derivation.md §15.1).",
    );
    let certified = (!extra.is_empty()).then_some(
        "  {free,fixed}_certified: the same, then a bound array per out array: |out - exact| <= bound.",
    );
    let abi = abi
        .iter()
        .take(4)
        .copied()
        .chain(rough)
        .chain(walton)
        .chain(certified)
        .chain(abi.iter().skip(4).copied());
    for l in abi.map(|l| l.to_string()).chain(lang.notes()) {
        s.push_str(format!("// {l}").trim_end());
        s.push('\n');
    }
    s.push_str("//\n");
    for u in units {
        let _ = writeln!(
            s,
            "// {}: {}; {} intermediate terms.",
            u.name,
            u.program.ops,
            u.program.terms()
        );
    }
    s.push('\n');
    s.push_str(&lang.prelude(guard));
    for p in Precision::ALL {
        s.push('\n');
        s.push_str(&lang.begin(p));
        for u in units {
            s.push('\n');
            s.push_str(&function(lang, u, p));
            s.push_str(&lang.after_function(u, p));
        }
        s.push_str(&lang.end(p));
    }
    s.push_str(extra);
    s.push('\n');
    s.push_str(&lang.epilogue(guard));
    s
}

/// The generic kernels of `dims` as one file of `lang`: `noslip_kernels.{h,cl}`, the
/// kernels ([`kernels_source`]) followed by their certified companions
/// ([`crate::certify::c::functions`]) and the energy-conserving correction
/// (`noslip_conserve_fixed_dN`, `noslip_conserve_free_dN`, the bits of
/// `collision_core::conserve`); in OpenCL each of these with its batch kernel `NAME_batch`.
pub fn generate(lang: Lang, dims: &[usize]) -> String {
    let mut extra = crate::certify::c::functions(lang.language(), dims);
    extra.push_str(&conserve::functions(lang, dims));
    kernels_source_with(lang, dims, &extra)
}

/// [`generate`] without the certified companions: the kernels alone (the OpenCL kernels'
/// faithfulness test builds this, the companions' test the companions).
pub fn kernels_source(lang: Lang, dims: &[usize]) -> String {
    kernels_source_with(lang, dims, "")
}

fn kernels_source_with(lang: Lang, dims: &[usize], extra: &str) -> String {
    assert!(
        dims.iter().all(|d| DIMS.contains(d)),
        "dimensions must be in {DIMS:?}: {dims:?}"
    );
    let units: Vec<Unit> = dims
        .iter()
        .flat_map(|&n| {
            generic_units(n)
                .into_iter()
                .chain(rough_units(n))
                .chain(walton_units(n))
        })
        .collect();
    let list = dims
        .iter()
        .map(usize::to_string)
        .collect::<Vec<_>>()
        .join(", ");
    source_with(
        lang.language(),
        "NOSLIP_KERNELS",
        &format!("No-slip collision kernels for n = {list}"),
        &units,
        extra,
    )
}

/// The file name of [`generate`]'s output.
pub fn file_name(lang: Lang) -> String {
    format!("noslip_kernels.{}", lang.language().extension())
}

/// The kernels specialised to `set` as one file of `lang`: `noslip_scene_{name}.{h,cl}`.
/// Refuses constants beyond the `f32` or `f64` range, as the Rust specialiser does.
pub fn generate_scene(
    lang: Lang,
    set: &PairSet,
) -> Result<String, crate::specialise::ConstantOutOfRange> {
    crate::specialise::check_ranges(set)?;
    let guard = format!("NOSLIP_SCENE_{}", set.name.to_uppercase());
    Ok(source(
        lang.language(),
        &guard,
        &format!(
            "Kernels specialised to scene `{}` (n = {})",
            set.name, set.dim
        ),
        &scene_units(set),
    ))
}

/// The file name of [`generate_scene`]'s output.
pub fn scene_file_name(lang: Lang, set: &PairSet) -> String {
    format!("noslip_scene_{}.{}", set.name, lang.language().extension())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn literals_read_back_exactly() {
        let r = |p: i64, q: i64| BigRational::new(p.into(), q.into());
        assert_eq!(constant_literal(&r(2, 1), Precision::F64), "2e0");
        assert_eq!(constant_literal(&r(-1, 2), Precision::F32), "-5e-1f");
        for x in [r(1, 3), r(1, 10), r(-7, 3), r(1, 1 << 40)] {
            let (x64, x32) = crate::literal::nearest_floats(&x);
            let l64 = constant_literal(&x, Precision::F64);
            assert_eq!(
                l64.parse::<f64>().unwrap().to_bits(),
                x64.to_bits(),
                "{l64}"
            );
            let l32 = constant_literal(&x, Precision::F32);
            let l32 = l32.trim_end_matches('f');
            assert_eq!(
                l32.parse::<f32>().unwrap().to_bits(),
                x32.to_bits(),
                "{l32}"
            );
        }
    }

    #[test]
    fn every_step_is_one_statement_in_schedule_order() {
        for unit in generic_units(3) {
            let text = function(&C, &unit, Precision::F64);
            let mut at = 0;
            for s in &unit.program.steps {
                let line = format!("    const double {} = ", s.name);
                let found = text[at..]
                    .find(&line)
                    .unwrap_or_else(|| panic!("{}: {} missing or out of order", unit.name, s.name));
                at += found + line.len();
            }
            assert_eq!(
                text.matches(" fma(").count(),
                unit.program.ops.fma,
                "{}",
                unit.name
            );
        }
    }
}
