//! Maxwellian velocities and spins for the homogeneous cooling state's start
//! (`random.velocities = "maxwellian"`, docs/granular.md): at granular temperature `T`, each
//! centre-velocity component is normal with mean 0 and variance `T / m`, and each compact
//! skew entry `U_ij` (`i < j`, one rotational degree of freedom each, kinetic energy
//! `1/2 I U_ij^2` with `I = 2 m lambda`) normal with variance `T / I`; a ball with
//! `lambda = 0` has no rotational degrees of freedom and gets no spin.

use collision_core::rng::Rng;
use collision_core::Ball;

/// A standard normal number (Box-Muller: `sqrt(-2 ln u) cos(2 pi v)`, `u` in `(0, 1]` and
/// `v` in `[0, 1)` from two words of `rng`).
pub fn normal(rng: &mut Rng) -> f64 {
    let u = 1.0 - rng.uniform(0.0, 1.0);
    let v = rng.uniform(0.0, 1.0);
    (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
}

/// A ball's `(velocity, spin)` drawn at temperature `t` (module docs): `N` then `S` normal
/// numbers from `rng`.
pub fn draw<const N: usize, const S: usize>(
    rng: &mut Rng,
    ball: &Ball<f64>,
    t: f64,
) -> ([f64; N], [f64; S]) {
    let m = 1.0 / ball.inv_mass;
    let inertia = 2.0 * m * ball.lambda();
    let (su, sw) = (
        (t / m).sqrt(),
        if inertia > 0.0 {
            (t / inertia).sqrt()
        } else {
            0.0
        },
    );
    let velocity = std::array::from_fn(|_| su * normal(rng));
    let spin = std::array::from_fn(|_| sw * normal(rng));
    (velocity, spin)
}

#[cfg(test)]
mod tests {
    use super::draw;
    use collision_core::rng::Rng;
    use collision_core::Ball;

    /// The second moments: `m <u_k^2> = T` and `I <U_ij^2> = T`. Over `n = 40000` balls a
    /// mean of `x^2` (`x` normal, variance `s^2`) has standard error `s^2 sqrt(2 / n)`, 0.7 %;
    /// each estimate is checked to 4 standard errors (2.8 %), a false failure about once in
    /// 16000 runs (the seed is fixed, so the test is deterministic anyway).
    #[test]
    fn the_draws_are_at_the_temperature_in_every_degree_of_freedom() {
        let ball = Ball {
            inv_mass: 0.5,
            radius: 1.0,
            gamma2: 0.4,
        };
        let (t, n) = (1.5, 40_000);
        let mut rng = Rng::new(7);
        let (mut tu, mut tw, mut mean) = ([0.0; 3], [0.0; 3], 0.0);
        for _ in 0..n {
            let (u, w) = draw::<3, 3>(&mut rng, &ball, t);
            for k in 0..3 {
                tu[k] += 2.0 * u[k] * u[k] / n as f64;
                tw[k] += 2.0 * 2.0 * ball.lambda() * w[k] * w[k] / n as f64;
                mean += u[k] / n as f64;
            }
        }
        let tolerance = 4.0 * t * (2.0 / n as f64).sqrt();
        for k in 0..3 {
            assert!((tu[k] - t).abs() < tolerance, "{tu:?}");
            assert!((tw[k] - t).abs() < tolerance, "{tw:?}");
        }
        // The mean velocity: standard error sqrt(T / m / n) per component (3 summed).
        assert!(
            mean.abs() < 4.0 * (3.0 * t / 2.0 / n as f64).sqrt(),
            "{mean}"
        );
        // A point mass gets no spin.
        let point = Ball {
            gamma2: 0.0,
            ..ball
        };
        assert_eq!(draw::<3, 3>(&mut rng, &point, t).1, [0.0; 3]);
    }
}
