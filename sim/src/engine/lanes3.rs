//! [`super::lanes::pair_times`] in 3D, written with AVX2 intrinsics: the four partners'
//! flights read as two 4x4 transposes instead of one value at a time. The list engine's pair
//! times run here (`crate::lists`, `lanes.rs`); the cell engine's stay in the generic form
//! (through this code it ran 0.98 of its speed: its images come from `f64` bases;
//! docs/benchmarks.md, session 51).
//!
//! A 3D flight record ([`Motion<3>`], `repr(C)`) is eight `f64`: `a_0, a_1, a_2, t` then
//! `u_0, u_1, u_2, R`. Two 32-byte loads per partner and a 4x4 transpose of each four
//! (`unpacklo`/`unpackhi`, then `permute2f128`) give the eight lane vectors the pair times
//! need, where the compiler's version of the generic loop read them one lane at a time and
//! spilled them (callgrind counted about 60 instructions a partner). The images are given
//! as lanes (the caller sums them in integers and converts them once).
//!
//! **Same bits.** Each vector operation is the generic loop's IEEE operation on each lane,
//! in its order ([`super::lanes`], "Same events, same bits"): `Motion::at` as `a + u dt`
//! (a product, then a sum: intrinsics are never fused), `(q - p) + k L`, the sums from
//! `+0.0` over `k = 0, 1, 2`, `1 / a`, `-b * (1 / a)`, the closest-approach root, and the
//! same NaN where the pair never meets. `maxpd(x, y)` returns `y` when `x` is NaN, as
//! `f64::max(x, y)` does for `y` not NaN; the two may differ only in the sign of a zero
//! (`max(-0, +0)`), and the time returned is `t_ref + t` with `t_ref >= +0`, whose bits do
//! not see that sign. Tested against the canonical scalar time on 200 000 pairs (below).

use crate::motion::Motion;
use crate::residents::Resident;
use core::arch::x86_64::{
    __m256d, _mm256_add_pd, _mm256_and_pd, _mm256_blendv_pd, _mm256_cmp_pd, _mm256_div_pd,
    _mm256_loadu_pd, _mm256_max_pd, _mm256_mul_pd, _mm256_permute2f128_pd, _mm256_set1_pd,
    _mm256_setzero_pd, _mm256_sqrt_pd, _mm256_sub_pd, _mm256_unpackhi_pd, _mm256_unpacklo_pd,
    _mm256_xor_pd, _CMP_GE_OQ, _CMP_LT_OQ,
};

// The layout the loads rely on (`Motion` is `repr(C)`).
const _: () = {
    assert!(std::mem::offset_of!(Motion<3>, pos) == 0);
    assert!(std::mem::offset_of!(Motion<3>, since) == 24);
    assert!(std::mem::offset_of!(Motion<3>, velocity) == 32);
    assert!(std::mem::offset_of!(Motion<3>, radius) == 56);
};

/// The 4x4 transpose of rows `r` (lane `l`'s four values in `r[l]`): column `c` of the
/// result holds value `c` of every lane.
///
/// # Safety
/// The CPU runs AVX2.
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn transpose(r: [__m256d; 4]) -> [__m256d; 4] {
    // [x0 y0 x2 y2] and [x1 y1 x3 y3] for rows x, y.
    let lo01 = _mm256_unpacklo_pd(r[0], r[1]);
    let hi01 = _mm256_unpackhi_pd(r[0], r[1]);
    let lo23 = _mm256_unpacklo_pd(r[2], r[3]);
    let hi23 = _mm256_unpackhi_pd(r[2], r[3]);
    [
        _mm256_permute2f128_pd::<0x20>(lo01, lo23),
        _mm256_permute2f128_pd::<0x20>(hi01, hi23),
        _mm256_permute2f128_pd::<0x31>(lo01, lo23),
        _mm256_permute2f128_pd::<0x31>(hi01, hi23),
    ]
}

