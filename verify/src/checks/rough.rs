//! Identity checks of the rough-ball kernels (`kernels::dN::rough`, docs/derivation.md §15):
//! the compiled kernel, run in exact rationals at random points (the restitutions `e`, `beta`
//! drawn like every other input), satisfies an identity built from the definitions (the
//! contact-point slip, the metric, the momenta, the smooth map) in [`crate::identities`]; the
//! same identity built on the symbolic kernel gives its degree for the Schwartz-Zippel bound.
//!
//! The law and the energy loss are rational identities in `(e, beta)` as in every other
//! input, so they are checked at points off the physical ranges too, which is stronger.

use crate::identities::{self as id, StateIds};
use crate::sample::{element, point, Point};
use crate::under_test::input_values;
use collision_core::rng::Rng;
use collision_core::{BodyState, Exact, Relaxing, Restitution, RoughKernel};
use collision_core::{ExactRelaxed, Generated, Kernel};
use noslip_codegen::ir::{Graph, Id, Node};
use noslip_codegen::model::{
    build_on, build_rough_on, names, symbolic_inputs, BodyOutput, KernelInputs, RestitutionInputs,
    Variant,
};
use num_traits::Zero;
use std::collections::HashMap;

/// The identity checks of the rough kernels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RoughIdentity {
    /// The normal slip: `dn+ = -e dn`.
    NormalLaw,
    /// The tangential slip: `t+ = -beta t`.
    TangentialLaw,
    /// `2 Delta E = -(1 - e^2) dn^2 / a - (1 - beta^2) |t|^2 / b`, `a = w_1 + w_2`,
    /// `b = a + w_1/g_1 + w_2/g_2` (fixed: body 2's, body 1 at rest).
    EnergyLoss,
    /// Total linear momentum (free only).
    LinearMomentum,
    /// Each movable body's angular momentum about the contact point.
    AngularMomentum,
    /// At `(e, beta) = (1, 1)` the outputs are the no-slip kernel's.
    NoSlipMember,
    /// At `(e, beta) = (1, -1)` the outputs are the smooth map's: spins kept, centre
    /// velocities changed along `nu` by `+-2 w_i dn / (w_1 + w_2)`.
    SmoothMember,
    /// Fixed: the kernel is the rough free map at `w_1 = 0`, the limit `m_1 -> inf`.
    MassLimit,
}

