//! # noslip-codegen
//!
//! The build-time generator of the no-slip collision kernels (generic, FMA, batch and
//! scene-specialised), run by build scripts. It emits and checks source text; it links no
//! runtime, runs no kernel and simulates nothing (`collision-core` compiles what it emits;
//! scenes come from `noslip-scene`).
//!
//! The general SO(n) formulas
//! (`U nu`, the slip `t`, the impulse `P`, `nu ^ t`, the updates) are expanded component by
//! component into a hash-consed expression DAG ([`ir`]), simplified and deduplicated as it is
//! built, scheduled ([`schedule`]) and emitted as unrolled, branch-free Rust ([`emit`]),
//! which is parsed back with `syn`, checked to be straight-line ([`straight_line`]) and
//! formatted with `prettyplease`.
//!
//! Pipeline: [`model::build`] -> [`schedule::schedule`] -> [`emit::emit_kernel`] -> [`generate`].
//!
//! ```
//! let module = noslip_codegen::generate(3, "crate");
//! assert!(module.source.starts_with("// @generated"));
//! assert_eq!(module.kernels.len(), 4); // free, fixed, free_fma, fixed_fma
//! ```

#![warn(missing_docs, unreachable_pub)]

pub mod arith;
pub mod backend;
pub mod batch;
mod bindings;
pub mod bound;
pub mod certify;
pub mod emit;
pub mod fuse;
pub mod ir;
pub mod laws;
pub mod literal;
pub mod model;
pub mod pressure;
pub mod program;
pub mod schedule;
pub mod specialise;
pub mod straight_line;
pub mod unbiased;
pub mod walton;

pub use arith::Arith;
pub use model::{Law, Variant};
pub use schedule::OpCount;

use std::io;
use std::path::{Path, PathBuf};

/// The dimensions the runtime crate ships kernels for.
pub const DIMS: std::ops::RangeInclusive<usize> = 2..=6;

/// Cost of one generated kernel.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct KernelSummary {
    /// The dimension `n`.
    pub dim: usize,
    /// Which bodies move.
    pub variant: Variant,
    /// Plain or fused arithmetic.
    pub arith: Arith,
    /// Its arithmetic operations.
    pub ops: OpCount,
    /// Intermediate terms (`let` bindings of computed values).
    pub terms: usize,
}

impl KernelSummary {
    /// The generated function's name: `free`, `fixed`, `free_fma`, `fixed_fma`.
    pub fn name(&self) -> String {
        self.arith.function_name(self.variant)
    }
}

/// The generated source of one dimension's module and the cost of each kernel in it.
#[derive(Clone, Debug)]
pub struct Module {
    /// The dimension `n`.
    pub dim: usize,
    /// The formatted file: header (provenance and costs), then the kernels.
    pub source: String,
    /// The cost of each kernel in the file, in emission order.
    pub kernels: Vec<KernelSummary>,
}

/// Generate every kernel variant for dimension `dim` (each of [`Variant::ALL`] in each
/// [`Arith::ALL`]) as one formatted source file.
/// `crate_path` is the path of the runtime crate as seen from where the file is included
/// (`"crate"` inside collision-core, `"collision_core"` elsewhere).
///
/// Panics if the emission is not valid Rust or not straight-line: both are generator bugs.
pub fn generate(dim: usize, crate_path: &str) -> Module {
    assemble(
        dim,
        model::build,
        emit::runtime_imports(crate_path),
        emit::header,
        "kernels",
    )
}

