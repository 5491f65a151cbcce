//! The energy-conserving correction (`collision_core::conserve`, issue 28 item 4) in C99:
//! `noslip_conserve_fixed_dN` and `noslip_conserve_free_dN`, appended to the C header after
//! the kernels. They spell the Rust functions' operations in their order (double-double
//! energies, the move, the stochastic rounding from the same hash), so that they return the
//! Rust correction's bits (`tests/c_backend/conserve.rs`). Handwritten, not generated from the DAG:
//! the correction is the same few loops for every kernel.
//!
//! The exact products are Dekker's (no `fma` call), as in Rust's default build; a Rust build
//! with FMA gives the same pair wherever Dekker's is exact (no partial product below the
//! normal range: products above about `10^-270`), as both are then the product split
//! into its rounding and the remainder.

/// The shared helpers, then the two corrections for each of `dims`.
pub(super) fn functions(dims: &[usize]) -> String {
    let mut s = String::from(HELPERS);
    for &n in dims {
        s.push_str(&for_dim(n));
    }
    s
}

/// The helpers of every dimension (`collision_core::conserve`'s private functions).
const HELPERS: &str = r#"
/* Energy-conserving correction (collision_core::conserve; docs/accuracy.md, "An
 * energy-conserving correction"): after a no-slip contact, the kernel's outputs `after` moved
 * onto the energy of its inputs `before`, each output rounded stochastically from a hash of
 * its inputs (bit for bit the Rust correction). For conservative contacts only. */
#include <stdint.h>
#include <string.h>

static inline NOSLIP_NO_CONTRACT void noslip_cons_halves(double a, double *hi, double *lo)
{
    NOSLIP_FP_CONTRACT_OFF
    double c = 134217729.0 * a;
    *hi = c - (c - a);
    *lo = a - *hi;
}

static inline NOSLIP_NO_CONTRACT void noslip_cons_two_prod(double a, double b, double *p, double *e)
{
    NOSLIP_FP_CONTRACT_OFF
    double ah, al, bh, bl;
    *p = a * b;
    noslip_cons_halves(a, &ah, &al);
    noslip_cons_halves(b, &bh, &bl);
    *e = ((ah * bh - *p) + ah * bl + al * bh) + al * bl;
}

static inline NOSLIP_NO_CONTRACT void noslip_cons_two_sum(double a, double b, double *s, double *e)
{
    NOSLIP_FP_CONTRACT_OFF
    double bb;
    *s = a + b;
    bb = *s - a;
    *e = (a - (*s - bb)) + (b - bb);
}

/* hi + lo += c x^2 (collision_core::conserve::weighted_squares, one term). */
static inline NOSLIP_NO_CONTRACT void noslip_cons_add(double c, double x, double *hi, double *lo)
{
    NOSLIP_FP_CONTRACT_OFF
    double sq, sq_lo, csq, csq_lo, s, e;
    noslip_cons_two_prod(x, x, &sq, &sq_lo);
    noslip_cons_two_prod(c, sq, &csq, &csq_lo);
    noslip_cons_two_sum(*hi, csq, &s, &e);
    *lo = e + *lo + csq_lo + c * sq_lo;
    *hi = s;
}

static inline uint64_t noslip_cons_bits(double x)
{
    uint64_t u;
    memcpy(&u, &x, sizeof u);
    return u;
}

static inline double noslip_cons_from_bits(uint64_t u)
{
    double x;
    memcpy(&x, &u, sizeof x);
    return x;
}

/* SplitMix64's finaliser. */
static inline uint64_t noslip_cons_mix(uint64_t z)
{
    z = (z ^ (z >> 30)) * UINT64_C(0xbf58476d1ce4e5b9);
    z = (z ^ (z >> 27)) * UINT64_C(0x94d049bb133111eb);
    return z ^ (z >> 31);
}

/* x + p rounded to one of its two neighbouring floats, each with probability one minus its
 * distance over their gap, the random number a hash of x, p and salt. */
