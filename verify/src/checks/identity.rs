//! Identity checks: the compiled kernel, run in exact rationals at random points, satisfies
//! an identity built from the definitions ([`crate::identities`]); the same identity built on
//! the symbolic kernel gives the degree for the Schwartz-Zippel bound.

use crate::identities::{self as id, StateIds};
use crate::sample::{point, Point};
use crate::under_test::{generated, input_values, ExactKernel};
use collision_core::rng::Rng;
use collision_core::{BodyState, Exact, Generated, Kernel};
use noslip_codegen::ir::{Graph, Id, Node};
use noslip_codegen::model::{build_on, symbolic_inputs, KernelInputs, Variant};
use num_traits::Zero;
use std::collections::HashMap;

/// The identity checks, per variant.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Identity {
    /// `xi+` is the metric reflection across `G_q`: `xi + xi+` in `G_q`, `xi+ - xi` in `E_q`.
    Reflection,
    /// Kinetic energy (free: both bodies; fixed: body 2 with body 1 at rest).
    Energy,
    /// Total linear momentum (free only).
    LinearMomentum,
    /// Each movable body's angular momentum about the contact point.
    AngularMomentum,
    /// `C o C = id`.
    Involution,
    /// Fixed: the kernel is the free map at `w_1 = 0`, i.e. the limit `m_1 -> inf`.
    MassLimit,
    /// Free: at `gamma2_1 = 0` the map is the point-mass limit of docs/derivation.md §10.
    PointMassLimit,
}

impl Identity {
    /// The identities checked for `variant`: linear momentum and the point-mass limit for `free`
    /// only, the mass limit for `fixed` only.
    pub fn for_variant(variant: Variant) -> &'static [Identity] {
        use Identity::*;
        match variant {
            Variant::Free => &[
                Reflection,
                Energy,
                LinearMomentum,
                AngularMomentum,
                Involution,
                PointMassLimit,
            ],
            Variant::Fixed => &[Reflection, Energy, AngularMomentum, Involution, MassLimit],
        }
    }

    /// The check's name in the report (`conserved: kinetic energy`).
    pub fn name(self) -> &'static str {
        match self {
            Identity::Reflection => "map: reflection across G_q",
            Identity::Energy => "conserved: kinetic energy",
            Identity::LinearMomentum => "conserved: linear momentum",
            Identity::AngularMomentum => "conserved: angular momentum about Q (each body)",
            Identity::Involution => "map: C o C = id",
            Identity::MassLimit => "limit m_1 -> inf (w_1 = 0)",
            Identity::PointMassLimit => "limit lambda_1 -> 0 (point mass)",
        }
    }

    /// Body 1 is held at rest for this check (the fixed variant's energy: an immovable body
    /// that moves does work).
    fn body1_at_rest(self, variant: Variant) -> bool {
        self == Identity::Energy && variant == Variant::Fixed
    }

    fn movable(variant: Variant) -> &'static [usize] {
        match variant {
            Variant::Free => &[0, 1],
            Variant::Fixed => &[1],
        }
    }

    /// The nodes that must vanish, given the named computed states.
    fn zeros(
        self,
        g: &mut Graph,
        inputs: &KernelInputs,
        variant: Variant,
        states: &HashMap<&str, [StateIds; 2]>,
    ) -> Vec<Id> {
        let before = id::before(inputs);
        let after = &states["after"];
        let fixed = variant == Variant::Fixed;
        match self {
            Identity::Reflection => id::reflection(g, inputs, &before, after, fixed),
            Identity::Energy => {
                id::energy_conserved(g, inputs, &before, after, Self::movable(variant))
            }
            Identity::LinearMomentum => id::momentum_conserved(g, inputs, &before, after),
            Identity::AngularMomentum => {
                id::angular_momentum_conserved(g, inputs, &before, after, Self::movable(variant))
            }
            Identity::Involution => id::equal(g, &states["twice"], &before),
            Identity::MassLimit => id::equal(g, &states["free_w1_0"], after),
            Identity::PointMassLimit => {
                let limit = id::point_mass_limit(g, inputs);
                id::equal(g, &states["free_g1_0"], &limit)
            }
        }
    }

    fn input_variant(self, variant: Variant) -> Variant {
        // The mass limit compares with the free map, which needs all free inputs.
        if self == Identity::MassLimit {
            Variant::Free
        } else {
            variant
        }
    }
}

