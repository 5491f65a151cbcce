//! The `free` map of two balls in plain `f64`, by hand, in two forms (`docs/accuracy.md`,
//! "Energy bias", the `free` kernel):
//!
//! ```text
//! c = (R_1 U_1 + R_2 U_2) nu,   dn = (u_2 - u_1) . nu,   t = u_2 - u_1 - dn nu - c
//! P = p_n nu + p_t t,   p_n = dn / (w_1 + w_2),   p_t = g_1 g_2 / D
//! D = w_1 g_2 (1 + g_1) + w_2 g_1 (1 + g_2)
//! u_1+ = u_1 + 2 w_1 P,   u_2+ = u_2 - 2 w_2 P,   U_i+ = U_i + rho_i nu ^ t
//! rho_i = 2 w_i g_j / (R_i D)
//! ```
//!
//! - [`Form::Shipped`]: every operation of the generated `free` kernel, in its order (each
//!   coefficient rounded once per call; checked bit for bit against `Generated::free` in
//!   `sim/tests/free_energy_bias_forms.rs`).
//! - [`Form::Consistent`]: the same, except ball 2's spin coefficient, taken from the exact
//!   identity `2 (w_1 + w_2) p_t + R_1 rho_1 + R_2 rho_2 = 2` with the *rounded* `p_t^` and
//!   `rho_1^`: `rho_2' = (2 - 2 w_1 p_t^ - 2 w_2 p_t^ - R_1 rho_1^) / R_2`, carried as
//!   `head + tail` (`tail` about `2^-20` of it). Then the map reverses the slip exactly to
//!   first order and the energy change per contact has no `|t|^2` term, whatever the
//!   roundings of `p_t^` and `rho_1^`. The products are exact by Dekker's TwoProduct (no
//!   fused operation).

use collision_core::{Ball, BodyState};

/// `a + b` as `hi + lo` exactly (Knuth's TwoSum).
pub fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// `a` as `hi + lo` with halves of 26 bits (Veltkamp's split, `2^27 + 1`).
fn split(a: f64) -> (f64, f64) {
    let c = 134_217_729.0 * a;
    let hi = c - (c - a);
    (hi, a - hi)
}

/// `a b` as `hi + lo` exactly, without a fused operation (Dekker's TwoProduct; exact barring
/// overflow and underflow).
pub fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
}

/// The skew pairs `(i, j)`, `i < j`, in the kernels' storage order.
pub fn skew_pairs(n: usize) -> Vec<(usize, usize)> {
    (0..n)
        .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
        .collect()
}

/// The per-call constants of the map, each computed as the generated kernel does.
#[derive(Clone, Debug)]
pub struct Shipped {
    /// `fl(w_1 + w_2)`, the divisor of `p_n`.
    pub w_sum: f64,
    /// `p_t^ = fl(fl(g_1 g_2) / D^)`.
    pub p_t: f64,
    /// `2 w_1`, `2 w_2` (exact).
    pub two_w: [f64; 2],
    /// `rho_i^ = fl(fl(g_j 2 w_i) / fl(R_i D^))`.
    pub rho: [f64; 2],
}

impl Shipped {
    /// The constants of `free(nu, b1, b2, ..)` in the generated kernel's operations.
    pub fn new(b1: &Ball<f64>, b2: &Ball<f64>) -> Self {
        let (w1, w2, g1, g2) = (b1.inv_mass, b2.inv_mass, b1.gamma2, b2.gamma2);
        let d = (g1 + 1.0) * (w1 * g2) + (g2 + 1.0) * (g1 * w2);
        let two_w = [2.0 * w1, 2.0 * w2];
        Shipped {
            w_sum: w1 + w2,
            p_t: (g1 * g2) / d,
            two_w,
            rho: [
                (g2 * two_w[0]) / (b1.radius * d),
                (g1 * two_w[1]) / (b2.radius * d),
            ],
        }
    }
}

