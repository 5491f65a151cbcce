//! The contact laws the engines apply ([`ContactKind`]), the TC model's elastic contacts
//! ([`tc_law`]), and the maps of each law (shared by the cell engine and the all-pairs
//! reference, so that both write the same log).
//!
//! **The TC model** (Luding & McNamara, Granular Matter 1, 113 (1998)): dissipation is
//! allowed only if the time between contacts exceeds a contact duration `t_c`. Here: a
//! contact with a rough law whose ball (either ball of a pair) had its previous contact
//! less than `t_c` before is elastic, and we take the elastic member `(e, beta) = (1, -1)`,
//! the smooth map: no energy is lost and none moves between translation and rotation, so a
//! cluster that would collapse inelastically passes its energy on as smooth elastic spheres
//! do (docs/granular.md says why this member).

use crate::rough::RoughLaw;
use crate::{smooth, PairKernels};
use collision_core::{Ball, BodyState, Restitution, Walton};

/// How a ball and what it meets exchange momentum at a contact (the scene's
/// `noslip_scene::ContactKind`, its numbers rounded to `f64`).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub enum ContactKind {
    /// `"no-slip"`: the no-slip map (the generated kernels); the default.
    #[default]
    NoSlip,
    /// `"smooth"`: specular, spins untouched.
    Smooth,
    /// The rough-ball law `dn+ = -e dn`, `t+ = -beta t` (`docs/derivation.md` §15):
    /// `0 <= e <= 1`, `-1 <= beta <= 1` (from a scene, never exactly `(1, 1)` or `(1, -1)`:
    /// those are the kinds above).
    Rough {
        /// Normal restitution `e`.
        e: f64,
        /// Tangential restitution `beta`.
        beta: f64,
    },
    /// The Walton law (`docs/derivation.md` §15.1): as [`ContactKind::Rough`] with
    /// `beta = min(beta0, beta_C)`, `beta_C` the tangential restitution at which the
    /// tangential impulse is `mu` times the normal one (sliding).
    Walton {
        /// Normal restitution `e`.
        e: f64,
        /// Friction coefficient `mu >= 0`.
        mu: f64,
        /// Tangential restitution `beta0` while the contact sticks.
        beta0: f64,
    },
}

impl ContactKind {
    /// The rough law's parameters, for [`crate::rough`]; `None` for the no-slip and smooth
    /// kinds.
    fn rough_law(self) -> Option<RoughLaw> {
        match self {
            ContactKind::Rough { e, beta } => Some(RoughLaw::Constant(Restitution { e, beta })),
            ContactKind::Walton { e, mu, beta0 } => Some(RoughLaw::Walton(Walton { e, mu, beta0 })),
            ContactKind::NoSlip | ContactKind::Smooth => None,
        }
    }
}

impl From<&noslip_scene::ContactKind> for ContactKind {
    /// The scene's kind, `e` and `beta` rounded to the nearest `f64` (the scene names the
    /// exact `(1, 1)` and `(1, -1)` as the no-slip and smooth kinds; a law that only rounds
    /// to them stays rough, and the rough kernels give the no-slip and smooth maps' bits there).
    fn from(kind: &noslip_scene::ContactKind) -> ContactKind {
        match kind {
            noslip_scene::ContactKind::NoSlip => ContactKind::NoSlip,
            noslip_scene::ContactKind::Smooth => ContactKind::Smooth,
            noslip_scene::ContactKind::Rough { e, beta } => ContactKind::Rough {
                e: crate::nearest::f(e),
                beta: crate::nearest::f(beta),
            },
            noslip_scene::ContactKind::Walton { e, mu, beta0 } => ContactKind::Walton {
                e: crate::nearest::f(e),
                mu: crate::nearest::f(mu),
                beta0: crate::nearest::f(beta0),
            },
        }
    }
}

