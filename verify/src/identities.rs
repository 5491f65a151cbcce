//! The identities the verifier checks, built once as nodes of the generator's expression
//! DAG from the definitions (metric, momenta, contact-point velocities), never from the
//! kernel's formula. Each builder returns nodes that must all be zero.
//!
//! The same builder serves twice: with the compiled kernel's exact outputs as fresh inputs
//! (the check itself, evaluated at sample points), and with the symbolic kernel outputs
//! (to bound the degree of the identity for the Schwartz-Zippel bound).

use noslip_codegen::ir::{Graph, Id};
use noslip_codegen::model::{skew_pairs, skew_times, wedge, BodyInputs, KernelInputs};

/// A body's velocity state as DAG nodes.
#[derive(Clone, Debug)]
pub struct StateIds {
    /// Compact skew entries of `U`, in `skew_pairs` order.
    pub spin: Vec<Id>,
    /// Centre velocity `u`, one node per component.
    pub velocity: Vec<Id>,
}

impl From<&BodyInputs> for StateIds {
    fn from(b: &BodyInputs) -> Self {
        StateIds {
            spin: b.spin.clone(),
            velocity: b.velocity.clone(),
        }
    }
}

/// The states before the collision: the kernel inputs' `U` and `u` of bodies 1 and 2.
pub fn before(inputs: &KernelInputs) -> [StateIds; 2] {
    [(&inputs.bodies[0]).into(), (&inputs.bodies[1]).into()]
}

/// Fresh named inputs standing for a computed state (`{stem}{body}_...`).
pub fn named_state(g: &mut Graph, n: usize, stem: &str) -> [StateIds; 2] {
    [1, 2].map(|b| StateIds {
        spin: skew_pairs(n)
            .into_iter()
            .map(|(i, j)| g.input(format!("{stem}{b}_U_{i}{j}")))
            .collect(),
        velocity: (0..n)
            .map(|k| g.input(format!("{stem}{b}_u_{k}")))
            .collect(),
    })
}

fn diff(g: &mut Graph, a: &[Id], b: &[Id]) -> Vec<Id> {
    a.iter().zip(b).map(|(&x, &y)| g.sub(x, y)).collect()
}

/// `a == b` componentwise.
pub fn equal(g: &mut Graph, a: &[StateIds; 2], b: &[StateIds; 2]) -> Vec<Id> {
    (0..2)
        .flat_map(|i| {
            let mut d = diff(g, &a[i].spin, &b[i].spin);
            d.extend(diff(g, &a[i].velocity, &b[i].velocity));
            d
        })
        .collect()
}

/// Contact-point velocities `V_1(Q) = R_1 U_1 nu + u_1`, `V_2(Q) = -R_2 U_2 nu + u_2`;
/// returns `V_2(Q) - V_1(Q)`.
pub fn slip(g: &mut Graph, inputs: &KernelInputs, s: &[StateIds; 2]) -> Vec<Id> {
    let n = inputs.nu.len();
    let [b1, b2] = &inputs.bodies;
    let u1nu = skew_times(g, n, &s[0].spin, &inputs.nu);
    let u2nu = skew_times(g, n, &s[1].spin, &inputs.nu);
    (0..n)
        .map(|k| {
            let r1 = g.mul(b1.radius, u1nu[k]);
            let v1 = g.add(r1, s[0].velocity[k]);
            let r2 = g.mul(b2.radius, u2nu[k]);
            let v2 = g.sub(s[1].velocity[k], r2);
            g.sub(v2, v1)
        })
        .collect()
}

