//! The statistics of a figure over cases or bodies: the mean, the 99th percentile (the sorted
//! value at index `round(0.99 (len - 1))`) and the maximum.

use serde::Serialize;

/// Mean, 99th percentile and maximum.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct Stats {
    /// The arithmetic mean.
    pub mean: f64,
    /// The 99th percentile: the sorted value at index `round(0.99 (len - 1))`.
    pub p99: f64,
    /// The largest value.
    pub max: f64,
}

impl Stats {
    /// The statistics of `values` (all zero when there are none).
    pub fn of(values: &[f64]) -> Stats {
        if values.is_empty() {
            return Stats::default();
        }
        let mut v = values.to_vec();
        v.sort_by(f64::total_cmp);
        let p99 = v[((v.len() - 1) as f64 * 0.99).round() as usize];
        Stats {
            mean: v.iter().sum::<f64>() / v.len() as f64,
            p99,
            max: v[v.len() - 1],
        }
    }
}
