//! Where a batch kernel reads and writes: its parameters and the type of one input block in
//! each mode (the lane types of `collision_core::batch`), and the place of each scalar kernel
//! input, a lane array of the block indexed by the lane `l` or a shared scalar.

use super::params::Params;
use crate::bindings::{ident, lit};
use crate::model::{self, names, skew_pairs, Variant};
use proc_macro2::TokenStream;
use quote::quote;

/// The place of a kernel input in the batch: a path to a lane array (indexed by `l`) or, for
/// a shared parameter, to a scalar.
pub(super) fn input_path(name: &str, n: usize, variant: Variant, params: Params) -> TokenStream {
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

/// The kernel's parameters, and the type of one input block.
pub(super) fn signature(
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