/// The reflection across `G_q` in the kinetic metric, characterised without the kernel:
/// (b) `xi + xi+` slips not at all (it lies in `G_q`), and (a) `xi+ - xi` lies in `E_q`:
/// `R_1 g_1 dU_1 = nu ^ du_1`, `R_2 g_2 dU_2 = -nu ^ du_2` (the angular change an impulse
/// causes) and `w_2 du_1 + w_1 du_2 = 0` (equal and opposite impulses). With
/// `G_q (+) E_q = T_q M` these determine `xi+` uniquely.
pub fn reflection(
    g: &mut Graph,
    inputs: &KernelInputs,
    before: &[StateIds; 2],
    after: &[StateIds; 2],
    fixed: bool,
) -> Vec<Id> {
    let n = inputs.nu.len();
    let sum: Vec<StateIds> = (0..2)
        .map(|i| StateIds {
            spin: before[i]
                .spin
                .iter()
                .zip(&after[i].spin)
                .map(|(&a, &b)| g.add(a, b))
                .collect(),
            velocity: before[i]
                .velocity
                .iter()
                .zip(&after[i].velocity)
                .map(|(&a, &b)| g.add(a, b))
                .collect(),
        })
        .collect();
    let mut zero = slip(g, inputs, &[sum[0].clone(), sum[1].clone()]);
    let delta: Vec<StateIds> = (0..2)
        .map(|i| StateIds {
            spin: diff(g, &after[i].spin, &before[i].spin),
            velocity: diff(g, &after[i].velocity, &before[i].velocity),
        })
        .collect();
    for (i, body) in inputs.bodies.iter().enumerate() {
        if fixed && i == 0 {
            // The immovable body does not change at all.
            zero.extend(delta[0].spin.iter().chain(&delta[0].velocity).copied());
            continue;
        }
        let rg = g.mul(body.radius, body.gamma2);
        let nu_du = wedge(g, n, &inputs.nu, &delta[i].velocity);
        for (&du, &x) in delta[i].spin.iter().zip(&nu_du) {
            let lhs = g.mul(rg, du);
            zero.push(if i == 0 { g.sub(lhs, x) } else { g.add(lhs, x) });
        }
    }
    if !fixed {
        let [b1, b2] = &inputs.bodies;
        for k in 0..n {
            let x = g.mul(b2.inv_mass, delta[0].velocity[k]);
            let y = g.mul(b1.inv_mass, delta[1].velocity[k]);
            zero.push(g.add(x, y));
        }
    }
    zero
}

/// Twice the kinetic energy of the movable bodies: `sum_i m_i [g_i R_i^2 |U_i|^2 + |u_i|^2]`
/// (`2 lambda = g R^2`; `Tr(U U^T) = 2 sum_{i<j} U_ij^2`), `m_i = 1 / w_i`.
pub fn energy(g: &mut Graph, inputs: &KernelInputs, s: &[StateIds; 2], bodies: &[usize]) -> Id {
    let one = g.int(1);
    let terms: Vec<Id> = bodies
        .iter()
        .map(|&i| {
            let b = &inputs.bodies[i];
            let spin2 = g.dot(&s[i].spin, &s[i].spin);
            let vel2 = g.dot(&s[i].velocity, &s[i].velocity);
            let r2 = g.mul(b.radius, b.radius);
            let inertia = g.mul(b.gamma2, r2);
            let rot = g.mul(inertia, spin2);
            let total = g.add(rot, vel2);
            let m = g.div(one, b.inv_mass);
            g.mul(m, total)
        })
        .collect();
    g.sum(terms)
}

/// `2 (E_after - E_before)` over the movable `bodies` (0-based): zero iff the kinetic energy
/// is kept.
pub fn energy_conserved(
    g: &mut Graph,
    inputs: &KernelInputs,
    before: &[StateIds; 2],
    after: &[StateIds; 2],
    bodies: &[usize],
) -> Vec<Id> {
    let e0 = energy(g, inputs, before, bodies);
    let e1 = energy(g, inputs, after, bodies);
    vec![g.sub(e1, e0)]
}

/// `m_1 u_1 + m_2 u_2` conserved.
pub fn momentum_conserved(
    g: &mut Graph,
    inputs: &KernelInputs,
    before: &[StateIds; 2],
    after: &[StateIds; 2],
) -> Vec<Id> {
    let n = inputs.nu.len();
    let one = g.int(1);
    let m: Vec<Id> = inputs
        .bodies
        .iter()
        .map(|b| g.div(one, b.inv_mass))
        .collect();
    (0..n)
        .map(|k| {
            let p = |g: &mut Graph, s: &[StateIds; 2]| {
                let x = g.mul(m[0], s[0].velocity[k]);
                let y = g.mul(m[1], s[1].velocity[k]);
                g.add(x, y)
            };
            let (p1, p0) = (p(g, after), p(g, before));
            g.sub(p1, p0)
        })
        .collect()
}