/// `rho_2' = (2 - 2 w_1 p_t^ - 2 w_2 p_t^ - R_1 rho_1^) / R_2` as `(head, tail)`: the exact
/// products summed in double-double (`Sigma = hi + lo`), divided by `R_2` in double-double
/// (`x_hi + x_lo`), then `head = fl(K x_hi)`, `K = 1 - 2^-20`, and
/// `tail = fl((x_hi - head) + x_lo)` (`x_hi - head` exact by Sterbenz), so that
/// `head + tail = rho_2'` to about `u 2^-20` relative and `tail t_k` survives the rounding of
/// `head t_k + tail t_k`.
pub fn consistent_rho2(k: &Shipped, b1: &Ball<f64>, b2: &Ball<f64>) -> (f64, f64) {
    let (a, a_lo) = two_prod(k.two_w[0], k.p_t);
    let (b, b_lo) = two_prod(k.two_w[1], k.p_t);
    let (c, c_lo) = two_prod(b1.radius, k.rho[0]);
    let (s, e1) = two_sum(2.0, -a);
    let (s, e2) = two_sum(s, -b);
    let (s, e3) = two_sum(s, -c);
    let lo = ((e1 + e2) + e3) - ((a_lo + b_lo) + c_lo);
    let (hi, lo) = two_sum(s, lo);
    let x_hi = hi / b2.radius;
    let (q, q_lo) = two_prod(x_hi, b2.radius);
    let rem = (hi - q) - q_lo;
    let x_lo = (rem + lo) / b2.radius;
    let head = (1.0 - 2f64.powi(-20)) * x_hi;
    let tail = (x_hi - head) + x_lo;
    (head, tail)
}

/// Which map to apply.
#[derive(Clone, Copy, Debug)]
pub enum Form {
    /// The generated kernel's operations.
    Shipped,
    /// Ball 2's spin by `(head + tail) (nu ^ t)` of [`consistent_rho2`].
    Consistent,
}

/// The constants of a pair for one form.
#[derive(Clone, Debug)]
pub struct Pair {
    /// The shipped constants (the consistent form uses all but `rho[1]`).
    pub shipped: Shipped,
    /// `rho_2'` as `(head, tail)`.
    pub rho2_pair: (f64, f64),
    /// The form.
    pub form: Form,
}

impl Pair {
    /// The constants of `b1`, `b2` for `form`.
    pub fn new(b1: &Ball<f64>, b2: &Ball<f64>, form: Form) -> Self {
        let shipped = Shipped::new(b1, b2);
        let rho2_pair = consistent_rho2(&shipped, b1, b2);
        Pair {
            shipped,
            rho2_pair,
            form,
        }
    }

    /// The map (module docs) on `nu`, in the generated kernel's order of operations; with
    /// [`Form::Consistent`] ball 2's spin increments are `fl(fl(head x) + fl(tail x))`,
    /// `x = (nu ^ t)_ij`.
    pub fn collide<const N: usize, const S: usize>(
        &self,
        nu: &[f64; N],
        b1: &Ball<f64>,
        b2: &Ball<f64>,
        s1: &BodyState<f64, N, S>,
        s2: &BodyState<f64, N, S>,
    ) -> [BodyState<f64, N, S>; 2] {
        let k = &self.shipped;
        let pairs = skew_pairs(N);
        // W = R_1 U_1 + R_2 U_2 (stored entries), c = W nu.
        let w: Vec<f64> = (0..S)
            .map(|e| s1.spin[e] * b1.radius + s2.spin[e] * b2.radius)
            .collect();
        let c: [f64; N] = std::array::from_fn(|i| {
            let mut acc: Option<f64> = None;
            for (e, &(a, b)) in pairs.iter().enumerate() {
                let term = if a == i {
                    nu[b] * w[e]
                } else if b == i {
                    -(nu[a] * w[e])
                } else {
                    continue;
                };
                acc = Some(acc.map_or(term, |x| x + term));
            }
            acc.unwrap_or(0.0)
        });
        let du: [f64; N] = std::array::from_fn(|i| s2.velocity[i] - s1.velocity[i]);
        let dn = (1..N).fold(nu[0] * du[0], |acc, i| acc + nu[i] * du[i]);
        let t: [f64; N] = std::array::from_fn(|i| (du[i] - nu[i] * dn) - c[i]);
        let p_n = dn / k.w_sum;
        let p: [f64; N] = std::array::from_fn(|i| nu[i] * p_n + t[i] * k.p_t);
        let nu_t: Vec<f64> = pairs
            .iter()
            .map(|&(a, b)| nu[b] * t[a] - nu[a] * t[b])
            .collect();
        let (head, tail) = self.rho2_pair;
        [
            BodyState {
                velocity: std::array::from_fn(|i| s1.velocity[i] + p[i] * k.two_w[0]),
                spin: std::array::from_fn(|e| s1.spin[e] + nu_t[e] * k.rho[0]),
            },
            BodyState {
                velocity: std::array::from_fn(|i| s2.velocity[i] - p[i] * k.two_w[1]),
                spin: std::array::from_fn(|e| match self.form {
                    Form::Shipped => s2.spin[e] + nu_t[e] * k.rho[1],
                    Form::Consistent => s2.spin[e] + (nu_t[e] * head + nu_t[e] * tail),
                }),
            },
        ]
    }
}
