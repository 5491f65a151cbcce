//! The rough-ball maps for the engine's generic dimension `N`: the generated kernels
//! `kernels::dN::rough::{free, fixed}` (`docs/derivation.md` §15), picked by `N` (a match
//! the compiler resolves for each `N`). With `nu` from body 1 to body 2, `g` the
//! contact-point relative velocity, the impulse makes the normal part `g_n` become `-e g_n`
//! and the tangential part `g_t` become `-beta g_t`; two balls lose
//! `(1 - e^2) |g_n|^2 / (2 a) + (1 - beta^2) |g_t|^2 / (2 b)` of kinetic energy, with
//! `a = w_1 + w_2`, `b = a + w_1 / gamma_1^2 + w_2 / gamma_2^2`. Under the Walton law
//! (`kernels::dN::walton`, §15.1) `beta = min(beta0, beta_C)`, `beta_C` the tangential
//! restitution at which the tangential impulse is `mu` times the normal one.

#[cfg(feature = "d2")]
use collision_core::kernels::d2;
#[cfg(feature = "d3")]
use collision_core::kernels::d3;
#[cfg(feature = "d4")]
use collision_core::kernels::d4;
#[cfg(feature = "d5")]
use collision_core::kernels::d5;
#[cfg(feature = "d6")]
use collision_core::kernels::d6;
use collision_core::{Ball, BodyState, Restitution, Walton};

/// A rough law's parameters: constant `(e, beta)`, or Walton's `(e, mu, beta0)`.
#[derive(Clone, Debug, PartialEq)]
pub enum RoughLaw {
    /// `dn+ = -e dn`, `t+ = -beta t`.
    Constant(Restitution<f64>),
    /// `beta = min(beta0, beta_C)` (Coulomb friction `mu`).
    Walton(Walton<f64>),
}

/// `x` as an array of length `M` (the same numbers: `M = N` wherever it is called).
fn cast<const N: usize, const M: usize>(x: &[f64; N]) -> [f64; M] {
    std::array::from_fn(|k| x[k])
}

fn state<const N: usize, const S: usize, const M: usize, const P: usize>(
    s: &BodyState<f64, N, S>,
) -> BodyState<f64, M, P> {
    BodyState {
        spin: cast(&s.spin),
        velocity: cast(&s.velocity),
    }
}

/// Two balls' states after a rough contact; `nu` from ball 1 to ball 2.
pub fn pair<const N: usize, const S: usize>(
    nu: &[f64; N],
    ball1: &Ball<f64>,
    ball2: &Ball<f64>,
    law: &RoughLaw,
    state1: &BodyState<f64, N, S>,
    state2: &BodyState<f64, N, S>,
) -> [BodyState<f64, N, S>; 2] {
    macro_rules! free {
        ($module:ident) => {{
            let (nu, s1, s2) = (&cast(nu), &state(state1), &state(state2));
            let [a, b] = match law {
                RoughLaw::Constant(l) => $module::rough::free(nu, ball1, ball2, l, s1, s2),
                RoughLaw::Walton(l) => $module::walton::free(nu, ball1, ball2, l, s1, s2),
            };
            [state(&a), state(&b)]
        }};
    }
    // Each dimension only with its feature (a build of n = 2 alone, as noslip-scene-example's).
    match N {
        #[cfg(feature = "d2")]
        2 => free!(d2),
        #[cfg(feature = "d3")]
        3 => free!(d3),
        #[cfg(feature = "d4")]
        4 => free!(d4),
        #[cfg(feature = "d5")]
        5 => free!(d5),
        #[cfg(feature = "d6")]
        6 => free!(d6),
        n => panic!("n = {n}: no rough kernels (noslip-sim built without feature d{n})"),
    }
}

/// A ball's state after a rough contact with an immovable body at rest; `nu` from the body
/// to the ball (the body's radius does not enter: the kernel uses it only times its spin, 0).
pub fn fixed<const N: usize, const S: usize>(
    nu: &[f64; N],
    ball: &Ball<f64>,
    law: &RoughLaw,
    s: &BodyState<f64, N, S>,
) -> BodyState<f64, N, S> {
    macro_rules! fixed {
        ($module:ident) => {{
            let (nu, rest, s) = (&cast(nu), &BodyState::zero(), &state(s));
            state(&match law {
                RoughLaw::Constant(l) => $module::rough::fixed(nu, &1.0, ball, l, rest, s),
                RoughLaw::Walton(l) => $module::walton::fixed(nu, &1.0, ball, l, rest, s),
            })
        }};
    }
    // Each dimension only with its feature (a build of n = 2 alone, as noslip-scene-example's).
    match N {
        #[cfg(feature = "d2")]
        2 => fixed!(d2),
        #[cfg(feature = "d3")]
        3 => fixed!(d3),
        #[cfg(feature = "d4")]
        4 => fixed!(d4),
        #[cfg(feature = "d5")]
        5 => fixed!(d5),
        #[cfg(feature = "d6")]
        6 => fixed!(d6),
        n => panic!("n = {n}: no rough kernels (noslip-sim built without feature d{n})"),
    }
}

#[cfg(test)]
mod tests {
    use super::RoughLaw;
    use super::{fixed, pair};
    use collision_core::{Ball, BodyState, Restitution, Walton};

