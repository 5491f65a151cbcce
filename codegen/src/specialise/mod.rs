//! Kernels specialised to a scene: only its dimension, only its pair kinds, each species'
//! constants and each kind's contact law (the no-slip map, a rough law's exact `e` and
//! `beta`, or a Walton law's exact `e`, `mu` and `beta0`: [`noslip_scene::PairLaws`]) folded
//! into exact literals before scheduling.
//!
//! The same model builder ([`crate::model::build_on`]) runs with constants in place of the
//! parameters, so the exact constant folding of [`crate::ir`] removes every division (the
//! quotients of constants become literals) and every product with a folded factor of 0 or 1:
//!
//! - ball-ball `(a, b)`: the `free` map with `w_i, R_i, g_i` of species `a` and `b`;
//! - ball-wall `(s, k, side)`: the `fixed` map with body 1 a wall at rest (`U_1 = 0`,
//!   `u_1 = 0`) and `nu = +e_k` (lower wall) or `-e_k` (upper wall), so only body 2's state
//!   is an input; the wall's radius multiplies `U_1 = 0` and drops out;
//! - ball-obstacle `s`: the `fixed` map with body 1 a fixed ball at rest and `nu` an input.
//!
//! [`generate`] emits them with a dispatch `impl PairKernels` (collision-core's `sim`) so the
//! simulator runs them in place of the generic kernels; [`Config`] is the build-script API.
//!
//! Every folded constant must have a finite `f32` and `f64` literal (the kernels are generic
//! over both): a scene whose species need a constant beyond either range is refused with a
//! [`ConstantOutOfRange`] naming the species field at fault (see [`crate::literal`]).

mod config;
mod range;

pub use config::{compile_scenes, Config};
pub use range::{check_ranges, ConstantOutOfRange, GenerateError};

use crate::bindings::{ident, lit};
use crate::emit::{self, array_pattern, doc_lines, state_pattern, EmittedBody};
use crate::ir::{Graph, Id};
use crate::literal::{f64_tokens, nearest_floats};
use crate::model::{self, names, skew_pairs, BodyInputs, KernelGraph, KernelInputs, Variant};
use crate::schedule::OpCount;
use noslip_scene::{ContactKind, Pair, PairSet, Species, WallSide};
use proc_macro2::TokenStream;
use quote::quote;

/// The generic kernel a specialised kernel for `pair` replaces: `free` for ball-ball,
/// `fixed` for contacts with an immovable body.
pub fn variant(pair: Pair) -> Variant {
    match pair {
        Pair::BallBall(..) => Variant::Free,
        _ => Variant::Fixed,
    }
}

/// The cost of one specialised kernel and of the generic kernel it replaces.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PairSummary {
    /// The contact kind it serves.
    pub pair: Pair,
    /// Its arithmetic operations, with the species constants folded in.
    pub ops: OpCount,
    /// Intermediate terms (`let` bindings of computed values).
    pub terms: usize,
    /// The operations of the generic kernel it replaces ([`variant`] of `pair`).
    pub generic_ops: OpCount,
}

/// A generated scene module and its costs.
#[derive(Clone, Debug)]
pub struct SceneModule {
    /// The module name (a Rust identifier: [`PairSet::name`]).
    pub name: String,
    /// The dimension `n`.
    pub dim: usize,
    /// The formatted file: header (provenance and costs), the kernels and their dispatch.
    pub source: String,
    /// The cost of each pair's kernel, in emission order.
    pub pairs: Vec<PairSummary>,
}

fn constant(g: &mut Graph, x: &num_rational::BigRational) -> Id {
    g.constant(x.clone())
}

/// A body at rest (a wall or an obstacle): the `fixed` variant's body 1 with zero state.
fn at_rest(g: &mut Graph, n: usize) -> BodyInputs {
    let zero = g.int(0);
    BodyInputs {
        spin: vec![zero; n * (n - 1) / 2],
        velocity: vec![zero; n],
        radius: g.int(1),
        inv_mass: zero,
        gamma2: g.int(1),
    }
}

