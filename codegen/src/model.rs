//! The no-slip collision map of two balls in R^n, built component-wise from the general
//! SO(n) formulas (see `docs/derivation.md`).
//!
//! With inverse masses `w_i`, radii `R_i`, `gamma_i^2 = 2 lambda_i / R_i^2` (written `g_i`),
//! unit normal `nu` from body 1 to body 2, angular velocities `U_i` (skew) and centre
//! velocities `u_i`:
//!
//! ```text
#![doc = include_str!("closed_form/free.txt")]
//! ```
//!
//! This is the closed form of `docs/derivation.md` §7 with `k_i = w_i / g_i` and the tangential denominator
//! `w_1 + w_2 + k_1 + k_2` multiplied through by `g_1 g_2`, and `nu ^ P = nu ^ P_t`
//! (`nu ^ nu = 0`). Every term of `D` is non-negative, and every coefficient stays finite
//! for an immovable body (`w_i = 0`) and for one point mass (`g_i = 0`).
//!
//! The immovable variant (body 1 immovable) is the same builder with `w_1 = 0`; the map is
//! homogeneous of degree 0 in `(w_1, w_2)`, so `w_2 = 1`, and with `w_1 = 0` it does not
//! depend on `g_1`, so `g_1 = 1`. Constant folding then leaves the reduced kernel; the
//! verifier checks exactly that it is the `w_1 -> 0` limit of the free map:
//!
//! ```text
#![doc = include_str!("closed_form/fixed.txt")]
//! ```
//!
//! These two text blocks ([`CLOSED_FORM_FREE`], [`CLOSED_FORM_FIXED`]) are written once, in
//! `codegen/src/closed_form/`; the generated kernels' doc comments are made from them.
//!
//! The rough-ball family ([`Law::Rough`], `docs/derivation.md` §15) is the same builder with
//! the normal part of `P` scaled by `h_n = (1 + e)/2` and its tangential part (and so the
//! angular updates) by `h_t = (1 + beta)/2`, `e` and `beta` two more kernel inputs
//! ([`CLOSED_FORM_ROUGH_FREE`], [`CLOSED_FORM_ROUGH_FIXED`]). At `(e, beta) = (1, 1)` both
//! factors are exactly 1, so the rough kernel computes the no-slip kernel's operations plus
//! multiplications by 1: the same values, bit for bit, in floats too (plain arithmetic; of
//! the FMA forms only `free`, since the no-slip `fixed` shares `nu_k dn` with the slip and so
//! cannot fuse it into `P`, while the rough one fuses `nu_k (h_n dn)`).

use crate::ir::{Graph, Id};
use crate::unbiased;

/// The free map as the kernels' docs state it (a text block, one formula a line).
pub const CLOSED_FORM_FREE: &str = include_str!("closed_form/free.txt");

/// The `fixed` map (body 1 immovable: `w_1 = 0`, `w_2 = 1`, `g_1 = 1`), likewise.
pub const CLOSED_FORM_FIXED: &str = include_str!("closed_form/fixed.txt");

/// The rough-ball free map (`docs/derivation.md` §15), likewise.
pub const CLOSED_FORM_ROUGH_FREE: &str = include_str!("closed_form/rough_free.txt");

/// The rough-ball `fixed` map, likewise.
pub const CLOSED_FORM_ROUGH_FIXED: &str = include_str!("closed_form/rough_fixed.txt");

/// The Walton free map as the kernels' docs state it (a text block).
pub const CLOSED_FORM_WALTON_FREE: &str = include_str!("closed_form/walton_free.txt");

/// The Walton `fixed` map (body 1 immovable), likewise.
pub const CLOSED_FORM_WALTON_FIXED: &str = include_str!("closed_form/walton_fixed.txt");