/// The pair times of flight `a` with the flights of `lanes` in 3D, lane `l`'s ball at image
/// `image[k][l]` (box lengths, whole numbers) along axis `k`, in a box of sides `size`; NaN
/// where the pair never meets: [`super::lanes::pair_times`]'s operations on each lane
/// (module docs).
///
/// # Safety
/// The CPU runs AVX2.
#[target_feature(enable = "avx2")]
#[inline]
pub(crate) unsafe fn times3(
    a: &Motion<3>,
    lanes: [&Resident<3>; 4],
    image: [__m256d; 3],
    size: &[f64; 3],
) -> __m256d {
    // No closures here: a closure is not compiled for the function's features.
    let at = |l: usize| -> *const f64 { (&lanes[l].motion as *const Motion<3>).cast() };
    let (p0, p1, p2, p3) = (at(0), at(1), at(2), at(3));
    // SAFETY: a `Motion<3>` is eight `f64` (the layout asserted above).
    let (first, second) = unsafe {
        (
            [
                _mm256_loadu_pd(p0),
                _mm256_loadu_pd(p1),
                _mm256_loadu_pd(p2),
                _mm256_loadu_pd(p3),
            ],
            [
                _mm256_loadu_pd(p0.add(4)),
                _mm256_loadu_pd(p1.add(4)),
                _mm256_loadu_pd(p2.add(4)),
                _mm256_loadu_pd(p3.add(4)),
            ],
        )
    };
    let [q0, q1, q2, since] = transpose(first);
    let [u0, u1, u2, radius] = transpose(second);
    let b_pos = [q0, q1, q2];
    let b_vel = [u0, u1, u2];
    let a_since = _mm256_set1_pd(a.since);
    let t_ref = _mm256_max_pd(since, a_since);
    let dt_a = _mm256_sub_pd(t_ref, a_since);
    let dt_b = _mm256_sub_pd(t_ref, since);
    let zero = _mm256_setzero_pd();
    let (mut aa, mut bb) = (zero, zero);
    let mut d = [zero; 3];
    let mut dv = [zero; 3];
    for k in 0..3 {
        let a_vel = _mm256_set1_pd(a.velocity[k]);
        let p = _mm256_add_pd(_mm256_set1_pd(a.pos[k]), _mm256_mul_pd(a_vel, dt_a));
        let q = _mm256_add_pd(b_pos[k], _mm256_mul_pd(b_vel[k], dt_b));
        let shift = _mm256_mul_pd(image[k], _mm256_set1_pd(size[k]));
        d[k] = _mm256_add_pd(_mm256_sub_pd(q, p), shift);
        dv[k] = _mm256_sub_pd(b_vel[k], a_vel);
    }
    for k in 0..3 {
        aa = _mm256_add_pd(aa, _mm256_mul_pd(dv[k], dv[k]));
        bb = _mm256_add_pd(bb, _mm256_mul_pd(d[k], dv[k]));
    }
    let inv_a = _mm256_div_pd(_mm256_set1_pd(1.0), aa);
    let t0 = _mm256_mul_pd(_mm256_xor_pd(bb, _mm256_set1_pd(-0.0)), inv_a);
    let mut h2 = zero;
    for k in 0..3 {
        let h = _mm256_add_pd(d[k], _mm256_mul_pd(t0, dv[k]));
        h2 = _mm256_add_pd(h2, _mm256_mul_pd(h, h));
    }
    let sigma = _mm256_add_pd(_mm256_set1_pd(a.radius), radius);
    let gap = _mm256_sub_pd(_mm256_mul_pd(sigma, sigma), h2);
    let root = _mm256_sqrt_pd(_mm256_max_pd(_mm256_mul_pd(gap, inv_a), zero));
    let t = _mm256_max_pd(_mm256_sub_pd(t0, root), zero);
    let meets = _mm256_and_pd(
        _mm256_cmp_pd::<_CMP_LT_OQ>(bb, zero),
        _mm256_cmp_pd::<_CMP_GE_OQ>(gap, zero),
    );
    let t = _mm256_blendv_pd(_mm256_set1_pd(f64::NAN), t, meets);
    _mm256_add_pd(t_ref, t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::canonical::pair_time;
    use core::arch::x86_64::{_mm256_setr_pd, _mm256_storeu_pd};

    /// 200 000 pairs (near, far, receding, grazing, at rest, from records of different times,
    /// at images): each lane's time is the scalar canonical time, bit for bit (NaN where it
    /// is NaN). Skipped (and says so) on a CPU without AVX2.
    #[test]
    fn lanes_give_the_scalar_times_in_3d() {
        if !is_x86_feature_detected!("avx2") {
            eprintln!("no AVX2 on this CPU: the 3D lanes are not run here");
            return;
        }
        let mut state: u64 = 0x2545_f491_4f6c_dd1d;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 * 4.0 - 2.0
        };
        let size = [7.5; 3];
        let mut met = 0;
        for round in 0..50_000 {
            let flight = |next: &mut dyn FnMut() -> f64| Motion::<3> {
                pos: std::array::from_fn(|_| next() * 3.0),
                since: if round % 3 == 0 { 0.0 } else { next().abs() },
                velocity: std::array::from_fn(|_| if round % 11 == 0 { 0.0 } else { next() }),
                radius: 1.0 + next().abs(),
            };
            let a = flight(&mut next);
            let residents: [Resident<3>; 4] = std::array::from_fn(|_| Resident {
                motion: flight(&mut next),
                wraps: [0; 3],
                ball: 1,
                count: 0,
            });
            let images: [[f64; 3]; 4] =
                std::array::from_fn(|_| std::array::from_fn(|_| (next() * 1.5).round()));
            let lanes = std::array::from_fn(|l| &residents[l]);
            let mut got = [0.0; 4];
            // SAFETY: the CPU runs AVX2 (checked above).
            unsafe {
                let image = std::array::from_fn(|k| {
                    _mm256_setr_pd(images[0][k], images[1][k], images[2][k], images[3][k])
                });
                _mm256_storeu_pd(got.as_mut_ptr(), times3(&a, lanes, image, &size));
            }
            for l in 0..4 {
                let want = pair_time(&a, &residents[l].motion, &images[l], &size);
                assert_eq!(got[l].is_nan(), want.is_nan(), "{round} {l}");
                if !want.is_nan() {
                    met += 1;
                    assert_eq!(got[l].to_bits(), want.to_bits(), "{round} {l}");
                }
            }
        }
        // The sample meets often enough to test the times, not only the NaNs.
        assert!(met > 1_000, "{met}");
    }
}
