//! The energy-conserving correction of a conservative contact's computed states (issue 28,
//! item 4): a kernel's outputs moved along themselves, in the energy metric, back onto the
//! energy the inputs had, so that a long run's energy random-walks instead of drifting
//! (`docs/accuracy.md`, "An energy-conserving correction").
//!
//! **Why.** A float kernel of the no-slip map changes the energy by a few `eps` per contact,
//! and part of that change has one sign: the rounding of its coefficients, of `R U` in the
//! slip, of the normal (`docs/accuracy.md`, "Energy bias"). Even the correctly rounded map
//! (each output of the exact map rounded once) keeps a bias on some one-ball tables: the
//! rounded normals of a wedge's edges, a strip's orbit locked onto a cycle. No kernel of the
//! map can remove that; a correction that restores the energy itself does.
//!
//! **The correction.** With `x` the outputs (velocities and spin entries of the movable
//! bodies), `E(x) = sum_b m_b (|u_b|^2 + w_b sum_{i<j} U_b,ij^2)` (`w = gamma^2 R^2`; twice
//! the kinetic energy), `E_in` the inputs' energy and `E_out` the outputs', the relative
//! velocities `r_b = u_b - v` about the centre of mass `v = sum m_b u_b / sum m_b` of the
//! outputs (`v = 0` for one movable body), and `E_rel` the energy of `(r, U)`:
//!
//! ```text
//! ds = (E_in - E_out) / (2 E_rel),    u_b <- u_b + ds r_b,    U_b <- U_b + ds U_b.
//! ```
//!
//! Then `E(x) = E_out + 2 ds E_rel + 2 ds v . (P_out - M v) + O(ds^2) = E_in + O(eps^2 E)`:
//! the momentum `P_out - M v` is zero up to the rounding of `v`, and `ds` is of the kernel's
//! relative energy error (a few `eps`). The momentum moves by `sum m_b ds r_b = ds (P_out -
//! M v)`, of order `eps ds`. The energies are summed in double-double (each square and
//! product split exactly, [`two_prod`], [`two_sum`]), so `E_in - E_out` is known to about
//! `eps^2 E`, and the correction does not conserve a rounded energy of its own.
//!
//! **The final rounding.** `ds` is often below half an ulp of an output: rounded to nearest,
//! `x + ds x'` would then give `x` back, the correction would be lost exactly where it is
//! smallest, and so would the part of the bias it is there to remove (measured: a corrected
//! run rounded to nearest still drifted by 4 standard errors). Each output is therefore
//! rounded *stochastically* ([`round_unbiased`]): to one of the two floats around `x + ds x'`,
//! each with probability one minus its distance over their gap, the random number a hash of
//! the output and the move, so that the result is a function of the inputs (the same bits
//! every run). The expected output is `x + ds x'`, and the expected energy `E_in` up to the
//! rounding's variance (`u^2 E`). What is left per contact is a rounding error of at most one
//! ulp per output, of either sign with mean zero: a random walk.
//!
//! **What is conserved.** The weights `m_b` and `m_b w_b` are rounded once each (`1 / w` where
//! a body is given by its inverse mass, `gamma^2 R R`): a fixed factor per species and part.
//! Conserving that form keeps the true energy within a fixed relative `O(eps)` band of its
//! start for ever (the form is within `(1 +- c eps)` of `E`): no drift.
//!
//! **Accuracy.** Moving `x` along itself by `ds` removes, to first order, the component of the
//! kernel's error along the sphere's normal: the normwise error against the exact map grows by
//! at most the final rounding (one ulp per output) and by the exact map's own distance from the
//! sphere (the exact map of a rounded normal, whose length is not exactly 1, does not conserve
//! `E` itself; nor do the rounded weights). For two bodies the move is along the relative
//! motion, so its size is the kernel's energy error times `|x|_E / |r|_E`. The correction is
//! therefore left out (the outputs returned unchanged) where `E / E_rel` would exceed
//! [`MAX_REL_RATIO`] (almost equal velocities), and where the energies are not normal numbers
//! or `|ds|` exceeds [`MAX_DS`] (no kernel of the map errs that much: something other than
//! rounding is at work, a dissipative law's contact for one).
//!
//! It is for the conservative laws only (the no-slip map, the specular one): a dissipative
//! contact's energy change is the law's.

use crate::{Ball, BodyState};

/// The largest `|ds|` the correction applies (about `4.4e-12`, `2^14 eps`): the kernels'
/// relative energy errors are below `10^3 eps` in every regime of the accuracy report.
pub const MAX_DS: f64 = 1.0 / (1u64 << 38) as f64;

/// The largest `E / E_rel` at which two bodies are corrected: the move, `|ds| |r|_E =
/// |E_in - E_out| / (2 sqrt(E_rel))`, is then at most `sqrt(E / E_rel) = 4` times the
/// kernel's error `|e|_E` (`|E_in - E_out| <= 2 sqrt(E) |e|_E` to first order).
pub const MAX_REL_RATIO: f64 = 16.0;

