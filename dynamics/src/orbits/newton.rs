//! Newton's method for a period-`K` orbit from one start (module docs of [`super`]), within a
//! [`Budget`] of contacts: every evaluation of `P^K` with its derivative follows `K` contacts,
//! and a search's starts share one budget, so its work is bounded whatever the grid and the
//! period.

use super::section::{self, return_map, Section};
use super::{energy, nearest, norm, poly, project, residual_vector, Miss, Orbit};
use super::{Verdict, CONVERGED, MAX_ITERATIONS, RESTING, STABILITY_TOL};
use crate::dual::Dual;
use crate::geometry::dot;
use crate::table::Table;
use collision_core::{Generated, Kernel};
use nalgebra::{DMatrix, DVector, SVD};

/// Step halvings per Newton iteration before a start is given up.
pub const MAX_HALVINGS: usize = 30;

/// Sweeps of the bidiagonal QR iteration allowed to one Newton step's SVD (a matrix of at
/// most `2n + S + 2 = 29` rows; nalgebra's `svd` has no cap of its own).
pub const SVD_SWEEPS: usize = 10_000;

/// The contacts a search may still follow: each evaluation of `P^K` (with its derivative)
/// costs `K`. One start costs at most `(MAX_ITERATIONS + 1) (MAX_HALVINGS + 1) K` contacts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Budget {
    /// The most contacts to follow.
    pub limit: u64,
    /// Contacts followed so far.
    pub used: u64,
}

impl Budget {
    /// A budget of `limit` contacts, none used.
    pub fn new(limit: u64) -> Budget {
        Budget { limit, used: 0 }
    }

    /// Takes `k` contacts, or [`Miss::Budget`] (nothing taken) if they do not fit.
    fn spend(&mut self, k: usize) -> Result<(), Miss> {
        let k = k as u64;
        if self.limit - self.used < k {
            return Err(Miss::Budget);
        }
        self.used += k;
        Ok(())
    }
}

/// A start put on boundary `b`'s contact surface with its energy reset to `energy0`, its
/// `k`-step return and its relative residual `|P^K(z) - z| / (1 + |z|)`.
#[allow(clippy::type_complexity)]
fn evaluate<const N: usize, const S: usize>(
    table: &Table<f64, N>,
    b: usize,
    energy0: f64,
    z: &[f64],
    k: usize,
    budget: &mut Budget,
) -> Result<(Vec<f64>, section::Return<f64, N, S>, Vec<f64>, f64), Miss>
where
    Generated: Kernel<f64, N, S> + Kernel<Dual<f64>, N, S>,
{
    let mut z = z.to_vec();
    let x: [f64; N] = std::array::from_fn(|i| z[i]);
    let (y, nu) = project(table, b, &x);
    z[..N].copy_from_slice(&y);
    let scale = (energy0 / energy(table, &z)).sqrt();
    for v in &mut z[N..] {
        *v *= scale;
    }
    let un = dot(&z[N..2 * N], &nu);
    if un.is_nan() || un <= 0.0 {
        return Err(Miss::LeftSection);
    }
    budget.spend(k)?;
    let r = return_map(table, &Section::<f64, N, S>::from_slice(&z), k).map_err(Miss::NoHit)?;
    let f = residual_vector(table, &r.states[k - 1].to_vec(), &z);
    let res = norm(&f) / (1.0 + norm(&z));
    Ok((z, r, f, res))
}

/// The least-squares Newton step of least norm for `(DP^K - I) dz = -F`, constrained to the
/// energy surface (`grad E . dz = 0`) and to the section (`nu . dx = 0`): without these two
/// rows the velocity scaling `(0, u, U)`, along which `(DP^K - I)` maps to the velocity part
/// of `F` itself off the orbit, would be used to shrink `F` by shrinking the velocity. `None`
/// if the SVD did not converge within [`SVD_SWEEPS`].
fn newton_step<const N: usize>(
    table: &Table<f64, N>,
    b0: usize,
    z: &[f64],
    columns: &[Vec<f64>],
    f: &[f64],
) -> Option<Vec<f64>> {
    let len = z.len();
    let x: [f64; N] = std::array::from_fn(|i| z[i]);
    let (_, nu) = project(table, b0, &x);
    let g = table.ball.gamma2 * table.ball.radius * table.ball.radius;
    let mut grad_e: Vec<f64> = (0..len)
        .map(|i| {
            if i < N {
                0.0
            } else if i < 2 * N {
                z[i]
            } else {
                g * z[i]
            }
        })
        .collect();
    let scale = norm(&grad_e);
    grad_e.iter_mut().for_each(|v| *v /= scale);
    let j = DMatrix::from_fn(len + 2, len, |a, b| {
        if a < len {
            columns[b][a] - f64::from(u8::from(a == b))
        } else if a == len {
            grad_e[b]
        } else if b < N {
            nu[b]
        } else {
            0.0
        }
    });
    let rhs = DVector::from_iterator(len + 2, f.iter().map(|v| -v).chain([0.0, 0.0]));
    let svd = SVD::try_new(j, true, true, f64::EPSILON, SVD_SWEEPS)?;
    let cut = 1e-9 * svd.singular_values.max();
    Some(
        svd.solve(&rhs, cut)
            .expect("u and v were computed")
            .iter()
            .copied()
            .collect(),
    )
}