impl RoughIdentity {
    /// The identities checked for `variant`.
    pub fn for_variant(variant: Variant) -> &'static [RoughIdentity] {
        use RoughIdentity::*;
        match variant {
            Variant::Free => &[
                NormalLaw,
                TangentialLaw,
                EnergyLoss,
                LinearMomentum,
                AngularMomentum,
                NoSlipMember,
                SmoothMember,
            ],
            Variant::Fixed => &[
                NormalLaw,
                TangentialLaw,
                EnergyLoss,
                AngularMomentum,
                NoSlipMember,
                SmoothMember,
                MassLimit,
            ],
        }
    }

    /// The check's name in the report.
    pub fn name(self) -> &'static str {
        match self {
            RoughIdentity::NormalLaw => "law: normal slip dn+ = -e dn",
            RoughIdentity::TangentialLaw => "law: tangential slip t+ = -beta t",
            RoughIdentity::EnergyLoss => "energy loss = (1-e^2) dn^2/(2a) + (1-beta^2) |t|^2/(2b)",
            RoughIdentity::LinearMomentum => "conserved: linear momentum",
            RoughIdentity::AngularMomentum => "conserved: angular momentum about Q (each body)",
            RoughIdentity::NoSlipMember => "(e, beta) = (1, 1) is the no-slip kernel",
            RoughIdentity::SmoothMember => "(e, beta) = (1, -1) is the smooth map",
            RoughIdentity::MassLimit => "limit m_1 -> inf (w_1 = 0)",
        }
    }

    /// The report's variant name of the rough kernel of `variant`: `rough free`, `rough fixed`.
    pub fn variant_name(variant: Variant) -> String {
        format!("rough {}", variant.name())
    }

    /// `(e, beta)` fixed by the identity, or `None` (drawn at each point).
    fn law(self) -> Option<(i64, i64)> {
        match self {
            RoughIdentity::NoSlipMember => Some((1, 1)),
            RoughIdentity::SmoothMember => Some((1, -1)),
            _ => None,
        }
    }

    fn body1_at_rest(self, variant: Variant) -> bool {
        self == RoughIdentity::EnergyLoss && variant == Variant::Fixed
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
        law: RestitutionInputs,
        variant: Variant,
        states: &HashMap<&str, [StateIds; 2]>,
    ) -> Vec<Id> {
        let before = id::before(inputs);
        let after = &states["after"];
        let n = inputs.nu.len();
        let split = |g: &mut Graph, s: &[StateIds; 2]| {
            let slip = id::slip(g, inputs, s);
            let dn = g.dot(&slip, &inputs.nu);
            let t: Vec<Id> = (0..n)
                .map(|k| {
                    let x = g.mul(dn, inputs.nu[k]);
                    g.sub(slip[k], x)
                })
                .collect();
            (dn, t)
        };
        match self {
            RoughIdentity::NormalLaw => {
                let (dn0, _) = split(g, &before);
                let (dn1, _) = split(g, after);
                let x = g.mul(law.e, dn0);
                vec![g.add(dn1, x)]
            }
            RoughIdentity::TangentialLaw => {
                let (_, t0) = split(g, &before);
                let (_, t1) = split(g, after);
                (0..n)
                    .map(|k| {
                        let x = g.mul(law.beta, t0[k]);
                        g.add(t1[k], x)
                    })
                    .collect()
            }
            RoughIdentity::EnergyLoss => {
                let movable = Self::movable(variant);
                let e0 = id::energy(g, inputs, &before, movable);
                let e1 = id::energy(g, inputs, after, movable);
                let twice_delta = g.sub(e1, e0);
                let (dn, t) = split(g, &before);
                let [b1, b2] = &inputs.bodies;
                let a = g.add(b1.inv_mass, b2.inv_mass);
                let k1 = g.div(b1.inv_mass, b1.gamma2);
                let k2 = g.div(b2.inv_mass, b2.gamma2);
                let b = g.sum(vec![a, k1, k2]);
                let one = g.int(1);
                let loss = |g: &mut Graph, r: Id, sq: Id, inv_mass: Id| {
                    let r2 = g.mul(r, r);
                    let f = g.sub(one, r2);
                    let x = g.mul(f, sq);
                    g.div(x, inv_mass)
                };
                let dn2 = g.mul(dn, dn);
                let t2 = g.dot(&t, &t);
                let normal = loss(g, law.e, dn2, a);
                let tangential = loss(g, law.beta, t2, b);
                let total = g.add(normal, tangential);
                vec![g.add(twice_delta, total)]
            }
            RoughIdentity::LinearMomentum => id::momentum_conserved(g, inputs, &before, after),
            RoughIdentity::AngularMomentum => {
                id::angular_momentum_conserved(g, inputs, &before, after, Self::movable(variant))
            }
            RoughIdentity::NoSlipMember => id::equal(g, after, &states["no_slip"]),
            RoughIdentity::SmoothMember => {
                let smooth = smooth_map(g, inputs);
                id::equal(g, after, &smooth)
            }
            RoughIdentity::MassLimit => id::equal(g, after, &states["free_w1_0"]),
        }
    }

    fn input_variant(self, variant: Variant) -> Variant {
        if self == RoughIdentity::MassLimit {
            Variant::Free
        } else {
            variant
        }
    }
}

/// The smooth map from its definition (`sim/src/smooth.rs`): `dn = (u_2 - u_1) . nu`,
/// `u_1+ = u_1 + 2 w_1 dn / (w_1 + w_2) nu`, `u_2+ = u_2 - 2 w_2 dn / (w_1 + w_2) nu`, spins
/// unchanged.
fn smooth_map(g: &mut Graph, inputs: &KernelInputs) -> [StateIds; 2] {
    let n = inputs.nu.len();
    let [b1, b2] = &inputs.bodies;
    let du: Vec<Id> = (0..n)
        .map(|k| g.sub(b2.velocity[k], b1.velocity[k]))
        .collect();
    let dn = g.dot(&du, &inputs.nu);
    let w = g.add(b1.inv_mass, b2.inv_mass);
    let two = g.int(2);
    let j = g.mul(two, dn);
    let j = g.div(j, w);
    let body = |g: &mut Graph, b: &noslip_codegen::model::BodyInputs, sign: i64| {
        let jb = g.mul(b.inv_mass, j);
        StateIds {
            spin: b.spin.clone(),
            velocity: (0..n)
                .map(|k| {
                    let x = g.mul(jb, inputs.nu[k]);
                    if sign > 0 {
                        g.add(b.velocity[k], x)
                    } else {
                        g.sub(b.velocity[k], x)
                    }
                })
                .collect(),
        }
    };
    [body(g, b1, 1), body(g, b2, -1)]
}

fn law_inputs(g: &mut Graph, identity: RoughIdentity) -> RestitutionInputs {
    match identity.law() {
        Some((e, beta)) => RestitutionInputs {
            e: g.int(e),
            beta: g.int(beta),
        },
        None => RestitutionInputs::symbolic(g),
    }
}