fn inputs_for(g: &mut Graph, n: usize, identity: Identity, variant: Variant) -> KernelInputs {
    let mut inputs = symbolic_inputs(g, n, identity.input_variant(variant));
    if identity.body1_at_rest(variant) {
        let zero = g.int(0);
        let b1 = &mut inputs.bodies[0];
        b1.spin
            .iter_mut()
            .chain(b1.velocity.iter_mut())
            .for_each(|x| *x = zero);
    }
    inputs
}

fn outputs_as_states(
    inputs: &KernelInputs,
    outs: Vec<noslip_codegen::model::BodyOutput>,
) -> [StateIds; 2] {
    let mut s = id::before(inputs);
    for o in outs {
        s[o.body - 1] = StateIds {
            spin: o.spin,
            velocity: o.velocity,
        };
    }
    s
}

fn with_states(inputs: &KernelInputs, s: &[StateIds; 2]) -> KernelInputs {
    let mut out = inputs.clone();
    for (b, st) in out.bodies.iter_mut().zip(s) {
        b.spin = st.spin.clone();
        b.velocity = st.velocity.clone();
    }
    out
}

/// The degree of `identity` for dimension `n` and `variant`, on the symbolic kernel.
pub fn degree(n: usize, variant: Variant, identity: Identity) -> u64 {
    let mut g = Graph::new();
    let inputs = inputs_for(&mut g, n, identity, variant);
    let mut states = HashMap::new();
    let kernel_inputs = if identity == Identity::MassLimit {
        symbolic_inputs(&mut g, n, Variant::Fixed)
    } else {
        inputs.clone()
    };
    let after = outputs_as_states(&kernel_inputs, build_on(&mut g, &kernel_inputs, variant));
    match identity {
        Identity::Involution => {
            let once = with_states(&inputs, &after);
            let twice = build_on(&mut g, &once, variant);
            states.insert("twice", outputs_as_states(&once, twice));
        }
        Identity::MassLimit => {
            let mut free = inputs.clone();
            free.bodies[0].inv_mass = g.int(0);
            states.insert(
                "free_w1_0",
                outputs_as_states(&free, build_on(&mut g, &free, Variant::Free)),
            );
        }
        Identity::PointMassLimit => {
            let mut free = inputs.clone();
            free.bodies[0].gamma2 = g.int(0);
            states.insert(
                "free_g1_0",
                outputs_as_states(&free, build_on(&mut g, &free, Variant::Free)),
            );
        }
        _ => {}
    }
    states.insert("after", after);
    let zeros = identity.zeros(&mut g, &inputs, variant, &states);
    crate::degree::identity_degree(&g, &zeros)
}

