//! What a QR run costs, and the choice of `k` it implies.
//!
//! `k` tangent vectors of the phase-space dimension `d` take `8 k d` bytes. Each
//! re-orthonormalisation (one every `every` contacts, and one at the end:
//! `ceil(events / every)` in all) is a modified Gram-Schmidt of `k` vectors of length `d`:
//! about `k^2 d` multiply-adds (`k (k - 1) / 2` dot products and as many updates, and `k`
//! norms). For the whole spectrum of a gas (`k = d = 5 N` disks, `every = N / 4`) that is
//! `500 N^2` multiply-adds per contact: the shipped gas2d (750 disks) needs `5.3e10` per
//! re-orthonormalisation, and `--events 200` (two of them) ran 223 s. So:
//!
//! - a requested `k` is refused if its vectors pass [`MAX_TANGENT_BYTES`] (the error names
//!   `--k`, the memory it needs and the cap);
//! - without `k`, the whole spectrum is computed when it fits [`DEFAULT_TANGENT_BYTES`] and
//!   [`DEFAULT_WORK`]; otherwise the largest `k` that fits both (at least 1): the run then
//!   takes seconds beyond the engine's own time, whatever the scene.

use super::LyapunovError;

/// The most memory the tangent vectors may take (`8 k d` bytes): 1 GiB.
pub const MAX_TANGENT_BYTES: u64 = 1 << 30;

/// The default `k`'s memory budget: 64 MiB of tangent vectors.
pub const DEFAULT_TANGENT_BYTES: u64 = 64 << 20;

/// The default `k`'s work budget: `2e9` multiply-adds of Gram-Schmidt over the run (3-4 s at
/// the 0.55-0.7 billion a second measured on the shared development machine,
/// docs/dynamics.md).
pub const DEFAULT_WORK: f64 = 2e9;

/// The `k` of a QR run and what it costs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Choice {
    /// The exponents computed.
    pub k: usize,
    /// The phase-space dimension.
    pub dimension: usize,
    /// Whether `k` was chosen by the default rule (no `k` asked for).
    pub default: bool,
    /// The memory of the tangent vectors, `8 k d` bytes.
    pub bytes: u64,
    /// The Gram-Schmidt work of the run, `ceil(events / every) k^2 d` multiply-adds.
    pub work: f64,
    /// The same for the whole spectrum (`k = d`).
    pub full_bytes: u64,
    /// The Gram-Schmidt work of the whole spectrum.
    pub full_work: f64,
}

/// `8 k d` bytes, saturating.
fn bytes(k: usize, d: usize) -> u64 {
    (k as u64).saturating_mul(d as u64).saturating_mul(8)
}

/// `ceil(events / every) k^2 d` multiply-adds.
fn work(k: usize, d: usize, events: u64, every: u64) -> f64 {
    events.div_ceil(every.max(1)) as f64 * (k as f64).powi(2) * d as f64
}

/// The `k` of a run of `events` contacts re-orthonormalised every `every`, in dimension `d`:
/// the one asked for (refused outside `1..=d` or past [`MAX_TANGENT_BYTES`]), or the default
/// rule (module docs; refused only if one vector passes the cap).
pub fn choose(
    asked: Option<usize>,
    dimension: usize,
    events: u64,
    every: u64,
) -> Result<Choice, LyapunovError> {
    let d = dimension;
    let k = match asked {
        Some(k) => {
            if !(1..=d).contains(&k) {
                return Err(LyapunovError::K { k, dimension: d });
            }
            k
        }
        None => {
            let by_memory = (DEFAULT_TANGENT_BYTES / 8 / d.max(1) as u64) as usize;
            let per_k2 = work(1, d, events, every);
            let by_work = (DEFAULT_WORK / per_k2).sqrt().floor() as usize;
            d.min(by_memory).min(by_work).max(1)
        }
    };
    if bytes(k, d) > MAX_TANGENT_BYTES {
        return Err(LyapunovError::Memory {
            k,
            dimension: d,
            bytes: bytes(k, d),
        });
    }
    Ok(Choice {
        k,
        dimension: d,
        default: asked.is_none(),
        bytes: bytes(k, d),
        work: work(k, d, events, every),
        full_bytes: bytes(d, d),
        full_work: work(d, d, events, every),
    })
}

