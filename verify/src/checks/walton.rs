//! Identity checks of the Walton kernels (`kernels::dN::walton`, docs/derivation.md §15.1),
//! on each side of the sticking/sliding switch, exactly and with a Schwartz-Zippel bound.
//!
//! The kernel is a rational map on each side of its select, and its root is rational only
//! where `|t|` is. So the points are drawn in variables that fix the side and make `|t|`
//! rational, every one uniform in `S` as in [`crate::sample`]: the usual point (normal,
//! balls, spins, `u_1`), `e`, `beta0`, the approach speed `delta` (`dn = -delta`), the slip's
//! norm `r` and direction `z` in `S^(n-2)`, and `m`. Body 2's velocity is then
//!
//! ```text
//! u_2 = u_1 + dn nu + c + r H (0, sigma(z)),   c = (R_1 U_1 + R_2 U_2) nu,
//! ```
//!
//! `sigma` the inverse stereographic projection and `H = I - 2 w w^T / |w|^2`, `w = e_0 - nu`,
//! the rational reflection taking `e_0` to `nu`: so `t = r H (0, sigma(z))`, `|t| = r`. With
//! `mu_* = h_0 g_1 g_2 a r / (h_n D delta)` the friction at which the contact is on the
//! switch, the checks put `mu = mu_* (1 + m)` (sticking: `C = (1 + m)^2 L > L`) or
//! `mu = mu_* m / 2^21` (sliding: `C < L / 4`, and `sqrt(rho) = m / 2^21`). Every input of the
//! kernel is then a rational function of the drawn variables, the identity is one in them,
//! and the degree is computed on the same construction (the root by the rule of
//! [`crate::degree`]; this construction is what makes its argument a square).

use crate::identities::{self as id, StateIds};
use crate::sample::{element, point, SET_SIZE};
use crate::under_test::input_values;
use collision_core::rng::Rng;
use collision_core::{BodyState, Exact, Generated, Walton, WaltonKernel};
use noslip_codegen::ir::{Graph, Id, Node};
use noslip_codegen::model::{
    build_rough_on, names, skew_times, symbolic_inputs, BodyOutput, KernelInputs,
    RestitutionInputs, Variant,
};
use noslip_codegen::walton::{build_walton_on, WaltonInputs};
use num_traits::Zero;

/// The identity checks of the Walton kernels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WaltonIdentity {
    /// Sticking: the outputs are the rough kernel's at `beta = beta0`.
    StickingIsRough,
    /// Sliding: the outputs are the rough kernel's at `beta_C`,
    /// `1 + beta_C = mu (1 + e) (b/a) |dn| / |t|`.
    SlidingIsRoughAtBetaC,
    /// Sliding: `|J_t|^2 = mu^2 |J_n|^2` (body 2's impulse).
    CoulombEdge,
    /// Sliding: `J_t` parallel to `t` (every `J_t,i t_j - J_t,j t_i` zero; that it opposes
    /// `t` is checked at each point as well).
    Antiparallel,
    /// Sliding: `dn+ = -e dn`.
    NormalLaw,
    /// Sliding: total linear momentum (free only).
    LinearMomentum,
    /// Sliding: each movable body's angular momentum about the contact point.
    AngularMomentum,
}

impl WaltonIdentity {
    /// The identities checked for `variant`.
    pub fn for_variant(variant: Variant) -> &'static [WaltonIdentity] {
        use WaltonIdentity::*;
        match variant {
            Variant::Free => &[
                StickingIsRough,
                SlidingIsRoughAtBetaC,
                CoulombEdge,
                Antiparallel,
                NormalLaw,
                LinearMomentum,
                AngularMomentum,
            ],
            Variant::Fixed => &[
                StickingIsRough,
                SlidingIsRoughAtBetaC,
                CoulombEdge,
                Antiparallel,
                NormalLaw,
                AngularMomentum,
            ],
        }
    }

    /// The check's name in the report.
    pub fn name(self) -> &'static str {
        match self {
            WaltonIdentity::StickingIsRough => "sticking: the rough kernel at beta0",
            WaltonIdentity::SlidingIsRoughAtBetaC => "sliding: the rough kernel at beta_C",
            WaltonIdentity::CoulombEdge => "sliding: |J_t|^2 = mu^2 |J_n|^2",
            WaltonIdentity::Antiparallel => "sliding: J_t antiparallel to t",
            WaltonIdentity::NormalLaw => "sliding: dn+ = -e dn",
            WaltonIdentity::LinearMomentum => "sliding: linear momentum conserved",
            WaltonIdentity::AngularMomentum => "sliding: angular momentum about Q (each body)",
        }
    }

    /// The report's variant name: `walton free`, `walton fixed`.
    pub fn variant_name(variant: Variant) -> String {
        format!("walton {}", variant.name())
    }

    fn sticks(self) -> bool {
        self == WaltonIdentity::StickingIsRough
    }
}

