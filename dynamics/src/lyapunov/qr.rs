//! The spectrum by tangent-space dynamics with periodic re-orthonormalisation.
//!
//! `k` tangent vectors `V = [v_1 .. v_k]` start random (seeded) and orthonormal. Between
//! re-orthonormalisations each is carried by the tangent maps along the engine's trajectory
//! (lazily per ball: a ball's block is flown only when the ball meets something, or at a
//! re-orthonormalisation). Every `every` contacts, modified Gram-Schmidt writes `V = Q R`,
//! `V <- Q`, and `log R_ii` is the growth of the `i`-dimensional volume's `i`-th factor: its
//! mean rate is exponent `i`. The metric is the plain Euclidean one of `[x, u, U]`; the
//! exponents do not depend on it (any fixed metric is equivalent).

use super::cost::{self, Choice};
use super::stats::Blocks;
use super::touch::{touch, Touch};
use super::{
    never, next_contact, Dim, Interrupted, LyapunovError, Options, Plan, Running, Spectrum,
};
use crate::law::{Law, LawKernels};
use crate::tangent::{block_len, boundary_contact, flight, pair_contact};
use collision_core::rng::Rng;
use collision_core::Generated;
use noslip_sim::{Setup, Simulation};

/// Default contacts between re-orthonormalisations: every contact for one ball, else a quarter
/// of the balls (each ball then meets about half another). Between two re-orthonormalisations
/// the rounding error of the last vector (`eps`) grows like the largest exponent while the
/// vector itself shrinks like the smallest: `eps exp((lambda_1 - lambda_k) tau)` must stay far
/// below 1. A dispersing contact stretches by a factor of order 10 (`lambda_1 - lambda_k`
/// is about 4 per contact in the Sinai table): ten contacts between re-orthonormalisations
/// gave the Sinai table's smooth spectrum a sum of 0.4 instead of 0, one contact gives 0.
fn default_every(balls: usize) -> u64 {
    (balls as u64 / 4).max(1)
}

/// `a . b` in eight interleaved partial sums, added pairwise at the end: the same products,
/// summed in another order (no less accurate than one running sum), which the compiler
/// vectorises; one running sum is a chain of dependent additions, and Gram-Schmidt is
/// dot products for half its work.
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut s = [0.0f64; 8];
    let (ca, cb) = (a.chunks_exact(8), b.chunks_exact(8));
    let tail: f64 = ca
        .remainder()
        .iter()
        .zip(cb.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in ca.zip(cb) {
        for i in 0..8 {
            s[i] += x[i] * y[i];
        }
    }
    tail + ((s[0] + s[4]) + (s[1] + s[5])) + ((s[2] + s[6]) + (s[3] + s[7]))
}

/// Modified Gram-Schmidt: orthonormalises `vectors` in place, returns `log R_ii`.
pub(crate) fn gram_schmidt(vectors: &mut [Vec<f64>]) -> Vec<f64> {
    let mut logs = Vec::with_capacity(vectors.len());
    for i in 0..vectors.len() {
        let (done, rest) = vectors.split_at_mut(i);
        let v = &mut rest[0];
        for q in done.iter() {
            let p = dot(v, q);
            for (a, b) in v.iter_mut().zip(q) {
                *a -= p * b;
            }
        }
        let norm = dot(v, v).sqrt();
        for a in v.iter_mut() {
            *a /= norm;
        }
        logs.push(norm.ln());
    }
    logs
}

/// The `k` a QR run of `setup` with `options` takes, and its cost ([`cost::choose`]): what
/// [`qr`] will do, known before it runs (the command prints the default's note first).
pub fn choice<const N: usize, const S: usize>(
    setup: &Setup<N, S>,
    options: &Options,
) -> Result<Choice, LyapunovError> {
    let plan = Plan::new(options)?;
    let balls = setup.bodies.len();
    cost::choose(
        options.k,
        balls * block_len(N, S),
        plan.events,
        plan.every(options.every, default_every(balls))?,
    )
}

/// The `k` largest exponents of the scene's dynamics (see the module docs).
pub fn qr<const N: usize, const S: usize>(
    setup: Setup<N, S>,
    options: &Options,
) -> Result<Spectrum, LyapunovError>
where
    Generated: Dim<N, S>,
{
    qr_interruptible(setup, options, &never)
}

