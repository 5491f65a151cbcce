//! Canonical contact times: every contact time is a function of the flight records of the
//! bodies that meet, never of when or by whom it was predicted, so that any correct engine
//! (the cell engine of [`crate::engine`], the all-pairs reference of the tests) computes the
//! same bits, takes the same contacts in the same order and writes the same event log, byte
//! for byte (docs/engine.md, "Canonical contact times").
//!
//! **Records.** Ball `i`'s record ([`Motion`]) is its centre `a_i` at local time `t_i`, its
//! velocity `u_i` and radius `R_i`. A record moves only at a contact of `i` (to the contact's
//! time) and at a re-basing of the clock (every record, to the re-basing's time); there its
//! centre is folded into the box on periodic axes ([`fold`]). Cell crossings and periodic
//! wraps do not move it: between record moves an engine may count the wraps `W_i` so that the
//! centre in the box is `a_i + (t - t_i) u_i - W_i L`.
//!
//! **Images.** A partner or obstacle is named with its image `k` in `Z^n`, in box lengths, in
//! record coordinates: ball `j`'s image `k` is `a_j + k L` on the clock of `j`'s record.
//!
//! **Pair time** ([`pair_time`]). For balls `i` and `j` and an image `k` of `j`:
//! `t_ref = max(t_i, t_j)`, `p_i = a_i + (t_ref - t_i) u_i` (and `p_j`),
//! `d = (p_j - p_i) + k L`, `dv = u_j - u_i`, `sigma = R_i + R_j`, and the time is
//! `t_ref + tau(d, dv, sigma)`, `tau` the earlier root of [`crate::predict::contact_time`]:
//! the same bits from `(j, i, -k)`. At the contact, body 1 is the lower index.
//!
//! **Fixed bodies.** An obstacle at centre `c` and image `k`: `d = (c + k L) - a_i`,
//! `dv = -u_i`, time `t_i + tau` ([`obstacle_time`]). A box wall or a table boundary: the
//! time the record's flight from `a_i` at `t_i` meets it, plus `t_i`.
//!
//! **Order** ([`Key`]). Events are taken in the order of `(t, key)`: the key orders the
//! events of one time by their lowest ball, then their kind (ball, wall, obstacle, boundary),
//! then the other body (the higher ball, the wall's side, the obstacle, the boundary), then
//! the image. A cell crossing (an engine's own event, moving no record) is keyed the same
//! way, its kind last: it comes after its own ball's contacts of its time, and among the
//! other balls' by its ball; since it moves no record, where it falls changes no contact.
//!
//! **Re-basing.** The clock is re-based at local time `T = sqrt(span^2 / v^2)` ([`rebase_at`]):
//! `span` is a number of the narrowest cell widths of the grid rule (`crate::cells`), `v^2`
//! the bound of the squared speeds, exact at the last re-basing and raised at each contact;
//! a contact whose time is already past the lowered `T` re-bases at its own time. Before any
//! event later than `T` every record moves to `T`, the clock restarts at 0, and every event is
//! predicted again. A table without a periodic axis may have its next contact arbitrarily far
//! ahead (a ball leaving an open wedge almost along its wall) with no event in between: after
//! [`QUIET_REBASES`] re-basings in a row without a contact each interval doubles, so such a
//! flight takes a logarithmic number of re-basings, not one per span (on a periodic axis the
//! interval stays, to bound the wraps `W_i` between record moves).

use crate::motion::Motion;
use crate::predict::{contact_time, contact_time_or_nan};

/// The time at which balls `a` and `b` meet, `b` at image `image` (box lengths, whole
/// numbers; module docs); NaN if they never do. `size` is the box (its sides `L_k`; images
/// are 0 on walled axes). The offset is spelled `(q - p) + k L`, so that
/// `pair_time(b, a, -k)` is the same number, bit for bit: IEEE rounding is symmetric, every
/// sign flips and the contact time's dot products do not see it. An engine need not order
/// the pair to get the canonical time.
#[inline]
pub(crate) fn pair_time<const N: usize>(
    a: &Motion<N>,
    b: &Motion<N>,
    image: &[f64; N],
    size: &[f64; N],
) -> f64 {
    let t_ref = a.since.max(b.since);
    let d = pair_offset(a, b, image, size, t_ref);
    let dv: [f64; N] = std::array::from_fn(|k| b.velocity[k] - a.velocity[k]);
    t_ref + contact_time_or_nan(&d, &dv, a.radius + b.radius)
}