/// Newton's method from `start` (moved onto its nearest boundary first) for a period-`k`
/// orbit, with a budget of its own (a start costs at most
/// `(MAX_ITERATIONS + 1) (MAX_HALVINGS + 1) k` contacts). See [`newton_within`].
pub fn newton<const N: usize, const S: usize>(
    table: &Table<f64, N>,
    start: &[f64],
    k: usize,
) -> Result<Orbit, Miss>
where
    Generated: Kernel<f64, N, S> + Kernel<Dual<f64>, N, S>,
{
    newton_within::<N, S>(table, start, k, &mut Budget::new(u64::MAX))
}

/// Newton's method from `start` for a period-`k` orbit, each evaluation of `P^k` taken from
/// `budget` ([`Miss::Budget`] once it is spent). Far from an orbit the full step may
/// overshoot (leave the section, or grow the residual): it is halved until it does neither
/// (at most [`MAX_HALVINGS`] times); near an orbit the full step is taken, so the convergence
/// is quadratic. At most [`MAX_ITERATIONS`] steps.
pub fn newton_within<const N: usize, const S: usize>(
    table: &Table<f64, N>,
    start: &[f64],
    k: usize,
    budget: &mut Budget,
) -> Result<Orbit, Miss>
where
    Generated: Kernel<f64, N, S> + Kernel<Dual<f64>, N, S>,
{
    let x: [f64; N] = std::array::from_fn(|i| start[i]);
    let (b0, _) = nearest(table, &x);
    let energy0 = energy(table, start);
    let (mut z, mut r, mut f, mut res) = evaluate::<N, S>(table, b0, energy0, start, k, budget)?;
    let mut residuals = vec![res];
    for iteration in 0..=MAX_ITERATIONS {
        if res < CONVERGED {
            // A ball at rest touching the table (its energy all in the spin, which smooth
            // contacts keep) is a fixed point of the map but no orbit: no flight.
            let speed2: f64 = z[N..2 * N].iter().map(|v| v * v).sum();
            if speed2 <= RESTING * energy0 {
                return Err(Miss::Resting);
            }
            let (eigenvalues, verdict) = match section_eigenvalues(&r.columns) {
                Some(e) => {
                    let v = verdict(&e);
                    (e, v)
                }
                None => (Vec::new(), Verdict::Undetermined),
            };
            return Ok(Orbit {
                boundaries: r.boundaries,
                start: z,
                states: r.states.iter().map(Section::to_vec).collect(),
                residual: res,
                residuals,
                verdict,
                eigenvalues,
                found_from: 1,
            });
        }
        if iteration == MAX_ITERATIONS {
            break;
        }
        let Some(step) = newton_step(table, b0, &z, &r.columns, &f) else {
            break;
        };
        let mut accepted = None;
        let mut s = 1.0;
        for _ in 0..MAX_HALVINGS {
            let candidate: Vec<f64> = z.iter().zip(&step).map(|(v, d)| v + s * d).collect();
            match evaluate::<N, S>(table, b0, energy0, &candidate, k, budget) {
                Ok(next) if next.3 < res => {
                    accepted = Some(next);
                    break;
                }
                Err(Miss::Budget) => return Err(Miss::Budget),
                _ => {}
            }
            s /= 2.0;
        }
        let Some(next) = accepted else { break };
        (z, r, f, res) = next;
        residuals.push(res);
    }
    Err(Miss::NoConvergence { residual: res })
}

/// The section map's eigenvalues: those of `DP^K` without the one nearest 0 (the flow
/// direction's); `None` if the eigenvalue iteration did not converge ([`poly::eigenvalues`]).
pub fn section_eigenvalues(columns: &[Vec<f64>]) -> Option<Vec<(f64, f64)>> {
    let mut e = poly::eigenvalues(columns)?;
    if let Some(i) =
        (0..e.len()).min_by(|&a, &b| e[a].0.hypot(e[a].1).total_cmp(&e[b].0.hypot(e[b].1)))
    {
        e.remove(i);
    }
    e.sort_by(|a, b| {
        b.0.hypot(b.1)
            .total_cmp(&a.0.hypot(a.1))
            .then(b.0.total_cmp(&a.0))
            .then(b.1.total_cmp(&a.1))
    });
    Some(e)
}

/// The verdict of these eigenvalues (module docs of [`super`]).
pub fn verdict(eigenvalues: &[(f64, f64)]) -> Verdict {
    if eigenvalues
        .iter()
        .any(|(re, im)| (re.hypot(*im) - 1.0).abs() > STABILITY_TOL)
    {
        Verdict::Hyperbolic
    } else if eigenvalues.iter().any(|(_, im)| im.abs() > STABILITY_TOL) {
        Verdict::Elliptic
    } else {
        Verdict::Parabolic
    }
}