/// Bytes as MiB (below 1 GiB) or GiB, three significant figures.
pub fn show_bytes(b: u64) -> String {
    let (v, unit) = if b < 1 << 30 {
        (b as f64 / (1u64 << 20) as f64, "MiB")
    } else {
        (b as f64 / (1u64 << 30) as f64, "GiB")
    };
    format!("{v:.3} {unit}")
}

impl Choice {
    /// A line saying what the default chose and why, when it is less than the whole
    /// spectrum; for a `k` asked for, the run's work when it passes the default's budget;
    /// `None` otherwise.
    pub fn note(&self) -> Option<String> {
        if !self.default {
            return (self.work > DEFAULT_WORK).then(|| {
                format!(
                    "--k {}: about {:.1e} multiply-adds of Gram-Schmidt over this run, {:.0} \
                     times the default's budget ({:.0e}): expect a long run",
                    self.k,
                    self.work,
                    self.work / DEFAULT_WORK,
                    DEFAULT_WORK
                )
            });
        }
        (self.k < self.dimension).then(|| {
            format!(
                "--k not given: the whole spectrum ({} exponents) would need {} of tangent \
                 vectors and {:.1e} multiply-adds of Gram-Schmidt over this run, beyond the \
                 default's budget ({} and {:.0e}); computing the {} largest (--k chooses, up \
                 to {} of tangent vectors)",
                self.dimension,
                show_bytes(self.full_bytes),
                self.full_work,
                show_bytes(DEFAULT_TANGENT_BYTES),
                DEFAULT_WORK,
                self.k,
                show_bytes(MAX_TANGENT_BYTES)
            )
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The shipped gas2d (750 disks, d = 3750, every = 187): the whole spectrum over 200
    /// contacts (two re-orthonormalisations) is `2 * 3750^3 = 1.05e11` multiply-adds, beyond
    /// the budget: the default is `floor(sqrt(2e9 / (2 * 3750))) = 516`. Over 10^5 contacts
    /// (535 re-orthonormalisations) it is 31. A one-ball table gets its whole spectrum.
    #[test]
    fn the_default_k_keeps_a_gas_within_the_budget() {
        let c = choose(None, 3750, 200, 187).unwrap();
        assert_eq!((c.k, c.default), (516, true));
        assert!(c.work <= DEFAULT_WORK && c.bytes <= DEFAULT_TANGENT_BYTES);
        assert_eq!(c.full_work, 2.0 * 3750f64.powi(3));
        let note = c.note().unwrap();
        assert!(note.contains("whole spectrum (3750 exponents)"), "{note}");
        assert!(note.contains("computing the 516 largest"), "{note}");
        assert_eq!(choose(None, 3750, 100_000, 187).unwrap().k, 31);
        let one = choose(None, 5, 1_000_000, 1).unwrap();
        assert_eq!(one.k, 5);
        assert_eq!(one.note(), None);
        // Asked for, the whole spectrum runs, with its cost said.
        let all = choose(Some(3750), 3750, 200, 187).unwrap();
        assert_eq!(all.work, all.full_work);
        let note = all.note().unwrap();
        assert!(
            note.starts_with("--k 3750: about 1.1e11 multiply-adds"),
            "{note}"
        );
        assert_eq!(choose(Some(2), 3750, 200, 187).unwrap().note(), None);
    }

    /// 12 000 disks (d = 60 000): the whole spectrum needs 28.8 GB (it aborted on a failed
    /// allocation); asked for, it is refused naming the memory and the cap. The default fits
    /// 64 MiB: `floor(2^26 / 8 / 60000) = 139` vectors.
    #[test]
    fn a_spectrum_beyond_the_memory_cap_is_refused() {
        let e = choose(Some(60_000), 60_000, 1000, 3000).unwrap_err();
        assert_eq!(
            e,
            LyapunovError::Memory {
                k: 60_000,
                dimension: 60_000,
                bytes: 28_800_000_000
            }
        );
        let text = e.to_string();
        assert!(text.starts_with("--k: 60000 tangent vectors"), "{text}");
        assert!(
            text.contains("26.822 GiB") && text.contains("1.000 GiB"),
            "{text}"
        );
        assert_eq!(choose(None, 60_000, 1000, 3000).unwrap().k, 139);
        // The largest k within the cap is accepted, one more is not.
        let most = (MAX_TANGENT_BYTES / 8 / 60_000) as usize;
        assert!(choose(Some(most), 60_000, 10, 3000).is_ok());
        assert!(choose(Some(most + 1), 60_000, 10, 3000).is_err());
    }
}
