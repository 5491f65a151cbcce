//! The generated rough-ball kernels (`kernels::dN::rough`, plain and FMA) for n = 2..6:
//! exactly equal, in rationals, to the map built from the definitions
//! (`reference::collide_rough`) for random `(e, beta)` including the ends of their ranges;
//! the law, the momenta and the energy loss of docs/derivation.md §15 exactly; and, at
//! `(e, beta) = (1, 1)`, the no-slip kernels' results bit for bit in `f64` and `f32` (the
//! plain forms and the free FMA form).

use collision_core::{
    reference, Ball, BodyState, Exact, Generated, Kernel, Restitution, RoughKernel, Scalar,
};
use noslip_tests::*;
use num_traits::{One, Zero};

const POINTS: usize = 12;

/// A random valid exact case; body 1 immovable when `fixed`.
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
    approaching(&nu, &mut states);
    (nu, balls, states)
}

/// `(e, beta)`: the four corners of the ranges, then random rationals inside them.
fn law(rng: &mut Rng, k: usize) -> Restitution<Exact> {
    let corners = [(1, 1), (1, -1), (0, 1), (0, -1)];
    let (e, beta) = match corners.get(k) {
        Some(&(e, beta)) => (Exact::from_integer(e), Exact::from_integer(beta)),
        None => (
            Exact::from_ratio(int(rng, 0, 12), 12),
            Exact::from_ratio(int(rng, -12, 12), 12),
        ),
    };
    Restitution::new(e, beta).expect("in range")
}

fn dot<T: Scalar>(a: &[T], b: &[T]) -> T {
    a.iter()
        .zip(b)
        .fold(T::zero(), |s, (x, y)| s + x.clone() * y.clone())
}

/// The slip of the contact point, `s = u_2 - u_1 - (R_1 U_1 + R_2 U_2) nu`, split into
/// `(dn, t)`.
fn slip<const N: usize, const S: usize>(
    nu: &[Exact; N],
    balls: &[Ball<Exact>; 2],
    st: &[BodyState<Exact, N, S>; 2],
) -> (Exact, Vec<Exact>) {
    let mut s: Vec<Exact> = (0..N)
        .map(|k| &st[1].velocity[k] - &st[0].velocity[k])
        .collect();
    for (b, sign) in [(0, -1), (1, -1)] {
        // (U nu)_i = sum_j U_ij nu_j, with U_ji = -U_ij.
        for ((i, j), u) in collision_core::skew_pairs(N).zip(&st[b].spin) {
            let r = &balls[b].radius * Exact::from_integer(sign);
            s[i] += &r * u * &nu[j];
            s[j] -= &r * u * &nu[i];
        }
    }
    let dn = dot(&s, nu);
    let t = s.iter().zip(nu).map(|(x, y)| x - &dn * y).collect();
    (dn, t)
}

fn rough_kernels_equal_the_definition<const N: usize, const S: usize>()
where
    Generated: RoughKernel<Exact, N, S>,
{
    let mut rng = Rng::new(300 + N as u64);
    for fixed in [false, true] {
        for k in 0..POINTS {
            let (nu, balls, states) = case::<N, S>(&mut rng, fixed);
            let law = law(&mut rng, k);
            let b = [&balls[0], &balls[1]];
            let st = [&states[0], &states[1]];
            let reference = reference::collide_rough(&nu, b, &law, st).unwrap();
            let at = format!(
                "n = {N}, fixed = {fixed}, e = {}, beta = {}",
                law.e, law.beta
            );
            if fixed {
                let r1 = &balls[0].radius;
                let plain = Generated::rough_fixed(&nu, r1, b[1], &law, st[0], st[1]);
                let fused = Generated::rough_fixed_fma(&nu, r1, b[1], &law, st[0], st[1]);
                assert_eq!(plain, reference[1], "{at}");
                assert_eq!(fused, reference[1], "FMA, {at}");
                assert_eq!(reference[0], states[0], "an immovable body is unchanged");
            } else {
                let plain = Generated::rough_free(&nu, b[0], b[1], &law, st[0], st[1]);
                let fused = Generated::rough_free_fma(&nu, b[0], b[1], &law, st[0], st[1]);
                assert_eq!(plain, reference, "{at}");
                assert_eq!(fused, reference, "FMA, {at}");
            }
        }
    }
}

