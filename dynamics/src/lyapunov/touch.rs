//! The engine's contacts as the tangent map needs them: which balls, and the contact surface.
//! This is the one place that knows the engine's contact kinds: a new boundary kind of the
//! engine is one arm here (its [`Geometry`]) and, if it has a law of its own, one in
//! [`crate::law`].

use crate::geometry::Geometry;
use noslip_sim::Contact;

/// A contact of the engine, for the tangent map.
#[derive(Clone, Debug, PartialEq)]
pub enum Touch {
    /// Ball `ball` and an immovable boundary.
    Boundary {
        /// The ball's index.
        ball: usize,
        /// The boundary's contact surface.
        geometry: Geometry<f64>,
    },
    /// Balls `i` (body 1) and `j` (body 2).
    Pair {
        /// Body 1.
        i: usize,
        /// Body 2.
        j: usize,
        /// [`Geometry::Pair`] with `sigma = r_i + r_j`.
        geometry: Geometry<f64>,
    },
}

/// The [`Touch`] of an engine contact whose surface the engine reports as `surface`
/// ([`noslip_sim::Simulation::geometry`]); `radius(i)` is ball `i`'s radius. The centre of a
/// ball of radius `r` touching a sphere of radius `R` moves on a sphere of radius `R + r`
/// (from outside) or `R - r` (from inside): that is the radius whose curvature turns `nu`.
pub fn touch(
    contact: &Contact,
    surface: noslip_sim::Geometry,
    radius: impl Fn(usize) -> f64,
) -> Touch {
    use noslip_sim::Geometry as Surface;
    let boundary = |ball: usize| {
        let geometry = match surface {
            Surface::Flat => Geometry::Flat,
            Surface::Outside { radius: r } => Geometry::Convex {
                r_eff: r + radius(ball),
            },
            Surface::Inside { radius: r } => Geometry::Concave {
                r_eff: r - radius(ball),
            },
            Surface::Pair => unreachable!("a ball-ball contact has two balls"),
        };
        Touch::Boundary { ball, geometry }
    };
    match *contact {
        Contact::Ball { i, j } => Touch::Pair {
            i,
            j,
            geometry: Geometry::Pair {
                sigma: radius(i) + radius(j),
            },
        },
        Contact::Wall { i, .. } | Contact::Obstacle { i, .. } | Contact::Boundary { i, .. } => {
            boundary(i)
        }
    }
}

/// The contact with its pair ordered (`i < j`), for comparing two runs' contact sequences.
pub fn unordered(contact: &Contact) -> Contact {
    match *contact {
        Contact::Ball { i, j } if j < i => Contact::Ball { i: j, j: i },
        c => c,
    }
}