    /// The contact-point relative velocity `g = (u_2 - R_2 U_2 nu) - (u_1 + R_1 U_1 nu)` in
    /// 3D, `U` from its compact entries `(U_01, U_02, U_12)`.
    fn slip(nu: &[f64; 3], b: [&Ball<f64>; 2], s: [&BodyState<f64, 3, 3>; 2]) -> [f64; 3] {
        let apply = |s: &BodyState<f64, 3, 3>, r: f64| -> [f64; 3] {
            let [u01, u02, u12] = s.spin;
            let x = nu.map(|v| r * v);
            [
                u01 * x[1] + u02 * x[2],
                -u01 * x[0] + u12 * x[2],
                -u02 * x[0] - u12 * x[1],
            ]
        };
        let (p1, p2) = (apply(s[0], b[0].radius), apply(s[1], -b[1].radius));
        std::array::from_fn(|k| (s[1].velocity[k] + p2[k]) - (s[0].velocity[k] + p1[k]))
    }

    /// The law at contact, `g_n -> -e g_n`, `g_t -> -beta g_t`, through the dimension
    /// dispatch (3D), to rounding: each output a few roundings of inputs of size 1, so
    /// `1e-14` is some hundred ulps of slack.
    #[test]
    fn the_dispatch_applies_the_law() {
        let nu = [0.6, 0.0, 0.8];
        let b1 = Ball {
            inv_mass: 1.0,
            radius: 1.0,
            gamma2: 0.4,
        };
        let b2 = Ball {
            inv_mass: 0.5,
            radius: 0.7,
            gamma2: 0.6,
        };
        let law = RoughLaw::Constant(Restitution::new(0.7, 0.3).unwrap());
        let s1 = BodyState {
            spin: [0.3, -0.2, 0.5],
            velocity: [1.0, 0.2, 0.4],
        };
        let s2 = BodyState {
            spin: [-0.1, 0.4, 0.2],
            velocity: [-0.5, 0.3, -0.9],
        };
        let [a, b] = pair(&nu, &b1, &b2, &law, &s1, &s2);
        let g = slip(&nu, [&b1, &b2], [&s1, &s2]);
        let h = slip(&nu, [&b1, &b2], [&a, &b]);
        let n = |v: [f64; 3]| v[0] * nu[0] + v[1] * nu[1] + v[2] * nu[2];
        let (gn, hn) = (n(g), n(h));
        assert!((hn + 0.7 * gn).abs() < 1e-14, "{hn} {gn}");
        for k in 0..3 {
            let (gt, ht) = (g[k] - gn * nu[k], h[k] - hn * nu[k]);
            assert!((ht + 0.3 * gt).abs() < 1e-14, "{ht} {gt}");
        }
        // On an immovable body: the normal velocity of the contact point reverses times e.
        let after = fixed(&nu, &b2, &law, &s2);
        let un = |s: &BodyState<f64, 3, 3>| n(s.velocity);
        assert!((un(&after) + 0.7 * un(&s2)).abs() < 1e-14);
    }

    /// The Walton law through the same dispatch: with a friction coefficient far above the
    /// slip's ratio the contact sticks and gives the constant law's bits at `beta0`; with a
    /// small one it slides, and the tangential impulse on ball 2 is `mu` times the normal
    /// one, to rounding (`1e-13` relative: a few hundred ulps of outputs of size 1).
    #[test]
    fn the_walton_law_sticks_or_slides_through_the_dispatch() {
        let nu = [0.6, 0.0, 0.8];
        let b1 = Ball {
            inv_mass: 1.0,
            radius: 1.0,
            gamma2: 0.4,
        };
        let b2 = Ball {
            inv_mass: 0.5,
            radius: 0.7,
            gamma2: 0.6,
        };
        let s1 = BodyState {
            spin: [0.3, -0.2, 0.5],
            velocity: [1.0, 0.2, 0.4],
        };
        let s2 = BodyState {
            spin: [-0.1, 0.4, 0.2],
            velocity: [-0.5, 0.3, -0.9],
        };
        let walton = |mu: f64| RoughLaw::Walton(Walton::new(0.7, mu, 0.3).unwrap());
        let constant = RoughLaw::Constant(Restitution::new(0.7, 0.3).unwrap());
        assert_eq!(
            pair(&nu, &b1, &b2, &walton(1e6), &s1, &s2),
            pair(&nu, &b1, &b2, &constant, &s1, &s2)
        );
        let mu = 0.05;
        let [_, b] = pair(&nu, &b1, &b2, &walton(mu), &s1, &s2);
        let j: Vec<f64> = (0..3)
            .map(|k| (b.velocity[k] - s2.velocity[k]) / b2.inv_mass)
            .collect();
        let jn = j[0] * nu[0] + j[1] * nu[1] + j[2] * nu[2];
        let jt2: f64 = (0..3).map(|k| (j[k] - jn * nu[k]).powi(2)).sum();
        assert!(
            (jt2.sqrt() - mu * jn.abs()).abs() < 1e-13 * jn.abs(),
            "|J_t| {} against mu |J_n| {}",
            jt2.sqrt(),
            mu * jn.abs()
        );
        // Sliding is not sticking: the constant law's tangential impulse is larger.
        assert_ne!(
            pair(&nu, &b1, &b2, &walton(mu), &s1, &s2),
            pair(&nu, &b1, &b2, &constant, &s1, &s2)
        );
    }
}
