//! The `fixed` kernel's spin coefficient, made consistent with its velocity coefficient so
//! that the rounded map has no energy bias (`docs/accuracy.md`, "Energy bias").
//!
//! The `fixed` map (body 1 immovable) multiplies the slip `t` by two constants,
//!
//! ```text
//! u_2+ = u_2 - 2 dn nu - 2 p t          p   = g / (1 + g)
//! U_2+ = U_2 + rho nu ^ t               rho = 2 / (R (1 + g)) = 2 (1 - p) / R
//! ```
//!
//! Computed once per call, each is rounded: `p (1 + e_p)`, `rho (1 + e_rho)`. To first order
//! the map then changes `|u|^2 + g R^2 |U|^2` by `4 g / (1 + g)^2 (g e_p + e_rho) |t|^2` at
//! every contact (plus a term that changes sign under time reversal): the same sign at every
//! contact of a ball, so the energy drifts linearly. The bias vanishes when
//! `g e_p + e_rho = 0`, that is when the spin coefficient is `rho' = 2 (1 - p^) / R`
//! for the rounded `p^` the velocity uses (then `e_rho = -p e_p / (1 - p) = -g e_p`). The
//! velocity keeps its accurate `p^` (exactly 0 for a point mass, whatever the slip).
//!
//! `rho'` is not a float, and a float `rho'^` would bring back an `e_rho` of its own. The
//! kernel carries `2 (1 - p^)` as an unevaluated sum `head + tail`, `tail` about `2^-20` of
//! it, and divides per component: `y_k = (head t_k + tail t_k) / R`, then
//! `U_2+ = U_2 + nu ^ y`. Every rounding in `y_k` is then of a value that varies from
//! contact to contact, so none is the same at every contact (roundings of products and
//! quotients by the fixed `R` still leave a smaller drift of either sign, measured in
//! `docs/accuracy.md`). The tail is large enough that
//! `tail t_k` survives the rounding of the sum (a correction below half an ulp of `head t_k`
//! would be rounded away once `head t_k` is rounded, which keeps the bias), and small enough
//! that its own rounding, `u 2^-20 |head t_k|`, is far below the per-contact noise. With the
//! exact operations on the right:
//!
//! ```text
//! q_hi = fl(1 - p^)              q_lo = fl(fl(1 - q_hi) - p^)    q_hi + q_lo = 1 - p^ exactly
//!                                                                (Fast2Sum: 1 >= p^ >= 0)
//! head = fl(K q_hi)              K = 2 - 2^-19                   head ~ (1 - 2^-20) 2 q_hi
//! tail = fl((2 q_hi - head) + 2 q_lo)                            2 q_hi - head exact (Sterbenz)
//! ```
//!
//! so `head + tail = 2 (1 - p^)` up to the one rounding of `tail`, a relative `u` of a quantity
//! `2^-20` of the sum: to about `u 2^-20`, where one float gives `u / 2` at best. In exact
//! rationals every step is exact: `q_lo = 0`, `head + tail = 2 (1 - p)`, `y = rho t`, so the
//! verifier's identities are those of the map as before.
//!
//! Cost against the previous `rho (nu ^ t)`: per call `2 n` products, `n` sums and `n`
//! divisions for `y` in place of `n (n - 1) / 2` products of `rho` with `nu ^ t` and one
//! division; no fused operation, so the plain kernels need no `fma` (a libm call where the
//! target has no FMA instruction).

use crate::ir::{Graph, Id};
use num_rational::BigRational;

/// `K = 2 (1 - 2^-20)`: `head` is `1 - 2^-20` of `2 (1 - p)`, `tail` the remaining `2^-20`
/// (exact in `f32` and `f64`).
fn head_factor() -> BigRational {
    let two = BigRational::from_integer(2.into());
    let eps = BigRational::new(1.into(), (1u64 << 19).into());
    two - eps
}