/// Body `b`'s state as named inputs, with species constants; `inv_mass` overrides `w`
/// (the fixed variant's `w_2 = 1`).
fn species_body(g: &mut Graph, n: usize, b: usize, s: &Species, fixed: bool) -> BodyInputs {
    let spin = skew_pairs(n)
        .into_iter()
        .map(|(i, j)| g.input(names::spin(b, i, j)))
        .collect();
    let velocity = (0..n).map(|k| g.input(names::velocity(b, k))).collect();
    BodyInputs {
        spin,
        velocity,
        radius: constant(g, &s.radius),
        inv_mass: if fixed {
            g.int(1)
        } else {
            constant(g, &s.inv_mass)
        },
        gamma2: constant(g, &s.gamma2),
    }
}

/// The DAG of one specialised kernel.
pub fn build(set: &PairSet, pair: Pair) -> KernelGraph {
    let n = set.dim;
    let mut g = Graph::new();
    g.fold_reciprocals(true);
    let nu_inputs = |g: &mut Graph| (0..n).map(|k| g.input(names::nu(k))).collect();
    let inputs = match pair {
        Pair::BallBall(a, b) => KernelInputs {
            nu: nu_inputs(&mut g),
            bodies: [
                species_body(&mut g, n, 1, &set.species[a], false),
                species_body(&mut g, n, 2, &set.species[b], false),
            ],
        },
        Pair::BallWall(s, axis, side) => {
            let sign = if side == WallSide::Lower { 1 } else { -1 };
            let nu = (0..n)
                .map(|k| g.int(if k == axis { sign } else { 0 }))
                .collect();
            KernelInputs {
                nu,
                bodies: [
                    at_rest(&mut g, n),
                    species_body(&mut g, n, 2, &set.species[s], true),
                ],
            }
        }
        Pair::BallObstacle(s) => KernelInputs {
            nu: nu_inputs(&mut g),
            bodies: [
                at_rest(&mut g, n),
                species_body(&mut g, n, 2, &set.species[s], true),
            ],
        },
    };
    let (law, outputs) = match set.laws.of(pair) {
        ContactKind::Rough { e, beta } => {
            let law = model::RestitutionInputs {
                e: constant(&mut g, e),
                beta: constant(&mut g, beta),
            };
            let outputs = model::build_rough_on(&mut g, &inputs, variant(pair), law);
            (model::Law::Rough, outputs)
        }
        ContactKind::Walton { e, mu, beta0 } => {
            let law = crate::walton::WaltonInputs {
                e: constant(&mut g, e),
                mu: constant(&mut g, mu),
                beta0: constant(&mut g, beta0),
            };
            let outputs = crate::walton::build_walton_on(&mut g, &inputs, variant(pair), law);
            (model::Law::Walton, outputs)
        }
        ContactKind::NoSlip => (
            model::Law::NoSlip,
            model::build_on(&mut g, &inputs, variant(pair)),
        ),
        other => panic!("{other:?} is not folded into kernels (PairLaws::foldable)"),
    };
    KernelGraph {
        dim: n,
        variant: variant(pair),
        law,
        graph: g,
        outputs,
    }
}

/// The generic kernel `pair`'s kernel replaces, by its path below `kernels::dN`: `free`,
/// `fixed`, or under a rough law `rough::free`, `rough::fixed` (Walton: `walton::free`, ...).
pub fn generic_name(set: &PairSet, pair: Pair) -> String {
    match set.laws.of(pair) {
        ContactKind::Rough { .. } => format!("rough::{}", variant(pair).name()),
        ContactKind::Walton { .. } => format!("walton::{}", variant(pair).name()),
        _ => variant(pair).name().to_string(),
    }
}

/// The law folded into `pair`'s kernel, as the kernels' docs name it: `no-slip`, or
/// `rough (e = .., beta = ..)`, `Walton (e = .., mu = .., beta0 = ..)`.
pub fn law_name(set: &PairSet, pair: Pair) -> String {
    match set.laws.of(pair) {
        ContactKind::Rough { e, beta } => format!("rough (e = {e}, beta = {beta})"),
        ContactKind::Walton { e, mu, beta0 } => {
            format!("Walton (e = {e}, mu = {mu}, beta0 = {beta0})")
        }
        _ => "no-slip".into(),
    }
}

