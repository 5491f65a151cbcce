//! Next-event times in free flight.

/// The time `t >= 0` at which two balls whose centres are `d` apart (`d = a_2 - a_1`) with
/// relative velocity `dv = u_2 - u_1` first touch, `|d + t dv| = sigma`, or `None` if they
/// never do. Only approaching pairs (`b = d . dv < 0`) collide. The root is taken from the
/// closest approach: with `a = |dv|^2`, the pair is closest at `t_0 = -b / a`, `h = d + t_0
/// dv` apart; it touches iff `|h|^2 <= sigma^2`, at `t = t_0 - sqrt((sigma^2 - |h|^2) / a)`,
/// or at once (`t = 0`) if it overlaps by rounding. Every rounding is of a number of the size
/// of `|d|` or `sigma`, none of `|d|^2`: the centres at contact are within a few `eps (|d| +
/// sigma)` of contact distance however far apart the pair starts (the usual `c / (-b +
/// sqrt(b^2 - a c))`, `c = |d|^2 - sigma^2`, rounds `|d|^2` and is off by about `eps |d|^2 /
/// sigma`, which the canonical times of long flights cannot afford).
#[inline]
pub fn contact_time<const N: usize>(d: &[f64; N], dv: &[f64; N], sigma: f64) -> Option<f64> {
    let t = contact_time_or_nan(d, dv, sigma);
    (!t.is_nan()).then_some(t)
}

/// [`contact_time`] without branches on the pair's geometry, NaN for `None` (NaN is never
/// less than a time, so a scan over many pairs keeps the least without the mispredicted
/// branches of early returns: most pairs of a scan recede or miss). One division, by `a`,
/// taken as `1 / a` for both of its uses.
#[inline]
pub fn contact_time_or_nan<const N: usize>(d: &[f64; N], dv: &[f64; N], sigma: f64) -> f64 {
    let (a, b) = dots(d, dv);
    let inv_a = 1.0 / a;
    let t0 = -b * inv_a;
    let mut h2 = 0.0;
    for k in 0..N {
        let h = d[k] + t0 * dv[k];
        h2 += h * h;
    }
    let gap = sigma * sigma - h2;
    let t = (t0 - (gap * inv_a).max(0.0).sqrt()).max(0.0);
    // b < 0 implies a > 0; NaN compares false, so NaN inputs give NaN.
    if b < 0.0 && gap >= 0.0 {
        t
    } else {
        f64::NAN
    }
}

/// `(|dv|^2, d . dv)`, each summed over `k = 0, 1, ...` in that order.
#[inline(always)]
fn dots<const N: usize>(d: &[f64; N], dv: &[f64; N]) -> (f64, f64) {
    let (mut a, mut b) = (0.0, 0.0);
    for k in 0..N {
        a += dv[k] * dv[k];
        b += d[k] * dv[k];
    }
    (a, b)
}