/// `a b` as `hi + lo` exactly: with a fused multiply-add where the build has one (its
/// rounding error in one operation), else Dekker's product of Veltkamp halves (17 operations,
/// no library call; exact while `|a|` and `|b|` are below `2^996` and no partial product
/// falls below the normal range, NaN beyond the first bound, which the callers treat as an
/// energy out of range). Where both are exact they give the same pair, so the default build
/// and an FMA build correct alike there.
#[inline]
pub fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    if cfg!(target_feature = "fma") {
        return (p, a.mul_add(b, -p));
    }
    let (a_hi, a_lo) = halves(a);
    let (b_hi, b_lo) = halves(b);
    (
        p,
        ((a_hi * b_hi - p) + a_hi * b_lo + a_lo * b_hi) + a_lo * b_lo,
    )
}

/// Veltkamp's split of `a` into two halves of 26 significant bits, `a = hi + lo` exactly.
#[inline]
fn halves(a: f64) -> (f64, f64) {
    let c = 134_217_729.0 * a; // 2^27 + 1
    let hi = c - (c - a);
    (hi, a - hi)
}

/// `a + b` as `hi + lo` exactly (Knuth's TwoSum).
#[inline]
pub fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// `sum c x^2` over `(c, x)` in double-double (`hi + lo`; relative error about `eps^2` per
/// term, for terms of one sign).
#[inline]
pub fn weighted_squares(terms: impl Iterator<Item = (f64, f64)>) -> (f64, f64) {
    terms.fold((0.0, 0.0), |(hi, lo), (c, x)| {
        let (sq, sq_lo) = two_prod(x, x);
        let (csq, csq_lo) = two_prod(c, sq);
        let (s, e) = two_sum(hi, csq);
        (s, e + lo + csq_lo + c * sq_lo)
    })
}

/// A movable body's energy terms `(c, x)`: `(m, u_k)`, then `(m w, U_ij)` (`w = gamma^2 R^2`),
/// each about the velocity `v` (the centre of mass, or 0).
fn terms<'a, const N: usize, const S: usize>(
    m: f64,
    ball: &Ball<f64>,
    s: &'a BodyState<f64, N, S>,
    v: &'a [f64; N],
) -> impl Iterator<Item = (f64, f64)> + 'a {
    let mw = m * (ball.gamma2 * ball.radius * ball.radius);
    let velocity = (0..N).map(move |k| (m, s.velocity[k] - v[k]));
    velocity.chain(s.spin.iter().map(move |&x| (mw, x)))
}

/// `hi + lo` collapsed.
#[inline]
fn value((hi, lo): (f64, f64)) -> f64 {
    hi + lo
}

/// `ds` of the module docs, or `None` where the correction is left out.
fn ds(e_in: (f64, f64), e_out: (f64, f64), e_rel: f64) -> Option<f64> {
    let (e_in_v, e_out_v) = (value(e_in), value(e_out));
    let normal = |e: f64| e.is_finite() && e >= f64::MIN_POSITIVE;
    if !(normal(e_in_v) && normal(e_out_v) && normal(e_rel)) {
        return None;
    }
    if e_out_v > MAX_REL_RATIO * e_rel {
        return None;
    }
    // E_in - E_out in double-double: the heads' difference is exact when they are close
    // (Sterbenz), the tails' terms are far below it.
    let (d, d_lo) = two_sum(e_in.0, -e_out.0);
    let diff = d + (d_lo + (e_in.1 - e_out.1));
    let ds = diff / (2.0 * e_rel);
    (ds.abs() <= MAX_DS).then_some(ds)
}

/// SplitMix64's finaliser: a well-mixed 64-bit hash of `z`.
#[inline]
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The float next to `x` towards `+inf` (`up`) or `-inf`, for finite `x`.
#[inline]
fn toward(x: f64, up: bool) -> f64 {
    if x == 0.0 {
        let tiny = f64::from_bits(1);
        return if up { tiny } else { -tiny };
    }
    let bits = x.to_bits();
    // Away from zero: the magnitude's bits up by one; towards zero: down by one.
    if (x > 0.0) == up {
        f64::from_bits(bits + 1)
    } else {
        f64::from_bits(bits - 1)
    }
}

