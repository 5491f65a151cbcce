//! Block statistics of a running exponent: the run after a warm-up is cut into `B` blocks of
//! equal numbers of contacts; the estimate is the sum of the logarithmic growths over the
//! whole measured run divided by its time, and its standard error is the spread of the
//! blocks' own estimates, `sd(block estimates) / sqrt(B)` (blocks long compared with the
//! correlation time of the growth are nearly independent).

use serde::Serialize;

/// An estimate and its standard error.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Estimate {
    /// The value.
    pub value: f64,
    /// The standard error over the blocks.
    pub error: f64,
}

/// Accumulates per-block growth and time for `k` exponents.
#[derive(Clone, Debug)]
pub struct Blocks {
    /// Per block: the summed logarithmic growth of each exponent.
    pub growth: Vec<Vec<f64>>,
    /// Per block: its time and its contacts.
    pub time: Vec<f64>,
    /// Per block: its contacts.
    pub contacts: Vec<u64>,
}

impl Blocks {
    /// `blocks` empty blocks for `k` exponents.
    pub fn new(blocks: usize, k: usize) -> Self {
        Self {
            growth: vec![vec![0.0; k]; blocks],
            time: vec![0.0; blocks],
            contacts: vec![0; blocks],
        }
    }

    /// Adds `log_growth` over `time` and `contacts` to block `b`.
    pub fn add(&mut self, b: usize, log_growth: &[f64], time: f64, contacts: u64) {
        for (g, x) in self.growth[b].iter_mut().zip(log_growth) {
            *g += x;
        }
        self.time[b] += time;
        self.contacts[b] += contacts;
    }

    /// Per exponent, per unit time and per contact: the whole-run estimate and its error.
    pub fn estimates(&self) -> (Vec<Estimate>, Vec<Estimate>) {
        let k = self.growth.first().map_or(0, Vec::len);
        let total_time: f64 = self.time.iter().sum();
        let total_contacts = self.contacts.iter().sum::<u64>() as f64;
        let each = |i: usize, per: &dyn Fn(usize) -> f64, total: f64| {
            let sum: f64 = self.growth.iter().map(|g| g[i]).sum();
            let values: Vec<f64> = (0..self.time.len())
                .map(|b| self.growth[b][i] / per(b))
                .collect();
            Estimate {
                value: sum / total,
                error: standard_error(&values),
            }
        };
        let per_time = |b: usize| self.time[b];
        let per_contact = |b: usize| self.contacts[b] as f64;
        (
            (0..k).map(|i| each(i, &per_time, total_time)).collect(),
            (0..k)
                .map(|i| each(i, &per_contact, total_contacts))
                .collect(),
        )
    }

    /// The sum of all `k` exponents per unit time, with its error over the blocks (the sum's
    /// own spread, which is smaller than the exponents' errors added).
    pub fn sum(&self) -> Estimate {
        let total_time: f64 = self.time.iter().sum();
        let values: Vec<f64> = (0..self.time.len())
            .map(|b| self.growth[b].iter().sum::<f64>() / self.time[b])
            .collect();
        Estimate {
            value: self.growth.iter().flatten().sum::<f64>() / total_time,
            error: standard_error(&values),
        }
    }
}

/// `sd(values) / sqrt(len)`, the sample standard deviation (`len - 1`); 0 for fewer than two.
pub fn standard_error(values: &[f64]) -> f64 {
    let b = values.len() as f64;
    if values.len() < 2 {
        return 0.0;
    }
    let mean = values.iter().sum::<f64>() / b;
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (b - 1.0);
    (var / b).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocks_give_the_ratio_of_sums_and_the_spread() {
        let mut blocks = Blocks::new(4, 1);
        for (b, g) in [1.0, 3.0, 2.0, 2.0].into_iter().enumerate() {
            blocks.add(b, &[g], 1.0, 2);
        }
        let (time, contact) = blocks.estimates();
        assert_eq!(time[0].value, 2.0);
        assert_eq!(contact[0].value, 1.0);
        // sd of (1, 3, 2, 2) = sqrt(2/3), over sqrt(4).
        assert!((time[0].error - (2.0f64 / 3.0).sqrt() / 2.0).abs() < 1e-15);
        assert_eq!(blocks.sum().value, 2.0);
    }
}
