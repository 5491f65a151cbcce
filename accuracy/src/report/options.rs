//! What a report run samples and times ([`Options`]), and the bound on its sampled cases
//! ([`MAX_SAMPLES`]).

use crate::family::FamilyRegime;
use crate::regime::Regime;
use serde::Serialize;

/// The most sampled cases per dimension and regime a report takes: 100 times the default
/// (1000), about 15 minutes; every case keeps its errors for the percentiles, so the memory
/// grows with it.
pub const MAX_SAMPLES: usize = 100_000;

/// `samples` if it is in `1..=`[`MAX_SAMPLES`], else the reason, for the caller to prefix
/// with the option's name (`--samples`, `samples`).
pub fn check_samples(samples: usize) -> Result<usize, String> {
    if (1..=MAX_SAMPLES).contains(&samples) {
        Ok(samples)
    } else {
        Err(format!("must be in 1..={MAX_SAMPLES}, got {samples}"))
    }
}

/// What a report run samples and times.
#[derive(Clone, Debug, Serialize)]
pub struct Options {
    /// The dimensions `n`.
    pub dims: Vec<usize>,
    /// The regimes, in report order.
    pub regimes: Vec<Regime>,
    /// Sampled cases per dimension and regime.
    pub samples: usize,
    /// The seed every random stream derives from (one per dimension and regime).
    pub seed: u64,
    /// Cases in the timed batch (in cache), and in the exact variant's batch.
    pub batch: usize,
    /// Cases in the exact variant's timed batch.
    pub exact_batch: usize,
    /// Timed samples per variant.
    pub timing_samples: usize,
    /// Cases per dimension and regime whose conditioning is estimated (besides every
    /// body whose error exceeds the bound).
    pub conditioned: usize,
    /// The rough-ball family's regimes, in report order (`crate::family`).
    pub family: Vec<FamilyRegime>,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            dims: (2..=6).collect(),
            regimes: Regime::ALL.to_vec(),
            samples: 1000,
            seed: 2026,
            batch: 256,
            exact_batch: 32,
            timing_samples: 21,
            conditioned: 50,
            family: FamilyRegime::ALL.to_vec(),
        }
    }
}