/// The contact law a kernel implements.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Law {
    /// The no-slip map: the metric reflection across `G_q` (`kernels::dN::free`, ...).
    NoSlip,
    /// The rough-ball family with run-time normal and tangential restitution `(e, beta)`:
    /// `dn+ = -e dn`, `t+ = -beta t` (`kernels::dN::rough::free`, ...).
    Rough,
    /// The Walton law with run-time `(e, mu, beta0)`: the rough law with
    /// `beta = min(beta0, beta_Coulomb)` (`kernels::dN::walton::free`, ...; [`crate::walton`]).
    Walton,
}

impl Law {
    /// The closed form of `variant` under this law, as the kernels' docs state it.
    pub fn closed_form(self, variant: Variant) -> &'static str {
        match (self, variant) {
            (Law::NoSlip, Variant::Free) => CLOSED_FORM_FREE,
            (Law::NoSlip, Variant::Fixed) => CLOSED_FORM_FIXED,
            (Law::Rough, Variant::Free) => CLOSED_FORM_ROUGH_FREE,
            (Law::Rough, Variant::Fixed) => CLOSED_FORM_ROUGH_FIXED,
            (Law::Walton, Variant::Free) => CLOSED_FORM_WALTON_FREE,
            (Law::Walton, Variant::Fixed) => CLOSED_FORM_WALTON_FIXED,
        }
    }
}

/// The DAG nodes of the rough law's parameters: the normal restitution `e` in `[0, 1]` and
/// the tangential restitution `beta` in `[-1, 1]` (inputs, or constants where a caller
/// fixes them).
#[derive(Clone, Copy, Debug)]
pub struct RestitutionInputs {
    /// `e`: `dn+ = -e dn`.
    pub e: Id,
    /// `beta`: `t+ = -beta t`.
    pub beta: Id,
}

impl RestitutionInputs {
    /// The named inputs `e` and `beta`.
    pub fn symbolic(g: &mut Graph) -> Self {
        RestitutionInputs {
            e: g.input(names::restitution_e()),
            beta: g.input(names::restitution_beta()),
        }
    }
}

/// Which bodies can move.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Variant {
    /// Both bodies free: `[body1+, body2+] = free(nu, ball1, ball2, state1, state2)`.
    Free,
    /// Body 1 immovable (infinite mass): `body2+ = fixed(nu, radius1, ball2, state1, state2)`.
    Fixed,
}

impl Variant {
    /// Both, in emission order.
    pub const ALL: [Variant; 2] = [Variant::Free, Variant::Fixed];

    /// The kernel's function name.
    pub fn name(self) -> &'static str {
        match self {
            Variant::Free => "free",
            Variant::Fixed => "fixed",
        }
    }
}

/// The index pairs `(i, j)`, `i < j`, of the independent entries of a skew n x n matrix, in
/// the order of the compact storage: `(0,1), (0,2), .., (0,n-1), (1,2), ..`.
pub fn skew_pairs(n: usize) -> Vec<(usize, usize)> {
    (0..n)
        .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
        .collect()
}

/// Binding names of the kernel inputs. Body numbers are 1 and 2, as in the math.
pub mod names {
    /// `nu_k`: component `k` of the contact normal `nu`.
    pub fn nu(k: usize) -> String {
        format!("nu_{k}")
    }
    /// `U{body}_{i}{j}`: entry `(i, j)`, `i < j`, of the body's skew angular velocity `U`.
    pub fn spin(body: usize, i: usize, j: usize) -> String {
        format!("U{body}_{i}{j}")
    }
    /// `u{body}_{k}`: component `k` of the body's centre velocity `u`.
    pub fn velocity(body: usize, k: usize) -> String {
        format!("u{body}_{k}")
    }
    /// `radius{body}`: the body's radius `R`.
    pub fn radius(body: usize) -> String {
        format!("radius{body}")
    }
    /// `inv_mass{body}`: the body's inverse mass `w = 1/m`.
    pub fn inv_mass(body: usize) -> String {
        format!("inv_mass{body}")
    }
    /// `gamma2_{body}`: the body's `gamma^2 = 2 lambda / R^2`.
    pub fn gamma2(body: usize) -> String {
        format!("gamma2_{body}")
    }
    /// `e`: the normal restitution of the rough law.
    pub fn restitution_e() -> String {
        "e".into()
    }
    /// `beta`: the tangential restitution of the rough law.
    pub fn restitution_beta() -> String {
        "beta".into()
    }
    /// `mu`: the friction coefficient of the Walton law.
    pub fn friction_mu() -> String {
        "mu".into()
    }
    /// `beta0`: the Walton law's tangential restitution while sticking.
    pub fn walton_beta0() -> String {
        "beta0".into()
    }
}

