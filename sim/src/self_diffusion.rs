//! The self-diffusion coefficient `D` from the mean square displacement, over independent
//! blocks of time (docs/granular.md, "Self-diffusion"), for `granular::Sampler`.
//!
//! At times long against the velocity's correlation time `tau_v`, a ball's displacement is a
//! sum of many nearly independent flights, and its mean square grows linearly,
//!
//! ```text
//! msd(t) = <|d_i(t) - d_i(t_0)|^2> ~ 2 n D (t - t_0) + const,
//! ```
//!
//! in R^n. The run after `from` is cut at the sampler's rows into consecutive blocks, each
//! with its own time origin `t_b` (the block's first row): the first starts at the first row
//! at or after `from`, and block `b` ends at the first row at or after its nominal end
//! `t_0 + (b + 1) block`, which starts the next (so the blocks keep to the grid of `block`
//! and do not drift by the rows' lateness). In block `b`,
//!
//! ```text
//! msd_b(t) = sum_i |(d_i(t) - D(t)) - (d_i(t_b) - D(t_b))|^2 / N_b,
//! D_b      = (least-squares slope of msd_b(t) over the block's rows with t >= t_b + (e_b - t_b) / 5) / (2 n),
//! ```
//!
//! `d_i` ball `i`'s unwrapped displacement and `D` the centre of mass's ([`crate::displacement`];
//! the centre of mass's ballistic drift in a periodic box is taken out, as in `msd_cm`; `e_b`
//! the block's nominal end). The first fifth of each block is left out of the fit: the slope
//! of `msd_b` approaches `2 n D` as the velocities forget the block's origin, as `1 -
//! exp(-(t - t_b) / tau_v)` for an exponential velocity autocorrelation (`msd_b = 2 n D (t -
//! t_b - tau_v (1 - exp(-(t - t_b) / tau_v)))`), so with blocks of `20 tau_v` the fit starts
//! at `4 tau_v` and its slope is low by about `tau_v (e^-4 - e^-20) / (16 tau_v)`, 0.1 %
//! (longer blocks: less). The estimate is the blocks' mean,
//!
//! ```text
//! D = sum_b D_b / B,    s_D = sqrt(sum_b (D_b - D)^2 / (B (B - 1))),
//! ```
//!
//! its standard error from the blocks' scatter: the blocks are independent when they are long
//! against `tau_v` (each has its own origin; what one block's balls carry into the next is
//! their velocity, forgotten after a few `tau_v`). An unfinished last block is dropped. `D` is
//! defined for a steady state (elastic or driven): in a cooling gas it falls with the
//! temperature, and each block's `D_b` is the value at its own time.

/// One finished block.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Block {
    /// Its origin `t_b`, a row's time.
    pub start: f64,
    /// Its last row's time.
    pub end: f64,
    /// `D_b`, the slope of `msd_b` over its last four fifths over `2 n`.
    pub d: f64,
}

/// The blocks of a run so far (module docs).
#[derive(Clone, Debug)]
pub struct SelfDiffusion {
    dim: usize,
    block: f64,
    from: f64,
    /// The current block's origin: its time and each ball's displacement about the centre of
    /// mass then (`dim` numbers a ball).
    origin: Option<(f64, Vec<f64>)>,
    /// The current block's nominal end.
    end: f64,
    /// `(t, msd_b(t))` at the current block's rows in its last four fifths.
    points: Vec<(f64, f64)>,
    blocks: Vec<Block>,
}

/// The least-squares slope of `y` over `x` (`NaN` with fewer than two distinct `x`).
pub fn slope(points: &[(f64, f64)]) -> f64 {
    let k = points.len() as f64;
    let mx = points.iter().map(|p| p.0).sum::<f64>() / k;
    let my = points.iter().map(|p| p.1).sum::<f64>() / k;
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
    if sxx > 0.0 {
        sxy / sxx
    } else {
        f64::NAN
    }
}

impl SelfDiffusion {
    /// Blocks of `block` (positive and finite) from the first row at or after `from`
    /// (finite, at least 0), in R^`dim`.
    pub fn new(dim: usize, block: f64, from: f64) -> Result<SelfDiffusion, String> {
        if !(block > 0.0 && block.is_finite()) {
            return Err(format!(
                "the block must be positive and finite, got {block}"
            ));
        }
        if !(from >= 0.0 && from.is_finite()) {
            return Err(format!(
                "the start must be at least 0 and finite, got {from}"
            ));
        }
        Ok(SelfDiffusion {
            dim,
            block,
            from,
            origin: None,
            end: f64::NAN,
            points: Vec::new(),
            blocks: Vec::new(),
        })
    }

    /// The block length.
    pub fn block(&self) -> f64 {
        self.block
    }

    /// The start of the first block.
    pub fn from(&self) -> f64 {
        self.from
    }

    /// Takes a row at `time` with each ball's displacement about the centre of mass
    /// (`dim` numbers a ball): starts the first block, adds a point of the current one or ends
    /// it (and starts the next at this row).
    pub fn sample(&mut self, time: f64, about_centre: &[f64]) {
        let Some((t_b, origin)) = &self.origin else {
            if time >= self.from {
                self.origin = Some((time, about_centre.to_vec()));
                self.end = time + self.block;
            }
            return;
        };
        if time >= t_b + (self.end - t_b) / 5.0 {
            let balls = (origin.len() / self.dim) as f64;
            let msd = about_centre
                .iter()
                .zip(origin)
                .map(|(x, x0)| (x - x0) * (x - x0))
                .sum::<f64>()
                / balls;
            self.points.push((time, msd));
        }
        if time >= self.end {
            let d = slope(&self.points) / (2.0 * self.dim as f64);
            self.blocks.push(Block {
                start: *t_b,
                end: time,
                d,
            });
            self.points.clear();
            self.origin = Some((time, about_centre.to_vec()));
            // The next nominal end on the grid; a gap of rows longer than a block restarts it.
            self.end += self.block;
            if self.end <= time {
                self.end = time + self.block;
            }
        }
    }

