//! What the list engine keeps per ball that its own events read and write ([`Own`]); what a
//! neighbour's prediction reads of it is the cell engine's [`crate::residents::Resident`]
//! (its flight record, its wraps `W_j` and its counter `count_j`), in one array by ball.

use crate::canonical::{key, kind, pair_key, Key};
use crate::last_contact::LastContact;
use crate::queue::{Slot, Slots};
use collision_core::BodyState;

/// A ball's pending event.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Next<const N: usize> {
    /// The contact with the ball in slot `j` (its index `id`) as of its counter `count`, at
    /// image `image` (box lengths, in the owner's record coordinates).
    Ball {
        j: u32,
        id: u32,
        count: u32,
        image: [i16; N],
    },
    /// The box wall of `axis` (at `L_k` if `upper`).
    Wall { axis: u8, upper: bool },
    /// Leaving its shell: the shell is drawn again ([`super::shells`]).
    Shell,
}

/// What a ball's own events read and write, in its slot (`crate::lists`, "Slots").
#[derive(Clone, Debug)]
pub(super) struct Own<const N: usize, const S: usize> {
    /// The ball's index (the setup's and the log's).
    pub id: u32,
    /// Its pending event's time and place in the calendar.
    pub slot: Slot,
    /// Its pending event.
    pub next: Option<Next<N>>,
    /// Its best contact found by its last predictions (`crate::lists::predict`), kept so
    /// that a new shell asks only the balls new to its list.
    pub found: Option<(f64, Next<N>)>,
    /// Its state `(U_i, u_i)`.
    pub state: BodyState<f64, N, S>,
    /// The absolute time of its last contact (`-inf` before the first), for the TC model.
    pub previous: f64,
    /// Its species.
    pub kind: u32,
    /// Its last contact, whose repeat while still touching is refused
    /// ([`crate::last_contact`]).
    pub last: LastContact,
}

/// The key of the event `next` of the ball of index `i` ([`crate::canonical::key`]: by the
/// balls' indices, not their slots); leaving a shell moves no record, and is keyed as the cell
/// engine's crossings are (the last kind).
#[inline]
pub(super) fn key_of<const N: usize>(i: usize, next: &Next<N>) -> Key {
    match *next {
        Next::Ball { id, image, .. } => pair_key(i, id as usize, &image),
        Next::Wall { axis, upper } => key(
            i,
            kind::WALL,
            2 * u32::from(axis) + u32::from(upper),
            &[0; N],
        ),
        Next::Shell => key(i, kind::CELL, 0, &[0; N]),
    }
}

impl<const N: usize, const S: usize> Slots for [Own<N, S>] {
    #[inline]
    fn slot(&self, ball: usize) -> &Slot {
        &self[ball].slot
    }

    #[inline]
    fn slot_mut(&mut self, ball: usize) -> &mut Slot {
        &mut self[ball].slot
    }

    #[inline]
    fn key(&self, ball: usize) -> Key {
        let own = &self[ball];
        own.next
            .map_or(Key::MAX, |next| key_of(own.id as usize, &next))
    }
}
