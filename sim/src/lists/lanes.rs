//! The pair times of a ball with the balls of its list, [`LANES`] at a time: the cell
//! engine's lanes ([`crate::engine::lanes`]), and in 3D on AVX2 the explicit form
//! ([`crate::engine::lanes3`]), each lane the canonical time, bit for bit.

use super::shells::Neighbour;
use crate::engine::lanes::{cell_image, pair_times, LANES};
use crate::residents::Resident;

/// The pair times of ball `i` (its flight and wraps in `flights`) with the balls of its
/// `list`, [`LANES`] at a time ([`pair_times`], the canonical time lane by lane: the same
/// bits as [`crate::canonical::pair_time`]), into `times`; returns the least of them (NaNs
/// skipped; infinite if every one is NaN). Compiled for AVX2 if `avx2` (the CPU runs it).
#[inline]
pub(super) fn list_times<const N: usize>(
    avx2: bool,
    i: usize,
    list: &[Neighbour<N>],
    flights: &[Resident<N>],
    size: &[f64; N],
    times: &mut Vec<f64>,
) -> f64 {
    #[cfg(target_arch = "x86_64")]
    if avx2 {
        if N == 3 {
            // SAFETY: the CPU runs AVX2 (detected when the engine was built); `N == 3`, so
            // every cast names the type it points to.
            return unsafe {
                list_times3(
                    i,
                    &*(list as *const [Neighbour<N>] as *const [Neighbour<3>]),
                    &*(flights as *const [Resident<N>] as *const [Resident<3>]),
                    &*(size as *const [f64; N]).cast::<[f64; 3]>(),
                    times,
                )
            };
        }
        // SAFETY: the CPU runs AVX2.
        return unsafe { list_times_avx2(i, list, flights, size, times) };
    }
    let _ = avx2;
    list_times_portable(i, list, flights, size, times)
}

/// [`list_times`] compiled for AVX2.
///
/// # Safety
/// The CPU must run AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn list_times_avx2<const N: usize>(
    i: usize,
    list: &[Neighbour<N>],
    flights: &[Resident<N>],
    size: &[f64; N],
    times: &mut Vec<f64>,
) -> f64 {
    list_times_portable(i, list, flights, size, times)
}

/// [`list_times`] for the target's baseline. The last chunk is padded with the ball itself,
/// whose pair time with itself is NaN (`|dv| = 0`).
#[inline(always)]
fn list_times_portable<const N: usize>(
    i: usize,
    list: &[Neighbour<N>],
    flights: &[Resident<N>],
    size: &[f64; N],
    times: &mut Vec<f64>,
) -> f64 {
    let me = &flights[i];
    times.clear();
    for chunk in list.chunks(LANES) {
        let bases: [[f64; N]; LANES] = std::array::from_fn(|l| {
            chunk
                .get(l)
                .map_or([0.0; N], |near| cell_image(&near.image, &me.wraps))
        });
        let lanes: [&Resident<N>; LANES] =
            std::array::from_fn(|l| &flights[chunk.get(l).map_or(i, |near| near.j as usize)]);
        let t = pair_times(&me.motion, lanes, bases.each_ref(), size);
        times.extend_from_slice(&t[..chunk.len()]);
    }
    // NaN is never less: `min` keeps the other.
    times.iter().fold(f64::INFINITY, |a, &t| a.min(t))
}

/// [`list_times`] in 3D on AVX2 ([`crate::engine::lanes3::times3`]): each lane's image
/// `m - W_j + W_i` summed in integers and converted once. These are whole numbers, so the
/// value is the one the generic form's `(m + W_i) - W_j` has in `f64`. (Its padded lanes take
/// the image 0 where the generic form takes `-W_i`: a ball's time with itself is NaN at any
/// image.)
///
/// # Safety
/// The CPU must run AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn list_times3(
    i: usize,
    list: &[Neighbour<3>],
    flights: &[Resident<3>],
    size: &[f64; 3],
    times: &mut Vec<f64>,
) -> f64 {
    use core::arch::x86_64::{_mm256_min_pd, _mm256_set1_pd, _mm256_storeu_pd};
    // Lane by lane, `minpd(t, least)` is `least` where `t` is NaN.
    let mut least = _mm256_set1_pd(f64::INFINITY);
    let me = &flights[i];
    let w_i = me.wraps.map(i32::from);
    let len = list.len();
    times.clear();
    times.resize(len.next_multiple_of(LANES), 0.0);
    let full = list.chunks_exact(LANES);
    // The last, partial chunk padded with the ball itself (image `0 - W_i + W_i = 0`).
    let mut last = [Neighbour {
        j: i as u32,
        twin: 0,
        image: [0; 3],
    }; LANES];
    last[..full.remainder().len()].copy_from_slice(full.remainder());
    let tail = (!full.remainder().is_empty()).then_some(&last);
    for (c, chunk) in full
        .map(|c| <&[Neighbour<3>; LANES]>::try_from(c).unwrap())
        .chain(tail)
        .enumerate()
    {
        let lanes: [&Resident<3>; LANES] = [
            &flights[chunk[0].j as usize],
            &flights[chunk[1].j as usize],
            &flights[chunk[2].j as usize],
            &flights[chunk[3].j as usize],
        ];
        // SAFETY: AVX2 (this function's).
        let t = unsafe {
            let image = [
                image_lanes(chunk, &lanes, &w_i, 0),
                image_lanes(chunk, &lanes, &w_i, 1),
                image_lanes(chunk, &lanes, &w_i, 2),
            ];
            crate::engine::lanes3::times3(&me.motion, lanes, image, size)
        };
        least = _mm256_min_pd(t, least);
        // SAFETY: four `f64` of room (`times` holds whole chunks).
        unsafe { _mm256_storeu_pd(times[c * LANES..c * LANES + LANES].as_mut_ptr(), t) };
    }
    times.truncate(len);
    let mut per_lane = [0.0; LANES];
    // SAFETY: four `f64` of room.
    unsafe { _mm256_storeu_pd(per_lane.as_mut_ptr(), least) };
    per_lane.iter().fold(f64::INFINITY, |a, &t| a.min(t))
}

/// The images `m - W_j + W_i` of a chunk's four partners along axis `k`, as `f64` lanes.
///
/// # Safety
/// The CPU must run AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn image_lanes(
    chunk: &[Neighbour<3>; LANES],
    lanes: &[&Resident<3>; LANES],
    w_i: &[i32; 3],
    k: usize,
) -> core::arch::x86_64::__m256d {
    use core::arch::x86_64::{_mm256_cvtepi32_pd, _mm_setr_epi32};
    let m = |l: usize| i32::from(chunk[l].image[k]) - i32::from(lanes[l].wraps[k]) + w_i[k];
    let (m0, m1, m2, m3) = (m(0), m(1), m(2), m(3));
    _mm256_cvtepi32_pd(_mm_setr_epi32(m0, m1, m2, m3))
}