    /// The finished blocks.
    pub fn blocks(&self) -> &[Block] {
        &self.blocks
    }

    /// `(D, s_D)`: the blocks' mean and its standard error (module docs); `s_D` is NaN with
    /// one block, both with none.
    pub fn estimate(&self) -> (f64, f64) {
        let b = self.blocks.len() as f64;
        let mean = self.blocks.iter().map(|x| x.d).sum::<f64>() / b;
        let var = self
            .blocks
            .iter()
            .map(|x| (x.d - mean).powi(2))
            .sum::<f64>()
            / (b - 1.0);
        (mean, (var / b).sqrt())
    }

    /// The blocks as CSV, units in the header in the scene's length `L` and time `T`:
    /// `block [1],start [T],end [T],D [L^2 T^-1]`, numbers in Rust's shortest round-trip form.
    pub fn csv(&self) -> String {
        let mut text = String::from("block [1],start [T],end [T],D [L^2 T^-1]\n");
        for (k, b) in self.blocks.iter().enumerate() {
            text.push_str(&format!("{k},{},{},{}\n", b.start, b.end, b.d));
        }
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two balls at constant velocities `+-(1, 1, 1)` about their centre of mass (no
    /// contacts): `msd_b = 3 (t - t_b)^2`. Rows at `t = 0, 0.5, ..., 12`, blocks of 5 from
    /// 0.7: the origins are the rows at 1, 6 and 11 (the grid 1 + 5 k), each block's fit takes
    /// its rows at `t - t_b >= 1`, `t - t_b = 1, 1.5, ..., 5` (nine points), where the
    /// least-squares slope of `3 s^2` is `3 * 2 * 3 = 18` exactly (the slope of `s^2` over
    /// points symmetric about their mean `3` is twice the mean), so `D_b = 18 / (2 n) = 3`; the
    /// unfinished block from 11 is dropped, and equal blocks give `s_D = 0`.
    #[test]
    fn ballistic_balls_give_the_slope_of_their_squares() {
        let mut s = SelfDiffusion::new(3, 5.0, 0.7).unwrap();
        for k in 0..=24 {
            let t = 0.5 * k as f64;
            s.sample(t, &[t, t, t, -t, -t, -t]);
        }
        let blocks = s.blocks();
        assert_eq!(
            blocks,
            [
                Block {
                    start: 1.0,
                    end: 6.0,
                    d: 3.0
                },
                Block {
                    start: 6.0,
                    end: 11.0,
                    d: 3.0
                }
            ]
        );
        assert_eq!(s.estimate(), (3.0, 0.0));
        assert_eq!(
            s.csv(),
            "block [1],start [T],end [T],D [L^2 T^-1]\n0,1,6,3\n1,6,11,3\n"
        );
    }

    /// A ball whose displacement from each block's origin grows as `sqrt(6 D_b (t - t_b))`
    /// (so `msd_b = 6 D_b (t - t_b)`, linear) gives `D_b` itself whatever the block's origin
    /// is; blocks with `D_b` = 1 and 3 give `D = 2` and `s_D = sqrt(((1 - 2)^2 + (3 - 2)^2) /
    /// (2 * 1)) = 1`. The rows come 0.25 apart, blocks of 2: each fit takes `t - t_b` in
    /// `[0.4, 2]`.
    #[test]
    fn linear_growth_gives_d_and_the_blocks_give_its_error() {
        let mut s = SelfDiffusion::new(3, 2.0, 0.0).unwrap();
        let mut x = 5.0;
        s.sample(0.0, &[x, 0.0, 0.0]);
        for (b, d) in [1.0, 3.0].into_iter().enumerate() {
            let (t_b, x_b) = (2.0 * b as f64, x);
            for k in 1..=8 {
                let since = 0.25 * k as f64;
                x = x_b + (6.0 * d * since).sqrt();
                s.sample(t_b + since, &[x, 0.0, 0.0]);
            }
        }
        let blocks = s.blocks();
        assert_eq!(blocks.len(), 2, "{blocks:?}");
        for (b, d) in blocks.iter().zip([1.0, 3.0]) {
            assert!((b.d - d).abs() < 1e-13 * d, "{blocks:?}");
        }
        let (mean, se) = s.estimate();
        assert!(
            (mean - 2.0).abs() < 1e-13 && (se - 1.0).abs() < 1e-12,
            "{mean} {se}"
        );
    }

    #[test]
    fn a_bad_block_or_start_is_refused() {
        assert!(SelfDiffusion::new(2, 0.0, 0.0)
            .unwrap_err()
            .contains("block"));
        assert!(SelfDiffusion::new(2, f64::NAN, 0.0).is_err());
        assert!(SelfDiffusion::new(2, 1.0, -1.0)
            .unwrap_err()
            .contains("start"));
        assert!(SelfDiffusion::new(2, 1.0, f64::INFINITY).is_err());
        let s = SelfDiffusion::new(2, 1.0, 0.0).unwrap();
        assert!(s.estimate().0.is_nan() && s.blocks().is_empty());
    }
}
