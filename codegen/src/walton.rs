//! The Walton law (`docs/derivation.md` §15.1): the rough-ball map of [`crate::model`] with
//! the tangential restitution chosen per contact,
//!
//! ```text
//! beta = min(beta0, beta_C),   1 + beta_C = mu (1 + e) (b / a) |dn| / |t|,
//! ```
//!
//! `beta_C` being the `beta` at which the tangential impulse is exactly `mu` times the
//! normal one (sliding), `beta0` the restitution while the contact sticks. With
//! `h = (1 + beta)/2` the kernel computes `h = h_0 sqrt(rho)` (`h_0 = (1 + beta0)/2`), where
//! the comparison of two squares decides the branch with no root and no division:
//!
//! ```text
//! L = (h_0 g_1 g_2 a)^2 |t|^2,   C = (mu h_n D)^2 dn^2          (sliding: C < L)
//! rho = select(C < L, C, 1) / select(C < L, L, 1)                (1 while sticking)
//! ```
//!
//! While sticking `rho = 1/1 = 1` and `sqrt(1) = 1` exactly, so `h = h_0` exactly (in floats
//! too) and the outputs are the rough kernel's at `beta = beta0`; no division by zero occurs
//! for `t = 0`, `g_1 g_2 = 0` or `dn = 0`, since then `C < L` is false or `L > 0`.
//! While sliding, `h = h_0 sqrt(C / L) = mu h_n D |dn| / (g_1 g_2 a |t|)`, `(1 + beta_C)/2`.

use crate::ir::{Graph, Id};
use crate::model::{
    build_scaled_on, denominator, names, slip, symbolic_inputs, BodyOutput, KernelGraph,
    KernelInputs, Law, Variant,
};

/// The DAG nodes of the Walton law's parameters: normal restitution `e` in `[0, 1]`,
/// friction coefficient `mu >= 0`, sticking tangential restitution `beta0` in `[-1, 1]`.
#[derive(Clone, Copy, Debug)]
pub struct WaltonInputs {
    /// `e`: `dn+ = -e dn`.
    pub e: Id,
    /// `mu`: the Coulomb bound `|J_t| <= mu |J_n|`.
    pub mu: Id,
    /// `beta0`: `t+ = -beta0 t` while the contact sticks.
    pub beta0: Id,
}

impl WaltonInputs {
    /// The named inputs `e`, `mu` and `beta0`.
    pub fn symbolic(g: &mut Graph) -> Self {
        WaltonInputs {
            e: g.input(names::restitution_e()),
            mu: g.input(names::friction_mu()),
            beta0: g.input(names::walton_beta0()),
        }
    }
}

/// Build the Walton kernel (run-time `e`, `mu`, `beta0`) for dimension `n >= 2`.
pub fn build_walton(n: usize, variant: Variant) -> KernelGraph {
    let mut graph = Graph::new();
    let inputs = symbolic_inputs(&mut graph, n, variant);
    let law = WaltonInputs::symbolic(&mut graph);
    let outputs = build_walton_on(&mut graph, &inputs, variant, law);
    KernelGraph {
        dim: n,
        variant,
        law: Law::Walton,
        graph,
        outputs,
    }
}

/// The nodes of the Walton law's tangential factor: `h_n = (1 + e)/2`, the sliding test's
/// two sides `(C, L)` (sliding: `C < L`), and `h = (1 + beta)/2` with
/// `beta = min(beta0, beta_C)` (module docs).
#[derive(Clone, Copy, Debug)]
pub struct WaltonFactors {
    /// `h_n = (1 + e)/2`.
    pub h_n: Id,
    /// `C = (mu h_n D)^2 dn^2`: the Coulomb side.
    pub coulomb: Id,
    /// `L = (h_0 g_1 g_2 a)^2 |t|^2`: the sticking side.
    pub sticking: Id,
    /// `h = h_0 sqrt(rho)`.
    pub h_t: Id,
}

