//! A scheduled kernel lowered to a language-neutral straight-line program: the one form every
//! back end emits from (Rust in [`crate::emit`], C and OpenCL C in [`crate::backend`]).
//!
//! [`Program::lower`] schedules the DAG ([`crate::schedule`]), plans the multiply-add fusion
//! for [`Arith::Fma`] ([`crate::fuse`]) and names every binding (`crate::bindings`'s namer):
//! constants first, then one [`Step`] per operation in schedule order, then the outputs. A back
//! end only spells these steps in its language; it never reorders, regroups or re-fuses them,
//! so every language evaluates the same operations in the same order, and a float kernel
//! rounds the same way in each (given IEEE `+ - * /` and a correctly rounded `fma`).

use crate::arith::Arith;
use crate::bindings::Namer;
use crate::fuse::{fuse, Fused, Fusion};
use crate::ir::{Id, Node};
use crate::model::{KernelGraph, Variant};
use crate::schedule::{schedule, OpCount};
use num_rational::BigRational;
use std::collections::{BTreeSet, HashMap};

/// A value a step reads.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Operand {
    /// A kernel input, by name (`nu_0`, `U1_01`, `inv_mass1`, ...; see [`crate::model::names`]).
    Input(String),
    /// The constant `constants[k]`.
    Const(usize),
    /// The result of `steps[k]`.
    Step(usize),
}

/// One operation. Each rounds once in floats: `+ - * /` and `sqrt` as IEEE, the fused ones
/// as `fma`; a select does not round.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Op {
    /// `a + b`.
    Add(Operand, Operand),
    /// `a - b`.
    Sub(Operand, Operand),
    /// `a * b`.
    Mul(Operand, Operand),
    /// `a / b`.
    Div(Operand, Operand),
    /// `-a`.
    Neg(Operand),
    /// `fma(a, b, c) = a b + c`.
    MulAdd(Operand, Operand, Operand),
    /// `fma(a, b, -c) = a b - c`.
    MulSub(Operand, Operand, Operand),
    /// `fma(-a, b, c) = c - a b`.
    NegMulAdd(Operand, Operand, Operand),
    /// `sqrt(a)`, correctly rounded (IEEE).
    Sqrt(Operand),
    /// `[x, y, a, b]`: `a` if `x < y`, else `b`; exact (no rounding).
    SelectLt([Operand; 4]),
}

/// A named exact constant.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Constant {
    /// Its binding name (`lit_2`, `lit_m1_2`).
    pub name: String,
    /// Its exact value (each back end rounds it correctly to its float formats).
    pub value: BigRational,
}

/// One binding: `name = op`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Step {
    /// Its binding name (`dn`, `t_0`, `tmp7`).
    pub name: String,
    /// What it computes.
    pub op: Op,
}

/// One body's result.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Output {
    /// 1 or 2.
    pub body: usize,
    /// The compact skew entries of `U+`, in [`crate::model::skew_pairs`] order.
    pub spin: Vec<Operand>,
    /// The centre velocity `u+`.
    pub velocity: Vec<Operand>,
}

/// A kernel as a straight-line program.
#[derive(Clone, Debug)]
pub struct Program {
    /// The dimension `n`.
    pub dim: usize,
    /// Which bodies move.
    pub variant: Variant,
    /// Plain or fused arithmetic.
    pub arith: Arith,
    /// The inputs the program reads, by name.
    pub inputs: BTreeSet<String>,
    /// The constants, in schedule order.
    pub constants: Vec<Constant>,
    /// The operations, operands before their uses.
    pub steps: Vec<Step>,
    /// The bodies returned, in the kernel's output order.
    pub outputs: Vec<Output>,
    /// The operations of the steps.
    pub ops: OpCount,
}

