//! One batch kernel's tokens: the scalar kernel's schedule split into the steps run once per
//! call (before the block loop) and those of the lane loop, the latter in the order that
//! holds fewer values at once (`pressure.rs`); the inputs bound once per call (shared) or
//! per lane; each output stored right after its last use in the lane loop.

use super::doc::docs;
use super::hoist::{count, uniform_nodes, BatchSummary};
use super::layout::{input_path, signature};
use super::params::{shared_inputs, Params};
use crate::bindings::{self, ident, lit, Namer};
use crate::emit;
use crate::ir::{Id, Node};
use crate::model::{self, names, KernelGraph, Variant};
use crate::pressure;
use crate::schedule::{schedule, Schedule};
use proc_macro2::TokenStream;
use quote::quote;
use std::collections::BTreeSet;

/// One emitted batch kernel and its cost.
pub(super) struct EmittedBatch {
    pub(super) summary: BatchSummary,
    pub(super) tokens: TokenStream,
}

/// The batch kernel of `kernel` in mode `params`.
pub(super) fn emit_batch(kernel: &KernelGraph, params: Params) -> EmittedBatch {
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
