//! A ball that leaves the table through a container: the one state after a contact from
//! which an event-driven run cannot go on.
//!
//! A container is a sphere `|x - c| = rho + R` seen from inside (concave): a ball of radius
//! `R` touches it when `|a - c| = rho`. After a contact with it the ball must move strictly
//! inwards, `(a - c) . u < 0`: every straight flight with `(a - c) . u >= 0` from there leaves
//! the sphere at once (at second order when `(a - c) . u = 0`, `|a + t u - c|^2 = rho^2 +
//! t^2 |u|^2`). The law sends the normal velocity to `-e` times itself, so in exact
//! arithmetic:
//!
//! - at `e > 0` the ball moves strictly inwards, and the next contact is the other end of
//!   the chord;
//! - at `e = 0` it moves along the wall's tangent (or stops, `u = 0`). The true motion
//!   slides along the concave wall in continuous contact, pressed against it, which no
//!   sequence of straight flights represents. Scenes refuse `e = 0` on a container
//!   (`noslip_scene`), where this would happen at the first slanted contact;
//! - at `0 < e < 1` without the TC model a lone ball collapses against the wall: with a
//!   smooth tangential law the angle `theta` between its velocity and the wall's tangent
//!   goes as `tan theta' = e tan theta` from one contact to the next, a chord of angle
//!   `2 theta` each, so the contacts accumulate in finite time (an inelastic collapse with
//!   the wall, as between balls), and once the chord is too shallow for the rounding of
//!   the positions rounding takes the normal velocity to 0 or outwards: the shipped circle
//!   table at `e = 1/2` does so after 33 contacts, its normal speed halving exactly from 0.99
//!   to 4.6e-10 (`sim/tests/collapse.rs`).
//!
//! An elastic contact that grazes the wall at an angle below about `1e-8` (a chord whose
//! depth is within the rounding of the positions) can end the same way, with probability
//! of that order per contact.
//!
//! The engines check `leaves` after every container contact and then stop with a
//! [`LeftTable`] ([`crate::Step::LeftTable`]) instead of letting the ball fly off (the run
//! used to end with the false note that the table is unbounded, or a gas to run on with a
//! ball outside it). The TC model (`[contact] tc`) ends the collapse: a contact within `t_c`
//! of the ball's previous one is elastic, so the angle stops shrinking.

use crate::table::Shape;
use std::fmt;

/// Ball `ball` left the table through boundary `boundary`, a container, after its contact
/// with it at absolute time `time`: its velocity's component along `a - c` was
/// `outward_speed >= 0` (the check `leaves`).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct LeftTable {
    /// The ball's index.
    pub ball: usize,
    /// The container's boundary id ([`crate::Contact::Boundary`]).
    pub boundary: usize,
    /// The absolute time of the contact.
    pub time: f64,
    /// `(a - c) . u / |a - c|` after the contact: 0 or the rounding residue that points out.
    pub outward_speed: f64,
}

impl LeftTable {
    /// The message, naming the container as `place` (the scene's key, `container[0]`).
    pub fn message(&self, place: &str) -> String {
        format!(
            "ball {} left the table through {place} after its contact at t = {}: its velocity \
             there points along the wall or out (outward speed {:e} >= 0), where the true motion \
             slides along the concave wall in continuous contact, which an event-driven run \
             cannot follow. At e < 1 this ends an inelastic collapse against the wall: the TC \
             model ([contact] tc) stops the collapse once the ball's contacts there come within \
             t_c of each other, so set it, or raise it if it is set (or raise e); at e = 1 the \
             contact grazed the wall within the rounding of the positions (docs/granular.md)",
            self.ball, self.time, self.outward_speed
        )
    }
}

impl fmt::Display for LeftTable {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(&self.message(&format!("boundary {} (a container)", self.boundary)))
    }
}

/// The outward speed `(a - c) . u / |a - c|` of a ball at `a` with velocity `u` right after a
/// contact with `shape`, if `shape` is a container and the ball does not move strictly inwards
/// (`(a - c) . u >= 0`, `u != 0`; module docs); `None` otherwise, and for every other shape.
pub(crate) fn leaves<const N: usize>(shape: &Shape<N>, a: &[f64; N], u: &[f64; N]) -> Option<f64> {
    let Shape::Container { centre, .. } = shape else {
        return None;
    };
    let d: [f64; N] = std::array::from_fn(|k| a[k] - centre[k]);
    let out: f64 = (0..N).map(|k| d[k] * u[k]).sum();
    let moving = u.iter().any(|&x| x != 0.0);
    (moving && out >= 0.0).then(|| out / d.iter().map(|x| x * x).sum::<f64>().sqrt())
}

#[cfg(test)]
mod tests {
    use super::{leaves, LeftTable};
    use crate::table::Shape;

    #[test]
    fn only_a_container_left_along_its_tangent_or_outwards_is_left() {
        let circle = Shape::Container {
            centre: [1.0, 0.0],
            radius: 2.0,
        };
        let a = [1.0, 1.5];
        // Inwards, by the least amount: kept.
        assert_eq!(leaves(&circle, &a, &[1.0, -1e-300]), None);
        // Along the tangent, or out by a rounding residue: left.
        assert_eq!(leaves(&circle, &a, &[1.0, 0.0]), Some(0.0));
        assert_eq!(leaves(&circle, &a, &[1.0, 1e-17]), Some(1e-17));
        // At rest at the wall: it stays.
        assert_eq!(leaves(&circle, &a, &[0.0, 0.0]), None);
        // A wall or a sphere seen from outside is never left this way.
        let wall = Shape::Wall {
            point: [0.0, 0.0],
            normal: [0.0, 1.0],
        };
        assert_eq!(leaves(&wall, &[0.0, 0.5], &[1.0, 0.0]), None);
        let sphere = Shape::Sphere {
            centre: [0.0, 0.0],
            radius: 1.0,
        };
        assert_eq!(leaves(&sphere, &[0.0, 1.5], &[1.0, 1.0]), None);
    }

    #[test]
    fn the_message_names_the_ball_the_place_and_the_cure() {
        let left = LeftTable {
            ball: 3,
            boundary: 1,
            time: 0.25,
            outward_speed: 0.0,
        };
        let m = left.message("container[0]");
        for part in [
            "ball 3",
            "through container[0]",
            "t = 0.25",
            "raise e",
            "[contact] tc",
        ] {
            assert!(m.contains(part), "{part} in {m}");
        }
        assert!(left.to_string().contains("boundary 1 (a container)"));
    }
}