/// The laws a [`PairKernels`]' kernels apply, per kind ([`PairKernels::laws`]): `None` for a
/// kind it has no kernel of (every contact of that kind then takes the generic kernels of its
/// law).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct FoldedLaws {
    /// The law of [`PairKernels::ball_ball`] for every pair of species (`None` also when the
    /// pairs' laws differ: [`PairKernels::ball_law`] then names each pair's).
    pub ball: Option<ContactKind>,
    /// The law of [`PairKernels::ball_wall`].
    pub wall: Option<ContactKind>,
    /// The law of [`PairKernels::ball_obstacle`].
    pub fixed: Option<ContactKind>,
}

impl FoldedLaws {
    /// The no-slip map for every kind: the generic kernels.
    pub const NO_SLIP: FoldedLaws = FoldedLaws {
        ball: Some(ContactKind::NoSlip),
        wall: Some(ContactKind::NoSlip),
        fixed: Some(ContactKind::NoSlip),
    };
}

/// The law a contact at absolute time `time` follows under the TC model with contact
/// duration `tc` (0: none), given the times of the previous contacts of its balls
/// (`-inf` before the first): a rough law becomes [`ContactKind::Smooth`] when `tc > 0` and
/// `time - previous < tc` for either ball; every other kind is kept. Without the model (`tc =
/// 0`) every contact follows its law, also one whose time rounds an ulp below its ball's
/// previous contact (a ball squeezed between two bodies; such a contact used to be made
/// elastic by `time - previous < 0`).
pub fn tc_law(kind: ContactKind, tc: f64, time: f64, previous: [f64; 2]) -> ContactKind {
    match kind {
        ContactKind::Rough { .. } | ContactKind::Walton { .. }
            if tc > 0.0 && previous.iter().any(|&p| time - p < tc) =>
        {
            ContactKind::Smooth
        }
        _ => kind,
    }
}

/// Two balls' states after a contact of law `kind` (species `a`, `b`; `nu` from ball 1 to
/// ball 2).
pub(crate) fn pair<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
    kernels: &K,
    species: &[Ball<f64>],
    kind: ContactKind,
    [a, b]: [usize; 2],
    nu: &[f64; N],
    pre: &[BodyState<f64, N, S>; 2],
) -> [BodyState<f64, N, S>; 2] {
    if kernels.ball_law(a, b) == Some(kind) {
        return kernels.ball_ball(a, b, nu, &pre[0], &pre[1]);
    }
    match kind {
        // No kernel of `kernels` has the no-slip law: the rough kernels at `(1, 1)` are the
        // no-slip map bit for bit.
        ContactKind::NoSlip => crate::rough::pair(
            nu,
            &species[a],
            &species[b],
            &RoughLaw::Constant(Restitution::no_slip()),
            &pre[0],
            &pre[1],
        ),
        ContactKind::Smooth => smooth::pair(
            nu,
            &species[a].inv_mass,
            &species[b].inv_mass,
            &pre[0],
            &pre[1],
        ),
        // Two point masses (`gamma2 = 0`, `D = 0`) under a law without tangential impulse:
        // the rough kernel's tangential coefficient is `0 / 0` there, so NaN times `h_t = 0`;
        // the law is the smooth map with restitution `e` (scenes refuse point masses under a
        // law with a tangential part).
        ContactKind::Rough { e, beta: -1.0 }
            if species[a].gamma2 == 0.0 && species[b].gamma2 == 0.0 =>
        {
            smooth::pair_restituted(
                nu,
                &species[a].inv_mass,
                &species[b].inv_mass,
                &e,
                &pre[0],
                &pre[1],
            )
        }
        ContactKind::Rough { .. } | ContactKind::Walton { .. } => crate::rough::pair(
            nu,
            &species[a],
            &species[b],
            &kind.rough_law().expect("a rough kind"),
            &pre[0],
            &pre[1],
        ),
    }
}