fn describe(set: &PairSet, pair: Pair) -> Vec<String> {
    let sp = |s: usize| {
        let x = &set.species[s];
        format!(
            "species {s} `{}` (m = {}, R = {}, gamma2 = {})",
            x.name, x.mass, x.radius, x.gamma2
        )
    };
    let n = set.dim;
    let law = law_name(set, pair);
    match pair {
        Pair::BallBall(a, b) => vec![
            format!("The `free` {law} map in R^{n} of body 1 of {} and body 2 of {}:", sp(a), sp(b)),
            "returns `[body 1+, body 2+]`; `nu` is the unit normal from body 1's centre to body 2's.".into(),
        ],
        Pair::BallWall(s, k, side) => vec![
            format!(
                "The `fixed` {law} map in R^{n} of {} on the {} wall of axis {k} (at rest,",
                sp(s),
                side.name()
            ),
            format!(
                "normal nu = {}e_{k} into the box): returns the ball's state after contact.",
                if side == WallSide::Lower { "+" } else { "-" }
            ),
        ],
        Pair::BallObstacle(s) => vec![
            format!("The `fixed` {law} map in R^{n} of {} on a fixed ball at rest:", sp(s)),
            "`nu` is the unit normal from the obstacle's centre to the ball's; returns the ball after contact.".into(),
        ],
    }
}

