//! Emission of the batch kernels: the scalar kernel's DAG and schedule, evaluated for a
//! block of `LANES` contacts at a time in a fixed-length lane loop that LLVM vectorizes.
//!
//! The layout is blocked (AoSoA): every scalar field of a contact is a `[T; LANES]` lane
//! array, and a batch is a slice of blocks (the runtime types are in
//! `collision_core::batch`). For each block the emitted code runs
//!
//! ```text
//! prefetch(blocks.get(k + ahead));                        (a few kB ahead, out of cache)
//! for group in 0..LANES / W {                             (W lanes at a time)
//!     for l in group * W..group * W + W {
//!         let nu_0: &T = &block.contact.nu[0][l];  ...   (the live inputs of lane l)
//!         let tmp0: T = U1_01 * radius1;  ...            (the scalar kernel's steps)
//!         post[0].spin[0][l] = tmp31;  ...               (each output of lane l, stored
//!         ...                                             right after its last use)
//!     }
//! }
//! ```
//!
//! An output stored at the end of the loop would stay live through it: in a register or,
//! at n = 5, 6 with AVX2's 16 registers, on the stack. Stored at once, it frees its register
//! (the disassembled AVX2 kernel of n = 6 went from 260 to 198 stack accesses per 4 lanes,
//! the AVX-512 one from 124 to 92 per 8).
//!
//! The lane loop has a constant trip count `W` and no dependence between lanes; LLVM's loop
//! vectorizer turns each step into one vector operation over the `W` lanes, with plain
//! vector loads and stores of the lane arrays: no gathers or scatters. The caller picks `W`
//! as the register width (8 `f64` for AVX-512, 4 for AVX2): with `W = LANES` on a narrower
//! ISA every live value would take several registers and the kernels of n = 5, 6 spill. `W
//! = 1` runs the steps lane by lane as straight-line scalar code, as the scalar kernel does.
//!
//! The steps are the scalar kernel's, with the same operands, so each lane rounds exactly as
//! the scalar kernel does on that contact: the batch result is bit for bit the scalar one
//! (Rust never contracts `a * b + c` into a fused multiply-add). Their order is the scalar
//! kernel's, or where it holds fewer values at once, the order of
//! [`crate::pressure::fewer_held`]: the shared quantities first, then each output's own steps
//! just before it, body 1's and body 2's component `k` together (n = 4..6: at most 12, 15, 20
//! values held instead of 13, 18, 24; the AVX2 kernels' stack accesses per pass fell from 58,
//! 113, 198 to 46, 93, 148).
//!
//! Two parameter modes per variant:
//!
//! - per contact ([`Params::PerContact`]): the balls are lane arrays of the block;
//! - shared ([`Params::Shared`]): one set of ball parameters for the whole batch, passed as
//!   scalars. Every node that depends only on them (`D`, `g_1 g_2 / D`, `rho_i`, ...) is
//!   computed once per call, before the block loop, by the same operations; only the
//!   per-contact rest runs in the lane loop.

use crate::bindings::{self, ident, lit, Namer};
use crate::emit;
use crate::ir::{Graph, Id, Node};
use crate::model::{self, names, skew_pairs, KernelGraph, Variant};
use crate::pressure;
use crate::schedule::{schedule, OpCount, Schedule};
use proc_macro2::TokenStream;
use quote::quote;
use std::collections::BTreeSet;

/// Where a batch kernel's ball parameters come from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Params {
    /// One set per contact, in the block's lanes.
    PerContact,
    /// One set for the whole batch, passed as scalars (broadcast).
    Shared,
    /// The ball parameters *and the law* of the rough-ball family per contact: each block
    /// carries the lanes of its contacts' laws (`WithLaw { block, law }`), so nothing is
    /// computed once per call. Emitted for the rough and Walton kernels only.
    Each,
}

impl Params {
    /// Both, in emission order.
    pub const ALL: [Params; 2] = [Params::PerContact, Params::Shared];