/// The offset `(p_b - p_a) + k L` of balls `a` and `b` (`b` at image `image`) at local time
/// `t`, the centres flown there: the difference [`pair_time`] solves from, and along which the
/// contact's normal lies (the caller normalises it).
#[inline]
pub(crate) fn pair_offset<const N: usize>(
    a: &Motion<N>,
    b: &Motion<N>,
    image: &[f64; N],
    size: &[f64; N],
    t: f64,
) -> [f64; N] {
    let (p, q) = (a.at(t), b.at(t));
    std::array::from_fn(|k| (q[k] - p[k]) + image[k] * size[k])
}

/// An image as whole numbers of box lengths in `f64` (exact).
#[inline]
pub(crate) fn image_f64<const N: usize>(image: &[i16; N]) -> [f64; N] {
    image.map(f64::from)
}

/// Obstacle `centre`, radius `radius`, at image `image`: the time ball `m` meets it (module
/// docs), or `None`.
#[inline]
pub(crate) fn obstacle_time<const N: usize>(
    m: &Motion<N>,
    centre: &[f64; N],
    radius: f64,
    image: &[i16; N],
    size: &[f64; N],
) -> Option<f64> {
    let d = obstacle_offset(m, centre, image, size);
    let dv: [f64; N] = std::array::from_fn(|k| -m.velocity[k]);
    contact_time(&d, &dv, m.radius + radius).map(|tau| m.since + tau)
}

/// Obstacle `centre` at image `image` less ball `m`'s record centre, `(c + k L) - a_i`: the
/// difference [`obstacle_time`] solves from.
#[inline]
pub(crate) fn obstacle_offset<const N: usize>(
    m: &Motion<N>,
    centre: &[f64; N],
    image: &[i16; N],
    size: &[f64; N],
) -> [f64; N] {
    let b = obstacle_image(centre, image, size);
    std::array::from_fn(|k| b[k] - m.pos[k])
}

/// An obstacle's centre at image `image`: `c + k L`.
#[inline]
pub(crate) fn obstacle_image<const N: usize>(
    centre: &[f64; N],
    image: &[i16; N],
    size: &[f64; N],
) -> [f64; N] {
    std::array::from_fn(|k| centre[k] + f64::from(image[k]) * size[k])
}

/// A centre folded into the box on the periodic axes: `x - floor(x / L) L` (in `[0, L]`,
/// `L` itself only by rounding), other axes unchanged.
///
/// A coordinate in `(0, L)` (most of them: a contact rarely happens across the box's side)
/// is returned as it is, without the division: there `x / L` rounds to a number in
/// `[0, 1)` (below 1 because `x <= L - ulp(L)` and the doubles below 1 are `2^-53` apart),
/// so the floor is `+0` and `x - 0 L = x`, the same bits. Zero itself takes the formula
/// (`-0` folds to `+0`).
#[inline]
pub(crate) fn fold<const N: usize>(
    x: &[f64; N],
    size: &[f64; N],
    periodic: &[bool; N],
) -> [f64; N] {
    std::array::from_fn(|k| {
        if periodic[k] && !(0.0 < x[k] && x[k] < size[k]) {
            x[k] - floor(x[k] / size[k]) * size[k]
        } else {
            x[k]
        }
    })
}

/// `floor(q)`, the same bits as [`f64::floor`] (signed zeros, infinities and NaN included),
/// without its library call on a baseline x86-64 (no `roundsd`): below `2^52` in magnitude
/// the truncation `t = q as i64` (exact), carrying `q`'s sign onto a zero, is `floor(q)`
/// unless it exceeds `q`, then `t - 1`; from `2^52` on (and for NaN) `q` is its own floor.
#[inline]
fn floor(q: f64) -> f64 {
    if q.abs() < 4_503_599_627_370_496.0 {
        let t = ((q as i64) as f64).copysign(q);
        if t > q {
            t - 1.0
        } else {
            t
        }
    } else {
        q
    }
}