/// Emit one specialised kernel function.
fn emit_pair(set: &PairSet, pair: Pair) -> (TokenStream, PairSummary) {
    let n = set.dim;
    let kernel = build(set, pair);
    let EmittedBody {
        live,
        statements,
        outputs,
        ops,
        terms,
    } = emit::emit_body(&kernel);
    let generic = emit::emit_body(&match set.laws.of(pair) {
        ContactKind::Rough { .. } => model::build_rough(n, variant(pair)),
        ContactKind::Walton { .. } => crate::walton::build_walton(n, variant(pair)),
        _ => model::build(n, variant(pair)),
    });
    let (nl, sl) = (lit(n), lit(n * (n - 1) / 2));
    let state_ty = quote!(BodyState<T, #nl, #sl>);
    let nu_pattern = array_pattern((0..n).map(names::nu), &live);
    let state1 = state_pattern(n, 1, &live);
    let state2 = state_pattern(n, 2, &live);
    let (params, prologue, ret_ty, ret) = match pair {
        Pair::BallBall(..) => (
            quote!(nu: &[T; #nl], state1: &#state_ty, state2: &#state_ty),
            quote!(let #nu_pattern = nu; let #state1 = state1; let #state2 = state2;),
            quote!([#state_ty; 2]),
            quote!([#(#outputs),*]),
        ),
        Pair::BallWall(..) => (
            quote!(state: &#state_ty),
            quote!(let #state2 = state;),
            state_ty.clone(),
            quote!(#(#outputs)*),
        ),
        Pair::BallObstacle(..) => (
            quote!(nu: &[T; #nl], state: &#state_ty),
            quote!(let #nu_pattern = nu; let #state2 = state;),
            state_ty.clone(),
            quote!(#(#outputs)*),
        ),
    };
    let mut doc = describe(set, pair);
    doc.push(String::new());
    doc.push(format!(
        "Ops: {ops}; {terms} intermediate terms (generic `{}`: {}).",
        generic_name(set, pair),
        generic.ops
    ));
    let doc = doc_lines(&doc);
    let name = ident(&pair.fn_name());
    let bound = scalar_bound(set.laws.of(pair));
    let tokens = quote! {
        #doc
        #[inline]
        #[allow(non_snake_case, unused_variables)]
        pub fn #name<T: #bound>(#params) -> #ret_ty
        where
            for<'a> &'a T: RefArith<T>,
        {
            #prologue
            #statements
            #ret
        }
    };
    let summary = PairSummary {
        pair,
        ops,
        terms,
        generic_ops: generic.ops,
    };
    (tokens, summary)
}

/// The scalar bound of a kernel under `law`: `ScalarRoot` for the Walton law (a square root),
/// else `Scalar`.
fn scalar_bound(law: &ContactKind) -> TokenStream {
    match law {
        ContactKind::Walton { .. } => quote!(ScalarRoot),
        _ => quote!(Scalar),
    }
}

/// Whether a kernel of `set` takes a square root (has a Walton law): its module then needs
/// `ScalarRoot`, and so does its dispatch.
fn needs_root(set: &PairSet) -> bool {
    set.all()
        .into_iter()
        .any(|p| matches!(set.laws.of(p), ContactKind::Walton { .. }))
}

/// The `impl PairKernels` that dispatches by species (and wall) to the kernels. A pair that
/// the scene cannot meet panics with the scene's name: the simulator never asks for one.
fn dispatch(set: &PairSet, sim_path: &syn::Path) -> TokenStream {
    let n = set.dim;
    let (nl, sl) = (lit(n), lit(n * (n - 1) / 2));
    let state_ty = quote!(BodyState<T, #nl, #sl>);
    let name = &set.name;
    let mut bb = Vec::new();
    for &(a, b) in &set.ball_ball {
        let f = ident(&Pair::BallBall(a, b).fn_name());
        let (la, lb) = (lit(a), lit(b));
        bb.push(quote!((#la, #lb) => #f(nu, state1, state2),));
        if a != b {
            bb.push(quote!((#lb, #la) => {
                let minus_nu = nu.clone().map(|x| -x);
                let [s2, s1] = #f(&minus_nu, state2, state1);
                [s1, s2]
            }));
        }
    }
    let bw = set.ball_wall.iter().map(|&(s, k, side)| {
        let f = ident(&Pair::BallWall(s, k, side).fn_name());
        let upper = side == WallSide::Upper;
        let (ls, lk) = (lit(s), lit(k));
        quote!((#ls, #lk, #upper) => #f(state),)
    });
    let bo = set.ball_obstacle.iter().map(|&s| {
        let f = ident(&Pair::BallObstacle(s).fn_name());
        let ls = lit(s);
        quote!(#ls => #f(nu, state),)
    });
    let law = |present: bool, law: &ContactKind| {
        if !present {
            return quote!(None);
        }
        match law {
            ContactKind::Rough { e, beta } => {
                let (e, beta) = (
                    f64_tokens(nearest_floats(e).0),
                    f64_tokens(nearest_floats(beta).0),
                );
                quote!(Some(#sim_path::ContactKind::Rough { e: #e, beta: #beta }))
            }
            ContactKind::Walton { e, mu, beta0 } => {
                let [e, mu, beta0] = [e, mu, beta0].map(|x| f64_tokens(nearest_floats(x).0));
                quote!(Some(#sim_path::ContactKind::Walton { e: #e, mu: #mu, beta0: #beta0 }))
            }
            _ => quote!(Some(#sim_path::ContactKind::NoSlip)),
        }
    };
    // One law for every ball-ball kernel: `laws().ball` names it. Several (a scene's
    // `[[contact.pair]]`): `laws().ball` is `None` and `ball_law` names each pair's.
    let pair_laws: Vec<&ContactKind> = (set.ball_ball.iter())
        .map(|&(a, b)| set.laws.ball_law(a, b))
        .collect();
    let one_law = pair_laws.windows(2).all(|w| w[0] == w[1]);
    let ball_law = match pair_laws.first() {
        Some(first) if one_law => law(true, first),
        _ => quote!(None),
    };
    let per_pair = if one_law {
        quote!()
    } else {
        let arms = set.ball_ball.iter().map(|&(a, b)| {
            let (la, lb) = (lit(a), lit(b));
            let l = law(true, set.laws.ball_law(a, b));
            if a == b {
                quote!((#la, #lb) => #l,)
            } else {
                quote!((#la, #lb) | (#lb, #la) => #l,)
            }
        });
        quote! {
            fn ball_law(&self, a: usize, b: usize) -> Option<#sim_path::ContactKind> {
                match (a, b) {
                    #(#arms)*
                    _ => None,
                }
            }
        }
    };
    let wall_law = law(!set.ball_wall.is_empty(), &set.laws.wall);
    let fixed_law = law(!set.ball_obstacle.is_empty(), &set.laws.fixed);
    let bound = if needs_root(set) {
        quote!(ScalarRoot)
    } else {
        quote!(Scalar)
    };
    quote! {
        /// The scene's kernels, dispatched by species for the simulator.
        #[derive(Clone, Copy, Debug, Default)]
        pub struct Kernels;

        #[allow(unused_variables, clippy::match_single_binding)]
        impl<T: #bound> #sim_path::PairKernels<T, #nl, #sl> for Kernels
        where
            for<'a> &'a T: RefArith<T>,
        {
            fn laws(&self) -> #sim_path::law::FoldedLaws {
                #sim_path::law::FoldedLaws {
                    ball: #ball_law,
                    wall: #wall_law,
                    fixed: #fixed_law,
                }
            }
            #per_pair
            fn ball_ball(&self, a: usize, b: usize, nu: &[T; #nl], state1: &#state_ty, state2: &#state_ty) -> [#state_ty; 2] {
                match (a, b) {
                    #(#bb)*
                    _ => panic!("scene {}: no ball-ball kernel for species ({a}, {b})", #name),
                }
            }
            fn ball_wall(&self, species: usize, axis: usize, upper: bool, state: &#state_ty) -> #state_ty {
                match (species, axis, upper) {
                    #(#bw)*
                    _ => panic!("scene {}: no ball-wall kernel for species {species}, axis {axis}", #name),
                }
            }
            fn ball_obstacle(&self, species: usize, nu: &[T; #nl], state: &#state_ty) -> #state_ty {
                match species {
                    #(#bo)*
                    _ => panic!("scene {}: no ball-obstacle kernel for species {species}", #name),
                }
            }
        }
    }
}

/// Generate the module of `set`: its kernels and the dispatch. `crate_path` is the runtime
/// crate as seen from where the file is included (`"collision_core"` in a user's crate),
/// `sim_path` the simulator's (`"noslip_sim"`), whose `PairKernels` the dispatch implements.
/// Refuses a path that is not a Rust path, and a set whose constants overflow `f32` or `f64`
/// ([`check_ranges`]).
///
/// Panics if the kernels are not valid, straight-line Rust: a generator bug.
pub fn generate(
    set: &PairSet,
    crate_path: &str,
    sim_path: &str,
) -> Result<SceneModule, GenerateError> {
    let rust_path = |p: &str| -> Result<syn::Path, GenerateError> {
        syn::parse_str(p).map_err(|_| GenerateError::CratePath(p.to_string()))
    };
    let path = rust_path(crate_path)?;
    let sim = rust_path(sim_path)?;
    check_ranges(set).map_err(GenerateError::OutOfRange)?;
    let (kernels, pairs): (Vec<TokenStream>, Vec<PairSummary>) =
        set.all().into_iter().map(|p| emit_pair(set, p)).unzip();
    // `Scalar` bounds the no-slip and rough kernels (and the dispatch without a Walton
    // kernel), `ScalarRoot` the Walton ones (and then the dispatch): import what is used.
    let plain = set
        .all()
        .into_iter()
        .any(|p| !matches!(set.laws.of(p), ContactKind::Walton { .. }));
    let imports = match (plain || !needs_root(set), needs_root(set)) {
        (true, true) => quote!(use #path::{BodyState, RefArith, Scalar, ScalarRoot};),
        (false, true) => quote!(use #path::{BodyState, RefArith, ScalarRoot};),
        _ => quote!(use #path::{BodyState, RefArith, Scalar};),
    };
    let kernel_file = emit::parse(quote!(#imports #(#kernels)*));
    let violations = crate::straight_line::check(&kernel_file);
    assert!(
        violations.is_empty(),
        "specialised kernels of {} are not straight-line: {violations:?}",
        set.name
    );
    let dim = lit(set.dim);
    let dispatch = dispatch(set, &sim);
    let file = emit::parse(quote! {
        #imports
        /// The dimension of this scene.
        pub const DIM: usize = #dim;
        #(#kernels)*
        #dispatch
    });
    let mut header = format!(
        "// @generated by noslip-codegen (codegen/src/specialise): kernels specialised to scene `{}`.\n\
         // Do not edit: the build script rewrites it.\n\
         // n = {}; species constants and contact laws folded into exact literals.\n",
        set.name,
        set.dim
    );
    for p in &pairs {
        header.push_str(&format!(
            "// {} ({}): {}; {} intermediate terms (generic {}: {}).\n",
            p.pair.fn_name(),
            p.pair.kind(),
            p.ops,
            p.terms,
            generic_name(set, p.pair),
            p.generic_ops
        ));
    }
    Ok(SceneModule {
        name: set.name.clone(),
        dim: set.dim,
        source: format!("{header}\n{}", prettyplease::unparse(&file)),
        pairs,
    })
}
