//! The first-order energy change of the `free` map with rounded coefficients, checked in
//! exact rationals (`docs/accuracy.md`, "Energy bias", the `free` kernel).
//!
//! The map (inverse masses `w_i`, `g_i`, radii `R_i`, unit normal `nu`; `W = w_1 + w_2`):
//!
//! ```text
//! t = u_2 - u_1 - dn nu - (R_1 U_1 + R_2 U_2) nu,   dn = (u_2 - u_1) . nu
//! u_1+ = u_1 + 2 w_1 (1 + a_1) P,   u_2+ = u_2 - 2 w_2 (1 + a_2) P
//! P = p_n (1 + e_n) nu + p_t (1 + e_t) t,   U_i+ = U_i + rho_i (1 + e_i) nu ^ t
//! ```
//!
//! with `p_n = dn / W`, `p_t = g_1 g_2 / D`, `rho_i = 2 w_i g_j / (R_i D)` and relative errors
//! `e_n`, `e_t`, `e_1`, `e_2` (the coefficients) and `a_1`, `a_2` (the factors `2 w_i`). With
//! `s = 2 W p_t`, `sigma_i = R_i rho_i`, `b_i = R_i U_i nu`, `V` the centre-of-mass velocity,
//! `a = (w_1 a_1 + w_2 a_2) / W` and `o_i = t . b_i + sigma_i |t|^2 / 2`, the change of
//! `E = sum_i (|u_i|^2 + g_i R_i^2 |U_i|^2) / (2 w_i)` is, to first order in the errors,
//!
//! ```text
//! dE = even + odd
//! even = 2 (a + e_n) dn^2 / W + p_t |t|^2 ((a + e_t) s + e_1 sigma_1 + e_2 sigma_2)
//! odd  = 2 (a_1 - a_2) (p_n V . nu + p_t V . t) - 2 (a + e_t) p_t (o_1 + o_2)
//!        + 2 p_t (e_1 o_1 + e_2 o_2)
//! ```
//!
//! `even` is unchanged and `odd` changes sign under time reversal (the contact from the
//! reversed outgoing state, `-C(x)`): `dn`, `t`, `p_n` are even, `V` and `o_i` odd. It uses
//! the exact identities `m_i g_i sigma_i = 2 p_t` and `s + sigma_1 + sigma_2 = 2` (the latter,
//! `(w_1 + w_2) p_t + (R_1 rho_1 + R_2 rho_2) / 2 = 1`, is the map's `t+ = -t`; the other,
//! `R_i rho_i = 2 w_i p_t / g_i`, holds too). The bias (`a = e_n = 0`: the factors `2 w_i`
//! are exact in binary, `W` exact for the masses measured) is `p_t |t|^2 delta` with
//! `delta = s^ + sigma_1^ + sigma_2^ - 2` of the rounded coefficients: it vanishes for any
//! rounding of `p_t` and `rho_1` when `rho_2' = (2 - 2 W p_t^ - R_1 rho_1^) / R_2`.

