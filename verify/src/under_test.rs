//! The kernel under test, as a function on exact values: the compiled generated kernels,
//! or (for the test that the verifier can fail) a deliberately corrupted evaluation of
//! the generator's DAG.

use collision_core::{Ball, BodyState, Exact, Generated, Kernel, Relaxing};
use noslip_codegen::ir::{Id, Node};
use noslip_codegen::model::{self, names, skew_pairs, Variant};
use std::collections::HashMap;

/// `[body 1+, body 2+]` from `(nu, balls, states)`; body 1 comes back unchanged for
/// [`Variant::Fixed`].
pub type ExactKernel<const N: usize, const S: usize> = dyn Fn(
    &[Exact; N],
    [&Ball<Exact>; 2],
    [&BodyState<Exact, N, S>; 2],
) -> [BodyState<Exact, N, S>; 2];

/// The compiled generated kernel of `variant`, in exact rationals: run relaxed (no GCD per
/// operation) and reduced at the end ([`Relaxing`]), the same values as in [`Exact`].
pub fn generated<const N: usize, const S: usize>(variant: Variant) -> Box<ExactKernel<N, S>>
where
    Generated: Kernel<Exact, N, S> + Kernel<collision_core::ExactRelaxed, N, S>,
{
    match variant {
        Variant::Free => Box::new(|nu, b, s| Relaxing::free(nu, b[0], b[1], s[0], s[1])),
        Variant::Fixed => Box::new(|nu, b, s| {
            [
                s[0].clone(),
                Relaxing::fixed(nu, &b[0].radius, b[1], s[0], s[1]),
            ]
        }),
    }
}

/// A deliberate corruption of the kernel's formula.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mutation {
    /// `dn = du . nu` computed with one product subtracted instead of added.
    FlippedSign,
    /// `c_0` loses the `R_2 U_2 nu` term.
    DroppedTerm,
    /// The constant 2 of the updates becomes 3.
    WrongConstant,
}

impl Mutation {
    /// Every mutation.
    pub const ALL: [Mutation; 3] = [
        Mutation::FlippedSign,
        Mutation::DroppedTerm,
        Mutation::WrongConstant,
    ];

    /// A short name, for messages.
    pub fn name(self) -> &'static str {
        match self {
            Mutation::FlippedSign => "flipped sign",
            Mutation::DroppedTerm => "dropped term",
            Mutation::WrongConstant => "wrong constant",
        }
    }
}

/// Values of the named inputs of a point.
pub fn input_values<const N: usize, const S: usize>(
    nu: &[Exact; N],
    balls: [&Ball<Exact>; 2],
    states: [&BodyState<Exact, N, S>; 2],
) -> HashMap<String, Exact> {
    let mut v = HashMap::new();
    for (k, x) in nu.iter().enumerate() {
        v.insert(names::nu(k), x.clone());
    }
    for b in 0..2 {
        let i = b + 1;
        for ((p, q), x) in skew_pairs(N).into_iter().zip(&states[b].spin) {
            v.insert(names::spin(i, p, q), x.clone());
        }
        for (k, x) in states[b].velocity.iter().enumerate() {
            v.insert(names::velocity(i, k), x.clone());
        }
        v.insert(names::radius(i), balls[b].radius.clone());
        v.insert(names::inv_mass(i), balls[b].inv_mass.clone());
        v.insert(names::gamma2(i), balls[b].gamma2.clone());
    }
    v
}

/// The generator's DAG evaluated exactly, with `mutation` applied: a corrupted kernel
/// (`None`: the DAG as generated, the control).
pub fn mutated<const N: usize, const S: usize>(
    variant: Variant,
    mutation: Option<Mutation>,
) -> Box<ExactKernel<N, S>> {
    let kernel = model::build(N, variant);
    Box::new(move |nu, balls, states| {
        let inputs = input_values(nu, balls, states);
        let g = &kernel.graph;
        let corrupt = |id: Id, node: &Node, values: &[Exact]| -> Option<Exact> {
            let label = g.label_of(id);
            match (mutation?, node) {
                (Mutation::WrongConstant, Node::Const(c)) if c.to_string() == "2" => {
                    Some(Exact::from_integer(3))
                }
                (Mutation::FlippedSign, Node::Add(a, b)) if label == Some("dn") => {
                    Some(&values[a.0 as usize] - &values[b.0 as usize])
                }
                (Mutation::DroppedTerm, Node::Add(a, _)) if label == Some("c_0") => {
                    Some(values[a.0 as usize].clone())
                }
                _ => None,
            }
        };
        let values = g
            .eval_all(&|name| inputs.get(name).cloned(), &corrupt)
            .expect(
                "every input is given and the kernel's denominators are positive at valid points",
            );
        let val = |values: &Vec<Exact>, id: Id| values[id.0 as usize].clone();
        let read = |o: &model::BodyOutput| BodyState {
            spin: std::array::from_fn(|k| val(&values, o.spin[k])),
            velocity: std::array::from_fn(|k| val(&values, o.velocity[k])),
        };
        match variant {
            Variant::Free => [read(&kernel.outputs[0]), read(&kernel.outputs[1])],
            Variant::Fixed => [states[0].clone(), read(&kernel.outputs[0])],
        }
    })
}