/// One body's post-collision state as DAG nodes.
#[derive(Debug)]
pub struct BodyOutput {
    /// 1 or 2.
    pub body: usize,
    /// Compact skew entries, in [`skew_pairs`] order.
    pub spin: Vec<Id>,
    /// Centre velocity `u+`, one node per component.
    pub velocity: Vec<Id>,
}

/// A built kernel: its DAG and the nodes of its outputs.
#[derive(Debug)]
pub struct KernelGraph {
    /// The dimension `n`.
    pub dim: usize,
    /// Which bodies move.
    pub variant: Variant,
    /// The contact law.
    pub law: Law,
    /// The DAG, holding the inputs, every intermediate and the outputs.
    pub graph: Graph,
    /// The bodies the kernel returns: both for [`Variant::Free`], body 2 for [`Variant::Fixed`].
    pub outputs: Vec<BodyOutput>,
}

/// The DAG nodes of one body's inputs.
#[derive(Clone, Debug)]
pub struct BodyInputs {
    /// Compact skew entries of `U`, in [`skew_pairs`] order.
    pub spin: Vec<Id>,
    /// Centre velocity `u`, one node per component.
    pub velocity: Vec<Id>,
    /// Radius `R`.
    pub radius: Id,
    /// Inverse mass `w = 1/m`: an input, or a constant where it is known (`fixed`,
    /// specialised).
    pub inv_mass: Id,
    /// `gamma^2 = 2 lambda / R^2`: an input, or a constant where it is known (`fixed`,
    /// specialised).
    pub gamma2: Id,
}

/// The DAG nodes of a kernel's inputs: the normal and both bodies.
#[derive(Clone, Debug)]
pub struct KernelInputs {
    /// The unit contact normal `nu`, from body 1 to body 2, one node per component.
    pub nu: Vec<Id>,
    /// Body 1 and body 2.
    pub bodies: [BodyInputs; 2],
}

fn body_inputs(g: &mut Graph, n: usize, b: usize, variant: Variant) -> BodyInputs {
    let spin = skew_pairs(n)
        .into_iter()
        .map(|(i, j)| g.input(names::spin(b, i, j)))
        .collect();
    let velocity = (0..n).map(|k| g.input(names::velocity(b, k))).collect();
    let radius = g.input(names::radius(b));
    let (inv_mass, gamma2) = match (variant, b) {
        // Immovable body 1: w_1 = 0, then w_2 = 1 and g_1 = 1 (see the module docs).
        (Variant::Fixed, 1) => (g.int(0), g.int(1)),
        (Variant::Fixed, _) => (g.int(1), g.input(names::gamma2(b))),
        (Variant::Free, _) => (g.input(names::inv_mass(b)), g.input(names::gamma2(b))),
    };
    BodyInputs {
        spin,
        velocity,
        radius,
        inv_mass,
        gamma2,
    }
}

/// The named inputs of a kernel (`nu_k`, `U1_ij`, `u1_k`, `radius1`, ...), with the
/// constants of the variant in place of the parameters it does not take.
pub fn symbolic_inputs(g: &mut Graph, n: usize, variant: Variant) -> KernelInputs {
    let nu = (0..n).map(|k| g.input(names::nu(k))).collect();
    let b1 = body_inputs(g, n, 1, variant);
    let b2 = body_inputs(g, n, 2, variant);
    KernelInputs {
        nu,
        bodies: [b1, b2],
    }
}