use num_rational::BigRational as Q;
use num_traits::{One, Signed, Zero};
use rand::{Rng as _, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn int(k: i64) -> Q {
    Q::from_integer(k.into())
}

fn ratio(n: i64, d: i64) -> Q {
    Q::new(n.into(), d.into())
}

fn dot(x: &[Q], y: &[Q]) -> Q {
    x.iter().zip(y).map(|(a, b)| a * b).sum()
}

fn pairs(n: usize) -> Vec<(usize, usize)> {
    (0..n)
        .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
        .collect()
}

/// Inverse mass, `g`, radius of each ball.
#[derive(Clone)]
struct Balls {
    w: [Q; 2],
    g: [Q; 2],
    r: [Q; 2],
}

/// Velocities and skew spins (entries `(i, j)`, `i < j`) of both balls.
#[derive(Clone, PartialEq, Debug)]
struct State {
    u: [Vec<Q>; 2],
    spin: [Vec<Q>; 2],
}

/// Relative errors of `p_n`, `p_t`, `rho_1`, `rho_2`, `2 w_1`, `2 w_2`.
#[derive(Clone)]
struct Errors {
    n: Q,
    t: Q,
    rho: [Q; 2],
    a: [Q; 2],
}

impl Errors {
    fn zero() -> Self {
        Errors {
            n: Q::zero(),
            t: Q::zero(),
            rho: [Q::zero(), Q::zero()],
            a: [Q::zero(), Q::zero()],
        }
    }
    fn scaled(&self, k: &Q) -> Self {
        Errors {
            n: &self.n * k,
            t: &self.t * k,
            rho: [&self.rho[0] * k, &self.rho[1] * k],
            a: [&self.a[0] * k, &self.a[1] * k],
        }
    }
}

/// `U nu` for the skew `U` of stored entries `spin`.
fn skew_times(spin: &[Q], nu: &[Q]) -> Vec<Q> {
    let mut out = vec![Q::zero(); nu.len()];
    for (e, &(i, j)) in pairs(nu.len()).iter().enumerate() {
        out[i] += &spin[e] * &nu[j];
        out[j] -= &spin[e] * &nu[i];
    }
    out
}

/// The exact coefficients and kinematics of a contact.
struct Contact {
    dn: Q,
    t: Vec<Q>,
    p_n: Q,
    p_t: Q,
    rho: [Q; 2],
}

fn contact(nu: &[Q], b: &Balls, x: &State) -> Contact {
    let n = nu.len();
    let c0 = skew_times(&x.spin[0], nu);
    let c1 = skew_times(&x.spin[1], nu);
    let du: Vec<Q> = (0..n).map(|k| &x.u[1][k] - &x.u[0][k]).collect();
    let dn = dot(&du, nu);
    let t = (0..n)
        .map(|k| &du[k] - &dn * &nu[k] - &b.r[0] * &c0[k] - &b.r[1] * &c1[k])
        .collect();
    let w_sum = &b.w[0] + &b.w[1];
    let d = &b.w[0] * &b.g[1] * (Q::one() + &b.g[0]) + &b.w[1] * &b.g[0] * (Q::one() + &b.g[1]);
    Contact {
        p_n: &dn / &w_sum,
        dn,
        t,
        p_t: &b.g[0] * &b.g[1] / &d,
        rho: [
            int(2) * &b.w[0] * &b.g[1] / (&b.r[0] * &d),
            int(2) * &b.w[1] * &b.g[0] / (&b.r[1] * &d),
        ],
    }
}

/// The map with the coefficients perturbed by `e` (module docs).
fn collide(nu: &[Q], b: &Balls, x: &State, e: &Errors) -> State {
    let n = nu.len();
    let k = contact(nu, b, x);
    let one = Q::one();
    let p: Vec<Q> = (0..n)
        .map(|i| &k.p_n * (&one + &e.n) * &nu[i] + &k.p_t * (&one + &e.t) * &k.t[i])
        .collect();
    let wedge: Vec<Q> = pairs(n)
        .iter()
        .map(|&(i, j)| &k.t[i] * &nu[j] - &nu[i] * &k.t[j])
        .collect();
    let sign = [int(1), int(-1)];
    let ball = |i: usize| {
        let f = int(2) * &b.w[i] * (&one + &e.a[i]) * &sign[i];
        let rho = &k.rho[i] * (&one + &e.rho[i]);
        (
            (0..n).map(|m| &x.u[i][m] + &f * &p[m]).collect::<Vec<Q>>(),
            (0..wedge.len())
                .map(|m| &x.spin[i][m] + &rho * &wedge[m])
                .collect::<Vec<Q>>(),
        )
    };
    let (u1, s1) = ball(0);
    let (u2, s2) = ball(1);
    State {
        u: [u1, u2],
        spin: [s1, s2],
    }
}

/// `E = sum_i (|u_i|^2 + g_i R_i^2 sum U_jk^2) / (2 w_i)`.
fn energy(b: &Balls, x: &State) -> Q {
    (0..2)
        .map(|i| {
            (dot(&x.u[i], &x.u[i]) + &b.g[i] * &b.r[i] * &b.r[i] * dot(&x.spin[i], &x.spin[i]))
                / (int(2) * &b.w[i])
        })
        .sum()
}

/// The first-order change `(even, odd)` of the module docs.
fn first_order(nu: &[Q], b: &Balls, x: &State, e: &Errors) -> (Q, Q) {
    let k = contact(nu, b, x);
    let w_sum = &b.w[0] + &b.w[1];
    let t2 = dot(&k.t, &k.t);
    let s = int(2) * &w_sum * &k.p_t;
    let sigma = [&b.r[0] * &k.rho[0], &b.r[1] * &k.rho[1]];
    let o: Vec<Q> = (0..2)
        .map(|i| {
            let b_i: Vec<Q> = skew_times(&x.spin[i], nu)
                .iter()
                .map(|v| &b.r[i] * v)
                .collect();
            dot(&k.t, &b_i) + &sigma[i] * &t2 / int(2)
        })
        .collect();
    let v: Vec<Q> = (0..nu.len())
        .map(|m| (&b.w[1] * &x.u[0][m] + &b.w[0] * &x.u[1][m]) / &w_sum)
        .collect();
    let a = (&b.w[0] * &e.a[0] + &b.w[1] * &e.a[1]) / &w_sum;
    let even = int(2) * (&a + &e.n) * &k.dn * &k.dn / &w_sum
        + &k.p_t * &t2 * ((&a + &e.t) * &s + &e.rho[0] * &sigma[0] + &e.rho[1] * &sigma[1]);
    let odd = int(2) * (&e.a[0] - &e.a[1]) * (&k.p_n * dot(&v, nu) + &k.p_t * dot(&v, &k.t))
        - int(2) * (&a + &e.t) * &k.p_t * (&o[0] + &o[1])
        + int(2) * &k.p_t * (&e.rho[0] * &o[0] + &e.rho[1] * &o[1]);
    (even, odd)
}

/// A rational in `[-1, 1]` with denominator 64.
fn small(rng: &mut ChaCha8Rng) -> Q {
    ratio(rng.random_range(-64..=64), 64)
}

/// A rational in `(0, max]` with denominator 16.
fn positive(rng: &mut ChaCha8Rng, max: i64) -> Q {
    ratio(rng.random_range(1..=16 * max), 16)
}

/// A random rational unit vector: the inverse stereographic projection
/// `(1 - |x|^2, 2 x) / (1 + |x|^2)` of a random rational `x` in R^(n-1).
fn unit(rng: &mut ChaCha8Rng, n: usize) -> Vec<Q> {
    let x: Vec<Q> = (1..n).map(|_| small(rng)).collect();
    let s = dot(&x, &x);
    let den = Q::one() + &s;
    std::iter::once((Q::one() - &s) / &den)
        .chain(x.iter().map(|v| int(2) * v / &den))
        .collect()
}

fn random_case(rng: &mut ChaCha8Rng, n: usize) -> (Vec<Q>, Balls, State) {
    let nu = unit(rng, n);
    assert_eq!(dot(&nu, &nu), Q::one());
    let b = Balls {
        w: [positive(rng, 2), positive(rng, 2)],
        g: [positive(rng, 1), positive(rng, 1)],
        r: [positive(rng, 1), positive(rng, 1)],
    };
    let s = n * (n - 1) / 2;
    let x = State {
        u: [
            (0..n).map(|_| small(rng)).collect(),
            (0..n).map(|_| small(rng)).collect(),
        ],
        spin: [
            (0..s).map(|_| small(rng)).collect(),
            (0..s).map(|_| small(rng)).collect(),
        ],
    };
    (nu, b, x)
}

/// Relative errors of order `10^-6`: `k / 10^9`, `|k| <= 1000`.
fn random_errors(rng: &mut ChaCha8Rng, with_factors: bool) -> Errors {
    let mut e = || ratio(rng.random_range(-1000..=1000), 1_000_000_000);
    let (n, t, r0, r1) = (e(), e(), e(), e());
    let a = if with_factors {
        [e(), e()]
    } else {
        [Q::zero(), Q::zero()]
    };
    Errors {
        n,
        t,
        rho: [r0, r1],
        a,
    }
}

/// With the factors `2 w_i` exact the outgoing state is linear in the errors, so, `E` being
/// quadratic, `dE = grad E . dx + E(dx)` exactly (`dx` the change of the outgoing state): the
/// first-order formula must equal `dE - E(dx)` exactly. The exact map conserves `E`.
#[test]
fn the_first_order_formula_is_exact_up_to_the_quadratic_term() {
    let mut rng = ChaCha8Rng::seed_from_u64(28);
    for n in [2, 3] {
        for _ in 0..20 {
            let (nu, b, x) = random_case(&mut rng, n);
            let exact = collide(&nu, &b, &x, &Errors::zero());
            assert_eq!(energy(&b, &exact), energy(&b, &x), "E conserved, n = {n}");
            let e = random_errors(&mut rng, false);
            let y = collide(&nu, &b, &x, &e);
            let dx = State {
                u: std::array::from_fn(|i| (0..n).map(|m| &y.u[i][m] - &exact.u[i][m]).collect()),
                spin: std::array::from_fn(|i| {
                    (0..exact.spin[i].len())
                        .map(|m| &y.spin[i][m] - &exact.spin[i][m])
                        .collect()
                }),
            };
            let (even, odd) = first_order(&nu, &b, &x, &e);
            assert_eq!(
                energy(&b, &y) - energy(&b, &x) - energy(&b, &dx),
                even + odd,
                "n = {n}"
            );
        }
    }
}

/// With every error present (the factors too) the remainder `dE - (even + odd)` is second
/// order: scaling the errors by 1/10 divides it by 100. It is a polynomial
/// `Q2 k^2 + Q3 k^3 + Q4 k^4` in the scale `k`, so the ratio is `100 (1 + O(|e|))` with
/// `|e| <= 10^-6`: a band of 1% is wide by four orders of magnitude.
#[test]
fn the_remainder_is_second_order() {
    let mut rng = ChaCha8Rng::seed_from_u64(41);
    let remainder = |nu: &[Q], b: &Balls, x: &State, e: &Errors| {
        let (even, odd) = first_order(nu, b, x, e);
        energy(b, &collide(nu, b, x, e)) - energy(b, x) - even - odd
    };
    for n in [2, 3] {
        for _ in 0..20 {
            let (nu, b, x) = random_case(&mut rng, n);
            let e = random_errors(&mut rng, true);
            let big = remainder(&nu, &b, &x, &e);
            let tenth = remainder(&nu, &b, &x, &e.scaled(&ratio(1, 10)));
            assert!(!tenth.is_zero(), "n = {n}: no second-order term");
            let r = big / tenth;
            assert!(
                (r.clone() - int(100)).abs() < int(1),
                "n = {n}: remainder ratio {r}"
            );
        }
    }
}

/// `even` is the same and `odd` of the other sign for the reversed contact: the incoming
/// state `-C(x)`, whose outgoing state is `-x` (the map is an involution).
#[test]
fn the_split_is_even_and_odd_under_time_reversal() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let negate = |x: &State| State {
        u: std::array::from_fn(|i| x.u[i].iter().map(|v| -v).collect()),
        spin: std::array::from_fn(|i| x.spin[i].iter().map(|v| -v).collect()),
    };
    for n in [2, 3] {
        for _ in 0..20 {
            let (nu, b, x) = random_case(&mut rng, n);
            let e = random_errors(&mut rng, true);
            let back = negate(&collide(&nu, &b, &x, &Errors::zero()));
            assert_eq!(collide(&nu, &b, &back, &Errors::zero()), negate(&x));
            let (even, odd) = first_order(&nu, &b, &x, &e);
            let (even_r, odd_r) = first_order(&nu, &b, &back, &e);
            assert_eq!(even_r, even, "n = {n}");
            assert_eq!(odd_r, -odd.clone(), "n = {n}");
            assert!(!odd.is_zero());
        }
    }
}

