//! The cell list: the box cut into `n_k` cells of width `w_k >= d_max` per axis (fewer only
//! when the box is narrower), where `d_max` is the largest contact distance `R_i + R_j`.
//!
//! A ball in cell `c` and one in cell `c + delta` (unwrapped: `shift = floor((c + delta) / n)`
//! box lengths on a periodic axis) have, along each axis, a centre offset in
//! `((delta - 1) w, (delta + 1) w)`, so they can touch only if `(|delta| - 1) w < d_max`:
//! `|delta| <= K = ceil(d_max / w)`. The offsets `delta` in `[-K, K]^N` therefore find every
//! possible partner, each image of it once, while both stay in their cells.

pub(crate) struct Grid<const N: usize> {
    pub n: [usize; N],
    pub width: [f64; N],
    pub size: [f64; N],
    pub periodic: [bool; N],
    offsets: Vec<[i64; N]>,
}

/// A neighbouring cell: its flat index and the image shift of its contents.
pub(crate) struct Neighbour<const N: usize> {
    pub cell: usize,
    pub shift: [i8; N],
}

impl<const N: usize> Grid<N> {
    pub fn new(size: [f64; N], periodic: [bool; N], d_max: f64) -> Self {
        let n = std::array::from_fn(|k| ((size[k] / d_max).floor() as usize).clamp(1, 1 << 16));
        let width: [f64; N] = std::array::from_fn(|k| size[k] / n[k] as f64);
        // 1e-9 of slack: rounding at cell boundaries must not hide a partner.
        let reach: [i64; N] =
            std::array::from_fn(|k| (d_max * (1.0 + 1e-9) / width[k]).ceil() as i64);
        let mut offsets = vec![[0i64; N]];
        for k in 0..N {
            offsets = offsets
                .into_iter()
                .flat_map(|o| {
                    (-reach[k]..=reach[k]).map(move |d| {
                        let mut o = o;
                        o[k] = d;
                        o
                    })
                })
                .collect();
        }
        Grid {
            n,
            width,
            size,
            periodic,
            offsets,
        }
    }

    pub fn cells(&self) -> usize {
        self.n.iter().product()
    }

    pub fn flat(&self, c: &[usize; N]) -> usize {
        (0..N).fold(0, |acc, k| acc * self.n[k] + c[k])
    }

    /// The cell of a point inside the box (clamped, for points on the far boundary).
    pub fn cell_of(&self, x: &[f64; N]) -> [usize; N] {
        std::array::from_fn(|k| {
            ((x[k] / self.width[k]).floor().max(0.0) as usize).min(self.n[k] - 1)
        })
    }

    /// Calls `f` for every cell within reach of cell `c` (with its image shift).
    pub fn for_neighbours(&self, c: &[usize; N], mut f: impl FnMut(Neighbour<N>)) {
        'offsets: for o in &self.offsets {
            let mut cell = [0usize; N];
            let mut shift = [0i8; N];
            for k in 0..N {
                let t = c[k] as i64 + o[k];
                let n = self.n[k] as i64;
                if self.periodic[k] {
                    cell[k] = t.rem_euclid(n) as usize;
                    shift[k] = t.div_euclid(n) as i8;
                } else if (0..n).contains(&t) {
                    cell[k] = t as usize;
                } else {
                    continue 'offsets;
                }
            }
            f(Neighbour {
                cell: self.flat(&cell),
                shift,
            });
        }
    }
}
