//! Queue entries: one ball's earliest predicted event, ordered by time (earliest first).

use std::cmp::Ordering;

/// What ball `ball` will meet.
#[derive(Clone, Copy, Debug)]
pub(crate) enum What<const N: usize> {
    /// Ball `j` as of `j`'s counter `count`, its image named in unwrapped coordinates: the
    /// cell shift `s` (box lengths on periodic axes) minus `j`'s wrap counters plus the
    /// owner's, modulo 256 (see the engine's image rule).
    Ball {
        j: u32,
        count: u32,
        shift: [i8; N],
    },
    /// Obstacle `o` shifted by `shift_k L_k` (the owner does not wrap while this is pending).
    Obstacle {
        o: u32,
        shift: [i8; N],
    },
    Wall {
        axis: u8,
        upper: bool,
    },
    /// Boundary `b` of the table (it never moves).
    Boundary {
        b: u32,
    },
    /// The boundary of its cell along `axis`, moving `up` or down.
    Cell {
        axis: u8,
        up: bool,
    },
}

#[derive(Clone, Copy, Debug)]
pub(crate) struct Entry<const N: usize> {
    pub time: f64,
    pub ball: u32,
    /// The ball's collision counter when this was predicted.
    pub count: u32,
    pub what: What<N>,
}

impl<const N: usize> PartialEq for Entry<N> {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl<const N: usize> Eq for Entry<N> {}

impl<const N: usize> PartialOrd for Entry<N> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl<const N: usize> Ord for Entry<N> {
    /// Reversed, so that `BinaryHeap` pops the earliest; ties by ball index (deterministic).
    fn cmp(&self, other: &Self) -> Ordering {
        other
            .time
            .total_cmp(&self.time)
            .then(other.ball.cmp(&self.ball))
            .then(other.count.cmp(&self.count))
    }
}
