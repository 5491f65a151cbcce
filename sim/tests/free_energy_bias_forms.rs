//! The hand-written forms of the `free` map of `energy_bias_free_consistent`
//! (`sim/examples/energy_bias_free_consistent/forms.rs`): the shipped form is the generated
//! kernel bit for bit, and the consistent form's coefficients meet the identity
//! `2 (w_1 + w_2) p_t + R_1 rho_1 + R_2 rho_2 = 2` far more closely than the shipped ones
//! (`docs/accuracy.md`, "Energy bias", the `free` kernel).

#[path = "../examples/energy_bias_free_consistent/forms.rs"]
mod forms;

use collision_core::{Ball, BodyState, Generated, Kernel};
use forms::{Form, Pair};
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive};
use rand::{Rng as _, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn random_balls(rng: &mut ChaCha8Rng) -> [Ball<f64>; 2] {
    std::array::from_fn(|_| Ball {
        inv_mass: rng.random_range(0.05..20.0),
        radius: rng.random_range(0.01..1.0),
        gamma2: rng.random_range(0.01..1.0),
    })
}

fn bits<const N: usize, const S: usize>(b: &[BodyState<f64, N, S>; 2]) -> Vec<u64> {
    b.iter()
        .flat_map(|x| x.velocity.iter().chain(&x.spin).map(|v| v.to_bits()))
        .collect()
}

/// 2000 random inputs per dimension (random parameters, states and normals, the normal not
/// even of unit length: the operations are compared, not the physics).
fn same_bits<const N: usize, const S: usize>(seed: u64)
where
    Generated: Kernel<f64, N, S>,
{
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    for _ in 0..2000 {
        let balls = random_balls(&mut rng);
        let mut state = || BodyState::<f64, N, S> {
            spin: std::array::from_fn(|_| rng.random_range(-3.0..3.0)),
            velocity: std::array::from_fn(|_| rng.random_range(-3.0..3.0)),
        };
        let (s1, s2) = (state(), state());
        let nu: [f64; N] = std::array::from_fn(|_| rng.random_range(-1.0..1.0));
        let want = <Generated as Kernel<f64, N, S>>::free(&nu, &balls[0], &balls[1], &s1, &s2);
        let got = Pair::new(&balls[0], &balls[1], Form::Shipped)
            .collide(&nu, &balls[0], &balls[1], &s1, &s2);
        assert_eq!(bits(&got), bits(&want), "n = {N}: {nu:?} {balls:?}");
    }
}

#[test]
fn the_shipped_form_is_the_generated_kernel_bit_for_bit() {
    same_bits::<2, 1>(2);
    same_bits::<3, 3>(3);
}

/// `delta = 2 (w_1 + w_2) p_t^ + R_1 rho_1^ + R_2 rho_2^ - 2`, exactly, for 2000 random pairs.
/// The consistent form's `rho_2' = head + tail` is off only by the one rounding of `tail`
/// (`u |tail| <= u 2^-20 rho_2'`, so `|delta| <= 2^-53 2^-20 sigma_2 <= 2^-72`, `sigma_2 =
/// R_2 rho_2 <= 2`) and the double-double steps (a few `u^2`): bound `2^-71`. The shipped
/// form's three rounded coefficients are off by up to about `u`: it must exceed `2^-56`
/// somewhere, or the check could not fail.
#[test]
fn the_consistent_coefficients_meet_the_identity() {
    let q = |x: f64| BigRational::from_float(x).expect("finite");
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let (mut worst_consistent, mut worst_shipped): (f64, f64) = (0.0, 0.0);
    for _ in 0..2000 {
        let balls = random_balls(&mut rng);
        let pair = Pair::new(&balls[0], &balls[1], Form::Consistent);
        let k = &pair.shipped;
        let common =
            (q(k.two_w[0]) + q(k.two_w[1])) * q(k.p_t) + q(balls[0].radius) * q(k.rho[0]) - q(2.0);
        let r2 = q(balls[1].radius);
        let consistent = &common + &r2 * (q(pair.rho2_pair.0) + q(pair.rho2_pair.1));
        let shipped = &common + &r2 * q(k.rho[1]);
        worst_consistent = worst_consistent.max(consistent.abs().to_f64().unwrap());
        worst_shipped = worst_shipped.max(shipped.abs().to_f64().unwrap());
    }
    eprintln!("worst |delta|: consistent {worst_consistent:e}, shipped {worst_shipped:e}");
    assert!(
        worst_consistent <= 2f64.powi(-71),
        "consistent off by {worst_consistent:e}"
    );
    assert!(
        worst_shipped >= 2f64.powi(-56),
        "shipped never off: {worst_shipped:e}"
    );
}