/// Body `i`'s angular momentum about the contact point, `m (r ^ u) + m g R^2 U` with
/// `r = a - Q` (`-R_1 nu`, `R_2 nu`), conserved for each body in `bodies`.
pub fn angular_momentum_conserved(
    g: &mut Graph,
    inputs: &KernelInputs,
    before: &[StateIds; 2],
    after: &[StateIds; 2],
    bodies: &[usize],
) -> Vec<Id> {
    let n = inputs.nu.len();
    let one = g.int(1);
    let mut zero = Vec::new();
    for &i in bodies {
        let b = &inputs.bodies[i];
        let m = g.div(one, b.inv_mass);
        let r: Vec<Id> = inputs
            .nu
            .iter()
            .map(|&x| {
                let y = g.mul(b.radius, x);
                if i == 0 {
                    g.neg(y)
                } else {
                    y
                }
            })
            .collect();
        let r2 = g.mul(b.radius, b.radius);
        let inertia = g.mul(b.gamma2, r2);
        let l = |g: &mut Graph, s: &StateIds| -> Vec<Id> {
            let ru = wedge(g, n, &r, &s.velocity);
            ru.iter()
                .zip(&s.spin)
                .map(|(&x, &u)| {
                    let a = g.mul(m, x);
                    let spin = g.mul(inertia, u);
                    let c = g.mul(m, spin);
                    g.add(a, c)
                })
                .collect()
        };
        let (l1, l0) = (l(g, &after[i]), l(g, &before[i]));
        zero.extend(diff(g, &l1, &l0));
    }
    zero
}

/// The point-mass limit of body 1 (docs/derivation.md §10) (`lambda_1 -> 0`): `P_t -> 0`, so the centre
/// velocities change only along `nu`, by `-+2 w_i dn / (w_1 + w_2) nu`;
/// `U_1+ = U_1 + (2/R_1) nu ^ t`; `U_2+ = U_2`.
pub fn point_mass_limit(g: &mut Graph, inputs: &KernelInputs) -> [StateIds; 2] {
    let n = inputs.nu.len();
    let nu = &inputs.nu;
    let [b1, b2] = &inputs.bodies;
    let s = before(inputs);
    let du = diff(g, &b2.velocity, &b1.velocity);
    let dn = g.dot(&du, nu);
    let slip = slip(g, inputs, &s);
    // t = V_2(Q) - V_1(Q) minus its normal part, which is dn nu.
    let t: Vec<Id> = (0..n)
        .map(|k| {
            let x = g.mul(dn, nu[k]);
            g.sub(slip[k], x)
        })
        .collect();
    let two = g.int(2);
    let ws = g.add(b1.inv_mass, b2.inv_mass);
    let nu_t = wedge(g, n, nu, &t);
    let coef = g.div(two, b1.radius);
    let spin1 = b1
        .spin
        .iter()
        .zip(&nu_t)
        .map(|(&u, &x)| {
            let d = g.mul(coef, x);
            g.add(u, d)
        })
        .collect();
    let mut velocity = |b: &BodyInputs, sign: bool| -> Vec<Id> {
        let num = g.mul(two, b.inv_mass);
        let num = g.mul(num, dn);
        let c = g.div(num, ws);
        b.velocity
            .iter()
            .zip(nu)
            .map(|(&u, &x)| {
                let d = g.mul(c, x);
                if sign {
                    g.add(u, d)
                } else {
                    g.sub(u, d)
                }
            })
            .collect()
    };
    let v1 = velocity(b1, true);
    let v2 = velocity(b2, false);
    [
        StateIds {
            spin: spin1,
            velocity: v1,
        },
        StateIds {
            spin: b2.spin.clone(),
            velocity: v2,
        },
    ]
}
