//! `collide_batch(..., contact=law)`'s rows with an immovable body (`inv_mass = 0`), on the
//! row path: gathered into row-major columns and run by `Exec::rough_fixed_rows` (the family's
//! `fixed` kernel, one law shared or one per row), routed as `collide_rough_unchecked` /
//! `collide_walton_unchecked` route them: body 1 immovable, `fixed` as it is; body 2
//! immovable, `fixed` with the bodies swapped and `-nu`. The moving body's state is the
//! kernel's, the immovable body's its input (as those functions return it): the scalar path's
//! bits on every row.

use super::inputs::{nu_row, param, BodyArrays, Inputs, LawColumns};
use super::outputs::{put, Outputs};
use collision_core::batch::{
    BallRows, EachLawBatchKernel, Exec, FixedRows, LawRowError, RestitutionLanes, RestitutionRows,
    RoughBatchKernel, StateRows, StateRowsMut, WaltonLanes, WaltonRows,
};
use collision_core::{Generated, RefArith, Restitution, Scalar, Walton};

/// The fixed rows gathered: row `j` of each column is the `j`-th row with an immovable body.
struct Gathered<T> {
    nu: Vec<T>,
    spin: [Vec<T>; 2],
    velocity: [Vec<T>; 2],
    radius1: Vec<T>,
    ball2: [Vec<T>; 3],
}

/// Row `i` of `body`'s angular velocity `(n, n)` and velocity, appended to `spin`, `velocity`.
fn push_state<T: Copy, const N: usize>(
    body: &BodyArrays<'_, T>,
    i: usize,
    spin: &mut Vec<T>,
    velocity: &mut Vec<T>,
) {
    for r in 0..N {
        for c in 0..N {
            spin.push(body.spin[[i, r, c]]);
        }
    }
    velocity.extend((0..N).map(|k| body.velocity[[i, k]]));
}

/// Every row of `input` with an immovable body, under `laws` (already checked), its two
/// states written into `out`; the other rows are left as they are.
pub(super) fn run_fixed_rows<T, const N: usize, const S: usize>(
    input: &Inputs<'_, T>,
    laws: &LawColumns<'_, T>,
    exec: Exec,
    out: &mut Outputs<'_, T>,
) -> Result<(), LawRowError>
where
    T: Scalar + Copy + Send + Sync + 'static,
    for<'x> &'x T: RefArith<T>,
    Generated: RoughBatchKernel<Restitution<T>, T, N, S>
        + RoughBatchKernel<Walton<T>, T, N, S>
        + EachLawBatchKernel<RestitutionLanes<T>, T, N, S>
        + EachLawBatchKernel<WaltonLanes<T>, T, N, S>,
{
    let zero = T::zero();
    let [a, b] = &input.bodies;
    // (row, whether body 2 is the immovable one), as `collide_*_unchecked` tests them.
    let fixed: Vec<(usize, bool)> = (0..input.rows)
        .filter_map(|i| {
            if param(&a.inv_mass, i) == zero {
                Some((i, false))
            } else if param(&b.inv_mass, i) == zero {
                Some((i, true))
            } else {
                None
            }
        })
        .collect();
    if fixed.is_empty() {
        return Ok(());
    }
    let k = fixed.len();
    let mut g = Gathered {
        nu: Vec::with_capacity(k * N),
        spin: [0, 1].map(|_| Vec::with_capacity(k * N * N)),
        velocity: [0, 1].map(|_| Vec::with_capacity(k * N)),
        radius1: Vec::with_capacity(k),
        ball2: [0, 1, 2].map(|_| Vec::with_capacity(k)),
    };
    for &(i, swapped) in &fixed {
        let (still, moving) = if swapped { (b, a) } else { (a, b) };
        let nu = nu_row::<T, N>(input, i);
        g.nu.extend(nu.map(|x| if swapped { -x } else { x }));
        let [s1, s2] = &mut g.spin;
        let [v1, v2] = &mut g.velocity;
        push_state::<T, N>(still, i, s1, v1);
        push_state::<T, N>(moving, i, s2, v2);
        g.radius1.push(param(&still.radius, i));
        let ball = moving.ball(i);
        let [w, r, gamma2] = &mut g.ball2;
        w.push(ball.inv_mass);
        r.push(ball.radius);
        gamma2.push(ball.gamma2);
    }
    let rows = FixedRows {
        nu: &g.nu,
        states: [0, 1].map(|s| StateRows {
            spin: &g.spin[s],
            velocity: &g.velocity[s],
        }),
        radius1: &g.radius1,
        ball2: BallRows {
            inv_mass: &g.ball2[0],
            radius: &g.ball2[1],
            gamma2: &g.ball2[2],
        },
    };
    // Each law column at the fixed rows (a shared column stays shared).
    let pick = |c: &[T]| -> Vec<T> {
        if c.len() == 1 {
            c.to_vec()
        } else {
            fixed.iter().map(|&(i, _)| c[i]).collect()
        }
    };
    let (mut spin, mut velocity) = (vec![zero; k * N * N], vec![zero; k * N]);
    let target = StateRowsMut {
        spin: &mut spin,
        velocity: &mut velocity,
    };
    match laws {
        LawColumns::Rough(l) => {
            let (e, beta) = (pick(l.e), pick(l.beta));
            let laws = RestitutionRows { e: &e, beta: &beta };
            exec.rough_fixed_rows::<_, T, N, S>(&laws, &rows, target)
        }
        LawColumns::Walton(l) => {
            let (e, mu, beta0) = (pick(l.e), pick(l.mu), pick(l.beta0));
            let laws = WaltonRows {
                e: &e,
                mu: &mu,
                beta0: &beta0,
            };
            exec.rough_fixed_rows::<_, T, N, S>(&laws, &rows, target)
        }
    }?;
    let pairs: [(usize, usize); S] = {
        let all: Vec<(usize, usize)> = collision_core::skew_pairs(N).collect();
        std::array::from_fn(|k| all[k])
    };
    for (j, &(i, swapped)) in fixed.iter().enumerate() {
        let (still, moving) = if swapped { (1, 0) } else { (0, 1) };
        out.spin[moving][i * N * N..(i + 1) * N * N]
            .copy_from_slice(&spin[j * N * N..(j + 1) * N * N]);
        out.velocity[moving][i * N..(i + 1) * N].copy_from_slice(&velocity[j * N..(j + 1) * N]);
        let state = input.bodies[still].state::<N, S>(i, &pairs);
        put(out, i, still, &state, &pairs);
    }
    Ok(())
}