/// `U v` for a skew `U` in compact storage: `(U v)_i = sum_{j>i} U_ij v_j - sum_{j<i} U_ji v_j`
/// (`U_ji = -U_ij`); the positive terms first, so that the negative ones become subtractions.
pub fn skew_times(g: &mut Graph, n: usize, spin: &[Id], v: &[Id]) -> Vec<Id> {
    let pairs = skew_pairs(n);
    (0..n)
        .map(|i| {
            let mut terms = Vec::new();
            for (&(p, q), &u) in pairs.iter().zip(spin) {
                if p == i {
                    terms.push(g.mul(u, v[q]));
                }
            }
            for (&(p, q), &u) in pairs.iter().zip(spin) {
                if q == i {
                    let x = g.mul(u, v[p]);
                    terms.push(g.neg(x));
                }
            }
            g.sum(terms)
        })
        .collect()
}

/// `a ^ b = b a^T - a b^T` in compact storage: `(a ^ b)_ij = b_i a_j - a_i b_j`.
pub fn wedge(g: &mut Graph, n: usize, a: &[Id], b: &[Id]) -> Vec<Id> {
    skew_pairs(n)
        .into_iter()
        .map(|(i, j)| {
            let x = g.mul(b[i], a[j]);
            let y = g.mul(a[i], b[j]);
            g.sub(x, y)
        })
        .collect()
}

fn label_all(g: &mut Graph, ids: &[Id], stem: &str) {
    for (k, &id) in ids.iter().enumerate() {
        g.label(id, format!("{stem}_{k}"));
    }
}

/// Build the collision kernel for dimension `n >= 2`.
pub fn build(n: usize, variant: Variant) -> KernelGraph {
    let mut graph = Graph::new();
    let inputs = symbolic_inputs(&mut graph, n, variant);
    let outputs = build_on(&mut graph, &inputs, variant);
    KernelGraph {
        dim: n,
        variant,
        law: Law::NoSlip,
        graph,
        outputs,
    }
}

/// Build the rough-ball kernel (run-time `e`, `beta`) for dimension `n >= 2`.
pub fn build_rough(n: usize, variant: Variant) -> KernelGraph {
    let mut graph = Graph::new();
    let inputs = symbolic_inputs(&mut graph, n, variant);
    let law = RestitutionInputs::symbolic(&mut graph);
    let outputs = build_rough_on(&mut graph, &inputs, variant, law);
    KernelGraph {
        dim: n,
        variant,
        law: Law::Rough,
        graph,
        outputs,
    }
}

/// The rough-ball map of `inputs` with restitutions `law` as nodes of `g`
/// (`docs/derivation.md` §15): [`build_on`]'s map with `P_n` scaled by `h_n = (1 + e)/2`,
/// `P_t` and the angular coefficients by `h_t = (1 + beta)/2`.
pub fn build_rough_on(
    g: &mut Graph,
    inputs: &KernelInputs,
    variant: Variant,
    law: RestitutionInputs,
) -> Vec<BodyOutput> {
    let one = g.int(1);
    let half = g.constant(num_rational::BigRational::new(1.into(), 2.into()));
    let h = |g: &mut Graph, x: Id, label: &str| {
        let one_x = g.add(one, x);
        let h = g.mul(half, one_x);
        g.label(h, label);
        h
    };
    let h_n = h(g, law.e, "h_n");
    let h_t = h(g, law.beta, "h_t");
    build_scaled_on(g, inputs, variant, Some((h_n, h_t)))
}

/// The collision map of `inputs` as nodes of `g` (both bodies for [`Variant::Free`], body 2
/// for [`Variant::Fixed`]). The dimension is `inputs.nu.len()`. Used by [`build`], and by
/// the verifier to compose the map with itself or substitute limits.
pub fn build_on(g: &mut Graph, inputs: &KernelInputs, variant: Variant) -> Vec<BodyOutput> {
    build_scaled_on(g, inputs, variant, None)
}