/// [`WaltonFactors`] of `inputs` under `law`, as nodes of `g`.
pub fn walton_factors(g: &mut Graph, inputs: &KernelInputs, law: WaltonInputs) -> WaltonFactors {
    let one = g.int(1);
    let half = g.constant(num_rational::BigRational::new(1.into(), 2.into()));
    let h = |g: &mut Graph, x: Id, label: &str| {
        let one_x = g.add(one, x);
        let h = g.mul(half, one_x);
        g.label(h, label);
        h
    };
    let h_n = h(g, law.e, "h_n");
    let h_0 = h(g, law.beta0, "h_0");
    let (dn, t) = slip(g, inputs);
    let d = denominator(g, inputs);
    let [b1, b2] = &inputs.bodies;
    let a = g.add(b1.inv_mass, b2.inv_mass);
    let g1g2 = g.mul(b1.gamma2, b2.gamma2);
    let square = |g: &mut Graph, x: Id| g.mul(x, x);
    // L = (h_0 g_1 g_2 a)^2 |t|^2
    let side = g.mul(h_0, g1g2);
    let side = g.mul(side, a);
    let side = square(g, side);
    let tt = g.dot(&t, &t);
    g.label(tt, "tt");
    let sticking = g.mul(side, tt);
    g.label(sticking, "side_l");
    // C = (mu h_n D)^2 dn^2
    let side = g.mul(law.mu, h_n);
    let side = g.mul(side, d);
    let side = square(g, side);
    let dn2 = square(g, dn);
    let coulomb = g.mul(side, dn2);
    g.label(coulomb, "side_c");
    // rho = select(C < L, C, 1) / select(C < L, L, 1); h = h_0 sqrt(rho)
    let num = g.select_lt(coulomb, sticking, coulomb, one);
    g.label(num, "rho_num");
    let den = g.select_lt(coulomb, sticking, sticking, one);
    g.label(den, "rho_den");
    let rho = g.div(num, den);
    g.label(rho, "rho");
    let root = g.sqrt(rho);
    g.label(root, "sqrt_rho");
    let h_t = g.mul(h_0, root);
    g.label(h_t, "h_t");
    WaltonFactors {
        h_n,
        coulomb,
        sticking,
        h_t,
    }
}

/// The Walton map of `inputs` with parameters `law` as nodes of `g`: the rough map of
/// [`crate::model::build_rough_on`] with `h_t` replaced by [`WaltonFactors::h_t`].
pub fn build_walton_on(
    g: &mut Graph,
    inputs: &KernelInputs,
    variant: Variant,
    law: WaltonInputs,
) -> Vec<BodyOutput> {
    let f = walton_factors(g, inputs, law);
    build_scaled_on(g, inputs, variant, Some((f.h_n, f.h_t)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ir::Node;
    use num_rational::BigRational;
    use std::collections::HashMap;

    fn q(p: i64, d: i64) -> BigRational {
        BigRational::new(p.into(), d.into())
    }

    /// 2D, fixed (`a = 1`, `g_1 g_2 = g_2`, `D = 1 + g_2`): the factor `h_t` evaluated
    /// exactly below, on and above the switch, against the definition
    /// `h_t = min(h_0, mu h_n D |dn| / (g_2 |t|))` worked out by hand.
    #[test]
    fn the_factor_is_min_of_sticking_and_coulomb() {
        let mut g = Graph::new();
        let inputs = symbolic_inputs(&mut g, 2, Variant::Fixed);
        let law = WaltonInputs::symbolic(&mut g);
        let f = walton_factors(&mut g, &inputs, law);
        // nu = (0, 1), body 2 at rest in spin, falling with u = (3, -4): dn = -4, t = (3, 0).
        // g_2 = 1/2, D = 3/2, e = 1 (h_n = 1), beta0 = 1 (h_0 = 1).
        let base: HashMap<&str, BigRational> = HashMap::from([
            ("nu_0", q(0, 1)),
            ("nu_1", q(1, 1)),
            ("u1_0", q(0, 1)),
            ("u1_1", q(0, 1)),
            ("U1_01", q(0, 1)),
            ("radius1", q(1, 1)),
            ("u2_0", q(3, 1)),
            ("u2_1", q(-4, 1)),
            ("U2_01", q(0, 1)),
            ("radius2", q(1, 1)),
            ("gamma2_2", q(1, 2)),
            ("e", q(1, 1)),
            ("beta0", q(1, 1)),
        ]);
        // Coulomb factor mu h_n D |dn| / (g_2 |t|) = mu (3/2) 4 / ((1/2) 3) = 4 mu.
        for (mu, expected) in [(q(1, 8), q(1, 2)), (q(1, 4), q(1, 1)), (q(1, 1), q(1, 1))] {
            let mut values = base.clone();
            values.insert("mu", mu.clone());
            let v = g
                .eval_all_rooted(
                    &|name| values.get(name).cloned(),
                    &|_, _, _| None,
                    &crate::ir::rational_sqrt,
                )
                .unwrap();
            assert_eq!(v[f.h_t.index()], expected, "mu = {mu}");
        }
        assert!(matches!(g.node(f.h_t), Node::Mul(..)));
    }
}