/// The time at which a coordinate `x` moving with speed `v` reaches `lo` (moving down) or
/// `hi` (moving up): `(lo - x) / v` or `(hi - x) / v`, at least 0; `None` at rest (or for a
/// NaN `v`).
///
/// The face is selected by a mask of its bits, not branched to: the sign of `v` is a coin
/// toss from one call to the next (the engine's `select` module).
#[inline]
pub fn exit_time(x: f64, v: f64, lo: f64, hi: f64) -> Option<(f64, bool)> {
    let up = v > 0.0;
    let face = crate::select::select(up, hi, lo);
    let tau = ((face - x) / v).max(0.0);
    (up || v < 0.0).then_some((tau, up))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn head_on_and_missing_pairs() {
        // Centres 4 apart, closing at 2: contact (distance 2) after 1.
        assert_eq!(contact_time(&[4.0, 0.0], &[-2.0, 0.0], 2.0), Some(1.0));
        // Receding, and passing at distance 3 > 2.
        assert_eq!(contact_time(&[4.0, 0.0], &[2.0, 0.0], 2.0), None);
        assert_eq!(contact_time(&[4.0, 3.0], &[-1.0, 0.0], 2.0), None);
        // Grazing approach with offset 1.2: |(4 - t, 1.2)| = 2 at t = 4 - 1.6.
        let t = contact_time(&[4.0, 1.2], &[-1.0, 0.0], 2.0).unwrap();
        assert!((t - 2.4).abs() < 1e-15);
        assert_eq!(exit_time(0.5, -0.25, 0.0, 1.0), Some((2.0, false)));
        // The branch-free form agrees on these too.
        for (d, dv) in [
            ([4.0, 0.0], [-2.0, 0.0]),
            ([4.0, 1.2], [-1.0, 0.0]),
            ([4.0, 3.0], [-1.0, 0.0]),
        ] {
            let t = contact_time_or_nan(&d, &dv, 2.0);
            assert_eq!(
                contact_time(&d, &dv, 2.0).unwrap_or(f64::NAN).to_bits(),
                t.to_bits()
            );
        }
        assert_eq!(exit_time(0.5, 0.0, 0.0, 1.0), None);
    }

    /// The face chosen by a select is the one the branches chose, bit for bit: both signs
    /// of `v` and of zero, NaN, infinities, and positions on and beyond the faces.
    #[test]
    fn exit_time_is_the_branching_formula() {
        let branching = |x: f64, v: f64, lo: f64, hi: f64| {
            if v > 0.0 {
                Some((((hi - x) / v).max(0.0), true))
            } else if v < 0.0 {
                Some((((lo - x) / v).max(0.0), false))
            } else {
                None
            }
        };
        let xs = [0.0, -0.0, 0.25, 1.0, 1.5, -3.0, 1e300];
        let vs = [
            0.0,
            -0.0,
            2.0,
            -0.5,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE / 8.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ];
        let bits = |r: Option<(f64, bool)>| r.map(|(t, up)| (t.to_bits(), up));
        for &x in &xs {
            for &v in &vs {
                for (lo, hi) in [(0.0, 1.0), (-0.0, 0.5), (1.0, 1.0 + 1e-16)] {
                    assert_eq!(
                        bits(exit_time(x, v, lo, hi)),
                        bits(branching(x, v, lo, hi)),
                        "x {x} v {v} lo {lo} hi {hi}"
                    );
                }
            }
        }
    }

    #[test]
    fn a_contact_after_a_long_flight_is_at_contact_distance() {
        // Centres 10^4 contact distances apart, closing head on, obliquely and almost
        // grazing: at the computed time the distance is sigma within the rounding of the
        // flown offset, 8 eps |d| (the form through c = |d|^2 - sigma^2 was off by about
        // eps |d|^2 / (2 sigma), 1e-8 here).
        let sigma = 1.0;
        for offset in [0.0, 0.3, 0.999, 0.999_999] {
            let d = [1e4, offset * sigma, 0.0];
            let dv = [-1.0, 0.0, 0.0];
            let t = contact_time(&d, &dv, sigma).expect("a contact");
            let distance = (0..3)
                .map(|k| (d[k] + t * dv[k]).powi(2))
                .sum::<f64>()
                .sqrt();
            let bound = 8.0 * f64::EPSILON * 1e4;
            assert!((distance - sigma).abs() <= bound, "{offset}: {distance}");
        }
    }

    /// The closest-approach form spelled with early returns, as the docs state it.
    fn branchy<const N: usize>(d: &[f64; N], dv: &[f64; N], sigma: f64) -> Option<f64> {
        let (a, b) = dots(d, dv);
        // Not approaching (or NaN).
        if b.partial_cmp(&0.0) != Some(std::cmp::Ordering::Less) {
            return None;
        }
        let inv_a = 1.0 / a;
        let t0 = -b * inv_a;
        let h2: f64 = (0..N)
            .map(|k| (d[k] + t0 * dv[k]) * (d[k] + t0 * dv[k]))
            .fold(0.0, |s, x| s + x);
        let gap = sigma * sigma - h2;
        if gap < 0.0 {
            return None;
        }
        Some((t0 - (gap * inv_a).sqrt()).max(0.0))
    }

    #[test]
    fn the_branch_free_time_is_the_branchy_one() {
        // Pairs at every distance (overlapping by rounding, touching, apart), approaching,
        // receding, passing, at rest, and grazing to the last bits (the impact parameter
        // set to sigma, then sigma moved by a few ulps), near and 10^6 apart: the same bits
        // as the form with early returns, NaN for None.
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 * 4.0 - 2.0
        };
        let mut grazing = 0;
        for round in 0..400_000 {
            let far = if round % 3 == 0 { 1e6 } else { 1.0 };
            let d = [far * next(), next(), next()];
            let mut dv = [next(), next(), next()];
            if round % 10 == 0 {
                dv = [0.0; 3];
            }
            let sigma = match round % 7 {
                0 => (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt(),
                1 | 2 => {
                    // The impact parameter, plus or minus a few ulps.
                    let (a, b) = dots(&d, &dv);
                    let t0 = -b / a;
                    let h2: f64 = (0..3).map(|k| (d[k] + t0 * dv[k]).powi(2)).sum();
                    let ulps = (next() * 4.0).round();
                    grazing += 1;
                    h2.sqrt() * (1.0 + ulps * f64::EPSILON)
                }
                _ => next().abs(),
            };
            let expected = branchy(&d, &dv, sigma).unwrap_or(f64::NAN);
            let got = contact_time_or_nan(&d, &dv, sigma);
            assert_eq!(got.to_bits(), expected.to_bits(), "{d:?} {dv:?} {sigma}");
            assert_eq!(
                contact_time(&d, &dv, sigma).unwrap_or(f64::NAN).to_bits(),
                got.to_bits()
            );
        }
        assert!(grazing > 100_000);
    }
}