/// `x + p` rounded to one of its two neighbouring floats at random, each with probability
/// one minus its distance from `x + p` over their gap, so that the expected result is
/// `x + p` (up to the `eps^2` of `p`'s own rounding): stochastic rounding. The random number
/// is a hash of `x`, `p` and `salt`, so the result is a function of the inputs (the same bits
/// every run).
///
/// Round to nearest would return `x` whenever `|p|` is below half an ulp of `x`, and the
/// kernels' energy errors are of that size: the correction would then be dropped exactly
/// where it is smallest, and the part of the bias it was to remove would stay.
#[inline]
pub fn round_unbiased(x: f64, p: f64, salt: u64) -> f64 {
    let (hi, lo) = two_sum(x, p);
    if lo == 0.0 || !hi.is_finite() {
        return hi;
    }
    let next = toward(hi, lo > 0.0);
    // Adjacent floats: their difference is exact.
    let gap = (next - hi).abs();
    let chance = lo.abs() / gap;
    let key = x.to_bits() ^ p.to_bits().rotate_left(29) ^ salt;
    // 53 random bits, uniform in [0, 1).
    let r = (mix(key) >> 11) as f64 * (1.0 / (1u64 << 53) as f64);
    if r < chance {
        next
    } else {
        hi
    }
}

/// Moves `s` by `ds` along its relative velocity `u - v` and its spin (module docs), each
/// output rounded without bias ([`round_unbiased`]); `salt` tells the bodies apart.
fn moved<const N: usize, const S: usize>(
    s: &BodyState<f64, N, S>,
    v: &[f64; N],
    ds: f64,
    spin: bool,
    salt: u64,
) -> BodyState<f64, N, S> {
    let salt = |k: usize| mix(salt.wrapping_add(k as u64));
    BodyState {
        velocity: std::array::from_fn(|k| {
            round_unbiased(s.velocity[k], ds * (s.velocity[k] - v[k]), salt(k))
        }),
        spin: if spin {
            std::array::from_fn(|k| round_unbiased(s.spin[k], ds * s.spin[k], salt(N + k)))
        } else {
            s.spin
        },
    }
}

/// Whether a ball's spin carries energy (`gamma^2 R^2 > 0`): a point mass's spin is left as
/// the kernel leaves it.
fn spins(ball: &Ball<f64>) -> bool {
    ball.gamma2 * ball.radius * ball.radius > 0.0
}

/// The state of `ball` after a conservative contact with an immovable body at rest (the
/// body's motion would change `ball`'s energy: this correction would undo that), the kernel's
/// `after` corrected onto the energy of `before` (module docs, one movable body: `v = 0`,
/// `E_rel = E_out`; the mass is a common factor and is left out).
pub fn fixed<const N: usize, const S: usize>(
    ball: &Ball<f64>,
    before: &BodyState<f64, N, S>,
    after: &BodyState<f64, N, S>,
) -> BodyState<f64, N, S> {
    let zero = [0.0; N];
    let e_in = weighted_squares(terms(1.0, ball, before, &zero));
    let e_out = weighted_squares(terms(1.0, ball, after, &zero));
    match ds(e_in, e_out, value(e_out)) {
        Some(ds) => moved(after, &zero, ds, spins(ball), 1),
        None => after.clone(),
    }
}

/// The states of `ball1` and `ball2` (both movable) after a conservative contact, the
/// kernel's `after` corrected onto the total energy of `before` along the motion relative to
/// the outputs' centre of mass (module docs).
pub fn free<const N: usize, const S: usize>(
    ball1: &Ball<f64>,
    ball2: &Ball<f64>,
    before: [&BodyState<f64, N, S>; 2],
    after: [&BodyState<f64, N, S>; 2],
) -> [BodyState<f64, N, S>; 2] {
    let (w1, w2) = (ball1.inv_mass, ball2.inv_mass);
    let unchanged = || [after[0].clone(), after[1].clone()];
    if !(w1 > 0.0 && w2 > 0.0) {
        return unchanged();
    }
    let (m1, m2) = (1.0 / w1, 1.0 / w2);
    // v = (m1 u1 + m2 u2) / (m1 + m2) = (w2 u1 + w1 u2) / (w1 + w2).
    let v: [f64; N] = std::array::from_fn(|k| {
        (w2 * after[0].velocity[k] + w1 * after[1].velocity[k]) / (w1 + w2)
    });
    let zero = [0.0; N];
    let energy = |s: [&BodyState<f64, N, S>; 2], v: &[f64; N]| {
        weighted_squares(terms(m1, ball1, s[0], v).chain(terms(m2, ball2, s[1], v)))
    };
    let (e_in, e_out) = (energy(before, &zero), energy(after, &zero));
    // E_rel sets only the size of the move: f64 is enough.
    let e_rel: f64 = terms(m1, ball1, after[0], &v)
        .chain(terms(m2, ball2, after[1], &v))
        .map(|(c, x)| c * x * x)
        .sum();
    match ds(e_in, e_out, e_rel) {
        Some(ds) => [
            moved(after[0], &v, ds, spins(ball1), 1),
            moved(after[1], &v, ds, spins(ball2), 2),
        ],
        None => unchanged(),
    }
}

#[cfg(test)]
mod tests;
