//! From a DAG and its outputs to a straight-line program: the live nodes in topological
//! order, deterministic names, and the operation counts stated in each kernel's docs.

use crate::ir::{Graph, Id, Node};
use std::collections::BTreeSet;
use std::fmt;

/// Arithmetic operations of a straight-line kernel.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OpCount {
    /// Additions and subtractions.
    pub add: usize,
    /// Multiplications.
    pub mul: usize,
    /// Divisions.
    pub div: usize,
    /// Negations.
    pub neg: usize,
    /// Fused multiply-adds (FMA kernels only): `a b + c` with one rounding.
    pub fma: usize,
    /// Square roots (the Walton kernels only).
    pub sqrt: usize,
    /// Selects `if x < y { a } else { b }` (the Walton kernels only).
    pub select: usize,
}

impl OpCount {
    /// All operations together (a fused multiply-add counts as one).
    pub fn total(&self) -> usize {
        self.add + self.mul + self.div + self.neg + self.fma + self.sqrt + self.select
    }
}

impl fmt::Display for OpCount {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.fma > 0 {
            write!(f, "{} fma, ", self.fma)?;
        }
        // Only where there are any, so that the other kernels' headers read as before.
        if self.sqrt > 0 || self.select > 0 {
            write!(f, "{} sqrt, {} select, ", self.sqrt, self.select)?;
        }
        write!(
            f,
            "{} add, {} mul, {} div, {} neg ({} total)",
            self.add,
            self.mul,
            self.div,
            self.neg,
            self.total()
        )
    }
}

/// The live part of a DAG, in emission order.
#[derive(Debug)]
pub struct Schedule {
    /// Live non-input, non-constant nodes, operands before their uses.
    pub steps: Vec<Id>,
    /// Live constants, in increasing id order.
    pub constants: Vec<Id>,
    /// Live inputs, by name.
    pub inputs: BTreeSet<String>,
    /// The operations of the steps.
    pub ops: OpCount,
}

/// Every node reachable from `roots`, classified, in increasing id order (a topological
/// order, since operands are created before the nodes that use them).
pub fn schedule(graph: &Graph, roots: impl IntoIterator<Item = Id>) -> Schedule {
    let mut live = vec![false; graph.len()];
    let mut stack: Vec<Id> = roots.into_iter().collect();
    while let Some(id) = stack.pop() {
        if std::mem::replace(&mut live[id.index()], true) {
            continue;
        }
        stack.extend(graph.node(id).operands());
    }
    let mut out = Schedule {
        steps: Vec::new(),
        constants: Vec::new(),
        inputs: BTreeSet::new(),
        ops: OpCount::default(),
    };
    for (index, _) in live.iter().enumerate().filter(|(_, &l)| l) {
        let id = Id(index as u32);
        match graph.node(id) {
            Node::Input(input) => {
                out.inputs.insert(input.0.clone());
            }
            Node::Const(_) => out.constants.push(id),
            node => {
                match node {
                    Node::Add(..) | Node::Sub(..) => out.ops.add += 1,
                    Node::Mul(..) => out.ops.mul += 1,
                    Node::Div(..) => out.ops.div += 1,
                    Node::Neg(..) => out.ops.neg += 1,
                    Node::Sqrt(..) => out.ops.sqrt += 1,
                    Node::SelectLt(..) => out.ops.select += 1,
                    Node::Input(_) | Node::Const(_) => unreachable!(),
                }
                out.steps.push(id);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dead_nodes_are_dropped_and_ops_counted() {
        let mut g = Graph::new();
        let (x, y) = (g.input("x"), g.input("y"));
        let _dead = g.div(x, y);
        let s = g.add(x, y);
        let p = g.mul(s, s);
        let n = g.neg(p);
        let sched = schedule(&g, [n]);
        assert_eq!(sched.steps, vec![s, p, n]);
        assert_eq!(
            sched.ops,
            OpCount {
                add: 1,
                mul: 1,
                div: 0,
                neg: 1,
                ..OpCount::default()
            }
        );
        assert_eq!(sched.inputs.len(), 2);
    }
}