impl Program {
    /// Schedule `kernel`, fuse it for `arith`, and name its bindings.
    pub fn lower(kernel: &KernelGraph, arith: Arith) -> Program {
        let roots: Vec<Id> = kernel
            .outputs
            .iter()
            .flat_map(|o| o.spin.iter().chain(&o.velocity).copied())
            .collect();
        let sched = schedule(&kernel.graph, roots.iter().copied());
        let fusion = match arith {
            Arith::Plain => Fusion::default(),
            Arith::Fma => fuse(&kernel.graph, &sched.steps, roots.iter().copied()),
        };
        let step_ids: Vec<Id> = sched
            .steps
            .iter()
            .copied()
            .filter(|id| !fusion.absorbed.contains(id))
            .collect();
        let mut ops = sched.ops;
        ops.fma = fusion.fused.len();
        ops.mul -= fusion.absorbed.len();
        ops.add -= fusion.fused.len();
        let namer = Namer::new(kernel, &sched, &step_ids);

        let g = &kernel.graph;
        let const_index: HashMap<Id, usize> = sched
            .constants
            .iter()
            .enumerate()
            .map(|(k, &id)| (id, k))
            .collect();
        let step_index: HashMap<Id, usize> = step_ids
            .iter()
            .enumerate()
            .map(|(k, &id)| (id, k))
            .collect();
        let operand = |id: Id| match g.node(id) {
            Node::Input(input) => Operand::Input(input.0.clone()),
            Node::Const(_) => Operand::Const(const_index[&id]),
            _ => Operand::Step(step_index[&id]),
        };
        let constants = sched
            .constants
            .iter()
            .map(|&id| Constant {
                name: namer.name(id).to_string(),
                value: g.as_const(id).expect("constant node").clone(),
            })
            .collect();
        let steps = step_ids
            .iter()
            .map(|&id| {
                let op = match fusion.fused.get(&id) {
                    Some(&Fused::MulAdd { a, b, c }) => {
                        Op::MulAdd(operand(a), operand(b), operand(c))
                    }
                    Some(&Fused::MulSub { a, b, c }) => {
                        Op::MulSub(operand(a), operand(b), operand(c))
                    }
                    Some(&Fused::NegMulAdd { a, b, c }) => {
                        Op::NegMulAdd(operand(a), operand(b), operand(c))
                    }
                    None => match *g.node(id) {
                        Node::Add(a, b) => Op::Add(operand(a), operand(b)),
                        Node::Sub(a, b) => Op::Sub(operand(a), operand(b)),
                        Node::Mul(a, b) => Op::Mul(operand(a), operand(b)),
                        Node::Div(a, b) => Op::Div(operand(a), operand(b)),
                        Node::Neg(a) => Op::Neg(operand(a)),
                        Node::Sqrt(a) => Op::Sqrt(operand(a)),
                        Node::SelectLt(ids) => Op::SelectLt(ids.map(operand)),
                        Node::Input(_) | Node::Const(_) => unreachable!("not a step"),
                    },
                };
                Step {
                    name: namer.name(id).to_string(),
                    op,
                }
            })
            .collect();
        let outputs = kernel
            .outputs
            .iter()
            .map(|o| Output {
                body: o.body,
                spin: o.spin.iter().map(|&id| operand(id)).collect(),
                velocity: o.velocity.iter().map(|&id| operand(id)).collect(),
            })
            .collect();
        Program {
            dim: kernel.dim,
            variant: kernel.variant,
            arith,
            inputs: sched.inputs,
            constants,
            steps,
            outputs,
            ops,
        }
    }

    /// Intermediate terms: bindings of computed values (one per step).
    pub fn terms(&self) -> usize {
        self.steps.len()
    }

    /// The binding name of an operand (an input's own name).
    pub fn name<'a>(&'a self, operand: &'a Operand) -> &'a str {
        match operand {
            Operand::Input(name) => name,
            Operand::Const(k) => &self.constants[*k].name,
            Operand::Step(k) => &self.steps[*k].name,
        }
    }

    /// How many output slots each operand fills.
    pub fn output_uses(&self) -> HashMap<&Operand, usize> {
        let mut uses = HashMap::new();
        for o in &self.outputs {
            for x in o.spin.iter().chain(&o.velocity) {
                *uses.entry(x).or_default() += 1;
            }
        }
        uses
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::build;

    #[test]
    fn lowering_keeps_the_schedule_and_the_counts() {
        for arith in Arith::ALL {
            let kernel = build(3, Variant::Free);
            let p = Program::lower(&kernel, arith);
            // Every step reads only inputs, constants and earlier steps.
            for (k, s) in p.steps.iter().enumerate() {
                let operands: Vec<&Operand> = match &s.op {
                    Op::Add(a, b) | Op::Sub(a, b) | Op::Mul(a, b) | Op::Div(a, b) => vec![a, b],
                    Op::Neg(a) | Op::Sqrt(a) => vec![a],
                    Op::SelectLt(ids) => ids.iter().collect(),
                    Op::MulAdd(a, b, c) | Op::MulSub(a, b, c) | Op::NegMulAdd(a, b, c) => {
                        vec![a, b, c]
                    }
                };
                for x in operands {
                    if let Operand::Step(j) = x {
                        assert!(*j < k, "{} reads a later step", s.name);
                    }
                }
            }
            let fused = p
                .steps
                .iter()
                .filter(|s| matches!(s.op, Op::MulAdd(..) | Op::MulSub(..) | Op::NegMulAdd(..)))
                .count();
            assert_eq!(fused, p.ops.fma);
            assert_eq!(p.terms(), p.ops.total());
            assert_eq!(p.outputs.len(), 2);
        }
    }
}
