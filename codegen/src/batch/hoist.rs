//! What a batch kernel runs once per call and what it runs per contact: a node is uniform
//! when it depends on no per-contact input (only on constants and the shared inputs); the
//! uniform steps run once, before the block loop, the others in the lane loop. The two
//! parts' operations are counted apart ([`BatchSummary`]); their sum is the scalar kernel's.

use super::params::Params;
use crate::ir::{Graph, Id, Node};
use crate::model::{self, Variant};
use crate::schedule::OpCount;
use std::collections::BTreeSet;

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

/// `uniform[id]`: the node depends on no per-contact input (only constants and `shared`).
pub(super) fn uniform_nodes(graph: &Graph, shared: &BTreeSet<String>) -> Vec<bool> {
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

/// The operations among `ids`, by kind (inputs and constants cost none).
pub(super) fn count(graph: &Graph, ids: &[Id]) -> OpCount {
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