/// `2 (1 - p)` as `(head, tail)` nodes (module docs), from the velocity coefficient `p` (the
/// rounded node the kernel uses).
pub fn twice_one_minus(g: &mut Graph, p: Id) -> (Id, Id) {
    let one = g.int(1);
    let two = g.int(2);
    let q_hi = g.sub(one, p);
    g.label(q_hi, "q_hi");
    let rest = g.sub(one, q_hi);
    let q_lo = g.sub(rest, p);
    g.label(q_lo, "q_lo");
    let k = g.constant(head_factor());
    let head = g.mul(k, q_hi);
    g.label(head, "q2_head");
    let two_q_hi = g.mul(two, q_hi);
    let gap = g.sub(two_q_hi, head);
    let two_q_lo = g.mul(two, q_lo);
    let tail = g.add(gap, two_q_lo);
    g.label(tail, "q2_tail");
    (head, tail)
}

/// `y_k = (head t_k + tail t_k) / R`, one node per component: `rho' t` with
/// `rho' = (head + tail) / R`.
pub fn scaled_slip(g: &mut Graph, (head, tail): (Id, Id), radius: Id, t: &[Id]) -> Vec<Id> {
    t.iter()
        .enumerate()
        .map(|(k, &t_k)| {
            let a = g.mul(head, t_k);
            let b = g.mul(tail, t_k);
            let s = g.add(a, b);
            let y = g.div(s, radius);
            g.label(y, format!("y_{k}"));
            y
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_traits::{Signed, ToPrimitive};

    /// In exact arithmetic `head + tail` is `2 (1 - p)` whatever `p`, and `tail` is its
    /// `2^-20`.
    #[test]
    fn head_and_tail_sum_to_the_coefficient_exactly() {
        let mut g = Graph::new();
        let p = g.input("p");
        let (head, tail) = twice_one_minus(&mut g, p);
        let r = |n: i64, d: i64| BigRational::new(n.into(), d.into());
        for pv in [r(2, 7), r(0, 1), r(1, 3), r(1, 2)] {
            let v = g.eval_all(&|_| Some(pv.clone()), &|_, _, _| None).unwrap();
            let sum = &v[head.0 as usize] + &v[tail.0 as usize];
            assert_eq!(sum, r(2, 1) * (r(1, 1) - &pv));
            assert_eq!(&v[tail.0 as usize] * r(1 << 20, 1), sum);
        }
    }

    /// In `f64`, as the kernel computes them, `head + tail` (summed in exact rationals) is
    /// `2 (1 - p^)` to `u 2^-20` (the module docs' one rounding of `tail`), on 2000 values of
    /// `p^` in `[0, 1/2]` (`g` in `[0, 1]`), where the one float `fl(2 (1 - p^))` is off by
    /// up to `u / 2`: each case compared exactly.
    #[test]
    fn in_f64_the_pair_is_far_more_accurate_than_one_float() {
        let exact = |x: f64| BigRational::from_float(x).expect("finite");
        let u = 2f64.powi(-53);
        let (mut worst_pair, mut worst_float): (f64, f64) = (0.0, 0.0);
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        for _ in 0..2000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let gamma2 = (state >> 11) as f64 / (1u64 << 53) as f64;
            let p = gamma2 / (1.0 + gamma2);
            let q_hi = 1.0 - p;
            let q_lo = (1.0 - q_hi) - p;
            let k = head_factor().to_f64().unwrap();
            let head = k * q_hi;
            let tail = (2.0 * q_hi - head) + 2.0 * q_lo;
            let want = BigRational::from_integer(2.into())
                * (BigRational::from_integer(1.into()) - exact(p));
            let rel = |x: BigRational| ((x - &want) / &want).abs().to_f64().unwrap();
            worst_pair = worst_pair.max(rel(exact(head) + exact(tail)));
            worst_float = worst_float.max(rel(exact(2.0 * q_hi)));
        }
        assert_eq!(head_factor().to_f64().unwrap(), 2.0 - 2f64.powi(-19));
        assert!(
            worst_pair <= u * 2f64.powi(-20),
            "pair off by {worst_pair:e}"
        );
        assert!(
            worst_float >= 0.25 * u,
            "one float was never off: {worst_float:e}"
        );
    }
}