/// The normal and tangential slip of the contact point, `(dn, t)`:
/// `c = (R_1 U_1 + R_2 U_2) nu`, `dn = (u_2 - u_1) . nu`, `t = u_2 - u_1 - dn nu - c`
/// (labelled `c_k`, `du_k`, `dn`, `t_k`).
pub(crate) fn slip(g: &mut Graph, inputs: &KernelInputs) -> (Id, Vec<Id>) {
    let n = inputs.nu.len();
    let nu = &inputs.nu;
    let [b1, b2] = &inputs.bodies;
    // c = R_1 U_1 nu + R_2 U_2 nu = (R_1 U_1 + R_2 U_2) nu: one skew product, not two.
    let w: Vec<Id> = b1
        .spin
        .iter()
        .zip(&b2.spin)
        .map(|(&x, &y)| {
            let x = g.mul(b1.radius, x);
            let y = g.mul(b2.radius, y);
            g.add(x, y)
        })
        .collect();
    let c = skew_times(g, n, &w, nu);
    label_all(g, &c, "c");

    // du = u_2 - u_1, dn = du . nu, t = du - dn nu - c
    let du: Vec<Id> = (0..n)
        .map(|k| g.sub(b2.velocity[k], b1.velocity[k]))
        .collect();
    label_all(g, &du, "du");
    let dn = g.dot(&du, nu);
    g.label(dn, "dn");
    let t: Vec<Id> = (0..n)
        .map(|k| {
            let normal = g.mul(dn, nu[k]);
            let tangential = g.sub(du[k], normal);
            g.sub(tangential, c[k])
        })
        .collect();
    label_all(g, &t, "t");

    (dn, t)
}

/// `D = w_1 g_2 (1 + g_1) + w_2 g_1 (1 + g_2)` (labelled `d`).
pub(crate) fn denominator(g: &mut Graph, inputs: &KernelInputs) -> Id {
    let [b1, b2] = &inputs.bodies;
    let (w1, w2, g1, g2) = (b1.inv_mass, b2.inv_mass, b1.gamma2, b2.gamma2);
    let one = g.int(1);
    let d = {
        let one_g1 = g.add(one, g1);
        let one_g2 = g.add(one, g2);
        let x = g.mul(w1, g2);
        let x = g.mul(x, one_g1);
        let y = g.mul(w2, g1);
        let y = g.mul(y, one_g2);
        g.add(x, y)
    };
    g.label(d, "d");
    d
}