/// The drawn variables beyond the usual point's: names and how many.
fn extra_names(n: usize) -> Vec<String> {
    let mut v: Vec<String> = ["e", "beta0", "delta", "r", "m"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    v.extend((0..n - 2).map(|j| format!("z_{j}")));
    v
}

/// The construction of the module docs as nodes of `g`: the kernel inputs (body 2's
/// velocity replaced), the law (with `mu` built) and the slip `t`.
struct Built {
    inputs: KernelInputs,
    law: WaltonInputs,
    t: Vec<Id>,
    beta_c: Id,
}

fn construct(g: &mut Graph, n: usize, variant: Variant, sticks: bool) -> Built {
    let mut inputs = symbolic_inputs(g, n, variant);
    let (e, beta0) = (
        g.input(names::restitution_e()),
        g.input(names::walton_beta0()),
    );
    let (delta, r, m) = (g.input("delta"), g.input("r"), g.input("m"));
    let z: Vec<Id> = (0..n - 2).map(|j| g.input(format!("z_{j}"))).collect();
    let one = g.int(1);
    let two = g.int(2);
    // x = (0, sigma(z)): sigma(z) = (2 z, |z|^2 - 1) / (|z|^2 + 1).
    let z2 = g.dot(&z, &z);
    let den = g.add(z2, one);
    let mut x = vec![g.int(0)];
    for &zj in &z {
        let y = g.mul(two, zj);
        x.push(g.div(y, den));
    }
    let last = g.sub(z2, one);
    x.push(g.div(last, den));
    // t = r H x, H x = x - 2 w (w . x) / |w|^2, w = e_0 - nu.
    let nu = inputs.nu.clone();
    let w: Vec<Id> = (0..n)
        .map(|k| {
            if k == 0 {
                g.sub(one, nu[0])
            } else {
                g.neg(nu[k])
            }
        })
        .collect();
    let wx = g.dot(&w, &x);
    let ww = g.dot(&w, &w);
    let f = g.mul(two, wx);
    let f = g.div(f, ww);
    let t: Vec<Id> = (0..n)
        .map(|k| {
            let y = g.mul(f, w[k]);
            let hx = g.sub(x[k], y);
            g.mul(r, hx)
        })
        .collect();
    // u_2 = u_1 + dn nu + c + t, dn = -delta.
    let [b1, b2] = &inputs.bodies;
    let spin: Vec<Id> = b1
        .spin
        .iter()
        .zip(&b2.spin)
        .map(|(&x1, &x2)| {
            let p = g.mul(b1.radius, x1);
            let q = g.mul(b2.radius, x2);
            g.add(p, q)
        })
        .collect();
    let c = skew_times(g, n, &spin, &nu);
    let u2: Vec<Id> = (0..n)
        .map(|k| {
            let normal = g.mul(delta, nu[k]);
            let v = g.sub(b1.velocity[k], normal);
            let v = g.add(v, c[k]);
            g.add(v, t[k])
        })
        .collect();
    inputs.bodies[1].velocity = u2;
    // mu_* = h_0 g_1 g_2 a r / (h_n D delta), h = (1 + x)/2; D and a of the variant.
    let [b1, b2] = &inputs.bodies;
    let (w1, w2, g1, g2) = (b1.inv_mass, b2.inv_mass, b1.gamma2, b2.gamma2);
    let a = g.add(w1, w2);
    let one_g1 = g.add(one, g1);
    let one_g2 = g.add(one, g2);
    let d1 = g.mul(w1, g2);
    let d1 = g.mul(d1, one_g1);
    let d2 = g.mul(w2, g1);
    let d2 = g.mul(d2, one_g2);
    let d = g.add(d1, d2);
    let h0 = g.add(one, beta0);
    let hn = g.add(one, e);
    let g1g2 = g.mul(g1, g2);
    let num = g.mul(h0, g1g2);
    let num = g.mul(num, a);
    let num = g.mul(num, r);
    let den = g.mul(hn, d);
    let den = g.mul(den, delta);
    let mu_star = g.div(num, den);
    let mu = if sticks {
        let k = g.add(one, m);
        g.mul(mu_star, k)
    } else {
        let scale = g.int(2 * SET_SIZE as i64);
        let k = g.div(m, scale);
        g.mul(mu_star, k)
    };
    // 1 + beta_C = mu (1 + e) (b / a) |dn| / |t| = mu (1 + e) D delta / (g_1 g_2 a r).
    let bc = g.mul(mu, hn);
    let bc = g.mul(bc, d);
    let bc = g.mul(bc, delta);
    let bden = g.mul(g1g2, a);
    let bden = g.mul(bden, r);
    let bc = g.div(bc, bden);
    let beta_c = g.sub(bc, one);
    Built {
        inputs,
        law: WaltonInputs { e, mu, beta0 },
        t,
        beta_c,
    }
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

/// The nodes that must vanish, `after` being the Walton kernel's outputs.
fn zeros(
    g: &mut Graph,
    identity: WaltonIdentity,
    variant: Variant,
    b: &Built,
    after: &[StateIds; 2],
) -> Vec<Id> {
    let n = b.inputs.nu.len();
    let before = id::before(&b.inputs);
    let nu = &b.inputs.nu;
    let rough = |g: &mut Graph, beta: Id| {
        let law = RestitutionInputs { e: b.law.e, beta };
        as_states(&b.inputs, build_rough_on(g, &b.inputs, variant, law))
    };
    // Body 2's impulse J = (u_2+ - u_2) / w_2, split along nu.
    let kick = |g: &mut Graph| {
        let w2 = b.inputs.bodies[1].inv_mass;
        let j: Vec<Id> = (0..n)
            .map(|k| {
                let dv = g.sub(after[1].velocity[k], before[1].velocity[k]);
                g.div(dv, w2)
            })
            .collect();
        let jn = g.dot(&j, nu);
        let jt: Vec<Id> = (0..n)
            .map(|k| {
                let x = g.mul(jn, nu[k]);
                g.sub(j[k], x)
            })
            .collect();
        (jn, jt)
    };
    match identity {
        WaltonIdentity::StickingIsRough => {
            let expected = rough(g, b.law.beta0);
            id::equal(g, after, &expected)
        }
        WaltonIdentity::SlidingIsRoughAtBetaC => {
            let expected = rough(g, b.beta_c);
            id::equal(g, after, &expected)
        }
        WaltonIdentity::CoulombEdge => {
            let (jn, jt) = kick(g);
            let jt2 = g.dot(&jt, &jt);
            let mu2 = g.mul(b.law.mu, b.law.mu);
            let jn2 = g.mul(jn, jn);
            let cone = g.mul(mu2, jn2);
            vec![g.sub(jt2, cone)]
        }
        WaltonIdentity::Antiparallel => {
            let (_, jt) = kick(g);
            let mut z = Vec::new();
            for i in 0..n {
                for j in i + 1..n {
                    let x = g.mul(jt[i], b.t[j]);
                    let y = g.mul(jt[j], b.t[i]);
                    z.push(g.sub(x, y));
                }
            }
            z
        }
        WaltonIdentity::NormalLaw => {
            let dn = |g: &mut Graph, s: &[StateIds; 2]| {
                let slip = id::slip(g, &b.inputs, s);
                g.dot(&slip, nu)
            };
            let (dn0, dn1) = (dn(g, &before), dn(g, after));
            let x = g.mul(b.law.e, dn0);
            vec![g.add(dn1, x)]
        }
        WaltonIdentity::LinearMomentum => id::momentum_conserved(g, &b.inputs, &before, after),
        WaltonIdentity::AngularMomentum => {
            let movable: &[usize] = match variant {
                Variant::Free => &[0, 1],
                Variant::Fixed => &[1],
            };
            id::angular_momentum_conserved(g, &b.inputs, &before, after, movable)
        }
    }
}

/// The degree of `identity` for dimension `n` and `variant` in the drawn variables, on the
/// symbolic Walton kernel of the construction.
pub fn degree(n: usize, variant: Variant, identity: WaltonIdentity) -> u64 {
    let mut g = Graph::new();
    let b = construct(&mut g, n, variant, identity.sticks());
    let out = build_walton_on(&mut g, &b.inputs, variant, b.law);
    let after = as_states(&b.inputs, out);
    let z = zeros(&mut g, identity, variant, &b, &after);
    crate::degree::identity_degree(&g, &z)
}

/// Evaluate `identity` at the point drawn from `rng`, on the sticking side when `sticks`
/// (else sliding); `Err` names what failed.
fn check_at<const N: usize, const S: usize>(
    variant: Variant,
    identity: WaltonIdentity,
    sticks: bool,
    rng: &mut Rng,
) -> Result<(), String>
where
    Generated: WaltonKernel<Exact, N, S>,
{
    let p = point::<N, S>(rng, variant == Variant::Fixed);
    let mut values = input_values(
        &p.nu,
        [&p.balls[0], &p.balls[1]],
        [&p.states[0], &p.states[1]],
    );
    for name in extra_names(N) {
        values.insert(name, element(rng));
    }
    let mut g = Graph::new();
    let b = construct(&mut g, N, variant, sticks);
    // The kernel's inputs from the construction, exactly (before the outputs' names exist).
    let v = g.eval_all(&|name| values.get(name).cloned(), &|_, _, _| None)?;
    let named = id::named_state(&mut g, N, "after");
    let z = zeros(&mut g, identity, variant, &b, &named);
    let at = |x: Id| v[x.0 as usize].clone();
    let mut state2 = p.states[1].clone();
    for (k, &u) in b.inputs.bodies[1].velocity.iter().enumerate() {
        state2.velocity[k] = at(u);
    }
    let law = Walton {
        e: at(b.law.e),
        mu: at(b.law.mu),
        beta0: at(b.law.beta0),
    };
    let (balls, s1) = (&p.balls, &p.states[0]);
    let after: [BodyState<Exact, N, S>; 2] = match variant {
        Variant::Free => Generated::walton_free(&p.nu, &balls[0], &balls[1], &law, s1, &state2),
        Variant::Fixed => [
            s1.clone(),
            Generated::walton_fixed(&p.nu, &balls[0].radius, &balls[1], &law, s1, &state2),
        ],
    };
    for bi in 0..2 {
        let pairs = named[bi].spin.iter().zip(&after[bi].spin);
        for (i, x) in pairs.chain(named[bi].velocity.iter().zip(&after[bi].velocity)) {
            let Node::Input(input) = g.node(*i) else {
                unreachable!("named states are inputs")
            };
            values.insert(input.0.clone(), x.clone());
        }
    }
    let v = g.eval_all(&|name| values.get(name).cloned(), &|_, _, _| None)?;
    if let Some(k) = z.iter().position(|x| !v[x.0 as usize].is_zero()) {
        return Err(format!(
            "component {k} of the identity is {} at the sample point, not 0",
            v[z[k].0 as usize]
        ));
    }
    if identity == WaltonIdentity::Antiparallel {
        // J_t . t < 0: the tangential impulse opposes the slip (w_2 > 0, so dv's sign).
        let dv_t: Exact = (0..N)
            .map(|k| (&after[1].velocity[k] - &state2.velocity[k]) * at(b.t[k]))
            .sum();
        if dv_t >= Exact::zero() {
            return Err(format!("J_t . t = {dv_t} / w_2 is not negative"));
        }
    }
    Ok(())
}

/// Run `identity` at `points` points; returns the first failure. `interrupted` is asked
/// before each point, as for the rough checks.
pub fn run<const N: usize, const S: usize>(
    variant: Variant,
    identity: WaltonIdentity,
    points: usize,
    seed: u64,
    interrupted: &dyn Fn() -> bool,
) -> Result<(), String>
where
    Generated: WaltonKernel<Exact, N, S>,
{
    let mut rng = Rng::new(seed);
    for k in 0..points {
        if interrupted() {
            return Err(format!("interrupted at point {k}"));
        }
        check_at::<N, S>(variant, identity, identity.sticks(), &mut rng)
            .map_err(|e| format!("point {k}: {e}"))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_walton_kernels_satisfy_every_identity() {
        for variant in Variant::ALL {
            for &identity in WaltonIdentity::for_variant(variant) {
                run::<3, 3>(variant, identity, 2, 17, &|| false)
                    .unwrap_or_else(|e| panic!("{variant:?} {identity:?}: {e}"));
                let d = degree(3, variant, identity);
                assert!(d > 0 && d < 100_000, "{identity:?}: degree {d}");
            }
        }
    }

    /// The construction decides the side: each side's identities fail at points of the
    /// other side (there the kernel is not the rough one at beta0, or not on the cone's edge).
    #[test]
    fn each_side_fails_the_other_sides_identities() {
        for variant in Variant::ALL {
            for identity in [
                WaltonIdentity::StickingIsRough,
                WaltonIdentity::SlidingIsRoughAtBetaC,
                WaltonIdentity::CoulombEdge,
            ] {
                let mut rng = Rng::new(9);
                let other = !identity.sticks();
                let err = check_at::<3, 3>(variant, identity, other, &mut rng)
                    .expect_err("passed on the other side");
                assert!(
                    err.starts_with("component"),
                    "{variant:?} {identity:?}: {err}"
                );
            }
        }
    }
}
