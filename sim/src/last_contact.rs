//! What a ball last touched, and the contacts that rule out: a contact cannot repeat at once.
//!
//! Right after a contact the two bodies separate or slide (the normal part of the contact
//! point's relative velocity is `-e` times what it was, so at least 0 in exact arithmetic).
//! In floats a rounding residue of that normal velocity, `1e-17` against velocities of order
//! 1, can point inwards, and a prediction then finds the same pair touching again at zero
//! flight time. Where the law changes no bit of the states at such a residue (the smooth
//! member of the TC model, `beta = -1`, `e = 0` at a normal velocity that rounds to 0), the
//! same contact would repeat forever at one time. Both engines (the cell engine and the
//! all-pairs reference) therefore refuse these repeats, by the same rules, so their logs stay
//! the same bytes:
//!
//! - **Two balls** `i`, `j` whose last contacts were with each other (neither has had another
//!   since, so neither velocity has changed) never meet again at the image where they touched:
//!   the normal part of their centres' relative velocity (the contact point's: a spin adds
//!   only tangential velocity) was left at least 0, so `|d + t dv|^2` is convex in `t` with a
//!   slope of at least 0 from the contact on. A rounding residue makes such a pair look
//!   approaching while it still touches, overlapping by an ulp or within one; the residue
//!   cannot bring it closer than that. So their contact at an image is refused while, at
//!   `t_ref = max(t_i, t_j)`, they touch there: `|d|^2 <= sigma^2 (1 + 2^-26)`
//!   ([`LastContact::repeats_pair`], [`touching`]; an ulp of overlap is `2^-52`). Another
//!   image is at least `L_k - sigma` away, so it is never refused in a box whose periodic
//!   sides exceed `2 sigma (1 + 2^-27)`; in a narrower one a ball touching two images of its
//!   last partner at one instant would have the second contact refused (a measure-zero
//!   coincidence, not guarded). A pair's first zero-flight repeat used to come at once
//!   (`t_ref`), later ones an ulp or two apart, each within the overlap: the distance, not
//!   the time, tells them apart.
//! - **A ball and obstacle** `o` it touched last: the same argument (a sphere, convex, and a
//!   normal velocity left at least 0), so the obstacle at that image is refused while the
//!   ball touches it there at its record's time, `|d|^2 <= sigma^2 (1 + 2^-26)`
//!   ([`LastContact::repeats_obstacle`]). At `e = 0` with a smooth tangential law a ball in
//!   the Sinai table used to repeat its obstacle contact forever (`t = 0.219265`).
//! - **A ball and table boundary** `b` it touched last: a boundary convex seen from the ball
//!   cannot be met again before another contact, a container not at the same instant
//!   ([`LastContact::repeats_boundary`]).
//!
//! Box walls have no rule: their normals are coordinate axes, and a one-ball box at `e = 0`
//! showed no repeat (measured, not proved for every law). Contacts that alternate between
//! partners at one instant (a ball pressed into a corner of the box by another at `e = 0`,
//! three balls left touching) are not repeats of one contact and pass these rules; the run
//! loop stops them ([`crate::collapse`]).

/// The tag of a ball partner: the high bit.
const BALL: u32 = 1 << 31;

/// The tag of an obstacle: the next bit (boundaries are `b + 1 < 2^30`).
const OBSTACLE: u32 = 1 << 30;

/// Ball `i`'s last contact, as far as a repeat matters (module docs): a ball, a table
/// boundary, or anything else (none yet, a wall, an obstacle, a kick).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct LastContact(u32);

impl LastContact {
    /// None that rules out a repeat: no contact yet, a wall, an obstacle, a kick.
    pub(crate) const NONE: LastContact = LastContact(0);

    /// Table boundary `b`.
    #[inline]
    pub(crate) fn boundary(b: usize) -> Self {
        debug_assert!(b + 1 < OBSTACLE as usize, "boundary index in range");
        LastContact(b as u32 + 1)
    }

    /// Obstacle `o`.
    #[inline]
    pub(crate) fn obstacle(o: usize) -> Self {
        debug_assert!(o < OBSTACLE as usize, "obstacle index in range");
        LastContact(OBSTACLE | o as u32)
    }

    /// Whether a contact with obstacle `o` is a repeat to refuse (module docs): this is `o`,
    /// and at the ball's record time it touches the obstacle's image, `offset` the centres'
    /// difference there (evaluated only if this is `o`) and `sigma` the contact distance.
    #[inline]
    pub(crate) fn repeats_obstacle<const N: usize>(
        self,
        o: usize,
        offset: impl FnOnce() -> [f64; N],
        sigma: f64,
    ) -> bool {
        self == LastContact::obstacle(o) && touching(&offset(), sigma)
    }

    /// Ball `j`.
    #[inline]
    pub(crate) fn ball(j: usize) -> Self {
        debug_assert!(j < BALL as usize, "ball index in range");
        LastContact(BALL | j as u32)
    }

