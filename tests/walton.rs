//! The generated Walton kernels (`kernels::dN::walton`, plain and FMA) for n = 2..6, against
//! the law's definition (docs/derivation.md §15.1) in exact rationals, at random points whose
//! slip `|t|` is rational (so that the one root the kernel takes is exact):
//!
//! - sticking (`|J_t| <= mu |J_n|` for the rough impulse at `beta0`, decided here from the
//!   rough kernel's own impulse): the outputs are the rough kernel's at `beta0`, exactly;
//! - sliding: the outputs are the rough kernel's at `beta_C`, `1 + beta_C = mu (1 + e) (b/a)
//!   |dn| / |t|`, exactly; so `|J_t|^2 = mu^2 |J_n|^2`, `J_t` antiparallel to `t`,
//!   `dn+ = -e dn`, both momenta kept and the energy not increased, each checked as well;
//! - in `f64` and `f32`, at points that stick with a margin far beyond rounding, the rough
//!   kernel's bits (plain and FMA).

use collision_core::{
    stereographic_normal, Ball, BodyState, Exact, Generated, Restitution, RoughKernel, Scalar,
    Walton, WaltonKernel,
};
use noslip_tests::*;
use num_traits::{One, Zero};

const POINTS: usize = 24;

fn dot(a: &[Exact], b: &[Exact]) -> Exact {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// The slip of the contact point, `s = u_2 - u_1 - (R_1 U_1 + R_2 U_2) nu`, as `(dn, t)`.
fn slip<const N: usize, const S: usize>(
    nu: &[Exact; N],
    balls: &[Ball<Exact>; 2],
    st: &[BodyState<Exact, N, S>; 2],
) -> (Exact, Vec<Exact>) {
    let mut s: Vec<Exact> = (0..N)
        .map(|k| &st[1].velocity[k] - &st[0].velocity[k])
        .collect();
    for b in 0..2 {
        // (U nu)_i = sum_j U_ij nu_j, with U_ji = -U_ij.
        for ((i, j), u) in collision_core::skew_pairs(N).zip(&st[b].spin) {
            let r = &balls[b].radius;
            s[i] -= r * u * &nu[j];
            s[j] += r * u * &nu[i];
        }
    }
    let dn = dot(&s, nu);
    let t = s.iter().zip(nu).map(|(x, y)| x - &dn * y).collect();
    (dn, t)
}

/// A vector of norm `r` orthogonal to `nu`, rational: `r` times the reflection taking `e_0`
/// to `nu` (`H = I - 2 w w^T / |w|^2`, `w = e_0 - nu`, orthogonal and rational) applied to
/// a rational unit vector of `e_0`'s complement (inverse stereographic projection).
fn tangent_of_norm<const N: usize>(rng: &mut Rng, nu: &[Exact; N], r: &Exact) -> Vec<Exact> {
    let y: Vec<Exact> = (0..N - 2).map(|_| ratio(rng, -5, 5, 4)).collect();
    let mut x = vec![Exact::zero()];
    x.extend(stereographic_normal(&y).into_iter().map(|c| c * r));
    let w: Vec<Exact> = (0..N)
        .map(|k| Exact::from_integer((k == 0) as i64) - &nu[k])
        .collect();
    let ww = dot(&w, &w);
    if ww.is_zero() {
        return x;
    }
    let f = Exact::from_integer(2) * dot(&w, &x) / ww;
    x.iter().zip(&w).map(|(xi, wi)| xi - &f * wi).collect()
}

/// A random case whose slip has rational norm; body 1 immovable when `fixed`.
fn case<const N: usize, const S: usize>(
    rng: &mut Rng,
    fixed: bool,
) -> ([Exact; N], [Ball<Exact>; 2], [BodyState<Exact, N, S>; 2]) {
    let nu = unit_normal::<N>(rng);
    let mut b1 = free_ball(rng, N);
    if fixed {
        b1.inv_mass = Exact::zero();
    }
    let balls = [b1, free_ball(rng, N)];
    let mut states = [state::<N, S>(rng), state::<N, S>(rng)];
    if fixed {
        // An immovable body at rest, so that body 2's energy is the system's.
        states[0] = BodyState::zero();
    }
    approaching(&nu, &mut states);
    // Replace the tangential slip by one of rational norm (`t` moves with `u_2`; `dn` not).
    let (_, t) = slip(&nu, &balls, &states);
    let norm = ratio(rng, 0, 12, 4);
    let target = tangent_of_norm(rng, &nu, &norm);
    for k in 0..N {
        states[1].velocity[k] += &target[k] - &t[k];
    }
    (nu, balls, states)
}

/// `(e, mu, beta0)`: ends of the ranges first, then random rationals inside them.
fn law(rng: &mut Rng, k: usize) -> Walton<Exact> {
    let ends = [(1, 0, 1), (0, 0, -1), (1, 1, 1), (0, 2, 0)];
    let (e, mu, beta0) = match ends.get(k) {
        Some(&(e, mu, beta0)) => (
            Exact::from_integer(e),
            Exact::from_integer(mu),
            Exact::from_integer(beta0),
        ),
        None => (
            Exact::from_ratio(int(rng, 0, 12), 12),
            Exact::from_ratio(int(rng, 0, 16), 16),
            Exact::from_ratio(int(rng, -12, 12), 12),
        ),
    };
    Walton::new(e, mu, beta0).expect("in range")
}

/// Body 2's velocity change split along `nu`: `(j_n, j_t)`; the impulse on body 2 is
/// `m_2` times it, so the ratio of the parts is the impulses'.
fn kick<const N: usize, const S: usize>(
    nu: &[Exact; N],
    before: &BodyState<Exact, N, S>,
    after: &BodyState<Exact, N, S>,
) -> (Exact, Vec<Exact>) {
    let dv: Vec<Exact> = (0..N)
        .map(|k| &after.velocity[k] - &before.velocity[k])
        .collect();
    let jn = dot(&dv, nu);
    let jt = dv.iter().zip(nu).map(|(x, y)| x - &jn * y).collect();
    (jn, jt)
}

/// Plain and FMA outputs, both bodies each.
type Both<const N: usize, const S: usize> = [[BodyState<Exact, N, S>; 2]; 2];

/// The Walton kernel (free, or fixed when `fixed`), plain and FMA; body 1 returned
/// unchanged by `fixed`.
fn walton<const N: usize, const S: usize>(
    fixed: bool,
    (nu, b, s): &([Exact; N], [Ball<Exact>; 2], [BodyState<Exact, N, S>; 2]),
    law: &Walton<Exact>,
) -> Both<N, S>
where
    Generated: WaltonKernel<Exact, N, S>,
{
    if fixed {
        let r1 = &b[0].radius;
        let plain = Generated::walton_fixed(nu, r1, &b[1], law, &s[0], &s[1]);
        let fused = Generated::walton_fixed_fma(nu, r1, &b[1], law, &s[0], &s[1]);
        [[s[0].clone(), plain], [s[0].clone(), fused]]
    } else {
        let plain = Generated::walton_free(nu, &b[0], &b[1], law, &s[0], &s[1]);
        let fused = Generated::walton_free_fma(nu, &b[0], &b[1], law, &s[0], &s[1]);
        [plain, fused]
    }
}

fn rough<const N: usize, const S: usize>(
    fixed: bool,
    (nu, b, s): &([Exact; N], [Ball<Exact>; 2], [BodyState<Exact, N, S>; 2]),
    law: &Restitution<Exact>,
) -> [BodyState<Exact, N, S>; 2]
where
    Generated: RoughKernel<Exact, N, S>,
{
    if fixed {
        let after = Generated::rough_fixed(nu, &b[0].radius, &b[1], law, &s[0], &s[1]);
        [s[0].clone(), after]
    } else {
        Generated::rough_free(nu, &b[0], &b[1], law, &s[0], &s[1])
    }
}

fn walton_is_the_law_exactly<const N: usize, const S: usize>()
where
    Generated: WaltonKernel<Exact, N, S> + RoughKernel<Exact, N, S>,
{
    let mut rng = Rng::new(700 + N as u64);
    let (mut sticking, mut sliding) = (0, 0);
    for fixed in [false, true] {
        for k in 0..POINTS {
            let c = case::<N, S>(&mut rng, fixed);
            let (nu, b, s) = &c;
            let law = law(&mut rng, k);
            let at = format!(
                "n = {N}, fixed = {fixed}, e = {}, mu = {}, beta0 = {}",
                law.e, law.mu, law.beta0
            );
            let outs = walton(fixed, &c, &law);
            // Sticking or sliding, by the definition: the rough impulse at beta0 against the cone.
            let at_beta0 = Restitution::new(law.e.clone(), law.beta0.clone()).unwrap();
            let stick = rough(fixed, &c, &at_beta0);
            let (jn, jt) = kick(nu, &s[1], &stick[1]);
            let slides = dot(&jt, &jt) > &law.mu * &law.mu * &jn * &jn;
            let expected = if !slides {
                sticking += 1;
                stick
            } else {
                sliding += 1;
                // 1 + beta_C = mu (1 + e) (b/a) |dn| / |t|, with the inverse effective masses
                // a = w_1 + w_2, b = a + w_1/g_1 + w_2/g_2 (w_1 = 0 for `fixed`).
                let (dn, t) = slip(nu, b, s);
                let norm_t = dot(&t, &t).exact_sqrt().expect("|t| is rational here");
                let a = &b[0].inv_mass + &b[1].inv_mass;
                let bb = &a + &b[0].inv_mass / &b[0].gamma2 + &b[1].inv_mass / &b[1].gamma2;
                let one = Exact::one();
                let one_plus =
                    &law.mu * (&one + &law.e) * (bb / a) * num_traits::Signed::abs(&dn) / norm_t;
                let beta_c = one_plus - &one;
                assert!(beta_c < law.beta0, "{at}: sliding means beta_C < beta0");
                let law_c = Restitution::new(law.e.clone(), beta_c).expect("beta_C >= -1");
                rough(fixed, &c, &law_c)
            };
            for (form, out) in ["plain", "FMA"].iter().zip(&outs) {
                assert_eq!(out, &expected, "{form}, {at}");
            }
            let after = &outs[0];
            let (jn_w, jt_w) = kick(nu, &s[1], &after[1]);
            let (dn, t) = slip(nu, b, s);
            let (dn_after, _) = slip(nu, b, after);
            assert_eq!(dn_after, -(&law.e * &dn), "{at}: dn+ = -e dn");
            // On the cone's edge while sliding, inside it while sticking.
            let cone = &law.mu * &law.mu * &jn_w * &jn_w;
            if slides {
                assert_eq!(dot(&jt_w, &jt_w), cone, "{at}: |J_t|^2 = mu^2 |J_n|^2");
            } else {
                assert!(dot(&jt_w, &jt_w) <= cone, "{at}: |J_t| <= mu |J_n|");
            }
            // J_t antiparallel to t: parallel (every 2x2 minor zero) and J_t . t <= 0.
            for i in 0..N {
                for j in 0..N {
                    assert_eq!(&jt_w[i] * &t[j], &jt_w[j] * &t[i], "{at}: J_t || t");
                }
            }
            assert!(dot(&jt_w, &t) <= Exact::zero(), "{at}: J_t opposes t");
            if !fixed {
                for kk in 0..N {
                    let p = |st: &[BodyState<Exact, N, S>; 2]| {
                        &st[0].velocity[kk] / &b[0].inv_mass + &st[1].velocity[kk] / &b[1].inv_mass
                    };
                    assert_eq!(p(after), p(s), "{at}: linear momentum");
                }
            }
            let movable = if fixed { 1..2 } else { 0..2 };
            for i in movable.clone() {
                assert_eq!(
                    angular_momentum(i, nu, &b[i], &after[i]),
                    angular_momentum(i, nu, &b[i], &s[i]),
                    "{at}: angular momentum of body {i} about Q"
                );
            }
            // Twice the energy of the movable bodies (body 1 of `fixed` is at rest).
            let e2 = |st: &[BodyState<Exact, N, S>; 2]| -> Exact {
                movable.clone().map(|i| energy(&b[i], &st[i])).sum()
            };
            assert!(e2(after) <= e2(s), "{at}: energy not increased");
        }
    }
    // Both branches are exercised in every dimension (the seeds are fixed).
    assert!(
        sticking >= 4 && sliding >= 4,
        "n = {N}: {sticking} sticking, {sliding} sliding"
    );
}

/// A float case: the normal, the balls, the states and `(e, mu, beta0)`.
type FloatCase<T, const N: usize, const S: usize> =
    ([T; N], [Ball<T>; 2], [BodyState<T, N, S>; 2], [f64; 3]);

/// A random float case (parameters in their ranges) and `(e, mu, beta0)`.
fn float_case<T: Scalar, const N: usize, const S: usize>(
    rng: &mut Rng,
    convert: impl Fn(f64) -> T,
) -> FloatCase<T, N, S> {
    let v: Vec<f64> = (0..N).map(|_| rng.uniform(-1.0, 1.0)).collect();
    let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let nu = std::array::from_fn(|k| convert(v[k] / norm));
    let ball = |rng: &mut Rng| Ball {
        inv_mass: convert(rng.uniform(0.1, 4.0)),
        radius: convert(rng.uniform(0.2, 3.0)),
        gamma2: convert(rng.uniform(0.01, 2.0 / N as f64)),
    };
    let balls = [ball(rng), ball(rng)];
    let st = |rng: &mut Rng| BodyState {
        spin: std::array::from_fn(|_| convert(rng.uniform(-5.0, 5.0))),
        velocity: std::array::from_fn(|_| convert(rng.uniform(-5.0, 5.0))),
    };
    let law = [
        rng.uniform(0.0, 1.0),
        rng.uniform(0.0, 2.0),
        rng.uniform(-1.0, 1.0),
    ];
    (nu, balls, [st(rng), st(rng)], law)
}

/// Where the rough impulse at `beta0` is inside the cone by a factor of 2 in `|J_t|^2`
/// (decided in f64 from the rough kernel's own output: its error, some ulps, cannot move a
/// point across a factor of 2), the Walton kernel's `rho` is `1/1` and `h_t = h_0 * 1`, so
/// its bits are the rough kernel's: plain and FMA, free and fixed.
fn sticking_bit_for_bit<T, const N: usize, const S: usize>(convert: impl Fn(f64) -> T)
where
    T: collision_core::ScalarRoot + std::fmt::Debug,
    for<'a> &'a T: collision_core::RefArith<T>,
    Generated: WaltonKernel<T, N, S> + RoughKernel<T, N, S>,
{
    let mut rng = Rng::new(800 + N as u64);
    let mut checked = 0;
    for _ in 0..400 {
        let (nu, b, s, [e, mu, beta0]) = float_case::<T, N, S>(&mut rng, &convert);
        let walton = Walton::new(convert(e), convert(mu), convert(beta0)).unwrap();
        let rough_law = Restitution::new(convert(e), convert(beta0)).unwrap();
        let r = Generated::rough_free(&nu, &b[0], &b[1], &rough_law, &s[0], &s[1]);
        let dv: Vec<f64> = (0..N)
            .map(|k| (r[1].velocity[k].clone() - s[1].velocity[k].clone()).to_f64())
            .collect();
        let nf: Vec<f64> = nu.iter().map(|x| x.to_f64()).collect();
        let jn: f64 = dv.iter().zip(&nf).map(|(x, y)| x * y).sum();
        let jt2: f64 = dv.iter().map(|x| x * x).sum::<f64>() - jn * jn;
        if 2.0 * jt2 > mu * mu * jn * jn {
            continue;
        }
        checked += 1;
        let show = |v: &[BodyState<T, N, S>]| format!("{v:?}");
        let same = |what: &str, x: &[BodyState<T, N, S>], y: &[BodyState<T, N, S>]| {
            assert_eq!(show(x), show(y), "{what}, n = {N}, {}", T::NAME);
        };
        same(
            "free",
            &Generated::walton_free(&nu, &b[0], &b[1], &walton, &s[0], &s[1]),
            &r,
        );
        same(
            "free_fma",
            &Generated::walton_free_fma(&nu, &b[0], &b[1], &walton, &s[0], &s[1]),
            &Generated::rough_free_fma(&nu, &b[0], &b[1], &rough_law, &s[0], &s[1]),
        );
        // The fixed kernels see body 2 only: the same point decides for them when body 2's
        // kick is recomputed, so they are compared where the fixed rough impulse sticks too.
        let r1 = &b[0].radius;
        let rf = Generated::rough_fixed(&nu, r1, &b[1], &rough_law, &s[0], &s[1]);
        let dv: Vec<f64> = (0..N)
            .map(|k| (rf.velocity[k].clone() - s[1].velocity[k].clone()).to_f64())
            .collect();
        let jn: f64 = dv.iter().zip(&nf).map(|(x, y)| x * y).sum();
        let jt2: f64 = dv.iter().map(|x| x * x).sum::<f64>() - jn * jn;
        if 2.0 * jt2 <= mu * mu * jn * jn {
            same(
                "fixed",
                &[Generated::walton_fixed(
                    &nu, r1, &b[1], &walton, &s[0], &s[1],
                )],
                &[rf],
            );
            same(
                "fixed_fma",
                &[Generated::walton_fixed_fma(
                    &nu, r1, &b[1], &walton, &s[0], &s[1],
                )],
                &[Generated::rough_fixed_fma(
                    &nu, r1, &b[1], &rough_law, &s[0], &s[1],
                )],
            );
        }
    }
    assert!(checked >= 40, "n = {N}: only {checked} sticking points");
}

macro_rules! per_dim {
    ($(($name:ident $n:literal $s:literal))*) => {$(
        mod $name {
            #[test]
            fn walton_kernels_are_the_law_exactly() {
                super::walton_is_the_law_exactly::<$n, $s>();
            }
            #[test]
            fn sticking_is_the_rough_kernel_bit_for_bit() {
                super::sticking_bit_for_bit::<f64, $n, $s>(|x| x);
                super::sticking_bit_for_bit::<f32, $n, $s>(|x| x as f32);
            }
        }
    )*};
}

collision_core::for_each_dim!(per_dim);