fn inputs_for(g: &mut Graph, n: usize, identity: RoughIdentity, variant: Variant) -> KernelInputs {
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

fn as_states(inputs: &KernelInputs, outs: Vec<BodyOutput>) -> [StateIds; 2] {
    let mut s = id::before(inputs);
    for o in outs {
        s[o.body - 1] = StateIds {
            spin: o.spin,
            velocity: o.velocity,
        };
    }
    s
}

/// The degree of `identity` for dimension `n` and `variant`, on the symbolic kernel.
pub fn degree(n: usize, variant: Variant, identity: RoughIdentity) -> u64 {
    let mut g = Graph::new();
    let inputs = inputs_for(&mut g, n, identity, variant);
    // `e` and `beta` stay variables even where the identity fixes them: the kernel's degree
    // at fixed values is at most its degree as a function of them, and with constants the
    // DAG would fold the rough map at (1, 1) into the no-slip one and report degree 0 for a
    // comparison the compiled code must still pass.
    let law = RestitutionInputs::symbolic(&mut g);
    let mut states = HashMap::new();
    let kernel_inputs = if identity == RoughIdentity::MassLimit {
        symbolic_inputs(&mut g, n, Variant::Fixed)
    } else {
        inputs.clone()
    };
    let after = as_states(
        &kernel_inputs,
        build_rough_on(&mut g, &kernel_inputs, variant, law),
    );
    match identity {
        RoughIdentity::NoSlipMember => {
            let no_slip = as_states(&inputs, build_on(&mut g, &inputs, variant));
            states.insert("no_slip", no_slip);
        }
        RoughIdentity::MassLimit => {
            let mut free = inputs.clone();
            free.bodies[0].inv_mass = g.int(0);
            let out = build_rough_on(&mut g, &free, Variant::Free, law);
            states.insert("free_w1_0", as_states(&free, out));
        }
        _ => {}
    }
    states.insert("after", after);
    let zeros = identity.zeros(&mut g, &inputs, law, variant, &states);
    crate::degree::identity_degree(&g, &zeros)
}

/// The compiled rough kernel of `variant` in exact rationals (relaxed, reduced at the end);
/// body 1 comes back unchanged for [`Variant::Fixed`].
fn rough<const N: usize, const S: usize>(
    variant: Variant,
    p: &Point<N, S>,
    law: &Restitution<Exact>,
) -> [BodyState<Exact, N, S>; 2]
where
    Generated: RoughKernel<ExactRelaxed, N, S>,
{
    let (b, s) = (&p.balls, &p.states);
    match variant {
        Variant::Free => Relaxing::rough_free(&p.nu, &b[0], &b[1], law, &s[0], &s[1]),
        Variant::Fixed => [
            s[0].clone(),
            Relaxing::rough_fixed(&p.nu, &b[0].radius, &b[1], law, &s[0], &s[1]),
        ],
    }
}

/// Evaluate `identity` at one point; `Err` names what failed.
pub fn check_at<const N: usize, const S: usize>(
    variant: Variant,
    identity: RoughIdentity,
    p: &Point<N, S>,
    law: &Restitution<Exact>,
) -> Result<(), String>
where
    Generated: RoughKernel<ExactRelaxed, N, S> + Kernel<ExactRelaxed, N, S>,
{
    let mut p = p.clone();
    if identity.body1_at_rest(variant) {
        p.states[0] = BodyState::zero();
    }
    let mut g = Graph::new();
    let inputs = inputs_for(&mut g, N, identity, variant);
    let law_ids = law_inputs(&mut g, identity);
    let mut values = input_values(
        &p.nu,
        [&p.balls[0], &p.balls[1]],
        [&p.states[0], &p.states[1]],
    );
    values.insert(names::restitution_e(), law.e.clone());
    values.insert(names::restitution_beta(), law.beta.clone());
    let mut named: HashMap<&str, [StateIds; 2]> = HashMap::new();
    let mut record = |g: &mut Graph, name: &'static str, s: [BodyState<Exact, N, S>; 2]| {
        let ids = id::named_state(g, N, name);
        for b in 0..2 {
            let pairs = ids[b].spin.iter().zip(&s[b].spin);
            for (i, x) in pairs.chain(ids[b].velocity.iter().zip(&s[b].velocity)) {
                let Node::Input(input) = g.node(*i) else {
                    unreachable!("named states are inputs")
                };
                values.insert(input.0.clone(), x.clone());
            }
        }
        named.insert(name, ids);
    };
    let after = rough(variant, &p, law);
    match identity {
        RoughIdentity::NoSlipMember => {
            let (b, s) = (&p.balls, &p.states);
            let no_slip = match variant {
                Variant::Free => Relaxing::free(&p.nu, &b[0], &b[1], &s[0], &s[1]),
                Variant::Fixed => [
                    s[0].clone(),
                    Relaxing::fixed(&p.nu, &b[0].radius, &b[1], &s[0], &s[1]),
                ],
            };
            record(&mut g, "no_slip", no_slip);
        }
        RoughIdentity::MassLimit => {
            let mut free = p.clone();
            free.balls[0].inv_mass = Exact::zero();
            record(&mut g, "free_w1_0", rough(Variant::Free, &free, law));
        }
        _ => {}
    }
    record(&mut g, "after", after);
    let zeros = identity.zeros(&mut g, &inputs, law_ids, variant, &named);
    let v = g.eval_all(&|name| values.get(name).cloned(), &|_, _, _| None)?;
    match zeros.iter().position(|z| !v[z.0 as usize].is_zero()) {
        None => Ok(()),
        Some(k) => Err(format!(
            "component {k} of the identity is {} at the sample point, not 0",
            v[zeros[k].0 as usize]
        )),
    }
}