/// A ball's state (species `a`) after a contact of law `kind` with an immovable body at
/// rest, `nu` from the body to the ball; `wall` is the box wall `(axis, upper)` when the body
/// is one (its no-slip kernel is the one specialised to the axis).
pub(crate) fn fixed<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
    kernels: &K,
    species: &[Ball<f64>],
    kind: ContactKind,
    a: usize,
    wall: Option<(usize, bool)>,
    nu: &[f64; N],
    pre: &BodyState<f64, N, S>,
) -> BodyState<f64, N, S> {
    let laws = kernels.laws();
    match (kind, wall) {
        (k, Some((axis, upper))) if laws.wall == Some(k) => kernels.ball_wall(a, axis, upper, pre),
        (k, None) if laws.fixed == Some(k) => kernels.ball_obstacle(a, nu, pre),
        (ContactKind::NoSlip, _) => crate::rough::fixed(
            nu,
            &species[a],
            &RoughLaw::Constant(Restitution::no_slip()),
            pre,
        ),
        (ContactKind::Smooth, _) => smooth::fixed(nu, pre),
        (ContactKind::Rough { .. } | ContactKind::Walton { .. }, _) => crate::rough::fixed(
            nu,
            &species[a],
            &kind.rough_law().expect("a rough kind"),
            pre,
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::{fixed, pair, tc_law, ContactKind, FoldedLaws};
    use crate::PairKernels;
    use collision_core::{Ball, BodyState, Restitution, State2};

    /// Kernels that return a marker (velocity `[k, 0]`, `k` the kind: 1 ball-ball, 2 wall,
    /// 3 obstacle) and fold a rough law into the ball-ball and obstacle kinds only.
    struct Marked;

    fn marker(k: f64) -> State2<f64> {
        BodyState {
            spin: [0.0],
            velocity: [k, 0.0],
        }
    }

    const ROUGH: ContactKind = ContactKind::Rough { e: 0.5, beta: 0.25 };

    /// The three kernels of a test's `PairKernels`, each returning its marker.
    macro_rules! marker_kernels {
        () => {
            fn ball_ball(
                &self,
                _: usize,
                _: usize,
                _: &[f64; 2],
                _: &State2<f64>,
                _: &State2<f64>,
            ) -> [State2<f64>; 2] {
                [marker(1.0), marker(1.0)]
            }
            fn ball_wall(&self, _: usize, _: usize, _: bool, _: &State2<f64>) -> State2<f64> {
                marker(2.0)
            }
            fn ball_obstacle(&self, _: usize, _: &[f64; 2], _: &State2<f64>) -> State2<f64> {
                marker(3.0)
            }
        };
    }

    impl PairKernels<f64, 2, 1> for Marked {
        fn laws(&self) -> FoldedLaws {
            FoldedLaws {
                ball: Some(ROUGH),
                wall: None,
                fixed: Some(ROUGH),
            }
        }
        marker_kernels!();
    }

    /// The engines call a kernel for the law it folds, and the generic kernels of every
    /// other law (the rough kernels, exactly as `crate::rough` runs them).
    #[test]
    fn contacts_take_the_kernels_of_their_law() {
        let species = [Ball {
            inv_mass: 1.0,
            radius: 0.5,
            gamma2: 0.5,
        }];
        let nu = [0.6, 0.8];
        let pre = [
            BodyState {
                spin: [0.3],
                velocity: [1.0, 0.5],
            },
            BodyState {
                spin: [-0.2],
                velocity: [-1.0, 0.25],
            },
        ];
        let k = Marked;
        assert_eq!(
            pair(&k, &species, ROUGH, [0, 0], &nu, &pre),
            [marker(1.0), marker(1.0)]
        );
        assert_eq!(
            fixed(&k, &species, ROUGH, 0, None, &nu, &pre[1]),
            marker(3.0)
        );
        // Another rough law, and the no-slip map, are the generic rough kernels'.
        let other = ContactKind::Rough { e: 0.5, beta: 0.5 };
        let generic = |e, beta| {
            let law = crate::rough::RoughLaw::Constant(Restitution { e, beta });
            crate::rough::pair(&nu, &species[0], &species[0], &law, &pre[0], &pre[1])
        };
        assert_eq!(
            pair(&k, &species, other, [0, 0], &nu, &pre),
            generic(0.5, 0.5)
        );
        assert_eq!(
            pair(&k, &species, ContactKind::NoSlip, [0, 0], &nu, &pre),
            generic(1.0, 1.0)
        );
        // The wall kind folds nothing: the generic rough `fixed` with the wall's normal.
        let wall = fixed(
            &k,
            &species,
            ROUGH,
            0,
            Some((1, false)),
            &[0.0, 1.0],
            &pre[1],
        );
        let law = crate::rough::RoughLaw::Constant(Restitution { e: 0.5, beta: 0.25 });
        assert_eq!(
            wall,
            crate::rough::fixed(&[0.0, 1.0], &species[0], &law, &pre[1])
        );
    }

    /// Kernels with a law per pair of species (`PairKernels::ball_law`): the marker kernel
    /// of the ball-ball kind serves the pair `(0, 1)` (either order) under `ROUGH` only.
    struct PerPair;

    impl PairKernels<f64, 2, 1> for PerPair {
        fn laws(&self) -> FoldedLaws {
            FoldedLaws {
                ball: None,
                wall: None,
                fixed: None,
            }
        }
        fn ball_law(&self, a: usize, b: usize) -> Option<ContactKind> {
            match (a, b) {
                (0, 1) | (1, 0) => Some(ROUGH),
                (0, 0) => Some(ContactKind::NoSlip),
                _ => None,
            }
        }
        marker_kernels!();
    }

    #[test]
    fn ball_contacts_take_the_kernel_of_their_pairs_law() {
        let ball = Ball {
            inv_mass: 1.0,
            radius: 0.5,
            gamma2: 0.5,
        };
        let species = [ball.clone(), ball];
        let nu = [0.6, 0.8];
        let state = |c: f64, u: [f64; 2]| BodyState {
            spin: [c],
            velocity: u,
        };
        let pre = [state(0.3, [1.0, 0.5]), state(-0.2, [-1.0, 0.25])];
        let k = PerPair;
        let marked = [marker(1.0), marker(1.0)];
        assert_eq!(pair(&k, &species, ROUGH, [0, 1], &nu, &pre), marked);
        assert_eq!(pair(&k, &species, ROUGH, [1, 0], &nu, &pre), marked);
        assert_eq!(
            pair(&k, &species, ContactKind::NoSlip, [0, 0], &nu, &pre),
            marked
        );
        // The same law on a pair the kernels fold another law (or none) into: generic.
        let law = crate::rough::RoughLaw::Constant(Restitution { e: 0.5, beta: 0.25 });
        let generic = crate::rough::pair(&nu, &species[1], &species[1], &law, &pre[0], &pre[1]);
        assert_eq!(pair(&k, &species, ROUGH, [1, 1], &nu, &pre), generic);
        assert_ne!(pair(&k, &species, ROUGH, [0, 0], &nu, &pre), marked);
    }

    #[test]
    fn the_tc_model_makes_close_contacts_of_rough_laws_elastic() {
        let rough = ContactKind::Rough { e: 0.5, beta: 0.2 };
        let never = f64::NEG_INFINITY;
        assert_eq!(tc_law(rough, 0.1, 1.0, [never, never]), rough);
        assert_eq!(tc_law(rough, 0.1, 1.0, [0.95, never]), ContactKind::Smooth);
        assert_eq!(tc_law(rough, 0.1, 1.0, [never, 0.95]), ContactKind::Smooth);
        assert_eq!(tc_law(rough, 0.1, 1.0, [0.8, 0.5]), rough);
        // No TC model (tc = 0): even a simultaneous contact keeps its law, and so does one
        // whose time rounds an ulp below its ball's previous contact (a Walton contact of a
        // ball squeezed between a ball and an obstacle was made elastic that way).
        assert_eq!(tc_law(rough, 0.0, 1.0, [1.0, 1.0]), rough);
        let walton = ContactKind::Walton {
            e: 0.6,
            mu: 0.1,
            beta0: 1.0,
        };
        let before: f64 = 25196.35956634659;
        let ulp_earlier = f64::from_bits(before.to_bits() - 1);
        assert_eq!(tc_law(walton, 0.0, ulp_earlier, [before, never]), walton);
        assert_eq!(tc_law(rough, 0.0, ulp_earlier, [never, before]), rough);
        assert_eq!(
            tc_law(ContactKind::NoSlip, 0.1, 1.0, [1.0, 1.0]),
            ContactKind::NoSlip
        );
    }
}