/// The local clock is re-based when the fastest ball could have moved this many widths of
/// the narrowest cell on it (module docs). Then a ball wraps at most `CLOCK_CELLS + 1` times
/// between two moves of its record, so every image fits a [`key`].
pub(crate) const CLOCK_CELLS: f64 = 128.0;

/// `span^2` of the re-basing time: `(CLOCK_CELLS w_min)^2`, `w_min` the narrowest of the
/// grid rule's cell widths `width` (`crate::cells`).
#[inline]
pub(crate) fn clock_span2<const N: usize>(width: &[f64; N]) -> f64 {
    let w_min = width.iter().copied().fold(f64::INFINITY, f64::min);
    (CLOCK_CELLS * w_min).powi(2)
}

/// Re-basings in a row without a contact after which, on a table without a periodic axis,
/// each interval is twice the last (module docs).
pub(crate) const QUIET_REBASES: u32 = 8;

/// The local time of the next re-basing: `sqrt(span2 / speed2)` (infinite at rest); after
/// `quiet` re-basings without a contact, on a table without a periodic axis, that times
/// `2^(quiet - QUIET_REBASES)` (module docs).
#[inline]
pub(crate) fn rebase_at(span2: f64, speed2: f64, quiet: u32, periodic: bool) -> f64 {
    if speed2 <= 0.0 {
        return f64::INFINITY;
    }
    let base = (span2 / speed2).sqrt();
    if periodic || quiet <= QUIET_REBASES {
        base
    } else {
        base * 2f64.powi((quiet - QUIET_REBASES).min(1024) as i32)
    }
}

/// The clock's origin moved on by `t`: `(origin, low) + t` as a compensated sum (Knuth's
/// two-sum), so that absolute times `origin + (low + t_local)` stay exact to the last bits
/// over any number of re-basings.
#[inline]
pub(crate) fn moved_origin(origin: f64, low: f64, t: f64) -> (f64, f64) {
    let sum = origin + t;
    let b = sum - origin;
    let error = (origin - (sum - b)) + (t - b);
    (sum, low + error)
}

/// The largest contact distance of balls of radius at most `r_ball` and obstacles of radius
/// at most `r_obstacle`, the cell rule's `d_max` (at least the least positive `f64`).
#[inline]
pub(crate) fn d_max(r_ball: f64, r_obstacle: f64) -> f64 {
    (2.0 * r_ball)
        .max(r_ball + r_obstacle)
        .max(f64::MIN_POSITIVE)
}

/// The order of the events of one time (module docs): `(lowest ball, kind, other body,
/// image)` packed in a `u128`, compared as a number.
pub(crate) type Key = u128;

/// The canonical order of events: by time, then by key (module docs). Every engine takes its
/// events in this order (the cell engine's calendar and scan, the reference's heap and scan),
/// so exactly simultaneous events are taken alike. Times are never NaN here (`total_cmp`
/// orders them as `<` does, `-0` never occurs: a time is a record time `>= 0` plus a
/// flight `>= 0`).
#[inline]
pub(crate) fn order(a: (f64, Key), b: (f64, Key)) -> std::cmp::Ordering {
    a.0.total_cmp(&b.0).then(a.1.cmp(&b.1))
}

/// The event kinds, in their order at equal times.
pub(crate) mod kind {
    pub(crate) const BALL: u8 = 0;
    pub(crate) const WALL: u8 = 1;
    pub(crate) const OBSTACLE: u8 = 2;
    pub(crate) const BOUNDARY: u8 = 3;
    /// A cell crossing: after its ball's contacts of its time (the last kind).
    pub(crate) const CELL: u8 = 15;
}

/// The most `|k|` an image may have in a [`Key`] (10 bits an axis).
pub(crate) const MAX_IMAGE: i16 = 511;

/// The key of an event of ball `first` (the lowest ball of the event) of kind `kind` with
/// body `other` at image `image` (module docs). Bits: `first` (32), `kind` (4), `other` (32),
/// then 10 bits an axis for `k + 512` (60 bits for n <= 6).
#[inline]
pub(crate) fn key<const N: usize>(first: usize, kind: u8, other: u32, image: &[i16; N]) -> Key {
    debug_assert!(N <= 6 && image.iter().all(|k| k.abs() <= MAX_IMAGE));
    let mut packed: u128 = 0;
    for &k in image {
        packed = (packed << 10) | (k + 512) as u128;
    }
    packed <<= 10 * (6 - N as u32);
    ((first as u128) << 96) | (u128::from(kind) << 92) | (u128::from(other) << 60) | packed
}

