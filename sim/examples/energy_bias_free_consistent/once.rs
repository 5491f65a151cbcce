//! Where the consistent form's residual comes from: the consistent form with chosen stages
//! evaluated in exact rationals (`Exact`) on the float inputs and rounded once.
//!
//! - `v`: the velocities `u_i+ = u_i -/+ 2 w_i (p_n nu + p_t^ t)` (`p_n = dn^ / fl(w_1 + w_2)`),
//!   each component rounded once;
//! - `s`: the spins `U_i+ = U_i + rho_i (nu ^ t)` (`rho_1^`, `rho_2' = head + tail`), each
//!   entry rounded once;
//! - `t`: the slip `dn = du . nu`, `t = du - dn nu - (R_1 U_1 + R_2 U_2) nu` exact from the
//!   float state (otherwise the kernel's rounded `dn` and `t`, as rationals).
//!
//! With `vst` only the coefficients (consistent: `p_t^`, `rho_1^`, `rho_2'`) and the one
//! rounding of each output remain.

use crate::forms::{skew_pairs, Pair};
use collision_core::{Ball, BodyState, Exact};

/// Stages rounded once.
#[derive(Clone, Copy, Debug)]
pub struct Once {
    /// The velocity update.
    pub velocity: bool,
    /// The spin update.
    pub spin: bool,
    /// The slip.
    pub slip: bool,
}

impl Once {
    /// From letters `v`, `s`, `t`; `None` on any other letter.
    pub fn parse(flags: &str) -> Option<Self> {
        flags.chars().all(|c| "vst".contains(c)).then(|| Once {
            velocity: flags.contains('v'),
            spin: flags.contains('s'),
            slip: flags.contains('t'),
        })
    }
}

fn x(v: f64) -> Exact {
    Exact::from_float(v).expect("finite")
}

/// The slip `(dn, t)` (module docs), exact or the kernel's float one.
fn slip<const N: usize, const S: usize>(
    nu: &[f64; N],
    b: &[Ball<f64>; 2],
    st: &[BodyState<f64, N, S>; 2],
    exact: bool,
) -> (Exact, Vec<Exact>) {
    let pairs = skew_pairs(N);
    if !exact {
        // The kernel's operations (forms.rs), kept as a float.
        let w: Vec<f64> = (0..S)
            .map(|e| st[0].spin[e] * b[0].radius + st[1].spin[e] * b[1].radius)
            .collect();
        let du: [f64; N] = std::array::from_fn(|i| st[1].velocity[i] - st[0].velocity[i]);
        let dn = (1..N).fold(nu[0] * du[0], |acc, i| acc + nu[i] * du[i]);
        let t = (0..N)
            .map(|i| {
                let mut c: Option<f64> = None;
                for (e, &(p, q)) in pairs.iter().enumerate() {
                    let term = if p == i {
                        nu[q] * w[e]
                    } else if q == i {
                        -(nu[p] * w[e])
                    } else {
                        continue;
                    };
                    c = Some(c.map_or(term, |y| y + term));
                }
                x((du[i] - nu[i] * dn) - c.unwrap_or(0.0))
            })
            .collect();
        return (x(dn), t);
    }
    let w: Vec<Exact> = (0..S)
        .map(|e| &(&x(st[0].spin[e]) * &x(b[0].radius)) + &(&x(st[1].spin[e]) * &x(b[1].radius)))
        .collect();
    let du: Vec<Exact> = (0..N)
        .map(|i| &x(st[1].velocity[i]) - &x(st[0].velocity[i]))
        .collect();
    let dn = (0..N).fold(x(0.0), |acc, i| &acc + &(&x(nu[i]) * &du[i]));
    let t = (0..N)
        .map(|i| {
            let mut c = x(0.0);
            for (e, &(p, q)) in pairs.iter().enumerate() {
                if p == i {
                    c = &c + &(&x(nu[q]) * &w[e]);
                } else if q == i {
                    c = &c - &(&x(nu[p]) * &w[e]);
                }
            }
            &(&du[i] - &(&x(nu[i]) * &dn)) - &c
        })
        .collect();
    (dn, t)
}

/// The consistent form (`pair`) with the stages of `once` rounded once (module docs).
pub fn collide<const N: usize, const S: usize>(
    pair: &Pair,
    once: Once,
    nu: &[f64; N],
    b: &[Ball<f64>; 2],
    st: &[BodyState<f64, N, S>; 2],
) -> [BodyState<f64, N, S>; 2] {
    let mut out = pair.collide(nu, &b[0], &b[1], &st[0], &st[1]);
    let k = &pair.shipped;
    let (dn, t) = slip(nu, b, st, once.slip);
    if once.velocity {
        let p_n = dn / x(k.w_sum);
        for i in 0..N {
            let p = &(&x(nu[i]) * &p_n) + &(&t[i] * &x(k.p_t));
            out[0].velocity[i] = (&x(st[0].velocity[i]) + &(&p * &x(k.two_w[0]))).to_f64();
            out[1].velocity[i] = (&x(st[1].velocity[i]) - &(&p * &x(k.two_w[1]))).to_f64();
        }
    }
    if once.spin {
        let rho2 = &x(pair.rho2_pair.0) + &x(pair.rho2_pair.1);
        for (e, &(p, q)) in skew_pairs(N).iter().enumerate() {
            let nu_t = &(&x(nu[q]) * &t[p]) - &(&x(nu[p]) * &t[q]);
            out[0].spin[e] = (&x(st[0].spin[e]) + &(&nu_t * &x(k.rho[0]))).to_f64();
            out[1].spin[e] = (&x(st[1].spin[e]) + &(&nu_t * &rho2)).to_f64();
        }
    }
    out
}
