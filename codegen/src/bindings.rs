//! The names of a kernel's bindings and the spelling of its leaves as Rust tokens: inputs and
//! computed nodes by name, constants as `T::from_ratio(p, q)` or `T::from_literal(...)`. What
//! every Rust emitter (`crate::emit`, `crate::batch`, `crate::specialise`) and the lowering to
//! a program (`crate::program`) share.

use crate::ir::{Id, Node};
use crate::model::KernelGraph;
use crate::schedule::Schedule;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive};
use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::quote;
use std::collections::{BTreeSet, HashMap};

pub(crate) fn ident(name: &str) -> Ident {
    Ident::new(name, Span::call_site())
}

pub(crate) fn lit(n: usize) -> Literal {
    Literal::usize_unsuffixed(n)
}

fn const_name(c: &BigRational) -> String {
    let part = |x: &BigInt| {
        if x.is_negative() {
            format!("m{}", x.abs())
        } else {
            x.to_string()
        }
    };
    if c.is_integer() {
        format!("lit_{}", part(c.numer()))
    } else {
        format!("lit_{}_{}", part(c.numer()), c.denom())
    }
}

/// Largest numerator and denominator emitted as `T::from_ratio(p, q)`: `2^24`, so that
/// both are exact in `f32` and `f64` and the quotient is correctly rounded in both.
const SMALL: i64 = 1 << 24;

/// An exact constant as a `T` expression: `T::from_ratio(p, q)` when `|p|, q <= 2^24` (all
/// constants of the generic kernels); otherwise (species constants folded by
/// `crate::specialise`) `T::from_literal(x64, x32, "p", "q")` with `x64` and `x32` the
/// correctly rounded `f64` and `f32` computed here, and the exact digits for rationals.
/// Panics if a float overflows: the specialiser refuses such constants before emitting
/// ([`crate::literal::overflows`]).
pub(crate) fn const_value(c: &BigRational) -> TokenStream {
    let small = |x: &BigInt| x.to_i64().filter(|v| v.abs() <= SMALL);
    if let (Some(p), Some(q)) = (small(c.numer()), small(c.denom())) {
        let (p, q) = (Literal::i64_unsuffixed(p), Literal::i64_unsuffixed(q));
        return quote!(T::from_ratio(#p, #q));
    }
    let (x64, x32) = crate::literal::nearest_floats(c);
    let x64 = crate::literal::f64_tokens(x64);
    let x32 = crate::literal::f32_tokens(x32);
    let (p, q) = (c.numer().to_string(), c.denom().to_string());
    quote!(T::from_literal(#x64, #x32, #p, #q))
}

pub(crate) struct Namer<'a> {
    pub(crate) kernel: &'a KernelGraph,
    names: HashMap<Id, String>,
}

impl<'a> Namer<'a> {
    pub(crate) fn new(kernel: &'a KernelGraph, sched: &Schedule, steps: &[Id]) -> Self {
        let g = &kernel.graph;
        let mut names = HashMap::new();
        let mut used = BTreeSet::new();
        let mut tmp = 0;
        for &id in &sched.constants {
            let name = const_name(g.as_const(id).expect("constant node"));
            assert!(used.insert(name.clone()), "duplicate binding {name}");
            names.insert(id, name);
        }
        for &id in steps {
            let name = match g.label_of(id) {
                Some(label) => label.to_string(),
                _ => {
                    tmp += 1;
                    format!("tmp{}", tmp - 1)
                }
            };
            assert!(used.insert(name.clone()), "duplicate binding {name}");
            names.insert(id, name);
        }
        Namer { kernel, names }
    }

    /// An operand as a `&T` expression.
    pub(crate) fn operand(&self, id: Id) -> TokenStream {
        match self.kernel.graph.node(id) {
            Node::Input(input) => {
                let i = ident(&input.0);
                quote!(#i)
            }
            _ => {
                let i = ident(&self.names[&id]);
                quote!(&#i)
            }
        }
    }

    pub(crate) fn binding(&self, id: Id) -> Ident {
        ident(&self.names[&id])
    }

    /// The binding name of a constant or computed node.
    pub(crate) fn name(&self, id: Id) -> &str {
        &self.names[&id]
    }

    /// An output as an owned `T`, moving a temporary when this is its only output use.
    pub(crate) fn output(&self, id: Id, output_uses: &HashMap<Id, usize>) -> TokenStream {
        match self.kernel.graph.node(id) {
            Node::Input(input) => {
                let i = ident(&input.0);
                quote!(#i.clone())
            }
            Node::Const(c) => const_value(c),
            _ => {
                let i = self.binding(id);
                if output_uses[&id] > 1 {
                    quote!(#i.clone())
                } else {
                    quote!(#i)
                }
            }
        }
    }
}