/// The key of the contact of balls `i` and `j`, `j` at image `image` in `i`'s record
/// coordinates: [`key`] of its lower ball, with the image as seen from that ball (`-k` from
/// the higher), so that the pair's event has one key whichever ball holds it.
#[inline]
pub(crate) fn pair_key<const N: usize>(i: usize, j: usize, image: &[i16; N]) -> Key {
    let lo_image = if i < j { *image } else { image.map(|k| -k) };
    key(i.min(j), kind::BALL, i.max(j) as u32, &lo_image)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floor_gives_the_library_floor_s_bits() {
        let two52 = 4_503_599_627_370_496.0_f64;
        let mut cases = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.0,
            -1.0,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
            5e-324,
            -5e-324,
            two52,
            -two52,
            two52 - 0.5,
            -(two52 - 0.5),
            two52 * 2.0 + 2.0,
            f64::MAX,
            f64::MIN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            9.223_372_036_854_776e18,
            -9.223_372_036_854_776e18,
        ];
        // Every magnitude from 2^-60 to 2^70, and one ulp either side of integers.
        let mut state = 0x9E37_79B9_7F4A_7C15_u64;
        for _ in 0..200_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let e = (state % 131) as i32 - 60;
            let mantissa = 1.0 + (state >> 11) as f64 / (1u64 << 53) as f64;
            let q = mantissa * 2f64.powi(e) * if state & 1 == 1 { -1.0 } else { 1.0 };
            cases.push(q);
            let n = q.round();
            if n != 0.0 {
                // One ulp up and down in magnitude: both sides of the integer.
                let b = n.to_bits();
                cases.extend([n, f64::from_bits(b + 1), f64::from_bits(b - 1)]);
            }
        }
        for q in cases {
            let (got, want) = (floor(q), q.floor());
            assert!(
                got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan()),
                "floor({q:e}) = {got:e}, library {want:e}"
            );
        }
    }

    fn m(pos: [f64; 2], since: f64, velocity: [f64; 2]) -> Motion<2> {
        Motion {
            pos,
            since,
            velocity,
            radius: 0.5,
        }
    }

    #[test]
    fn a_pair_time_depends_on_the_records_only() {
        // Balls 1 apart (contact distance 1) closing at 1 along x, their records at different
        // times: the pair meets at t = 3 whichever record is later.
        let a = m([0.0, 0.0], 1.0, [0.5, 0.0]);
        let b = m([3.0, 0.0], 0.0, [-0.5, 0.0]);
        // At t_ref = 1: a at 0, b at 2.5; gap 2.5 - 1 closes at 1: t = 1 + 1.5.
        assert_eq!(pair_time(&a, &b, &[0.0, 0.0], &[10.0, 10.0]), 2.5);
        // The image one box length down on x puts b at 2.5 - 10: they separate.
        assert!(pair_time(&a, &b, &[-1.0, 0.0], &[10.0, 10.0]).is_nan());
        // The offset at the contact is the contact distance.
        assert_eq!(
            pair_offset(&a, &b, &[0.0, 0.0], &[10.0, 10.0], 2.5),
            [1.0, 0.0]
        );
    }

    #[test]
    fn a_pair_time_is_the_same_bits_from_either_ball() {
        // Records at odd times and places, images across a periodic box of odd sides: the
        // time from (a, b, k) and from (b, a, -k) are the same number.
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let size = [3.7, 5.3];
        let mut met = 0;
        for _ in 0..100_000 {
            let mut m = || Motion {
                pos: [size[0] * next(), size[1] * next()],
                since: 10.0 * next(),
                velocity: [2.0 * next() - 1.0, 2.0 * next() - 1.0],
                radius: 0.2 + 0.5 * next(),
            };
            let (a, b) = (m(), m());
            let k = [(3.0 * next()).floor() - 1.0, (3.0 * next()).floor() - 1.0];
            let forward = pair_time(&a, &b, &k, &size);
            let back = pair_time(&b, &a, &k.map(|x| -x), &size);
            assert_eq!(forward.to_bits(), back.to_bits(), "{a:?} {b:?} {k:?}");
            met += usize::from(!forward.is_nan());
        }
        assert!(met > 2_000, "{met}");
    }

    #[test]
    fn obstacles_are_met_from_the_record() {
        let a = m([0.0, 0.0], 2.0, [1.0, 0.0]);
        // Obstacle of radius 1 at x = 4 - 10 shifted by one box length: distance 4, reach 1.5.
        let t = obstacle_time(&a, &[-6.0, 0.0], 1.0, &[1, 0], &[10.0, 10.0]);
        assert_eq!(t, Some(2.0 + 2.5));
        assert_eq!(
            obstacle_time(&a, &[-6.0, 0.0], 1.0, &[0, 0], &[10.0, 10.0]),
            None
        );
    }

    #[test]
    fn folding_puts_centres_in_the_box_on_periodic_axes_only() {
        let size = [2.0, 2.0];
        assert_eq!(fold(&[-0.5, -0.5], &size, &[true, false]), [1.5, -0.5]);
        assert_eq!(fold(&[4.25, 1.0], &size, &[true, true]), [0.25, 1.0]);
    }

    /// The fold's shortcut for a coordinate inside `(0, L)` gives the bits of the formula
    /// `x - floor(x / L) L`: at the ends of the interval (the largest double below `L`, the
    /// least positive doubles), at both zeros, at `L`, outside, and at 10^5 random points,
    /// for sides of every binade's shape.
    #[test]
    fn the_fold_s_shortcut_is_the_formula_bit_for_bit() {
        let formula = |x: f64, l: f64| x - floor(x / l) * l;
        let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
        let mut unit = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let sides = [
            1.0,
            2.0,
            3.0,
            7.5,
            21.873_7,
            137.823,
            626.657,
            1e-3,
            1e12,
            f64::MAX / 4.0,
        ];
        for l in sides {
            let below = f64::from_bits(l.to_bits() - 1);
            let mut xs = vec![
                below,
                f64::from_bits(below.to_bits() - 1),
                f64::MIN_POSITIVE,
                f64::from_bits(1),
                0.0,
                -0.0,
                l,
                -below,
                l + below,
                -f64::MIN_POSITIVE,
            ];
            xs.extend((0..10_000).map(|_| unit() * l));
            xs.extend((0..100).map(|_| (unit() * 3.0 - 1.0) * l));
            for x in xs {
                let got = fold(&[x], &[l], &[true])[0];
                assert_eq!(
                    got.to_bits(),
                    formula(x, l).to_bits(),
                    "x = {x:e}, L = {l:e}"
                );
            }
        }
    }

    #[test]
    fn keys_order_by_lowest_ball_then_kind_then_other_then_image() {
        let ball = key(3, kind::BALL, 9, &[0i16, 0]);
        assert!(ball < key(3, kind::WALL, 0, &[0, 0]));
        assert!(key(3, kind::BOUNDARY, 7, &[0, 0]) < key(4, kind::BALL, 5, &[0, 0]));
        assert!(key(3, kind::BALL, 8, &[1, 1]) < ball);
        assert!(key(3, kind::BALL, 9, &[-1, 0]) < ball);
        assert!(ball < key(3, kind::BALL, 9, &[0, 1]));
        assert!(key(3, kind::CELL, 0, &[0, 0]) > key(3, kind::BOUNDARY, u32::MAX, &[511, 511]));
        // Six axes fill the 60 bits: the last axis still orders.
        let six = |k: i16| key(0, kind::BALL, 1, &[0, 0, 0, 0, 0, k]);
        assert!(six(-511) < six(0) && six(0) < six(511));
    }

    #[test]
    fn rebasing_waits_for_motion_and_stretches_on_quiet_tables_without_periodic_axes() {
        assert_eq!(rebase_at(16.0, 4.0, 0, true), 2.0);
        assert_eq!(rebase_at(16.0, 0.0, 0, false), f64::INFINITY);
        assert_eq!(rebase_at(16.0, 4.0, QUIET_REBASES, false), 2.0);
        assert_eq!(rebase_at(16.0, 4.0, QUIET_REBASES + 3, false), 16.0);
        assert_eq!(rebase_at(16.0, 4.0, QUIET_REBASES + 3, true), 2.0);
    }
}
