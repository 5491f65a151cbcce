//! The contact normal `nu = d / |d|` from the line of centres `d`, with `|nu|^2 - 1` of mean
//! zero.
//!
//! The plain `d / sqrt(sum d_k^2)` rounds the sum, the square root and each quotient; the
//! first two errors are shared by every component and do not average out over a run: in the
//! Sinai table `|nu|^2 - 1` has a mean of +0.03 eps, and a reflection at a non-unit normal
//! changes the energy by `2 m (|nu|^2 - 1) (dn^2/(1+g) + g |t|^2/(1+g)^2)` to first order,
//! so the energy drifted linearly (docs/scenes.md, "Energy drift of the one-ball tables").
//! Here `S = sum d_k^2` is summed in double-double (each square split exactly by Dekker's
//! product, the sum by Knuth's two-sum), `|d| = sqrt(S)` is corrected by one Newton step in
//! that precision, so it is within `0.5 + 2^-40` ulps of the true norm; each `nu_k` then
//! carries one rounding of its own, of either sign.

/// `(p, e)` with `p + e = a b` exactly (`p = fl(a b)`): Dekker's product, by Veltkamp's
/// splitting (no FMA needed; exact while `|a|, |b| < 2^996`).
#[inline]
fn two_product(a: f64, b: f64) -> (f64, f64) {
    const SPLIT: f64 = 134_217_729.0; // 2^27 + 1
    let split = |x: f64| {
        let c = SPLIT * x;
        let hi = c - (c - x);
        (hi, x - hi)
    };
    let p = a * b;
    let ((ah, al), (bh, bl)) = (split(a), split(b));
    let e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
    (p, e)
}

/// `(s, e)` with `s + e = a + b` exactly (`s = fl(a + b)`): Knuth's two-sum.
#[inline]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// `|d|`, within `0.5 + 2^-40` ulps: `S = |d|^2` in double-double, `r = sqrt(S_hi)`, then
/// `r + (S - r^2) / (2 r)` with `S - r^2` computed from the exact square of `r`.
#[inline]
pub(crate) fn norm<const N: usize>(d: &[f64; N]) -> f64 {
    let (mut hi, mut lo) = (0.0, 0.0);
    for x in d {
        let (p, e) = two_product(*x, *x);
        let (s, t) = two_sum(hi, p);
        hi = s;
        lo += t + e;
    }
    let (s, t) = two_sum(hi, lo);
    let (hi, lo) = (s, t);
    let r = hi.sqrt();
    if r == 0.0 || !r.is_finite() {
        return r;
    }
    let (p, e) = two_product(r, r);
    r + (((hi - p) - e) + lo) / (2.0 * r)
}

/// `d / |d|`, each component one rounding of the quotient by the accurate [`norm`].
#[inline]
pub(crate) fn unit<const N: usize>(d: [f64; N]) -> [f64; N] {
    let r = norm(&d);
    d.map(|x| x / r)
}

#[cfg(test)]
mod tests {
    use super::*;
    use collision_core::Exact;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn q(x: f64) -> Exact {
        Exact::from_float(x).expect("finite")
    }

    /// `|r - sqrt(S)| <= (1/2 + 2^-30) ulp(r)`, decided exactly: `S` lies between the squares
    /// of `r -+ (1/2 + 2^-30) ulp`.
    fn nearly_correctly_rounded(d: &[f64], r: f64) -> bool {
        let s: Exact = d.iter().map(|x| q(*x) * q(*x)).sum();
        let ulp = q(f64::from_bits(r.to_bits() + 1) - r);
        let slack = ulp * (Exact::pow2(-1) + Exact::pow2(-30));
        let (below, above) = (q(r) - &slack, q(r) + &slack);
        &below * &below <= s && s <= &above * &above
    }

    #[test]
    fn the_norm_is_within_half_an_ulp_and_a_little() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let mut plain_misses = 0;
        for case in 0..20_000 {
            let scale = 2f64.powi(rng.random_range(-300..300));
            let d: [f64; 4] = std::array::from_fn(|k| {
                if case % 7 == 0 && k > 1 {
                    0.0
                } else {
                    scale * rng.random_range(-1.0..1.0)
                }
            });
            let r = norm(&d);
            assert!(nearly_correctly_rounded(&d, r), "{d:?}: {r}");
            let plain = d.iter().map(|x| x * x).sum::<f64>().sqrt();
            plain_misses += usize::from(!nearly_correctly_rounded(&d, plain));
        }
        // The plain form is often more than half an ulp off: the test can tell them apart.
        assert!(plain_misses > 1000, "{plain_misses}");
    }
}