/// Both identities hold exactly; only the sum identity gives a consistent `rho_2`: from it,
/// `rho_2' = (2 - 2 W p_t^ - R_1 rho_1^) / R_2` leaves `even = 0` for any errors of `p_t` and
/// `rho_1`; from the other, `rho_i' = 2 w_i p_t^ / (g_i R_i)` (both spins scaled with `p_t^`)
/// leaves `even = 2 e_t p_t |t|^2`.
#[test]
fn the_consistent_spin_coefficient_removes_the_bias_for_any_rounding() {
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    for n in [2, 3] {
        for _ in 0..20 {
            let (nu, b, x) = random_case(&mut rng, n);
            let k = contact(&nu, &b, &x);
            let w_sum = &b.w[0] + &b.w[1];
            let sigma_sum = &b.r[0] * &k.rho[0] + &b.r[1] * &k.rho[1];
            assert_eq!(&w_sum * &k.p_t + sigma_sum / int(2), Q::one());
            for i in 0..2 {
                assert_eq!(&b.r[i] * &k.rho[i], int(2) * &b.w[i] * &k.p_t / &b.g[i]);
            }
            let mut e = random_errors(&mut rng, false);
            e.n = Q::zero();
            assert!(!e.t.is_zero());
            let p_t = &k.p_t * (Q::one() + &e.t);
            let rho_1 = &k.rho[0] * (Q::one() + &e.rho[0]);
            let rho_2 = (int(2) - int(2) * &w_sum * &p_t - &b.r[0] * &rho_1) / &b.r[1];
            e.rho[1] = rho_2 / &k.rho[1] - Q::one();
            assert_eq!(first_order(&nu, &b, &x, &e).0, Q::zero(), "n = {n}");
            // The other identity: both spins' coefficients from p_t^.
            e.rho = [e.t.clone(), e.t.clone()];
            let t2 = dot(&k.t, &k.t);
            assert_eq!(
                first_order(&nu, &b, &x, &e).0,
                int(2) * &e.t * &k.p_t * t2,
                "n = {n}"
            );
        }
    }
}
