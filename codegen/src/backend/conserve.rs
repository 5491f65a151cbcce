//! The energy-conserving correction (`collision_core::conserve`, issue 28 item 4) in C99 and
//! OpenCL C: `noslip_conserve_fixed_dN` and `noslip_conserve_free_dN`, appended to the
//! generated file after the kernels (in OpenCL inside the `cl_khr_fp64` section, each with its
//! batch kernel `NAME_batch`). They spell the Rust functions' operations in their order
//! (double-double energies, the move, the stochastic rounding from the same hash), so that
//! they return the Rust correction's bits (`tests/c_backend/conserve.rs`,
//! `tests/opencl_backend/conserve.rs`). Handwritten, not generated from the DAG: the correction
//! is the same few loops for every kernel. One text serves both languages; [`Spelling`] holds
//! the few words in which they differ.
//!
//! The exact products are Dekker's (no `fma` call), as in Rust's default build; a Rust build
//! with FMA gives the same pair wherever Dekker's is exact (no partial product below the
//! normal range: products above about `10^-270`), as both are then the product split
//! into its rounding and the remainder.

use super::lang::Lang;
use super::precision::Precision;

/// The words of the correction's text that differ between C99 and OpenCL C.
struct Spelling {
    /// Before each function: `static inline`, and in C the no-contraction attribute.
    qualifiers: &'static str,
    /// The first line of each body: in C the no-contraction pragma (OpenCL's is file-wide).
    prologue: &'static str,
    /// The unsigned 64-bit integer type.
    u64: &'static str,
    /// The suffix of a 64-bit unsigned literal.
    suffix: &'static str,
    /// The headers, and the reinterpretation of a double's bits as an integer and back.
    bits: &'static str,
}

impl Spelling {
    fn of(lang: Lang) -> Spelling {
        match lang {
            Lang::C => Spelling {
                qualifiers: "static inline NOSLIP_NO_CONTRACT",
                prologue: "\n    NOSLIP_FP_CONTRACT_OFF",
                u64: "uint64_t",
                suffix: "ULL",
                bits: C_BITS,
            },
            Lang::OpenCl => Spelling {
                qualifiers: "static inline",
                prologue: "",
                u64: "ulong",
                suffix: "UL",
                bits: OPENCL_BITS,
            },
        }
    }

    /// `text` with its placeholders (`$QUALIFIERS`, `$PROLOGUE`, `$U64`, `$UL`, `$BITS`)
    /// spelled.
    fn spell(&self, text: &str) -> String {
        text.replace("$BITS", self.bits)
            .replace("$QUALIFIERS", self.qualifiers)
            .replace("$PROLOGUE", self.prologue)
            .replace("$U64", self.u64)
            .replace("$UL", self.suffix)
    }
}

/// The shared helpers, then the two corrections for each of `dims`, spelled in `lang`.
pub(super) fn functions(lang: Lang, dims: &[usize]) -> String {
    let spelling = Spelling::of(lang);
    let language = lang.language();
    let mut s = language.begin(Precision::F64);
    s.push_str(&spelling.spell(HELPERS));
    for &n in dims {
        s.push_str(&spelling.spell(&for_dim(n)));
        if lang == Lang::OpenCl {
            s.push_str(&batches(n));
        }
    }
    s.push_str(&language.end(Precision::F64));
    s
}

/// C's headers and bit casts.
const C_BITS: &str = r#"#include <stdint.h>
#include <string.h>

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
}"#;

/// OpenCL C's bit casts.
const OPENCL_BITS: &str = r#"static inline ulong noslip_cons_bits(double x)
{
    return as_ulong(x);
}

static inline double noslip_cons_from_bits(ulong u)
{
    return as_double(u);
}"#;

/// The helpers of every dimension (`collision_core::conserve`'s private functions).
const HELPERS: &str = r#"
/* Energy-conserving correction (collision_core::conserve; docs/accuracy.md, "An
 * energy-conserving correction"): after a no-slip contact, the kernel's outputs `after` moved
 * onto the energy of its inputs `before`, each output rounded stochastically from a hash of
 * its inputs (bit for bit the Rust correction). For conservative contacts only. */
$BITS

$QUALIFIERS void noslip_cons_halves(double a, double *hi, double *lo)
{$PROLOGUE
    double c = 134217729.0 * a;
    *hi = c - (c - a);
    *lo = a - *hi;
}

$QUALIFIERS void noslip_cons_two_prod(double a, double b, double *p, double *e)
{$PROLOGUE
    double ah, al, bh, bl;
    *p = a * b;
    noslip_cons_halves(a, &ah, &al);
    noslip_cons_halves(b, &bh, &bl);
    *e = ((ah * bh - *p) + ah * bl + al * bh) + al * bl;
}

$QUALIFIERS void noslip_cons_two_sum(double a, double b, double *s, double *e)
{$PROLOGUE
    double bb;
    *s = a + b;
    bb = *s - a;
    *e = (a - (*s - bb)) + (b - bb);
}

/* hi + lo += c x^2 (collision_core::conserve::weighted_squares, one term). */
$QUALIFIERS void noslip_cons_add(double c, double x, double *hi, double *lo)
{$PROLOGUE
    double sq, sq_lo, csq, csq_lo, s, e;
    noslip_cons_two_prod(x, x, &sq, &sq_lo);
    noslip_cons_two_prod(c, sq, &csq, &csq_lo);
    noslip_cons_two_sum(*hi, csq, &s, &e);
    *lo = e + *lo + csq_lo + c * sq_lo;
    *hi = s;
}