static inline NOSLIP_NO_CONTRACT double noslip_cons_round(double x, double p, uint64_t salt)
{
    NOSLIP_FP_CONTRACT_OFF
    double hi, lo, next, gap, chance, r;
    uint64_t pb, key;
    noslip_cons_two_sum(x, p, &hi, &lo);
    if (lo == 0.0 || !isfinite(hi))
        return hi;
    if (hi == 0.0)
        next = lo > 0.0 ? noslip_cons_from_bits(1) : -noslip_cons_from_bits(1);
    else if ((hi > 0.0) == (lo > 0.0))
        next = noslip_cons_from_bits(noslip_cons_bits(hi) + 1);
    else
        next = noslip_cons_from_bits(noslip_cons_bits(hi) - 1);
    gap = fabs(next - hi);
    chance = fabs(lo) / gap;
    pb = noslip_cons_bits(p);
    key = noslip_cons_bits(x) ^ ((pb << 29) | (pb >> 35)) ^ salt;
    r = (double)(noslip_cons_mix(key) >> 11) * (1.0 / 9007199254740992.0);
    return r < chance ? next : hi;
}

/* ds of the correction, or 0 with *ok = 0 where it is left out. */
static inline NOSLIP_NO_CONTRACT double noslip_cons_ds(double in_hi, double in_lo, double out_hi, double out_lo, double e_rel, int *ok)
{
    NOSLIP_FP_CONTRACT_OFF
    double e_in = in_hi + in_lo, e_out = out_hi + out_lo, d, d_lo, diff, ds;
    *ok = 0;
    if (!(isfinite(e_in) && e_in >= DBL_MIN && isfinite(e_out) && e_out >= DBL_MIN
          && isfinite(e_rel) && e_rel >= DBL_MIN))
        return 0.0;
    if (e_out > 16.0 * e_rel)
        return 0.0;
    noslip_cons_two_sum(in_hi, -out_hi, &d, &d_lo);
    diff = d + (d_lo + (in_lo - out_lo));
    ds = diff / (2.0 * e_rel);
    if (!(fabs(ds) <= 1.0 / 274877906944.0))
        return 0.0;
    *ok = 1;
    return ds;
}

/* Moves a state (spin[s], velocity[n]) by ds along u - v and U, each output rounded by
 * noslip_cons_round with salt mix(salt + k). */
static inline NOSLIP_NO_CONTRACT void noslip_cons_move(double *state, int n, int s, const double *v, double ds, int spin, uint64_t salt)
{
    NOSLIP_FP_CONTRACT_OFF
    int k;
    for (k = 0; k < n; k++) {
        double x = state[s + k];
        state[s + k] = noslip_cons_round(x, ds * (x - v[k]), noslip_cons_mix(salt + (uint64_t)k));
    }
    if (spin)
        for (k = 0; k < s; k++) {
            double x = state[k];
            state[k] = noslip_cons_round(x, ds * x, noslip_cons_mix(salt + (uint64_t)(n + k)));
        }
}

/* hi + lo += the energy terms of a state: (m, u_k - v_k), then (m gamma^2 R R, U_ij). */
static inline NOSLIP_NO_CONTRACT void noslip_cons_energy(const double ball[3], double m, const double *state, int n, int s, const double *v, double *hi, double *lo)
{
    NOSLIP_FP_CONTRACT_OFF
    double mw = m * (ball[2] * ball[1] * ball[1]);
    int k;
    for (k = 0; k < n; k++)
        noslip_cons_add(m, state[s + k] - v[k], hi, lo);
    for (k = 0; k < s; k++)
        noslip_cons_add(mw, state[k], hi, lo);
}

/* E_rel: the same terms summed in plain double. */
static inline NOSLIP_NO_CONTRACT double noslip_cons_plain(const double ball[3], double m, const double *state, int n, int s, const double *v, double sum)
{
    NOSLIP_FP_CONTRACT_OFF
    double mw = m * (ball[2] * ball[1] * ball[1]);
    int k;
    for (k = 0; k < n; k++) {
        double x = state[s + k] - v[k];
        sum += m * x * x;
    }
    for (k = 0; k < s; k++)
        sum += mw * state[k] * state[k];
    return sum;
}
"#;

