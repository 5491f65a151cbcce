//! What the engine reports: a contact's bodies ([`Contact`]), the contact with the states
//! around it ([`Event`]), what a step found ([`Step`]), and the setups it refuses
//! ([`SetupError`]).

use crate::left_table::LeftTable;
use crate::no_contact::NoContact;
use collision_core::BodyState;
use std::fmt;

/// A contact: ball-ball (`i` is body 1), ball-wall or ball-obstacle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Contact {
    /// Two balls.
    Ball {
        /// Body 1's ball index.
        i: usize,
        /// Body 2's ball index.
        j: usize,
    },
    /// A ball and a wall.
    Wall {
        /// The ball's index.
        i: usize,
        /// The wall's axis `k`.
        axis: usize,
        /// The wall at `x_k = L_k` if `true`, at `x_k = 0` if `false`.
        upper: bool,
    },
    /// A ball and a fixed ball obstacle.
    Obstacle {
        /// The ball's index.
        i: usize,
        /// The obstacle's index in [`Setup::obstacles`](crate::Setup::obstacles).
        obstacle: usize,
    },
    /// A ball and a boundary of the table besides the box and the obstacles: a wall, a
    /// container, a polygon obstacle's edge or vertex ([`crate::table`]).
    Boundary {
        /// The ball's index.
        i: usize,
        /// The boundary's id, its index in [`crate::Table::boundaries`].
        boundary: usize,
    },
}

impl Contact {
    /// The contact's balls in the order of an [`Event`]'s indices: `i` then `j` for two balls,
    /// the lone ball for an immovable body (enumerated, each ball's index in `Event::pre`,
    /// `post` and `position`).
    pub fn balls(&self) -> impl Iterator<Item = usize> {
        let (first, second) = match *self {
            Contact::Ball { i, j } => (i, Some(j)),
            Contact::Wall { i, .. } | Contact::Obstacle { i, .. } | Contact::Boundary { i, .. } => {
                (i, None)
            }
        };
        std::iter::once(first).chain(second)
    }
}

/// One contact with the states around it. Index 0 is ball `i`, index 1 ball `j` of a
/// ball-ball contact (for a wall or an obstacle, index 1 repeats index 0). `nu` is the unit
/// normal from body 1 (ball `i`, the wall or the obstacle) to body 2 (ball `j`, or ball `i`).
#[derive(Clone, Debug, PartialEq)]
pub struct Event<const N: usize, const S: usize> {
    /// The simulated time of the contact.
    pub time: f64,
    /// Which bodies touch.
    pub contact: Contact,
    /// The unit contact normal `nu`, from body 1 to body 2.
    pub nu: [f64; N],
    /// The centres `a` of index 0 and index 1 at `time`.
    pub position: [[f64; N]; 2],
    /// The states `(U, u)` of index 0 and index 1 before the contact.
    pub pre: [BodyState<f64, N, S>; 2],
    /// The states `(U, u)` of index 0 and index 1 after the contact.
    pub post: [BodyState<f64, N, S>; 2],
}

#[cfg(test)]
impl Event<2, 1> {
    /// A 2D contact at `time` for the tests of what reads events: `nu = e_x`, both centres at
    /// the origin, no spin, the velocity `u` before and after.
    pub(crate) fn at_rest_but(time: f64, contact: Contact, u: [f64; 2]) -> Self {
        let s = BodyState {
            spin: [0.0],
            velocity: u,
        };
        Event {
            time,
            contact,
            nu: [1.0, 0.0],
            position: [[0.0; 2]; 2],
            pre: [s.clone(), s.clone()],
            post: [s.clone(), s],
        }
    }
}

/// What [`Simulation::step`](crate::Simulation::step) found.
#[derive(Clone, Debug, PartialEq)]
pub enum Step<const N: usize, const S: usize> {
    /// The next contact.
    Contact(Event<N, S>),
    /// No contact at or before `until`; the clock is at `until`.
    Until,
    /// No contact will happen again (the clock is at `until` if that is finite, else where it
    /// was found out).
    Never(NoContact),
    /// The run cannot go on: a ball left the table through a container after its last
    /// contact (that contact was the last [`Step::Contact`]; the state stays as it was then,
    /// and stepping again returns this again). See [`crate::left_table`].
    LeftTable(LeftTable),
    /// A notice, not an end: no contact yet while every moving ball travelled `box_lengths`
    /// times the longest box side since the last contact (first at
    /// [`QUIET_BOX_LENGTHS`](crate::no_contact::QUIET_BOX_LENGTHS), then at twice, four times
    /// ... that). Contacts may still come (a flight nearly along a corridor of a periodic
    /// table); stepping again goes on.
    Quiet {
        /// The distance every moving ball travelled since the last contact, in longest box
        /// sides.
        box_lengths: f64,
    },
}

/// A setup the engine cannot run; each variant names the place.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum SetupError {
    /// Box side `axis` is not positive and finite.
    BoxSize {
        /// The axis `k`.
        axis: usize,
        /// The side `L_k` given.
        size: f64,
    },
    /// Ball `ball` names species `species`, which does not exist.
    Species {
        /// The ball's index.
        ball: usize,
        /// The species index it names.
        species: usize,
    },
    /// Ball `ball` is outside the box along `axis`.
    Outside {
        /// The ball's index.
        ball: usize,
        /// The axis `k` along which it is outside.
        axis: usize,
    },
    /// Periodic box side `axis` is shorter than half the largest contact distance `d_max`:
    /// a body would touch more than two images of another.
    ShortSide {
        /// The periodic axis `k`.
        axis: usize,
        /// The side `L_k`.
        size: f64,
        /// The largest contact distance, a sum of two radii (ball-ball or ball-obstacle).
        d_max: f64,
    },
}

impl fmt::Display for SetupError {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        match self {
            SetupError::BoxSize { axis, .. } => write!(f, "box size {axis} must be positive"),
            SetupError::Species { ball, species } => {
                write!(
                    f,
                    "ball {ball} names species {species}, which does not exist"
                )
            }
            SetupError::Outside { ball, axis } => {
                write!(f, "ball {ball} is outside the box along axis {axis}")
            }
            SetupError::ShortSide { axis, size, d_max } => write!(
                f,
                "box side {axis} ({size}) is shorter than half the largest contact distance \
                 ({d_max}): a body would touch more than two images of another"
            ),
        }
    }
}

impl std::error::Error for SetupError {}