/* SplitMix64's finaliser. */
static inline $U64 noslip_cons_mix($U64 z)
{
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9$UL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111eb$UL;
    return z ^ (z >> 31);
}

/* x + p rounded to one of its two neighbouring floats, each with probability one minus its
 * distance over their gap, the random number a hash of x, p and salt. */
$QUALIFIERS double noslip_cons_round(double x, double p, $U64 salt)
{$PROLOGUE
    double hi, lo, next, gap, chance, r;
    $U64 pb, key;
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
$QUALIFIERS double noslip_cons_ds(double in_hi, double in_lo, double out_hi, double out_lo, double e_rel, int *ok)
{$PROLOGUE
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
$QUALIFIERS void noslip_cons_move(double *state, int n, int s, const double *v, double ds, int spin, $U64 salt)
{$PROLOGUE
    int k;
    for (k = 0; k < n; k++) {
        double x = state[s + k];
        state[s + k] = noslip_cons_round(x, ds * (x - v[k]), noslip_cons_mix(salt + ($U64)k));
    }
    if (spin)
        for (k = 0; k < s; k++) {
            double x = state[k];
            state[k] = noslip_cons_round(x, ds * x, noslip_cons_mix(salt + ($U64)(n + k)));
        }
}

/* hi + lo += the energy terms of a state: (m, u_k - v_k), then (m gamma^2 R R, U_ij). */
$QUALIFIERS void noslip_cons_energy(const double ball[3], double m, const double *state, int n, int s, const double *v, double *hi, double *lo)
{$PROLOGUE
    double mw = m * (ball[2] * ball[1] * ball[1]);
    int k;
    for (k = 0; k < n; k++)
        noslip_cons_add(m, state[s + k] - v[k], hi, lo);
    for (k = 0; k < s; k++)
        noslip_cons_add(mw, state[k], hi, lo);
}

/* E_rel: the same terms summed in plain double. */
$QUALIFIERS double noslip_cons_plain(const double ball[3], double m, const double *state, int n, int s, const double *v, double sum)
{$PROLOGUE
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
$QUALIFIERS void noslip_conserve_fixed_d{n}(const double ball[3], const double before[{len}], double after[{len}])
{{$PROLOGUE
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
$QUALIFIERS void noslip_conserve_free_d{n}(const double ball1[3], const double ball2[3], const double before1[{len}], const double before2[{len}], double after1[{len}], double after2[{len}])
{{$PROLOGUE
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

/// OpenCL's batch kernels of dimension `n`, one contact per work item over arrays of
/// structures, as the kernels' (`OpenCl::batch`): `noslip_conserve_fixed_d{n}_batch(count,
/// ball, before, after, out)` and `noslip_conserve_free_d{n}_batch(count, ball1, ball2,
/// before1, before2, after1, after2, out1, out2)`, `out` the corrected `after` (the inputs
/// stay as they are).
fn batches(n: usize) -> String {
    let len = n * (n - 1) / 2 + n;
    format!(
        r#"
// noslip_conserve_fixed_d{n} on contact i = get_global_id(0) < count: ball[3], before[{len}] and
// after[{len}] in, out[{len}] the corrected after.
__kernel void noslip_conserve_fixed_d{n}_batch(const uint count, __global const double *ball, __global const double *before, __global const double *after, __global double *out)
{{
    const size_t i = get_global_id(0);
    double ball_i[3], before_i[{len}], out_i[{len}];
    int k;
    if (i >= count) return;
    for (k = 0; k < 3; k++)
        ball_i[k] = ball[i * 3 + k];
    for (k = 0; k < {len}; k++) {{
        before_i[k] = before[i * {len} + k];
        out_i[k] = after[i * {len} + k];
    }}
    noslip_conserve_fixed_d{n}(ball_i, before_i, out_i);
    for (k = 0; k < {len}; k++)
        out[i * {len} + k] = out_i[k];
}}

// noslip_conserve_free_d{n} on contact i = get_global_id(0) < count: ball1[3], ball2[3],
// before1[{len}], before2[{len}], after1[{len}] and after2[{len}] in, out1[{len}] and out2[{len}] the
// corrected after1 and after2.
__kernel void noslip_conserve_free_d{n}_batch(const uint count, __global const double *ball1, __global const double *ball2, __global const double *before1, __global const double *before2, __global const double *after1, __global const double *after2, __global double *out1, __global double *out2)
{{
    const size_t i = get_global_id(0);
    double ball1_i[3], ball2_i[3], before1_i[{len}], before2_i[{len}], out1_i[{len}], out2_i[{len}];
    int k;
    if (i >= count) return;
    for (k = 0; k < 3; k++) {{
        ball1_i[k] = ball1[i * 3 + k];
        ball2_i[k] = ball2[i * 3 + k];
    }}
    for (k = 0; k < {len}; k++) {{
        before1_i[k] = before1[i * {len} + k];
        before2_i[k] = before2[i * {len} + k];
        out1_i[k] = after1[i * {len} + k];
        out2_i[k] = after2[i * {len} + k];
    }}
    noslip_conserve_free_d{n}(ball1_i, ball2_i, before1_i, before2_i, out1_i, out2_i);
    for (k = 0; k < {len}; k++) {{
        out1[i * {len} + k] = out1_i[k];
        out2[i * {len} + k] = out2_i[k];
    }}
}}
"#
    )
}