/// [`qr`], asking `interrupted` before every contact ([`LyapunovError::Interrupted`] when it
/// says stop).
pub fn qr_interruptible<const N: usize, const S: usize>(
    setup: Setup<N, S>,
    options: &Options,
    interrupted: Interrupted<'_>,
) -> Result<Spectrum, LyapunovError>
where
    Generated: Dim<N, S>,
{
    let plan = Plan::new(options)?;
    let species = setup.species.clone();
    let kinds: Vec<usize> = setup.bodies.iter().map(|b| b.species).collect();
    let balls = kinds.len();
    let len = block_len(N, S);
    let dimension = balls * len;
    let every = plan.every(options.every, default_every(balls))?;
    let k = choice(&setup, options)?.k;
    // The engine runs smooth contacts itself; its kernels are the no-slip ones.
    let kernels = LawKernels {
        law: Law::NoSlip,
        species: species.clone(),
    };
    let setup = super::overridden(setup, options.law);
    let mut sim = Simulation::new(setup, kernels).map_err(LyapunovError::Setup)?;
    let mut rng = Rng::new(options.seed);
    let mut vectors: Vec<Vec<f64>> = (0..k)
        .map(|_| (0..dimension).map(|_| rng.uniform(-1.0, 1.0)).collect())
        .collect();
    gram_schmidt(&mut vectors);
    let radius = |i: usize| species[kinds[i]].radius;
    let mut since = vec![0.0f64; balls];
    let mut blocks = Blocks::new(plan.blocks, k);
    let mut running = Vec::new();
    let stride = (plan.events / every / 1000).max(1);
    let (mut last_time, mut last_contact, mut renormalised) = (0.0f64, 0u64, 0u64);
    let (mut measured_growth, mut measured_time) = (vec![0.0f64; k], 0.0f64);
    let fly =
        |v: &mut [f64], b: usize, dt: f64| flight::<f64, N>(&mut v[b * len..(b + 1) * len], &dt);
    for c in 1..=plan.events {
        let e = next_contact(&mut sim, &species, interrupted)?;
        let law = Law::of(sim.contact_kind(&e.contact)).ok_or(LyapunovError::Rough)?;
        match touch(&e.contact, sim.geometry(&e.contact), radius) {
            Touch::Boundary { ball, geometry } => {
                let dt = e.time - since[ball];
                for v in vectors.iter_mut() {
                    fly(v, ball, dt);
                    boundary_contact(
                        &geometry,
                        law,
                        &species[kinds[ball]],
                        &e.nu,
                        &e.pre[0],
                        &mut v[ball * len..(ball + 1) * len],
                    );
                }
                since[ball] = e.time;
            }
            Touch::Pair { i, j, geometry } => {
                let (dti, dtj) = (e.time - since[i], e.time - since[j]);
                for v in vectors.iter_mut() {
                    fly(v, i, dti);
                    fly(v, j, dtj);
                    let (bi, bj) = two_blocks(v, i, j, len);
                    pair_contact(
                        &geometry,
                        law,
                        [&species[kinds[i]], &species[kinds[j]]],
                        &e.nu,
                        [&e.pre[0], &e.pre[1]],
                        bi,
                        bj,
                    );
                }
                since[i] = e.time;
                since[j] = e.time;
            }
        }
        if c % every == 0 || c == plan.events {
            for (b, s) in since.iter_mut().enumerate() {
                for v in vectors.iter_mut() {
                    fly(v, b, e.time - *s);
                }
                *s = e.time;
            }
            let logs = gram_schmidt(&mut vectors);
            if logs.iter().any(|l| !l.is_finite()) {
                return Err(if c - last_contact > 1 {
                    LyapunovError::Overflow {
                        from: last_contact,
                        at: c,
                    }
                } else {
                    LyapunovError::Singular { at: c }
                });
            }
            if let Some(b) = plan.block(c) {
                let dt = e.time - last_time;
                blocks.add(b, &logs, dt, c - last_contact);
                measured_time += dt;
                for (m, l) in measured_growth.iter_mut().zip(&logs) {
                    *m += l;
                }
                renormalised += 1;
                if renormalised % stride == 0 || c == plan.events {
                    running.push(Running {
                        contacts: c,
                        time: e.time,
                        exponents: measured_growth.iter().map(|g| g / measured_time).collect(),
                    });
                }
            }
            last_time = e.time;
            last_contact = c;
        }
    }
    let (per_time, per_contact) = blocks.estimates();
    Ok(Spectrum {
        method: "qr",
        law: options.law,
        dimension,
        contacts: plan.events,
        warmup: plan.warmup,
        every,
        time: measured_time,
        sum: blocks.sum(),
        per_time,
        per_contact,
        running,
    })
}

/// Disjoint mutable blocks `i` and `j` of a tangent vector (in that order).
fn two_blocks(v: &mut [f64], i: usize, j: usize, len: usize) -> (&mut [f64], &mut [f64]) {
    if i < j {
        let (a, b) = v.split_at_mut(j * len);
        (&mut a[i * len..(i + 1) * len], &mut b[..len])
    } else {
        let (a, b) = v.split_at_mut(i * len);
        let (bj, bi) = (&mut a[j * len..(j + 1) * len], &mut b[..len]);
        (bi, bj)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `V = Q R` with `Q` orthonormal; the logs are `log R_ii` of the hand-computed QR of
    /// `[(3, 4, 0), (1, 0, 2)]`: `R_11 = 5`, `v_2 - (3/5) q_1 = (16/25, -12/25, 2)`.
    #[test]
    fn gram_schmidt_is_qr() {
        let mut v = vec![vec![3.0, 4.0, 0.0], vec![1.0, 0.0, 2.0]];
        let logs = gram_schmidt(&mut v);
        let r22 = ((16.0f64 / 25.0).powi(2) + (12.0f64 / 25.0).powi(2) + 4.0).sqrt();
        assert!((logs[0] - 5f64.ln()).abs() < 1e-15);
        assert!((logs[1] - r22.ln()).abs() < 1e-15);
        let dot: f64 = v[0].iter().zip(&v[1]).map(|(a, b)| a * b).sum();
        assert!(dot.abs() < 1e-15);
        let mut w = vec![0.0; 6];
        w[..3].copy_from_slice(&[1.0, 2.0, 3.0]);
        w[3..].copy_from_slice(&[4.0, 5.0, 6.0]);
        let (b1, b0) = two_blocks(&mut w, 1, 0, 3);
        assert_eq!((b1[0], b0[0]), (4.0, 1.0));
    }
}