/// Evaluate `identity` at one point with `kernel`'s outputs; `Err` names what failed.
pub fn check_at<const N: usize, const S: usize>(
    kernel: &ExactKernel<N, S>,
    free_kernel: &ExactKernel<N, S>,
    variant: Variant,
    identity: Identity,
    p: &Point<N, S>,
) -> Result<(), String> {
    let mut p = p.clone();
    if identity.body1_at_rest(variant) {
        p.states[0] = BodyState::zero();
    }
    let balls = [&p.balls[0], &p.balls[1]];
    let states = [&p.states[0], &p.states[1]];
    let mut g = Graph::new();
    let inputs = inputs_for(&mut g, N, identity, variant);
    let mut values = input_values(&p.nu, balls, states);
    let mut named: HashMap<&str, [StateIds; 2]> = HashMap::new();
    let mut record = |g: &mut Graph, name: &'static str, s: [BodyState<Exact, N, S>; 2]| {
        let ids = id::named_state(g, N, name);
        for b in 0..2 {
            for (i, x) in ids[b].spin.iter().zip(&s[b].spin) {
                values.insert(input_name(g, *i), x.clone());
            }
            for (i, x) in ids[b].velocity.iter().zip(&s[b].velocity) {
                values.insert(input_name(g, *i), x.clone());
            }
        }
        named.insert(name, ids);
    };
    let after = kernel(&p.nu, balls, states);
    match identity {
        Identity::Involution => {
            let twice = kernel(&p.nu, balls, [&after[0], &after[1]]);
            record(&mut g, "twice", twice);
        }
        Identity::MassLimit => {
            let mut b1 = p.balls[0].clone();
            b1.inv_mass = Exact::zero();
            let free = free_kernel(&p.nu, [&b1, &p.balls[1]], states);
            record(&mut g, "free_w1_0", free);
        }
        Identity::PointMassLimit => {
            let mut b1 = p.balls[0].clone();
            b1.gamma2 = Exact::zero();
            let free = free_kernel(&p.nu, [&b1, &p.balls[1]], states);
            record(&mut g, "free_g1_0", free);
        }
        _ => {}
    }
    record(&mut g, "after", after);
    let zeros = identity.zeros(&mut g, &inputs, variant, &named);
    let v = g.eval_all(&|name| values.get(name).cloned(), &|_, _, _| None)?;
    match zeros.iter().position(|z| !v[z.0 as usize].is_zero()) {
        None => Ok(()),
        Some(k) => Err(format!(
            "component {k} of the identity is {} at the sample point, not 0",
            v[zeros[k].0 as usize]
        )),
    }
}

fn input_name(g: &Graph, id: Id) -> String {
    match g.node(id) {
        Node::Input(i) => i.0.clone(),
        _ => unreachable!("named states are inputs"),
    }
}

/// Run `identity` at `points` random points; returns the first failure. `interrupted` is
/// asked before each point (a front end's Ctrl-C): when it says stop, the check fails with
/// "interrupted at point k" and the caller discards the run.
pub fn run<const N: usize, const S: usize>(
    kernel: &ExactKernel<N, S>,
    variant: Variant,
    identity: Identity,
    points: usize,
    seed: u64,
    interrupted: &dyn Fn() -> bool,
) -> Result<(), String>
where
    Generated: Kernel<Exact, N, S> + Kernel<collision_core::ExactRelaxed, N, S>,
{
    let free = generated::<N, S>(Variant::Free);
    let mut rng = Rng::new(seed);
    for k in 0..points {
        if interrupted() {
            return Err(format!("interrupted at point {k}"));
        }
        let p = point::<N, S>(&mut rng, variant == Variant::Fixed);
        check_at(kernel, free.as_ref(), variant, identity, &p)
            .map_err(|e| format!("point {k}: {e}"))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn all_pass<const N: usize, const S: usize>()
    where
        Generated: Kernel<Exact, N, S> + Kernel<collision_core::ExactRelaxed, N, S>,
    {
        for variant in Variant::ALL {
            let kernel = generated::<N, S>(variant);
            for &identity in Identity::for_variant(variant) {
                run::<N, S>(kernel.as_ref(), variant, identity, 1, 7, &|| false)
                    .unwrap_or_else(|e| panic!("n = {N} {variant:?} {identity:?}: {e}"));
                let d = degree(N, variant, identity);
                assert!(d > 0 && d < 100_000, "degree {d}");
            }
        }
    }

    #[test]
    fn the_generated_kernels_satisfy_every_identity() {
        all_pass::<2, 1>();
        all_pass::<3, 3>();
    }
}