/// `noslip_conserve_fixed_d{n}` and `noslip_conserve_free_d{n}`.
fn for_dim(n: usize) -> String {
    let s = n * (n - 1) / 2;
    format!(
        r#"
/* Ball `ball` (inv_mass, radius, gamma2) after a no-slip contact with an immovable body:
 * `after` (spin[{s}], velocity[{n}], the kernel's output for the state `before`) corrected in
 * place onto the energy of `before` (collision_core::conserve::fixed). */
static inline NOSLIP_NO_CONTRACT void noslip_conserve_fixed_d{n}(const double ball[3], const double before[{len}], double after[{len}])
{{
    NOSLIP_FP_CONTRACT_OFF
    const double zero[{n}] = {{0}};
    double in_hi = 0.0, in_lo = 0.0, out_hi = 0.0, out_lo = 0.0, ds;
    int ok;
    noslip_cons_energy(ball, 1.0, before, {n}, {s}, zero, &in_hi, &in_lo);
    noslip_cons_energy(ball, 1.0, after, {n}, {s}, zero, &out_hi, &out_lo);
    ds = noslip_cons_ds(in_hi, in_lo, out_hi, out_lo, out_hi + out_lo, &ok);
    if (ok)
        noslip_cons_move(after, {n}, {s}, zero, ds, ball[2] * ball[1] * ball[1] > 0.0, 1);
}}

/* Balls `ball1`, `ball2` (both movable) after a no-slip contact: `after1`, `after2` (the
 * kernel's outputs for `before1`, `before2`) corrected in place onto the total energy of the
 * inputs, along the motion relative to the outputs' centre of mass
 * (collision_core::conserve::free). */
static inline NOSLIP_NO_CONTRACT void noslip_conserve_free_d{n}(const double ball1[3], const double ball2[3], const double before1[{len}], const double before2[{len}], double after1[{len}], double after2[{len}])
{{
    NOSLIP_FP_CONTRACT_OFF
    const double zero[{n}] = {{0}};
    double w1 = ball1[0], w2 = ball2[0], m1, m2, v[{n}], e_rel;
    double in_hi = 0.0, in_lo = 0.0, out_hi = 0.0, out_lo = 0.0, ds;
    int k, ok;
    if (!(w1 > 0.0 && w2 > 0.0))
        return;
    m1 = 1.0 / w1;
    m2 = 1.0 / w2;
    for (k = 0; k < {n}; k++)
        v[k] = (w2 * after1[{s} + k] + w1 * after2[{s} + k]) / (w1 + w2);
    noslip_cons_energy(ball1, m1, before1, {n}, {s}, zero, &in_hi, &in_lo);
    noslip_cons_energy(ball2, m2, before2, {n}, {s}, zero, &in_hi, &in_lo);
    noslip_cons_energy(ball1, m1, after1, {n}, {s}, zero, &out_hi, &out_lo);
    noslip_cons_energy(ball2, m2, after2, {n}, {s}, zero, &out_hi, &out_lo);
    e_rel = noslip_cons_plain(ball1, m1, after1, {n}, {s}, v, 0.0);
    e_rel = noslip_cons_plain(ball2, m2, after2, {n}, {s}, v, e_rel);
    ds = noslip_cons_ds(in_hi, in_lo, out_hi, out_lo, e_rel, &ok);
    if (!ok)
        return;
    noslip_cons_move(after1, {n}, {s}, v, ds, ball1[2] * ball1[1] * ball1[1] > 0.0, 1);
    noslip_cons_move(after2, {n}, {s}, v, ds, ball2[2] * ball2[1] * ball2[1] > 0.0, 2);
}}
"#,
        len = s + n
    )
}
