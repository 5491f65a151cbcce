//! The exact type's change of representation (issue 15) changed no value: the generated
//! kernels in [`Exact`] (dashu's reduced rationals) and through the fast path
//! ([`collide_exact`]: relaxed inside, reduced at the end) give, on every regime of the
//! accuracy report, the same reduced fractions, the same `p/q` text and the same nearest
//! `f64` as in the former exact type, num-rational's `BigRational` ([`ExactNumRational`]);
//! and [`Relaxing`]'s `free` and `fixed` (the verifier's kernels) equal the kernels in `Exact`.

use collision_core::{
    collide_exact, collide_unchecked, BodyState, Exact, ExactNumRational, ExactRelaxed, Generated,
    Kernel, Relaxing, Scalar,
};
use noslip_accuracy::{case::Case, Regime};

/// Cases per regime and dimension (9 regimes): 72 per n, both kernels (the `Immovable`
/// regime runs `fixed`, the others `free`).
const CASES: usize = 8;

/// Every output as its reduced `(p, q)` digits, its text and its nearest `f64` (as bits,
/// so that `-0.0` and `0.0` differ).
fn view<T: Scalar, const N: usize, const S: usize>(
    out: &[BodyState<T, N, S>; 2],
    parts: impl Fn(&T) -> (String, String),
) -> Vec<((String, String), String, u64)> {
    out.iter()
        .flat_map(|b| b.spin.iter().chain(&b.velocity))
        .map(|x| (parts(x), x.to_string(), x.to_f64().to_bits()))
        .collect()
}

fn same_values<const N: usize, const S: usize>()
where
    Generated: Kernel<Exact, N, S> + Kernel<ExactNumRational, N, S> + Kernel<ExactRelaxed, N, S>,
{
    let mut rng = collision_core::rng::Rng::new(0x15 + N as u64);
    for regime in Regime::ALL {
        for _ in 0..CASES {
            let new: Case<Exact, N, S> = regime.sample::<N, S>(&mut rng).to_exact();
            let old: Case<ExactNumRational, N, S> = new.map(|x| x.convert());
            // The inputs themselves convert exactly.
            assert_eq!(old.map(|x| x.parts()), new.map(|x| x.parts()));
            let want = view(
                &collide_unchecked(&old.nu, old.ball_refs(), old.state_refs()),
                ExactNumRational::parts,
            );
            let plain = collide_unchecked(&new.nu, new.ball_refs(), new.state_refs());
            let fast = collide_exact(&new.nu, new.ball_refs(), new.state_refs());
            assert_eq!(
                view(&plain, Exact::parts),
                want,
                "n = {N}, {regime:?}: Exact"
            );
            assert_eq!(
                view(&fast, Exact::parts),
                want,
                "n = {N}, {regime:?}: fast path"
            );
            // The verifier's entry points, `Relaxing::free` and `::fixed`, called directly.
            let (nu, [b1, b2], [s1, s2]) = (&new.nu, &new.balls, &new.states);
            assert_eq!(
                Relaxing::free(nu, b1, b2, s1, s2),
                <Generated as Kernel<Exact, N, S>>::free(nu, b1, b2, s1, s2),
            );
            assert_eq!(
                Relaxing::fixed(nu, &b1.radius, b2, s1, s2),
                <Generated as Kernel<Exact, N, S>>::fixed(nu, &b1.radius, b2, s1, s2),
            );
        }
    }
}

#[test]
fn the_exact_kernels_give_the_former_type_s_values_n2() {
    same_values::<2, 1>();
}

#[test]
fn the_exact_kernels_give_the_former_type_s_values_n3() {
    same_values::<3, 3>();
}

#[test]
fn the_exact_kernels_give_the_former_type_s_values_n4() {
    same_values::<4, 6>();
}

#[test]
fn the_exact_kernels_give_the_former_type_s_values_n5() {
    same_values::<5, 10>();
}

#[test]
fn the_exact_kernels_give_the_former_type_s_values_n6() {
    same_values::<6, 15>();
}
