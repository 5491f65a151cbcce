//! The pair correlation `g(r)` of the balls' centres in a periodic box, sampled by
//! `granular::Sampler::with_pair_correlation` and averaged over its samples (docs/granular.md).
//!
//! With `N_b` balls in a box of volume `V`, `C_b` the ordered pairs `(i, j)`, `i != j`, whose
//! nearest-image distance is in bin `b` (`[r_b, r_b+1)`, width `r_max / bins`), summed over `K`
//! samples, and `v_n` the volume of the unit ball of R^n,
//!
//! ```text
//! g(r_b..r_b+1) = C_b / (K N_b rho' v_n (r_b+1^n - r_b^n)),   rho' = (N_b - 1) / V,
//! ```
//!
//! the mean number of other centres in the shell over the number an ideal gas of the same
//! `N_b - 1` other balls puts there. Pairs are found through a grid of cells at least `r_max`
//! wide: `O(N_b)` per sample at fixed density and `r_max`, not `O(N_b^2)`.

use crate::{PairKernels, Simulation};

/// The most bins of a pair correlation (8 MiB of counts): a bound given by every front end
/// (`--pair-bins`, Python's `pair_bins`), so that no argument asks for gigabytes.
pub const MAX_BINS: usize = 1 << 20;

/// The histogram of pair distances over the samples so far.
#[derive(Clone, Debug)]
pub struct PairCorrelation {
    r_max: f64,
    sides: Vec<f64>,
    /// Cells per axis, each at least `r_max` wide.
    cells: Vec<usize>,
    counts: Vec<u64>,
    samples: u64,
    balls: usize,
}

impl PairCorrelation {
    /// `bins` bins over `[0, r_max]` in a periodic box of sides `sides`: `0 < r_max <= min
    /// L_k / 2` (beyond, a pair's nearest image is not its only one within `r_max`).
    pub fn new(r_max: f64, bins: usize, sides: &[f64]) -> Result<PairCorrelation, String> {
        let half = sides.iter().fold(f64::INFINITY, |a, &l| a.min(l / 2.0));
        if !(r_max > 0.0 && r_max <= half) {
            return Err(format!(
                "the pair correlation's r_max = {r_max} must be in (0, {half}], half the box's \
                 shortest side"
            ));
        }
        if !(1..=MAX_BINS).contains(&bins) {
            return Err(format!(
                "the pair correlation's bins must be in 1..={MAX_BINS}, got {bins}"
            ));
        }
        Ok(PairCorrelation {
            r_max,
            sides: sides.to_vec(),
            cells: sides
                .iter()
                .map(|&l| ((l / r_max).floor() as usize).max(1))
                .collect(),
            counts: vec![0; bins],
            samples: 0,
            balls: 0,
        })
    }

    /// Adds the pairs of `sim`'s balls now.
    pub fn sample<const N: usize, const S: usize, K: PairKernels<f64, N, S>>(
        &mut self,
        sim: &Simulation<N, S, K>,
    ) {
        let (l, c) = (&self.sides, &self.cells);
        let x: Vec<[f64; N]> = (0..sim.len())
            .map(|i| {
                let p = sim.position(i);
                std::array::from_fn(|k| p[k].rem_euclid(l[k]))
            })
            .collect();
        // The balls by cell (a counting sort): cell `q`'s are `order[start[q]..start[q + 1]]`.
        let cell_of = |p: &[f64; N]| -> [usize; N] {
            std::array::from_fn(|k| ((p[k] / l[k] * c[k] as f64) as usize).min(c[k] - 1))
        };
        let flat = |q: &[usize; N]| (0..N).fold(0, |a, k| a * c[k] + q[k]);
        let total: usize = c.iter().product();
        let mut start = vec![0usize; total + 1];
        let index: Vec<usize> = x.iter().map(|p| flat(&cell_of(p))).collect();
        for &q in &index {
            start[q + 1] += 1;
        }
        for q in 0..total {
            start[q + 1] += start[q];
        }
        let mut fill = start.clone();
        let mut order = vec![0usize; x.len()];
        for (i, &q) in index.iter().enumerate() {
            order[fill[q]] = i;
            fill[q] += 1;
        }
        // Per axis, the distinct neighbour offsets `{-1, 0, 1} mod c_k`.
        let offsets: Vec<Vec<usize>> = c
            .iter()
            .map(|&ck| {
                let mut o = vec![0, 1 % ck, (ck - 1) % ck];
                o.sort_unstable();
                o.dedup();
                o
            })
            .collect();
        let combos: usize = offsets.iter().map(Vec::len).product();
        let width = self.r_max / self.counts.len() as f64;
        for (i, p) in x.iter().enumerate() {
            let q = cell_of(p);
            for mut m in 0..combos {
                let mut neighbour = [0usize; N];
                for k in (0..N).rev() {
                    let o = &offsets[k];
                    neighbour[k] = (q[k] + o[m % o.len()]) % c[k];
                    m /= o.len();
                }
                let nq = flat(&neighbour);
                for &j in &order[start[nq]..start[nq + 1]] {
                    if j == i {
                        continue;
                    }
                    let r2: f64 = (0..N)
                        .map(|k| {
                            let d = p[k] - x[j][k];
                            let d = d - l[k] * (d / l[k]).round();
                            d * d
                        })
                        .sum();
                    let r = r2.sqrt();
                    if r < self.r_max {
                        let b = ((r / width) as usize).min(self.counts.len() - 1);
                        self.counts[b] += 1;
                    }
                }
            }
        }
        self.samples += 1;
        self.balls = x.len();
    }

    /// Samples taken.
    pub fn samples(&self) -> u64 {
        self.samples
    }

    /// The ordered pairs counted in each bin over all samples.
    pub fn counts(&self) -> &[u64] {
        &self.counts
    }

    /// `(r, g)` of each bin: its centre and `g` (module docs; `NaN` before a sample).
    pub fn g(&self) -> Vec<[f64; 2]> {
        let n = self.sides.len();
        // The unit ball's volume: v_0 = 1, v_1 = 2, v_n = v_(n-2) 2 pi / n.
        let mut v = [1.0, 2.0];
        for k in 2..=n {
            v[k % 2] *= 2.0 * std::f64::consts::PI / k as f64;
        }
        let unit = v[n % 2];
        let volume: f64 = self.sides.iter().product();
        let rho = (self.balls as f64 - 1.0) / volume;
        let width = self.r_max / self.counts.len() as f64;
        let norm = self.samples as f64 * self.balls as f64 * rho * unit;
        self.counts
            .iter()
            .enumerate()
            .map(|(b, &count)| {
                let (lo, hi) = (b as f64 * width, (b + 1) as f64 * width);
                let shell = hi.powi(n as i32) - lo.powi(n as i32);
                [(lo + hi) / 2.0, count as f64 / (norm * shell)]
            })
            .collect()
    }

    /// `g(r)` as CSV: a header line `r [L],g [1]`, then a line per bin.
    pub fn csv(&self) -> String {
        let mut text = "r [L],g [1]\n".to_string();
        for [r, g] in self.g() {
            text.push_str(&format!("{r},{g}\n"));
        }
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn r_max_is_at_most_half_the_shortest_side() {
        assert!(PairCorrelation::new(5.0, 10, &[10.0, 12.0]).is_ok());
        assert!(PairCorrelation::new(5.1, 10, &[10.0, 12.0]).is_err());
        assert!(PairCorrelation::new(0.0, 10, &[10.0, 12.0]).is_err());
        assert!(PairCorrelation::new(1.0, 0, &[10.0, 12.0]).is_err());
    }
}