    /// The batch kernel's function name: `free`, `fixed`, `free_shared`, `fixed_shared`.
    pub fn function_name(self, variant: Variant) -> String {
        match self {
            Params::PerContact => variant.name().to_string(),
            Params::Shared => format!("{}_shared", variant.name()),
            Params::Each => format!("{}_each", variant.name()),
        }
    }

    /// [`Params::function_name`] under `law`: the rough and Walton kernels' names start with
    /// `rough_` and `walton_`.
    pub fn function_name_of(self, law: model::Law, variant: Variant) -> String {
        match law {
            model::Law::Rough => format!("rough_{}", self.function_name(variant)),
            model::Law::Walton => format!("walton_{}", self.function_name(variant)),
            model::Law::NoSlip => self.function_name(variant),
        }
    }
}

/// Cost of one batch kernel, split into the part run for every contact and the part run
/// once per call (nonzero only with shared parameters). Their sum is the scalar kernel's.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BatchSummary {
    /// The dimension `n`.
    pub dim: usize,
    /// The contact law: the no-slip map, or the rough law with `(e, beta)` shared by the call.
    pub law: model::Law,
    /// Which bodies move: the scalar kernel the batch kernel repeats.
    pub variant: Variant,
    /// Where its ball parameters come from.
    pub params: Params,
    /// Operations run for every contact.
    pub per_contact: OpCount,
    /// Operations run once per call, on the shared parameters (zero for [`Params::PerContact`]).
    pub per_batch: OpCount,
}

/// The generated source of one dimension's batch module and the cost of its kernels.
#[derive(Clone, Debug)]
pub struct BatchModule {
    /// The dimension `n`.
    pub dim: usize,
    /// The formatted file: header (provenance and costs), then the batch kernels.
    pub source: String,
    /// The cost of each batch kernel in the file, in emission order.
    pub kernels: Vec<BatchSummary>,
}

/// The file name of dimension `dim`'s batch module: `batch_{dim}.rs`.
pub fn file_name(dim: usize) -> String {
    format!("batch_{dim}.rs")
}

/// The ball inputs a variant takes as shared scalars in [`Params::Shared`] mode.
fn shared_inputs(variant: Variant) -> BTreeSet<String> {
    let mut set: BTreeSet<String> = [names::radius(1), names::radius(2), names::gamma2(2)]
        .into_iter()
        .collect();
    if variant == Variant::Free {
        set.extend([names::inv_mass(1), names::inv_mass(2), names::gamma2(1)]);
    }
    set
}

/// `uniform[id]`: the node depends on no per-contact input (only constants and `shared`).
fn uniform_nodes(graph: &Graph, shared: &BTreeSet<String>) -> Vec<bool> {
    let mut uniform: Vec<bool> = Vec::with_capacity(graph.len());
    for index in 0..graph.len() {
        let u = match graph.node(Id(index as u32)) {
            Node::Input(input) => shared.contains(&input.0),
            Node::Const(_) => true,
            node => node.operands().all(|a| uniform[a.0 as usize]),
        };
        uniform.push(u);
    }
    uniform
}