    /// Whether this is ball `j`.
    #[inline]
    pub(crate) fn is_ball(self, j: usize) -> bool {
        self == LastContact::ball(j)
    }

    /// Whether a contact with boundary `b` at flight time `tau` (from the ball's record) is a
    /// repeat to refuse: the last contact was with `b` and `b` is convex seen from the ball,
    /// or `tau` is 0.
    #[inline]
    pub(crate) fn repeats_boundary(self, b: usize, convex: bool, tau: f64) -> bool {
        self == LastContact::boundary(b) && (convex || tau == 0.0)
    }

    /// Whether a contact of balls `i` and `j` is a repeat to refuse (module docs): `last_i`
    /// is `j`, `last_j` is `i`, and at `t_ref` the pair touches at the contact's image,
    /// `offset` its centres' difference there (`crate::canonical::pair_offset`) and `sigma`
    /// their contact distance. `last_j` and `offset` are evaluated only if what comes before
    /// holds (the partner's record, and the offset, are then read).
    #[inline]
    pub(crate) fn repeats_pair<const N: usize>(
        (i, last_i): (usize, LastContact),
        (j, last_j): (usize, impl FnOnce() -> LastContact),
        offset: impl FnOnce() -> [f64; N],
        sigma: f64,
    ) -> bool {
        last_i.is_ball(j) && last_j().is_ball(i) && touching(&offset(), sigma)
    }
}

/// Whether centres `d` apart touch or overlap at contact distance `sigma`, up to a relative
/// `2^-26` of `sigma^2`: `sum_k d_k^2 <= sigma^2 (1 + 2^-26)` (module docs).
#[inline]
pub(crate) fn touching<const N: usize>(d: &[f64; N], sigma: f64) -> bool {
    let d2: f64 = d.iter().map(|x| x * x).sum();
    d2 <= sigma * sigma * (1.0 + f64::EPSILON * (1u64 << 26) as f64)
}

#[cfg(test)]
mod tests {
    use super::LastContact;

    #[test]
    fn a_pair_repeats_only_while_touching_and_only_between_each_others_last() {
        let (a, b) = (LastContact::ball(7), LastContact::ball(3));
        // Touching (an ulp of overlap, or a relative 2^-27 apart): refused.
        let touch = || [0.6, 0.8 * (1.0 - f64::EPSILON)];
        let near = || [0.6, 0.8 * (1.0 + f64::EPSILON * (1u64 << 26) as f64 / 4.0)];
        assert!(LastContact::repeats_pair((3, a), (7, || b), touch, 1.0));
        assert!(LastContact::repeats_pair((3, a), (7, || b), near, 1.0));
        // Apart (another image, or slid away): allowed.
        let apart = || [0.6, 0.8 + 1e-7];
        assert!(!LastContact::repeats_pair((3, a), (7, || b), apart, 1.0));
        assert!(!LastContact::repeats_pair(
            (3, a),
            (7, || b),
            || [3.0, 0.0],
            1.0
        ));
        // Ball 7 has touched something else since: allowed.
        for other in [
            LastContact::NONE,
            LastContact::ball(4),
            LastContact::boundary(3),
        ] {
            assert!(!LastContact::repeats_pair(
                (3, a),
                (7, || other),
                touch,
                1.0
            ));
        }
        // Ball 3 has: allowed, and neither ball 7's record nor the offset is read.
        let unread = || -> LastContact { panic!("read") };
        let no_offset = || -> [f64; 2] { panic!("read") };
        assert!(!LastContact::repeats_pair(
            (3, LastContact::NONE),
            (7, unread),
            no_offset,
            1.0
        ));
        // A boundary index equal to the ball's is not the ball.
        assert!(!LastContact::boundary(7).is_ball(7));
        assert!(!LastContact::NONE.is_ball(0));
    }

    #[test]
    fn a_boundary_repeats_if_convex_or_at_once() {
        let last = LastContact::boundary(2);
        assert!(last.repeats_boundary(2, true, 1.0));
        assert!(last.repeats_boundary(2, false, 0.0));
        assert!(!last.repeats_boundary(2, false, 1e-300));
        assert!(!last.repeats_boundary(1, true, 0.0));
        assert!(!LastContact::ball(2).repeats_boundary(2, true, 0.0));
        assert!(!LastContact::obstacle(2).repeats_boundary(2, true, 0.0));
    }

    #[test]
    fn an_obstacle_repeats_only_while_touching_and_only_if_last() {
        let last = LastContact::obstacle(5);
        let touch = || [0.0, 1.0 - f64::EPSILON];
        assert!(last.repeats_obstacle(5, touch, 1.0));
        assert!(!last.repeats_obstacle(5, || [0.0, 2.0], 1.0));
        assert!(!last.repeats_obstacle(4, touch, 1.0));
        let unread = || -> [f64; 2] { panic!("read") };
        for other in [
            LastContact::NONE,
            LastContact::ball(5),
            LastContact::boundary(5),
        ] {
            assert!(!other.repeats_obstacle(5, unread, 1.0));
        }
    }
}
