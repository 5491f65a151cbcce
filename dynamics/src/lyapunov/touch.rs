//! The engine's contacts as the tangent map needs them: which balls, and the contact surface.
//! This is the one place that knows the engine's contact kinds: a new boundary kind of the
//! engine is one arm here (its [`Geometry`]) and, if it has a law of its own, one in
//! [`crate::law`].

use crate::geometry::Geometry;
use noslip_sim::{Contact, FixedBall};

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

/// The [`Touch`] of an engine contact; `radius(i)` is ball `i`'s radius.
pub fn touch<const N: usize>(
    contact: &Contact,
    radius: impl Fn(usize) -> f64,
    obstacles: &[FixedBall<N>],
) -> Touch {
    match *contact {
        Contact::Ball { i, j } => Touch::Pair {
            i,
            j,
            geometry: Geometry::Pair {
                sigma: radius(i) + radius(j),
            },
        },
        Contact::Wall { i, .. } => Touch::Boundary {
            ball: i,
            geometry: Geometry::Flat,
        },
        Contact::Obstacle { i, obstacle } => Touch::Boundary {
            ball: i,
            geometry: Geometry::Convex {
                r_eff: obstacles[obstacle].radius + radius(i),
            },
        },
    }
}

/// The contact with its pair ordered (`i < j`), for comparing two runs' contact sequences.
pub fn unordered(contact: &Contact) -> Contact {
    match *contact {
        Contact::Ball { i, j } if j < i => Contact::Ball { i: j, j: i },
        c => c,
    }
}
