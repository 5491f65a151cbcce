//! The engines' local clock: its origin, and when it is re-based (`crate::canonical`).
//!
//! Times are kept on a local clock whose origin, an absolute time, is kept as a compensated
//! sum `origin + origin_low`, and moved forward ("re-based") at the canonical time
//! `T = sqrt(span^2 / v^2)` ([`rebase_at`]): `span` from the cell rule's narrowest cell, `v^2`
//! a bound of the squared speeds, exact at the last re-basing and raised at each contact
//! (which may bring `T` before the contact's own time: the engine then re-bases there). The
//! cell engine and the list engine keep one each; the all-pairs reference of the tests keeps
//! its own fields, to share with them only the definitions of `crate::canonical`.

use crate::canonical::{moved_origin, rebase_at};

/// A local clock's origin and re-basing rule (module docs).
#[derive(Clone, Debug)]
pub(crate) struct Clock {
    origin: f64,
    origin_low: f64,
    /// An upper bound of `|u_i|^2` (exact at the last re-basing).
    speed2: f64,
    /// `(CLOCK_CELLS w_min)^2` ([`crate::canonical::clock_span2`]).
    span2: f64,
    /// The local time of the next re-basing.
    rebase_at: f64,
    /// Re-basings in a row without a contact.
    quiet: u32,
    /// Whether an axis is periodic (the re-basing interval then never grows).
    periodic: bool,
}

impl Clock {
    /// A clock at absolute time 0 for balls of velocities `velocities` (their squared speeds
    /// summed over the axes in order, as the engines' `speed2_of`).
    pub(crate) fn start<'a, const N: usize>(
        span2: f64,
        velocities: impl IntoIterator<Item = &'a [f64; N]>,
        periodic: bool,
    ) -> Self {
        let speed2 = velocities
            .into_iter()
            .map(|u| u.iter().map(|x| x * x).sum())
            .fold(0.0, f64::max);
        Self::new(span2, speed2, periodic)
    }

    /// A clock at absolute time 0 for balls whose squared speeds are at most `speed2`.
    fn new(span2: f64, speed2: f64, periodic: bool) -> Self {
        Clock {
            origin: 0.0,
            origin_low: 0.0,
            speed2,
            span2,
            rebase_at: rebase_at(span2, speed2, 0, periodic),
            quiet: 0,
            periodic,
        }
    }

    /// The absolute time of local time `local`.
    #[inline]
    pub(crate) fn absolute(&self, local: f64) -> f64 {
        self.origin + (self.origin_low + local)
    }

    /// The local time of absolute time `absolute`.
    #[inline]
    pub(crate) fn local(&self, absolute: f64) -> f64 {
        (absolute - self.origin) - self.origin_low
    }

    /// The local time of the next re-basing.
    #[inline]
    pub(crate) fn rebase_at(&self) -> f64 {
        self.rebase_at
    }

    /// After a contact at local time `t` that gave balls the squared speeds `speed2`: the
    /// bound raised and the re-basing time found again; whether `t` is past it (the engine
    /// then re-bases at `t`).
    #[inline]
    pub(crate) fn contact(&mut self, speed2: impl IntoIterator<Item = f64>, t: f64) -> bool {
        for v2 in speed2 {
            self.speed2 = self.speed2.max(v2);
        }
        self.quiet = 0;
        self.rebase_at = rebase_at(self.span2, self.speed2, 0, self.periodic);
        t > self.rebase_at
    }

    /// Re-based at local time `t`, the squared speeds now at most `speed2` (exact); `quiet`:
    /// no contact since the last re-basing. Local times after are `t` less.
    pub(crate) fn rebase(&mut self, t: f64, quiet: bool, speed2: f64) {
        (self.origin, self.origin_low) = moved_origin(self.origin, self.origin_low, t);
        self.speed2 = speed2;
        self.quiet = if quiet { self.quiet + 1 } else { 0 };
        self.rebase_at = rebase_at(self.span2, speed2, self.quiet, self.periodic);
    }
}
