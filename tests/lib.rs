//! Shared helpers of the cross-crate tests: deterministic exact sampling of valid collision
//! inputs, and the physical quantities the tests compare.

/// The project's seeded stream, so that every exact test is reproducible.
pub use collision_core::rng::Rng;
use collision_core::{skew_pairs, stereographic_normal, Ball, BodyState, Exact, Scalar};
use num_traits::{One, Zero};

/// Uniform integer in `lo..=hi`.
pub fn int(rng: &mut Rng, lo: i64, hi: i64) -> i64 {
    lo + rng.integer(0..=hi.abs_diff(lo)) as i64
}

/// `p/q` with `p` in `lo..=hi`, `q` in `1..=den`.
pub fn ratio(rng: &mut Rng, lo: i64, hi: i64, den: i64) -> Exact {
    Exact::from_ratio(int(rng, lo, hi), int(rng, 1, den))
}

/// An exactly unit normal: the inverse stereographic projection of a rational point.
pub fn unit_normal<const N: usize>(rng: &mut Rng) -> [Exact; N] {
    let y: Vec<Exact> = (0..N - 1).map(|_| ratio(rng, -5, 5, 4)).collect();
    stereographic_normal(&y).try_into().expect("N components")
}

/// A valid movable ball: mass in [1/4, 4], radius in [1/3, 3], gamma2 in (0, 2/n].
pub fn free_ball(rng: &mut Rng, n: usize) -> Ball<Exact> {
    let gamma2 = Exact::from_ratio(2 * int(rng, 1, 12), 12 * n as i64);
    Ball {
        inv_mass: Exact::from_ratio(int(rng, 1, 16), 4),
        radius: Exact::from_ratio(int(rng, 1, 9), 3),
        gamma2,
    }
}

pub fn state<const N: usize, const S: usize>(rng: &mut Rng) -> BodyState<Exact, N, S> {
    BodyState {
        spin: std::array::from_fn(|_| ratio(rng, -9, 9, 5)),
        velocity: std::array::from_fn(|_| ratio(rng, -9, 9, 5)),
    }
}

/// Make the pair approach (or graze): if `(u_2 - u_1) . nu > 0`, reflect `u_2`'s normal part.
pub fn approaching<const N: usize, const S: usize>(
    nu: &[Exact; N],
    states: &mut [BodyState<Exact, N, S>; 2],
) {
    let dn = relative_normal_velocity(nu, states);
    if dn > Exact::zero() {
        for (v, x) in states[1].velocity.iter_mut().zip(nu) {
            *v -= Exact::from_ratio(2, 1) * &dn * x;
        }
    }
}

/// `(u_2 - u_1) . nu`.
pub fn relative_normal_velocity<T: Scalar, const N: usize, const S: usize>(
    nu: &[T; N],
    s: &[BodyState<T, N, S>; 2],
) -> T {
    (0..N).fold(T::zero(), |acc, k| {
        acc + (s[1].velocity[k].clone() - s[0].velocity[k].clone()) * nu[k].clone()
    })
}

/// Twice the kinetic energy of a movable body, `m [lambda Tr(U U^T) + |u|^2]`, with
/// `Tr(U U^T) = 2 sum_{i<j} U_ij^2`.
pub fn energy<const N: usize, const S: usize>(
    ball: &Ball<Exact>,
    s: &BodyState<Exact, N, S>,
) -> Exact {
    let m = Exact::one() / &ball.inv_mass;
    let spin2: Exact = s.spin.iter().map(|x| x * x).sum();
    let vel2: Exact = s.velocity.iter().map(|x| x * x).sum();
    m * (ball.lambda() * Exact::from_ratio(2, 1) * spin2 + vel2)
}

/// Angular momentum about the contact point `Q` of body `i` (0 or 1), as compact skew
/// entries: `m (r ^ u) + 2 m lambda U` with `r = a - Q` (`-R_1 nu` for body 1, `R_2 nu`
/// for body 2) and `(a ^ b)_ij = b_i a_j - a_i b_j`.
pub fn angular_momentum<const N: usize, const S: usize>(
    body: usize,
    nu: &[Exact; N],
    ball: &Ball<Exact>,
    s: &BodyState<Exact, N, S>,
) -> Vec<Exact> {
    let m = Exact::one() / &ball.inv_mass;
    let sign = if body == 0 {
        -Exact::one()
    } else {
        Exact::one()
    };
    let r: Vec<Exact> = nu.iter().map(|x| &sign * &ball.radius * x).collect();
    skew_pairs(N)
        .zip(&s.spin)
        .map(|((i, j), u)| {
            let r_wedge_u = &s.velocity[i] * &r[j] - &r[i] * &s.velocity[j];
            &m * r_wedge_u + Exact::from_ratio(2, 1) * &m * ball.lambda() * u
        })
        .collect()
}
