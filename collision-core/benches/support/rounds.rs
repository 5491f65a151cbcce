//! What the alternated-round benchmarks share (`batch_rounds.rs`, `family_rounds.rs`): the
//! thread's CPU clock, the contacts as row-major arrays, and the median (min-max) summary.

use super::cases::Case;
use collision_core::batch::{BallRows, FreeRows, StateRows, StateRowsMut};

/// CPU seconds of the calling thread.
pub fn thread_seconds() -> f64 {
    let mut t = libc_timespec::default();
    // SAFETY: `t` is a valid timespec to write into; clock 3 is CLOCK_THREAD_CPUTIME_ID.
    let rc = unsafe { clock_gettime(3, &mut t) };
    assert_eq!(rc, 0, "clock_gettime(CLOCK_THREAD_CPUTIME_ID)");
    t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
}

#[repr(C)]
#[derive(Default)]
#[allow(non_camel_case_types)]
struct libc_timespec {
    tv_sec: i64,
    tv_nsec: i64,
}

extern "C" {
    fn clock_gettime(clock: i32, t: *mut libc_timespec) -> i32;
}

/// The contacts as row-major arrays (one contact per row, full skew matrices), as NumPy
/// holds them, and outputs of the same shape.
pub struct RowArrays {
    pub nu: Vec<f64>,
    pub spin: [Vec<f64>; 2],
    pub velocity: [Vec<f64>; 2],
    pub params: [[Vec<f64>; 3]; 2],
    pub out: [[Vec<f64>; 2]; 2],
}

impl RowArrays {
    pub fn new<const N: usize, const S: usize>(cases: &[Case<N, S>]) -> Self {
        let pairs: Vec<(usize, usize)> = collision_core::skew_pairs(N).collect();
        let mut a = RowArrays {
            nu: cases.iter().flat_map(|c| c.nu).collect(),
            spin: [vec![], vec![]],
            velocity: [vec![], vec![]],
            params: Default::default(),
            out: Default::default(),
        };
        for b in 0..2 {
            for c in cases {
                let s = &c.states[b];
                let mut m = vec![0.0; N * N];
                for (&x, &(r, k)) in s.spin.iter().zip(&pairs) {
                    m[r * N + k] = x;
                    m[k * N + r] = -x;
                }
                a.spin[b].extend(m);
                a.velocity[b].extend(s.velocity);
                let ball = &c.balls[b];
                a.params[b][0].push(ball.inv_mass);
                a.params[b][1].push(ball.radius);
                a.params[b][2].push(ball.gamma2);
            }
            a.out[b] = [vec![0.0; cases.len() * N * N], vec![0.0; cases.len() * N]];
        }
        a
    }

    pub fn split(&mut self) -> (FreeRows<'_, f64>, [StateRowsMut<'_, f64>; 2]) {
        let [[s1, v1], [s2, v2]] = &mut self.out;
        let rows = FreeRows {
            nu: &self.nu,
            states: [0, 1].map(|b| StateRows {
                spin: &self.spin[b],
                velocity: &self.velocity[b],
            }),
            balls: [0, 1].map(|b| BallRows {
                inv_mass: &self.params[b][0],
                radius: &self.params[b][1],
                gamma2: &self.params[b][2],
            }),
        };
        let out = [
            StateRowsMut {
                spin: s1,
                velocity: v1,
            },
            StateRowsMut {
                spin: s2,
                velocity: v2,
            },
        ];
        (rows, out)
    }
}

/// `median (min-max)` of `v`, sorted in place.
pub fn summary(v: &mut [f64]) -> String {
    v.sort_by(f64::total_cmp);
    format!("{:.2} ({:.2}-{:.2})", v[v.len() / 2], v[0], v[v.len() - 1])
}
