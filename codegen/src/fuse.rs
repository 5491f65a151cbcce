//! Multiply-add fusion for the FMA kernels.
//!
//! A product whose only use is one addition or subtraction is folded into it, so that the
//! pair is computed with one rounding instead of two:
//!
//! ```text
//! a * b + c  ->  T::mul_add(a, b, c)        a * b - c  ->  T::mul_sub(a, b, c)
//! c - a * b  ->  T::neg_mul_add(a, b, c)
//! ```
//!
//! Products used more than once, or returned as outputs, stay separate (fusing them would
//! compute the product twice). The DAG and its operation order are otherwise unchanged, so
//! the fused kernel is the plain one with some roundings removed.

use crate::ir::{Graph, Id, Node};
use std::collections::{HashMap, HashSet};

/// One fused step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fused {
    /// `a * b + c`.
    MulAdd {
        /// The product's first factor.
        a: Id,
        /// The product's second factor.
        b: Id,
        /// The term the product is added to.
        c: Id,
    },
    /// `a * b - c`.
    MulSub {
        /// The product's first factor.
        a: Id,
        /// The product's second factor.
        b: Id,
        /// The term subtracted from the product.
        c: Id,
    },
    /// `c - a * b`.
    NegMulAdd {
        /// The product's first factor.
        a: Id,
        /// The product's second factor.
        b: Id,
        /// The term the product is subtracted from.
        c: Id,
    },
}

/// Which steps become fused operations, and which products they absorb.
#[derive(Debug, Default)]
pub struct Fusion {
    /// The fused steps: the id of the addition or subtraction, and its fused form.
    pub fused: HashMap<Id, Fused>,
    /// Products folded into a fused step: not emitted on their own.
    pub absorbed: HashSet<Id>,
}

/// Plan the fusion of the scheduled `steps` (operands before uses) with the given outputs.
pub fn fuse(graph: &Graph, steps: &[Id], outputs: impl IntoIterator<Item = Id>) -> Fusion {
    let mut uses: HashMap<Id, usize> = HashMap::new();
    for id in outputs {
        *uses.entry(id).or_default() += 2; // an output is never absorbed
    }
    for &id in steps {
        for a in graph.node(id).operands() {
            *uses.entry(a).or_default() += 1;
        }
    }
    let product = |id: Id| match graph.node(id) {
        Node::Mul(a, b) if uses.get(&id) == Some(&1) => Some((*a, *b)),
        _ => None,
    };
    let mut plan = Fusion::default();
    for &id in steps {
        let step = match *graph.node(id) {
            Node::Add(x, y) => match (product(x), product(y)) {
                (Some((a, b)), _) => Some((x, Fused::MulAdd { a, b, c: y })),
                (None, Some((a, b))) => Some((y, Fused::MulAdd { a, b, c: x })),
                (None, None) => None,
            },
            Node::Sub(x, y) => match (product(y), product(x)) {
                (Some((a, b)), _) => Some((y, Fused::NegMulAdd { a, b, c: x })),
                (None, Some((a, b))) => Some((x, Fused::MulSub { a, b, c: y })),
                (None, None) => None,
            },
            _ => None,
        };
        if let Some((absorbed, fused)) = step {
            plan.absorbed.insert(absorbed);
            plan.fused.insert(id, fused);
        }
    }
    plan
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn single_use_products_fold_into_their_sum() {
        let mut g = Graph::new();
        let (x, y, z) = (g.input("x"), g.input("y"), g.input("z"));
        let xy = g.mul(x, y);
        let s = g.add(xy, z); // x y + z: fused
        let yz = g.mul(y, z);
        let d = g.sub(s, yz); // s - y z: fused
        let shared = g.mul(x, z);
        let e = g.add(shared, d); // x z is also an output: not fused
        let plan = fuse(&g, &[xy, s, yz, d, shared, e], [e, shared]);
        assert_eq!(plan.fused[&s], Fused::MulAdd { a: x, b: y, c: z });
        assert_eq!(plan.fused[&d], Fused::NegMulAdd { a: y, b: z, c: s });
        assert!(!plan.fused.contains_key(&e));
        assert_eq!(plan.absorbed, HashSet::from([xy, yz]));
    }
}