/// Every variant of `build` in every [`Arith`], emitted after `imports`, checked to be valid
/// straight-line Rust (panics otherwise, naming the `family`: a generator bug), formatted
/// under `header`: the pipeline [`generate`] and [`generate_rough`] share.
fn assemble(
    dim: usize,
    build: fn(usize, Variant) -> model::KernelGraph,
    imports: proc_macro2::TokenStream,
    header: fn(usize, &[emit::EmittedKernel]) -> String,
    family: &str,
) -> Module {
    let kernels: Vec<emit::EmittedKernel> = Arith::ALL
        .iter()
        .flat_map(|&arith| {
            Variant::ALL
                .iter()
                .map(move |&v| emit::emit_kernel_as(&build(dim, v), arith))
        })
        .collect();
    let items = kernels.iter().map(|k| &k.tokens);
    let file = emit::parse(quote::quote!(#imports #(#items)*));
    let violations = straight_line::check(&file);
    assert!(
        violations.is_empty(),
        "generated {family} for n = {dim} are not straight-line: {violations:?}"
    );
    let source = format!(
        "{}\n{}",
        header(dim, &kernels),
        prettyplease::unparse(&file)
    );
    Module {
        dim,
        source,
        kernels: kernels
            .iter()
            .map(|k| KernelSummary {
                dim: k.dim,
                variant: k.variant,
                arith: k.arith,
                ops: k.ops,
                terms: k.terms,
            })
            .collect(),
    }
}

/// Generate the rough-ball kernels (run-time restitutions `e`, `beta`;
/// `docs/derivation.md` §15) for dimension `dim`: `free`, `fixed`, `free_fma`,
/// `fixed_fma`, through the same pipeline as [`generate`], as one formatted file
/// ([`rough_file_name`]) that `collision-core` includes as `kernels::dN::rough`.
///
/// Panics if the emission is not valid Rust or not straight-line: both are generator bugs.
pub fn generate_rough(dim: usize, crate_path: &str) -> Module {
    assemble(
        dim,
        model::build_rough,
        emit::rough_imports(crate_path),
        emit::rough_header,
        "rough kernels",
    )
}

/// Generate the Walton kernels (run-time `e`, `mu`, `beta0`; `docs/derivation.md` §15.1)
/// for dimension `dim`: `free`, `fixed`, `free_fma`, `fixed_fma`, through the same pipeline
/// as [`generate`], as one formatted file ([`walton_file_name`]) that `collision-core`
/// includes as `kernels::dN::walton`.
///
/// Panics if the emission is not valid Rust or not straight-line: both are generator bugs.
pub fn generate_walton(dim: usize, crate_path: &str) -> Module {
    assemble(
        dim,
        walton::build_walton,
        emit::walton_imports(crate_path),
        emit::walton_header,
        "Walton kernels",
    )
}

/// The file name of dimension `dim`'s Walton module: `walton_{dim}.rs`.
pub fn walton_file_name(dim: usize) -> String {
    format!("walton_{dim}.rs")
}

/// The file name of dimension `dim`'s rough-ball module: `rough_{dim}.rs`.
pub fn rough_file_name(dim: usize) -> String {
    format!("rough_{dim}.rs")
}

/// The file name of dimension `dim`'s module: `kernels_{dim}.rs`.
pub fn file_name(dim: usize) -> String {
    format!("kernels_{dim}.rs")
}

/// Write `contents` to `path` unless the file already holds exactly that (so that cargo
/// and editors see no change). Returns whether it wrote.
pub fn write_if_changed(path: &Path, contents: &str) -> io::Result<bool> {
    if std::fs::read_to_string(path).is_ok_and(|old| old == contents) {
        return Ok(false);
    }
    let tmp = path.with_extension("rs.tmp");
    std::fs::write(&tmp, contents)?;
    std::fs::rename(&tmp, path)?;
    Ok(true)
}

/// Generate the modules of `dims` into `out_dir` (one [`file_name`] each), writing only
/// what changed. For a build script.
pub fn generate_into(
    out_dir: &Path,
    dims: impl IntoIterator<Item = usize>,
    crate_path: &str,
) -> io::Result<Vec<(PathBuf, Module)>> {
    dims.into_iter()
        .map(|dim| {
            let module = generate(dim, crate_path);
            let path = out_dir.join(file_name(dim));
            write_if_changed(&path, &module.source)?;
            Ok((path, module))
        })
        .collect()
}