/// The map with `P_n` scaled by `h.0` and `P_t`, `rho_1`, `rho_2` by `h.1` (the rough law),
/// or unscaled (`None`: no-slip, no node added).
pub(crate) fn build_scaled_on(
    g: &mut Graph,
    inputs: &KernelInputs,
    variant: Variant,
    h: Option<(Id, Id)>,
) -> Vec<BodyOutput> {
    let n = inputs.nu.len();
    assert!(n >= 2, "the collision map needs n >= 2");
    let nu = &inputs.nu;
    let [b1, b2] = &inputs.bodies;

    let (dn, t) = slip(g, inputs);

    // P = dn / (w_1 + w_2) nu + (g_1 g_2 / D) t
    let (w1, w2, g1, g2) = (b1.inv_mass, b2.inv_mass, b1.gamma2, b2.gamma2);
    // The constant 1 is interned here, before `D` ([`denominator`]) uses it, so that node
    // ids, and with them the operand order of `1 + g_i`, are those of the generated goldens.
    g.int(1);
    let two = g.int(2);
    let w_sum = g.add(w1, w2);
    let p_n = g.div(dn, w_sum);
    g.label(p_n, "p_n");
    let scaled = |g: &mut Graph, x: Id, k: usize, label: &str| match h {
        None => x,
        Some(h) => {
            let factor = if k == 0 { h.0 } else { h.1 };
            let y = g.mul(x, factor);
            g.label(y, label);
            y
        }
    };
    let p_n = scaled(g, p_n, 0, "pe_n");
    let d = denominator(g, inputs);
    let g1g2 = g.mul(g1, g2);
    let p_t = g.div(g1g2, d);
    g.label(p_t, "p_t");
    let p_t_unscaled = p_t;
    let p_t = scaled(g, p_t, 1, "pe_t");
    let p: Vec<Id> = (0..n)
        .map(|k| {
            let x = g.mul(p_n, nu[k]);
            let y = g.mul(p_t, t[k]);
            g.add(x, y)
        })
        .collect();
    label_all(g, &p, "p");

    // Body 2's spin increment of the `fixed` map with parameters as inputs:
    // `nu ^ (rho' t)`, `rho' = 2 (1 - p) / R` of the rounded `p` (`crate::unbiased`), with
    // `2 (1 - p)` carried as head + tail. With constant parameters (specialised kernels) the
    // DAG folds `rho'` exactly, so they keep `rho (nu ^ t)`.
    let unbiased = variant == Variant::Fixed
        && !(g.as_const(p_t_unscaled).is_some() && g.as_const(b2.radius).is_some());
    let fixed_increment = if unbiased {
        let (head, tail) = unbiased::twice_one_minus(g, p_t_unscaled);
        let head = scaled(g, head, 1, "q2e_head");
        let tail = scaled(g, tail, 1, "q2e_tail");
        let y = unbiased::scaled_slip(g, (head, tail), b2.radius, &t);
        let x = wedge(g, n, nu, &y);
        for (&id, (i, j)) in x.iter().zip(skew_pairs(n)) {
            g.label(id, format!("nu_y_{i}{j}"));
        }
        Some(x)
    } else {
        None
    };

    // nu ^ t, shared by both angular updates.
    let nu_t = if unbiased {
        Vec::new()
    } else {
        wedge(g, n, nu, &t)
    };
    for (&id, (i, j)) in nu_t.iter().zip(skew_pairs(n)) {
        g.label(id, format!("nu_t_{i}{j}"));
    }

    let update = |g: &mut Graph, body: &BodyInputs, other_g: Id, sign: i64, index: usize| {
        // u_i+ = u_i -/+ 2 w_i P
        let scale = g.mul(two, body.inv_mass);
        let velocity = (0..n)
            .map(|k| {
                let dv = g.mul(scale, p[k]);
                if sign > 0 {
                    g.add(body.velocity[k], dv)
                } else {
                    g.sub(body.velocity[k], dv)
                }
            })
            .collect();
        if let Some(increment) = &fixed_increment {
            let spin = body
                .spin
                .iter()
                .zip(increment)
                .map(|(&u, &x)| g.add(u, x))
                .collect();
            return BodyOutput {
                body: index,
                spin,
                velocity,
            };
        }
        // U_i+ = U_i + (2 w_i g_j / (R_i D)) nu ^ t
        let num = g.mul(scale, other_g);
        let den = g.mul(body.radius, d);
        let rho = g.div(num, den);
        g.label(rho, format!("rho{index}"));
        let rho = scaled(g, rho, 1, &format!("rhoe{index}"));
        let spin = body
            .spin
            .iter()
            .zip(&nu_t)
            .map(|(&u, &x)| {
                let du = g.mul(rho, x);
                g.add(u, du)
            })
            .collect();
        BodyOutput {
            body: index,
            spin,
            velocity,
        }
    };
    let mut outputs = Vec::new();
    if variant == Variant::Free {
        outputs.push(update(g, b1, g2, 1, 1));
    }
    outputs.push(update(g, b2, g1, -1, 2));
    outputs
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn skew_pairs_are_lexicographic() {
        assert_eq!(skew_pairs(2), vec![(0, 1)]);
        assert_eq!(skew_pairs(3), vec![(0, 1), (0, 2), (1, 2)]);
        assert_eq!(skew_pairs(6).len(), 15);
    }

    #[test]
    fn output_shapes_match_dimension() {
        for n in 2..=6 {
            for v in Variant::ALL {
                let k = build(n, v);
                let bodies = if v == Variant::Free { 2 } else { 1 };
                assert_eq!(k.outputs.len(), bodies);
                for out in &k.outputs {
                    assert_eq!(out.spin.len(), n * (n - 1) / 2);
                    assert_eq!(out.velocity.len(), n);
                }
            }
        }
    }
}
