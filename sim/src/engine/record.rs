//! A ball's records in one place: what an event of the ball reads and writes, gathered so
//! that it costs one cache miss at a million balls instead of one per array (the calendar's
//! slot, the event, the kept contact, the cell, the counter, each once a `Vec` of its own).
//!
//! **Layout.** `#[repr(C)]`, aligned to a cache line (64 bytes), the hot fields first: the
//! calendar's slot (`t_i` and its place, 16 bytes), the kept contact (its time and what it
//! is, 24), the cell (`4 n`), the counter `count_i`, the flight record's place in the cell
//! slab (4) and the pending crossing (2): 62 bytes in 3D, 58 in 2D, one line in both. A crossing, the most frequent event, reads and writes
//! only that line. The state `(U_i, u_i)`, the last boundary touched, the species and the
//! previous contact's time follow (a contact's reads): two lines a ball in 2D and 3D
//! (128 bytes, against 192 in the arrays before).
//!
//! **The pending event** is the earlier of the kept contact and the crossing (a crossing is
//! kept only when it beat the contact), so it is not stored twice; its key, which orders
//! the events of one time (`canonical::key`), is a function of the ball and the event
//! ([`key_of`]), computed when two times tie instead of stored (16 bytes a ball).

use crate::canonical::{key, kind, pair_key, Key};
use crate::last_contact::LastContact;
use crate::queue::{Slot, Slots, What};
use crate::residents::Homes;
use collision_core::BodyState;

/// Ball `i`'s records (module docs).
#[derive(Clone, Debug)]
#[repr(C, align(64))]
pub(super) struct BallRecord<const N: usize, const S: usize> {
    /// Its pending event's time and place in the calendar.
    pub slot: Slot,
    /// Its best contact (any event but a crossing) found by its last scans, kept so that a
    /// crossing scans only the newly reached cells (`scan.rs`).
    pub found: Option<(f64, What<N>)>,
    /// Its cell.
    pub cell: [u32; N],
    /// `count_i`: its contacts so far (its velocity changes only at them).
    pub count: u32,
    /// Its flight record's index in the slab (`residents.rs`, "Homes").
    pub home: u32,
    /// The crossing of its cell's face (axis, up) if that is its pending event, else `None`
    /// (the kept contact is).
    pub crossing: Option<(u8, bool)>,
    /// Its state `(U_i, u_i)`.
    pub state: BodyState<f64, N, S>,
    /// The absolute time of its last contact (`-inf` before the first), for the TC model
    /// ([`crate::law::tc_law`]).
    pub previous: f64,
    /// Its species.
    pub kind: u32,
    /// Its last contact (a ball, an obstacle or a table boundary), whose repeat while still
    /// touching is refused ([`crate::last_contact`]).
    pub last: LastContact,
}

impl<const N: usize, const S: usize> BallRecord<N, S> {
    /// A ball of species `kind` in cell `cell` with state `state`, no event yet.
    pub(super) fn new(state: BodyState<f64, N, S>, kind: usize, cell: [usize; N]) -> Self {
        BallRecord {
            slot: Slot::EMPTY,
            found: None,
            cell: cell.map(|c| c as u32),
            count: 0,
            home: u32::MAX,
            crossing: None,
            state,
            previous: f64::NEG_INFINITY,
            kind: kind as u32,
            last: LastContact::NONE,
        }
    }

    /// Its cell, as the grid's indices.
    #[inline]
    pub(super) fn cell(&self) -> [usize; N] {
        self.cell.map(|c| c as usize)
    }

    /// Its pending event: the crossing if it has one, else the kept contact.
    #[inline]
    pub(super) fn next(&self) -> Option<What<N>> {
        match self.crossing {
            Some((axis, up)) => Some(What::Cell { axis, up }),
            None => self.found.map(|(_, what)| what),
        }
    }
}

/// The key of ball `i`'s event `what` ([`crate::canonical::key`]): its lowest ball, kind,
/// other body and image (a pair's image as seen from its lower ball, `-k` from the higher).
#[inline]
pub(super) fn key_of<const N: usize>(i: usize, what: &What<N>) -> Key {
    match *what {
        What::Ball { j, image, .. } => pair_key(i, j as usize, &image),
        What::Obstacle { o, image } => key(i, kind::OBSTACLE, o, &image),
        What::Wall { axis, upper } => key(
            i,
            kind::WALL,
            2 * u32::from(axis) + u32::from(upper),
            &[0; N],
        ),
        What::Boundary { b } => key(i, kind::BOUNDARY, b, &[0; N]),
        What::Cell { axis, up } => key(i, kind::CELL, 2 * u32::from(axis) + u32::from(up), &[0; N]),
    }
}

impl<const N: usize, const S: usize> Slots for [BallRecord<N, S>] {
    #[inline]
    fn slot(&self, ball: usize) -> &Slot {
        &self[ball].slot
    }

    #[inline]
    fn slot_mut(&mut self, ball: usize) -> &mut Slot {
        &mut self[ball].slot
    }

    /// The key of ball `ball`'s pending event (only balls with one are in the calendar).
    #[inline]
    fn key(&self, ball: usize) -> Key {
        self[ball]
            .next()
            .map_or(Key::MAX, |what| key_of(ball, &what))
    }
}

impl<const N: usize, const S: usize> Homes for [BallRecord<N, S>] {
    #[inline]
    fn home(&self, ball: usize) -> u32 {
        self[ball].home
    }

    #[inline]
    fn set_home(&mut self, ball: usize, at: u32) {
        self[ball].home = at;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ball_s_hot_fields_share_one_cache_line_in_2d_and_3d() {
        // The calendar's slot, the kept contact, the cell, the counter, the home and the
        // crossing: the offset just past the crossing is at most 64, and a record starts on
        // a line.
        fn hot_end<const N: usize, const S: usize>() -> usize {
            std::mem::offset_of!(BallRecord<N, S>, crossing)
                + std::mem::size_of::<Option<(u8, bool)>>()
        }
        assert!(hot_end::<2, 1>() <= 64, "2D: {}", hot_end::<2, 1>());
        assert!(hot_end::<3, 3>() <= 64, "3D: {}", hot_end::<3, 3>());
        assert_eq!(std::mem::align_of::<BallRecord<3, 3>>(), 64);
        assert_eq!(std::mem::size_of::<BallRecord<2, 1>>(), 128);
        assert_eq!(std::mem::size_of::<BallRecord<3, 3>>(), 128);
    }

    #[test]
    fn a_pair_s_key_is_the_same_from_either_ball() {
        // Ball 3 sees ball 7 at image k; ball 7 sees ball 3 at -k: one event, one key.
        let from_3 = What::<3>::Ball {
            j: 7,
            count: 0,
            image: [1, 0, -2],
        };
        let from_7 = What::<3>::Ball {
            j: 3,
            count: 5,
            image: [-1, 0, 2],
        };
        assert_eq!(key_of(3, &from_3), key_of(7, &from_7));
        assert_eq!(key_of(3, &from_3), key(3, kind::BALL, 7, &[1, 0, -2]));
    }
}