fn law_momenta_and_energy_loss<const N: usize, const S: usize>()
where
    Generated: RoughKernel<Exact, N, S>,
{
    let mut rng = Rng::new(400 + N as u64);
    for k in 0..POINTS {
        let (nu, balls, states) = case::<N, S>(&mut rng, false);
        let law = law(&mut rng, k);
        let b = [&balls[0], &balls[1]];
        let after = Generated::rough_free(&nu, b[0], b[1], &law, &states[0], &states[1]);
        // The law: dn+ = -e dn, t+ = -beta t.
        let (dn, t) = slip(&nu, &balls, &states);
        let (dn_after, t_after) = slip(&nu, &balls, &after);
        assert_eq!(dn_after, -(&law.e * &dn), "n = {N}: dn+");
        let minus_beta_t: Vec<Exact> = t.iter().map(|x| -(&law.beta * x)).collect();
        assert_eq!(t_after, minus_beta_t, "n = {N}: t+");
        // Linear momentum and each body's angular momentum about Q.
        for kk in 0..N {
            let p = |s: &[BodyState<Exact, N, S>; 2]| {
                &s[0].velocity[kk] / &b[0].inv_mass + &s[1].velocity[kk] / &b[1].inv_mass
            };
            assert_eq!(p(&after), p(&states), "n = {N}: linear momentum");
        }
        for i in 0..2 {
            assert_eq!(
                angular_momentum(i, &nu, b[i], &after[i]),
                angular_momentum(i, &nu, b[i], &states[i]),
                "n = {N}: angular momentum of body {i}"
            );
        }
        // Delta E = -(1 - e^2) dn^2 / (2 a) - (1 - beta^2) |t|^2 / (2 b), with the inverse
        // effective masses a = w_1 + w_2, b = a + w_1/g_1 + w_2/g_2. `energy` is twice E.
        let e2 = |s: &[BodyState<Exact, N, S>; 2]| energy(b[0], &s[0]) + energy(b[1], &s[1]);
        let a = &b[0].inv_mass + &b[1].inv_mass;
        let bt = &a + &b[0].inv_mass / &b[0].gamma2 + &b[1].inv_mass / &b[1].gamma2;
        let one = Exact::one();
        let loss2 = (&one - &law.e * &law.e) * &dn * &dn / &a
            + (&one - &law.beta * &law.beta) * dot(&t, &t) / &bt;
        assert_eq!(e2(&after) - e2(&states), -loss2, "n = {N}: energy loss");
    }
}

/// A random float case: `nu` normalised in floats, parameters in their ranges.
fn float_case<T: Scalar, const N: usize, const S: usize>(
    rng: &mut Rng,
    convert: impl Fn(f64) -> T,
) -> ([T; N], [Ball<T>; 2], [BodyState<T, N, S>; 2]) {
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
    (nu, balls.clone(), [st(rng), st(rng)])
}

/// `(1, 1)` multiplies by factors that are exactly 1: the rough kernels compute the no-slip
/// kernels' values, so their bits must agree (plain forms, and the free FMA form).
fn no_slip_member_bit_for_bit<T, const N: usize, const S: usize>(convert: impl Fn(f64) -> T)
where
    T: Scalar + std::fmt::Debug,
    for<'a> &'a T: collision_core::RefArith<T>,
    Generated: RoughKernel<T, N, S> + Kernel<T, N, S>,
{
    let mut rng = Rng::new(500 + N as u64);
    let law = Restitution::no_slip();
    for _ in 0..200 {
        let (nu, b, s) = float_case::<T, N, S>(&mut rng, &convert);
        let same = |what: &str, x: &[BodyState<T, N, S>], y: &[BodyState<T, N, S>]| {
            // Bits, not `==`: -0.0 against 0.0 would pass `==`.
            let show = |v: &[BodyState<T, N, S>]| format!("{v:?}");
            assert_eq!(show(x), show(y), "{what}, n = {N}, {}", T::NAME);
        };
        same(
            "free",
            &Generated::rough_free(&nu, &b[0], &b[1], &law, &s[0], &s[1]),
            &Generated::free(&nu, &b[0], &b[1], &s[0], &s[1]),
        );
        same(
            "free_fma",
            &Generated::rough_free_fma(&nu, &b[0], &b[1], &law, &s[0], &s[1]),
            &Generated::free_fma(&nu, &b[0], &b[1], &s[0], &s[1]),
        );
        let r1 = &b[0].radius;
        same(
            "fixed",
            &[Generated::rough_fixed(&nu, r1, &b[1], &law, &s[0], &s[1])],
            &[Generated::fixed(&nu, r1, &b[1], &s[0], &s[1])],
        );
        // Not `fixed_fma`: the no-slip `fixed` kernel shares `nu_k dn` between the slip and `P`,
        // so its FMA form cannot fuse that product into `P`; the rough kernel's `nu_k (h_n dn)`
        // is used once and is fused. Same values in exact arithmetic (checked above), rounded
        // differently; the plain forms (which the simulator runs) agree bit for bit.
    }
}

macro_rules! per_dim {
    ($(($name:ident $n:literal $s:literal))*) => {$(
        mod $name {
            #[test]
            fn rough_kernels_equal_the_definition_exactly() {
                super::rough_kernels_equal_the_definition::<$n, $s>();
            }
            #[test]
            fn law_momenta_and_energy_loss_exactly() {
                super::law_momenta_and_energy_loss::<$n, $s>();
            }
            #[test]
            fn no_slip_member_is_the_no_slip_kernel_bit_for_bit() {
                super::no_slip_member_bit_for_bit::<f64, $n, $s>(|x| x);
                super::no_slip_member_bit_for_bit::<f32, $n, $s>(|x| x as f32);
            }
        }
    )*};
}

collision_core::for_each_dim!(per_dim);
