//! Next-event times in free flight.

/// The time `t >= 0` at which two balls whose centres are `d` apart (`d = a_2 - a_1`) with
/// relative velocity `dv = u_2 - u_1` first touch, `|d + t dv| = sigma`, or `None` if they
/// never do. Only approaching pairs (`b = d . dv < 0`) collide; with `a = |dv|^2`,
/// `c = |d|^2 - sigma^2` and discriminant `b^2 - a c >= 0`, the earlier root is
/// `t = c / (-b + sqrt(b^2 - a c))` (the form without cancellation). A pair that overlaps by
/// rounding (`c < 0`) while approaching collides at once (`t = 0`).
#[inline]
pub fn contact_time<const N: usize>(d: &[f64; N], dv: &[f64; N], sigma: f64) -> Option<f64> {
    let (a, b, dd) = dots(d, dv);
    if b >= 0.0 {
        return None;
    }
    let c = dd - sigma * sigma;
    if c <= 0.0 {
        return Some(0.0);
    }
    let disc = b * b - a * c;
    if disc < 0.0 {
        return None;
    }
    Some(c / (disc.sqrt() - b))
}

/// [`contact_time`] without branches on the pair's geometry: the same time, bit for bit, when
/// it is `Some`, and NaN when it is `None` (NaN is never less than a time, so a scan over many
/// pairs keeps the least without the branch mispredictions of the early returns).
#[inline]
pub fn contact_time_or_nan<const N: usize>(d: &[f64; N], dv: &[f64; N], sigma: f64) -> f64 {
    let (a, b, dd) = dots(d, dv);
    let c = dd - sigma * sigma;
    let disc = b * b - a * c;
    // With c <= 0, disc >= b^2 >= 0: a negative disc means c > 0.
    let t = if c <= 0.0 {
        0.0
    } else {
        c / (disc.max(0.0).sqrt() - b)
    };
    if b < 0.0 && disc >= 0.0 {
        t
    } else {
        f64::NAN
    }
}

/// `(|dv|^2, d . dv, |d|^2)`, each summed over `k = 0, 1, ...` in that order (both contact
/// times take them from here, so they round alike).
#[inline(always)]
fn dots<const N: usize>(d: &[f64; N], dv: &[f64; N]) -> (f64, f64, f64) {
    let (mut a, mut b, mut dd) = (0.0, 0.0, 0.0);
    for k in 0..N {
        a += dv[k] * dv[k];
        b += d[k] * dv[k];
        dd += d[k] * d[k];
    }
    (a, b, dd)
}

/// The time at which a coordinate `x` moving with speed `v` reaches `lo` (moving down) or
/// `hi` (moving up): `(lo - x) / v` or `(hi - x) / v`, at least 0; `None` at rest.
#[inline]
pub fn exit_time(x: f64, v: f64, lo: f64, hi: f64) -> Option<(f64, bool)> {
    if v > 0.0 {
        Some((((hi - x) / v).max(0.0), true))
    } else if v < 0.0 {
        Some((((lo - x) / v).max(0.0), false))
    } else {
        None
    }
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

    #[test]
    fn the_branch_free_time_is_the_same_number() {
        // Pairs at every distance (overlapping by rounding, touching, apart), approaching,
        // receding, passing, at rest: the same bits, or NaN for None.
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 * 4.0 - 2.0
        };
        for round in 0..200_000 {
            let d = [next(), next(), next()];
            let mut dv = [next(), next(), next()];
            if round % 10 == 0 {
                dv = [0.0; 3];
            }
            let sigma = if round % 7 == 0 {
                (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
            } else {
                next().abs()
            };
            let expected = contact_time(&d, &dv, sigma).unwrap_or(f64::NAN);
            let got = contact_time_or_nan(&d, &dv, sigma);
            assert_eq!(got.to_bits(), expected.to_bits(), "{d:?} {dv:?} {sigma}");
        }
    }
}