/// The place of a kernel input in the batch: a path to a lane array (indexed by `l`) or, for
/// a shared parameter, to a scalar.
fn input_path(name: &str, n: usize, variant: Variant, params: Params) -> TokenStream {
    // The law: one for the call (`law.e`), or a lane of the block's law lanes (`law.e[l]`).
    let lane = match params {
        Params::Each => quote!([l]),
        _ => quote!(),
    };
    if name == names::restitution_e() {
        return quote!(law.e #lane);
    }
    if name == names::restitution_beta() {
        return quote!(law.beta #lane);
    }
    if name == names::friction_mu() {
        return quote!(law.mu #lane);
    }
    if name == names::walton_beta0() {
        return quote!(law.beta0 #lane);
    }
    let contact = match params {
        Params::PerContact | Params::Each => quote!(block.contact),
        Params::Shared => quote!(block),
    };
    for k in 0..n {
        if name == names::nu(k) {
            let k = lit(k);
            return quote!(#contact.nu[#k][l]);
        }
    }
    for body in 1..=2 {
        let b = lit(body - 1);
        for (idx, (i, j)) in skew_pairs(n).into_iter().enumerate() {
            if name == names::spin(body, i, j) {
                let idx = lit(idx);
                return quote!(#contact.states[#b].spin[#idx][l]);
            }
        }
        for k in 0..n {
            if name == names::velocity(body, k) {
                let k = lit(k);
                return quote!(#contact.states[#b].velocity[#k][l]);
            }
        }
        let fields = [
            (names::inv_mass(body), "inv_mass"),
            (names::radius(body), "radius"),
            (names::gamma2(body), "gamma2"),
        ];
        if let Some((_, field)) = fields.iter().find(|(n, _)| n == name) {
            let field = ident(field);
            return match (params, variant, body) {
                (Params::Shared, Variant::Fixed, 1) => quote!(radius1),
                (Params::Shared, _, 1) => quote!(ball1.#field),
                (Params::Shared, _, _) => quote!(ball2.#field),
                (_, Variant::Fixed, 1) => quote!(block.radius1[l]),
                (_, Variant::Fixed, _) => quote!(block.ball2.#field[l]),
                (_, Variant::Free, _) => quote!(block.balls[#b].#field[l]),
            };
        }
    }
    panic!("unknown kernel input {name}")
}

fn count(graph: &Graph, ids: &[Id]) -> OpCount {
    let mut ops = OpCount::default();
    for &id in ids {
        match graph.node(id) {
            Node::Add(..) | Node::Sub(..) => ops.add += 1,
            Node::Mul(..) => ops.mul += 1,
            Node::Div(..) => ops.div += 1,
            Node::Neg(..) => ops.neg += 1,
            Node::Sqrt(..) => ops.sqrt += 1,
            Node::SelectLt(..) => ops.select += 1,
            Node::Input(_) | Node::Const(_) => {}
        }
    }
    ops
}

/// One emitted batch kernel and its cost.
struct EmittedBatch {
    summary: BatchSummary,
    tokens: TokenStream,
}

/// The kernel's parameters, and the type of one input block.
fn signature(
    n: usize,
    law: model::Law,
    variant: Variant,
    params: Params,
) -> (TokenStream, TokenStream) {
    let (nl, sl) = (lit(n), lit(n * (n - 1) / 2));
    let post = match variant {
        Variant::Free => quote!([StateLanes<T, #nl, #sl>; 2]),
        Variant::Fixed => quote!(StateLanes<T, #nl, #sl>),
    };
    let law_lanes = match law {
        model::Law::Walton => quote!(WaltonLanes<T>),
        _ => quote!(RestitutionLanes<T>),
    };
    let (shared, block) = match (params, variant) {
        (Params::PerContact, Variant::Free) => (quote!(), quote!(FreeLanes<T, #nl, #sl>)),
        (Params::PerContact, Variant::Fixed) => (quote!(), quote!(FixedLanes<T, #nl, #sl>)),
        (Params::Each, Variant::Free) => (
            quote!(),
            quote!(WithLaw<FreeLanes<T, #nl, #sl>, #law_lanes>),
        ),
        (Params::Each, Variant::Fixed) => (
            quote!(),
            quote!(WithLaw<FixedLanes<T, #nl, #sl>, #law_lanes>),
        ),
        (Params::Shared, Variant::Free) => (
            quote!(ball1: &Ball<T>, ball2: &Ball<T>,),
            quote!(ContactLanes<T, #nl, #sl>),
        ),
        (Params::Shared, Variant::Fixed) => (
            quote!(radius1: &T, ball2: &Ball<T>,),
            quote!(ContactLanes<T, #nl, #sl>),
        ),
    };
    let law = match (law, params) {
        (_, Params::Each) | (model::Law::NoSlip, _) => quote!(),
        (model::Law::Rough, _) => quote!(law: &Restitution<T>,),
        (model::Law::Walton, _) => quote!(law: &Walton<T>,),
    };
    (
        quote!(#shared #law blocks: &[#block], out: &mut [#post]),
        block,
    )
}

fn docs(
    kernel: &KernelGraph,
    params: Params,
    per_contact: OpCount,
    per_batch: OpCount,
) -> TokenStream {
    let scalar = match kernel.law {
        model::Law::Rough => format!("rough::{}", kernel.variant.name()),
        model::Law::Walton => format!("walton::{}", kernel.variant.name()),
        model::Law::NoSlip => kernel.variant.name().to_string(),
    };
    let mut lines = vec![
        format!(
            "Batch form of [`crate::kernels::d{}::{scalar}`]: block `k` of `blocks` into `out[k]`,",
            kernel.dim
        ),
        "lane by lane, for `min(blocks.len(), out.len())` blocks.".into(),
    ];
    match (kernel.law, params) {
        (model::Law::Rough | model::Law::Walton, Params::Each) => lines.push(
            "The law: per contact, in the lanes of each block's `law`; computed in the lane loop.".into(),
        ),
        (model::Law::Rough, _) => lines.push(
            "The law `(e, beta)`: shared by every contact; `h_n`, `h_t` are computed once.".into(),
        ),
        (model::Law::Walton, _) => lines.push(
            "The law `(e, mu, beta0)`: shared by every contact; what depends on it alone is computed once."
                .into(),
        ),
        (model::Law::NoSlip, _) => {}
    }
    match params {
        Params::PerContact | Params::Each => {
            lines.push("Ball parameters: per contact, in the lanes.".into())
        }
        Params::Shared => lines.push(
            "Ball parameters: shared by every contact; what depends on them alone is computed once."
                .into(),
        ),
    }
    lines.extend([
        "Each lane runs the scalar kernel's operations on the same operands: the same bits in floats."
            .into(),
        String::new(),
    ]);
    // The scalar kernel's description, less its straight-line note (this one loops).
    // Its links are relative to the scalar kernel's module (`super::free` from
    // `dN::rough`); here they name the scalar kernels by their full path.
    let dim_module = format!("[`crate::kernels::d{}::", kernel.dim);
    lines.extend(
        emit::description(kernel)
            .into_iter()
            .filter(|l| !l.starts_with("Straight-line"))
            .map(|l| l.replace("[`super::", &dim_module)),
    );
    lines.push(String::new());
    lines.push(format!("Ops per contact: {per_contact}."));
    if params == Params::Shared {
        lines.push(format!(
            "Ops per call, on the shared parameters: {per_batch}."
        ));
    }
    emit::doc_lines(&lines)
}

fn emit_batch(kernel: &KernelGraph, params: Params) -> EmittedBatch {
    let (n, variant) = (kernel.dim, kernel.variant);
    let roots = kernel
        .outputs
        .iter()
        .flat_map(|o| o.spin.iter().chain(&o.velocity).copied());
    let sched: Schedule = schedule(&kernel.graph, roots);
    let namer = Namer::new(kernel, &sched, &sched.steps);
    let mut shared = match params {
        Params::PerContact | Params::Each => BTreeSet::new(),
        Params::Shared => shared_inputs(variant),
    };
    match kernel.law {
        _ if params == Params::Each => {}
        model::Law::Rough => shared.extend([names::restitution_e(), names::restitution_beta()]),
        model::Law::Walton => shared.extend([
            names::restitution_e(),
            names::friction_mu(),
            names::walton_beta0(),
        ]),
        model::Law::NoSlip => {}
    }
    let uniform = uniform_nodes(&kernel.graph, &shared);
    let (hoisted, lane): (Vec<Id>, Vec<Id>) =
        sched.steps.iter().partition(|id| uniform[id.0 as usize]);
    // The same steps in an order that holds fewer values at once where one exists
    // (`pressure.rs`): the same bits, fewer spills.
    let bodies: Vec<Vec<Id>> = kernel
        .outputs
        .iter()
        .map(|o| o.velocity.iter().chain(&o.spin).copied().collect())
        .collect();
    let lane = pressure::fewer_held(&kernel.graph, &lane, &bodies);

    let bind = |name: &String| {
        let (i, path) = (ident(name), input_path(name, n, variant, params));
        if shared.contains(name) {
            // Shared parameters are copied into locals once per call: the stores into `out`
            // cannot alias a local, so the lane loop keeps them in registers and vectorizes.
            quote!(let #i: &T = &#path.clone();)
        } else {
            quote!(let #i: &T = &#path;)
        }
    };
    let shared_bindings = sched
        .inputs
        .iter()
        .filter(|i| shared.contains(*i))
        .map(bind);
    let lane_bindings = sched
        .inputs
        .iter()
        .filter(|i| !shared.contains(*i))
        .map(bind);
    let constants = sched.constants.iter().map(|&id| {
        let name = namer.binding(id);
        let value = bindings::const_value(kernel.graph.as_const(id).expect("constant"));
        quote!(let #name: T = #value;)
    });
    let hoisted_steps = hoisted.iter().map(|&id| emit::step(&namer, id));

    let output_uses = emit::output_uses(kernel);
    let stores = kernel.outputs.iter().enumerate().flat_map(|(slot, o)| {
        let target = match variant {
            Variant::Free => {
                let slot = lit(slot);
                quote!(post[#slot])
            }
            Variant::Fixed => quote!(post),
        };
        let spin = o
            .spin
            .iter()
            .enumerate()
            .map(|(k, &id)| (quote!(spin), k, id));
        let velocity = o
            .velocity
            .iter()
            .enumerate()
            .map(|(k, &id)| (quote!(velocity), k, id));
        let namer = &namer;
        let output_uses = &output_uses;
        let uniform = &uniform;
        let graph = &kernel.graph;
        spin.chain(velocity)
            .map(move |(field, k, id)| {
                assert!(
                    !uniform[id.0 as usize] || matches!(graph.node(id), Node::Const(_)),
                    "an output of the n = {n} {variant:?} kernel depends on shared parameters only"
                );
                let value = namer.output(id, output_uses);
                let k = lit(k);
                (id, quote!(#target.#field[#k][l] = #value;))
            })
            .collect::<Vec<_>>()
    });
    // Each output is stored as soon as it is computed and no later step reads it, so that
    // it does not stay live (in a register, or spilled) to the end of the lane loop.
    let position: std::collections::HashMap<Id, usize> =
        lane.iter().enumerate().map(|(i, &id)| (id, i)).collect();
    let last_read = pressure::last_reads(&kernel.graph, &lane);
    let mut after: Vec<Vec<TokenStream>> = vec![Vec::new(); lane.len() + 1];
    for (id, store) in stores {
        let slot = position.get(&id).map_or(lane.len(), |&p| last_read[p]);
        after[slot].push(store);
    }
    let lane_steps = lane.iter().enumerate().map(|(i, &id)| {
        let step = emit::step(&namer, id);
        let stores = &after[i];
        quote!(#step #(#stores)*)
    });
    let stores = after[lane.len()].iter();

    let per_contact = count(&kernel.graph, &lane);
    let per_batch = count(&kernel.graph, &hoisted);
    let doc = docs(kernel, params, per_contact, per_batch);
    let fn_name = ident(&params.function_name_of(kernel.law, variant));
    let (sig, block_ty) = signature(n, kernel.law, variant, params);
    // The Walton kernels take a square root and a select: `ScalarRoot`.
    let bound = match kernel.law {
        model::Law::Walton => quote!(ScalarRoot),
        _ => quote!(Scalar),
    };
    let block_binding = match params {
        Params::Each => {
            quote!(let (block, law, post) = (&blocks[k].block, &blocks[k].law, &mut out[k]);)
        }
        _ => quote!(let (block, post) = (&blocks[k], &mut out[k]);),
    };
    let tokens = quote! {
        #doc
        #[inline(always)]
        #[allow(non_snake_case, clippy::needless_range_loop)]
        pub fn #fn_name<T: #bound, const W: usize>(#sig)
        where
            for<'a> &'a T: RefArith<T>,
        {
            const { assert!(W > 0 && LANES % W == 0, "W divides LANES") };
            #(#shared_bindings)*
            #(#constants)*
            #(#hoisted_steps)*
            let ahead = prefetch_distance::<#block_ty>();
            for k in 0..blocks.len().min(out.len()) {
                prefetch(blocks.get(k + ahead));
                #block_binding
                for group in 0..LANES / W {
                    for l in group * W..group * W + W {
                        #(#lane_bindings)*
                        #(#lane_steps)*
                        #(#stores)*
                    }
                }
            }
        }
    };
    EmittedBatch {
        summary: BatchSummary {
            dim: n,
            law: kernel.law,
            variant,
            params,
            per_contact,
            per_batch,
        },
        tokens,
    }
}

fn header(dim: usize, kernels: &[BatchSummary]) -> String {
    let mut h = format!(
        "// @generated by noslip-codegen from the general SO(n) formulas (codegen/src/model.rs),\n\
         // batch form (codegen/src/batch.rs). Do not edit: it is rewritten by collision-core's build.rs.\n\
         // No-slip, rough-ball and Walton collision batch kernels for n = {dim}, blocks of LANES contacts.\n"
    );
    for k in kernels {
        h.push_str(&format!(
            "// {}: per contact {}; per call {}.\n",
            k.params.function_name_of(k.law, k.variant),
            k.per_contact,
            k.per_batch
        ));
    }
    h
}

/// Generate the batch kernels of dimension `dim` (`free`, `fixed`, `free_shared`,
/// `fixed_shared`, and the rough-ball and Walton laws' `rough_free`, ..., `walton_free`, ...,
/// with the law shared by the call, and `rough_free_each`, `rough_fixed_each`,
/// `walton_free_each`, `walton_fixed_each` with a law per contact) as one formatted source file; `crate_path` as in
/// [`crate::generate`].
///
/// Panics if the emission is not valid Rust: a generator bug.
pub fn generate(dim: usize, crate_path: &str) -> BatchModule {
    let built: Vec<KernelGraph> = (Variant::ALL.iter().map(|&v| model::build(dim, v)))
        .chain(Variant::ALL.iter().map(|&v| model::build_rough(dim, v)))
        .chain(
            Variant::ALL
                .iter()
                .map(|&v| crate::walton::build_walton(dim, v)),
        )
        .collect();
    // The no-slip kernels in two modes; the family's in three (`Params::Each`: the law per
    // contact).
    let each = built
        .iter()
        .filter(|k| k.law != model::Law::NoSlip)
        .map(|k| emit_batch(k, Params::Each));
    let emitted: Vec<EmittedBatch> = Params::ALL
        .iter()
        .flat_map(|&p| built.iter().map(move |k| emit_batch(k, p)))
        .chain(each)
        .collect();
    let path: syn::Path = syn::parse_str(crate_path).expect("crate path is a Rust path");
    let imports = quote! {
        use #path::batch::{prefetch, ContactLanes, FixedLanes, FreeLanes, StateLanes, LANES, prefetch_distance, RestitutionLanes, WaltonLanes, WithLaw};
        use #path::{Ball, RefArith, Restitution, Scalar, ScalarRoot, Walton};
    };
    let items = emitted.iter().map(|e| &e.tokens);
    let file = emit::parse(quote!(#imports #(#items)*));
    let kernels: Vec<BatchSummary> = emitted.into_iter().map(|e| e.summary).collect();
    BatchModule {
        dim,
        source: format!(
            "{}\n{}",
            header(dim, &kernels),
            prettyplease::unparse(&file)
        ),
        kernels,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::DIMS;
    use std::collections::HashMap;

    /// How many lane stores one block writes: every output component of every lane.
    fn stores_per_lane(dim: usize, variant: Variant) -> usize {
        let bodies = match variant {
            Variant::Free => 2,
            Variant::Fixed => 1,
        };
        bodies * (dim + dim * (dim - 1) / 2)
    }

    fn add(a: OpCount, b: OpCount) -> OpCount {
        OpCount {
            add: a.add + b.add,
            mul: a.mul + b.mul,
            div: a.div + b.div,
            neg: a.neg + b.neg,
            fma: a.fma + b.fma,
            sqrt: a.sqrt + b.sqrt,
            select: a.select + b.select,
        }
    }

    #[test]
    fn per_contact_and_per_call_ops_partition_the_scalar_kernel() {
        for dim in DIMS {
            let scalar: HashMap<Variant, OpCount> = crate::generate(dim, "crate")
                .kernels
                .into_iter()
                .filter(|k| k.arith == crate::Arith::Plain)
                .map(|k| (k.variant, k.ops))
                .collect();
            for k in generate(dim, "crate").kernels {
                let ops = match k.law {
                    model::Law::Rough => emit::emit_body(&model::build_rough(dim, k.variant)).ops,
                    model::Law::Walton => {
                        emit::emit_body(&crate::walton::build_walton(dim, k.variant)).ops
                    }
                    model::Law::NoSlip => scalar[&k.variant],
                };
                assert_eq!(
                    add(k.per_contact, k.per_batch),
                    ops,
                    "n = {dim}, {:?} {:?} {:?}",
                    k.law,
                    k.variant,
                    k.params
                );
                // The rough law's h_n = (1 + e)/2 and h_t = (1 + beta)/2 are computed once
                // per call in both modes.
                let law = match k.law {
                    model::Law::Rough => OpCount {
                        add: 2,
                        mul: 2,
                        ..OpCount::default()
                    },
                    // h_n, h_0 and the Coulomb side's mu h_n: law-only nodes.
                    model::Law::Walton => k.per_batch,
                    model::Law::NoSlip => OpCount::default(),
                };
                match k.params {
                    Params::PerContact => assert_eq!(k.per_batch, law),
                    // The law per contact: nothing is left for the call.
                    Params::Each => assert_eq!(k.per_batch, OpCount::default(), "{k:?}"),
                    // D, g_1 g_2 / D and the rho_i leave the lane loop; of `fixed`,
                    // g_2 / (1 + g_2) does, and the divisions of y_k = .. / R_2 stay in it
                    // (`crate::unbiased`).
                    Params::Shared => {
                        let hoisted = if k.variant == Variant::Free { 2 } else { 1 };
                        assert!(k.per_batch.div >= hoisted, "{k:?}");
                    }
                }
            }
        }
    }

    #[test]
    fn every_output_lane_is_stored_once() {
        for dim in DIMS {
            let source = generate(dim, "crate").source;
            let file = syn::parse_file(&source).expect("generated source parses");
            assert_eq!(file.items.len(), 2 + 16, "two use items, sixteen kernels");
            for (law, v) in [model::Law::NoSlip, model::Law::Rough, model::Law::Walton]
                .into_iter()
                .flat_map(|l| Variant::ALL.map(|v| (l, v)))
            {
                let each = (law != model::Law::NoSlip).then_some(Params::Each);
                for p in Params::ALL.into_iter().chain(each) {
                    let name = p.function_name_of(law, v);
                    let body = source
                        .split(&format!("pub fn {name}<"))
                        .nth(1)
                        .expect("kernel emitted");
                    let body = body.split("\npub fn ").next().unwrap_or(body);
                    let stores = body.matches("[l] = ").count();
                    assert_eq!(stores, stores_per_lane(dim, v), "n = {dim}, {name}");
                }
            }
        }
    }

    #[test]
    fn outputs_are_stored_right_after_their_last_use() {
        // In every lane loop, a stored value is read by no later line, and the nearest line
        // before its store (other than stores) defines or reads it.
        let is_store = |l: &str| l.contains("[l] = ");
        for dim in DIMS {
            let source = generate(dim, "crate").source;
            for body in source.split("for l in group * W..group * W + W {").skip(1) {
                let lines: Vec<&str> = body.lines().map(str::trim).collect();
                let end = lines
                    .iter()
                    .position(|l| *l == "}")
                    .expect("end of the lane loop");
                let lines = &lines[..end];
                for (i, line) in lines.iter().enumerate().filter(|(_, l)| is_store(l)) {
                    let value = line.split(" = ").nth(1).unwrap().trim_end_matches(';');
                    let value = value.trim_end_matches(".clone()");
                    if !value.starts_with("tmp") && !value.chars().any(|c| c == '_') {
                        continue; // a constant or an input
                    }
                    let reads = |l: &str| {
                        l.split(|c: char| !(c.is_alphanumeric() || c == '_'))
                            .any(|w| w == value)
                    };
                    assert!(
                        !lines[i + 1..].iter().any(|l| !is_store(l) && reads(l)),
                        "n = {dim}: {value} is read after its store"
                    );
                    let before = lines[..i].iter().rev().find(|l| !is_store(l));
                    assert!(
                        before.is_some_and(|l| reads(l)),
                        "n = {dim}: {line} is not right after the last use of {value}"
                    );
                }
            }
        }
    }

    /// The rough kernels' law is a parameter of the call: `h_n`, `h_t` leave the lane loop
    /// in both modes, and in the per-contact mode nothing else does.
    #[test]
    fn the_rough_law_leaves_the_lane_loop() {
        let source = generate(3, "crate").source;
        for name in ["rough_free", "rough_fixed", "rough_free_shared"] {
            let body = source.split(&format!("pub fn {name}<")).nth(1).unwrap();
            let (before_loop, in_loop) = body.split_once("for k in 0..").unwrap();
            let in_loop = in_loop.split("\npub fn ").next().unwrap();
            assert!(before_loop.contains("law: &Restitution<T>"), "{name}");
            assert!(before_loop.contains("let h_n: T ="), "{name}");
            assert!(before_loop.contains("let h_t: T ="), "{name}");
            assert!(
                !in_loop.contains("law."),
                "{name}: the law is read per lane"
            );
        }
    }

    /// With a law per contact (`_each`), every law field is read per lane from the block's
    /// law lanes, and `h_n` is computed in the lane loop.
    #[test]
    fn the_law_per_contact_is_read_in_the_lane_loop() {
        let source = generate(3, "crate").source;
        for (name, fields) in [
            ("rough_free_each", &["law.e[l]", "law.beta[l]"][..]),
            ("rough_fixed_each", &["law.e[l]", "law.beta[l]"]),
            (
                "walton_free_each",
                &["law.e[l]", "law.mu[l]", "law.beta0[l]"],
            ),
            (
                "walton_fixed_each",
                &["law.e[l]", "law.mu[l]", "law.beta0[l]"],
            ),
        ] {
            let body = source.split(&format!("pub fn {name}<")).nth(1).unwrap();
            let (before_loop, in_loop) = body.split_once("for k in 0..").unwrap();
            let in_loop = in_loop.split("\npub fn ").next().unwrap();
            assert!(before_loop.contains("WithLaw<"), "{name}");
            assert!(
                !before_loop.contains("law."),
                "{name}: nothing of the law per call"
            );
            for f in fields {
                assert!(in_loop.contains(f), "{name}: {f} per lane");
            }
            assert!(in_loop.contains("let h_n: T ="), "{name}");
        }
    }

    #[test]
    fn shared_parameters_leave_the_lane_loop() {
        let source = generate(3, "crate").source;
        let shared = source.split("pub fn free_shared<").nth(1).unwrap();
        let (before_loop, in_loop) = shared.split_once("for k in 0..").unwrap();
        let in_loop = in_loop.split("\npub fn ").next().unwrap();
        assert!(before_loop.contains("let d: T ="), "D is computed once");
        assert!(before_loop.contains("let rho1: T ="));
        assert!(
            !in_loop.contains("ball1."),
            "no ball field is read per lane"
        );
    }
}