/// Run `identity` at `points` random points (`e`, `beta` drawn like every other input unless
/// the identity fixes them); returns the first failure. `interrupted` is asked before each
/// point: once it says stop the check fails at once ("interrupted at point k").
pub fn run<const N: usize, const S: usize>(
    variant: Variant,
    identity: RoughIdentity,
    points: usize,
    seed: u64,
    interrupted: &dyn Fn() -> bool,
) -> Result<(), String>
where
    Generated: RoughKernel<ExactRelaxed, N, S> + Kernel<ExactRelaxed, N, S>,
{
    let mut rng = Rng::new(seed);
    for k in 0..points {
        if interrupted() {
            return Err(format!("interrupted at point {k}"));
        }
        let p = point::<N, S>(&mut rng, variant == Variant::Fixed);
        let (e, beta) = (element(&mut rng), element(&mut rng));
        let law = match identity.law() {
            Some((e, beta)) => Restitution {
                e: Exact::from_integer(e),
                beta: Exact::from_integer(beta),
            },
            None => Restitution { e, beta },
        };
        check_at(variant, identity, &p, &law).map_err(|e| format!("point {k}: {e}"))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn all_pass<const N: usize, const S: usize>()
    where
        Generated: RoughKernel<ExactRelaxed, N, S> + Kernel<ExactRelaxed, N, S>,
    {
        for variant in Variant::ALL {
            for &identity in RoughIdentity::for_variant(variant) {
                run::<N, S>(variant, identity, 2, 11, &|| false)
                    .unwrap_or_else(|e| panic!("n = {N} {variant:?} {identity:?}: {e}"));
                let d = degree(N, variant, identity);
                assert!(d > 0 && d < 100_000, "degree {d}");
            }
        }
    }

    #[test]
    fn the_rough_kernels_satisfy_every_identity() {
        all_pass::<2, 1>();
        all_pass::<3, 3>();
    }

    /// The checks can fail: a law that is not the kernel's (the point's `e` and `beta`
    /// swapped when the identities are evaluated) breaks the law and the energy loss.
    #[test]
    fn a_wrong_law_fails_the_law_and_energy_checks() {
        let mut rng = Rng::new(5);
        let p = point::<3, 3>(&mut rng, false);
        let law = Restitution {
            e: element(&mut rng),
            beta: element(&mut rng),
        };
        for identity in [
            RoughIdentity::NormalLaw,
            RoughIdentity::TangentialLaw,
            RoughIdentity::EnergyLoss,
        ] {
            assert!(check_at(Variant::Free, identity, &p, &law).is_ok());
            let mut g = Graph::new();
            let inputs = inputs_for(&mut g, 3, identity, Variant::Free);
            let law_ids = RestitutionInputs::symbolic(&mut g);
            let mut values = input_values(
                &p.nu,
                [&p.balls[0], &p.balls[1]],
                [&p.states[0], &p.states[1]],
            );
            // The kernel ran with (e, beta); the identity is told (beta, e).
            values.insert(names::restitution_e(), law.beta.clone());
            values.insert(names::restitution_beta(), law.e.clone());
            let ids = id::named_state(&mut g, 3, "after");
            let after = rough(Variant::Free, &p, &law);
            for b in 0..2 {
                let pairs = ids[b].spin.iter().zip(&after[b].spin);
                for (i, x) in pairs.chain(ids[b].velocity.iter().zip(&after[b].velocity)) {
                    let Node::Input(input) = g.node(*i) else {
                        unreachable!()
                    };
                    values.insert(input.0.clone(), x.clone());
                }
            }
            let states = HashMap::from([("after", ids)]);
            let zeros = identity.zeros(&mut g, &inputs, law_ids, Variant::Free, &states);
            let v = g
                .eval_all(&|name| values.get(name).cloned(), &|_, _, _| None)
                .unwrap();
            assert!(
                zeros.iter().any(|z| !v[z.0 as usize].is_zero()),
                "{identity:?} passed with the wrong law"
            );
        }
    }
}
