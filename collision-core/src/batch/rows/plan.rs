//! Transposes of a full block (8 rows) as two-source permutes, planned at compile time.
//!
//! A full block's transpose moves whole vectors of 8 values: the gather builds each lane
//! array `lanes[d][l] = rows[o_d + l m]` (row width `m`, offset `o_d` of field `d`) and the
//! scatter each 8-value piece `rows[8 d .. 8 d + 8]` of the 8 rows from the lane arrays. Every
//! value `p` of a destination vector `d` is one value of one *source* vector (a
//! destination's `src[p] = (source, position)`), or `+0`, or `0 - ` a source value (the
//! scatter's entries below the diagonal). A [`Plan`] groups each destination's sources in
//! ascending order, two at a time, into [`Step`]s: one two-source permute
//! (`out[p] = (a ++ b)[idx[p]]`, AVX-512 `vpermt2pd`) whose values replace the destination's
//! at the positions of `mask` (or `0 - ` them, `neg`), starting from `+0`. So a destination
//! fed by `k` sources takes `ceil(k / 2)` permutes per kind (plain, negated), where the
//! scalar transpose takes 8 loads and 8 stores (`avx512.rs` runs the plans; `interpret`
//! below runs them on plain arrays, for the tests).

/// Most destinations of a plan: 36, the pieces of 8 rows of a 6 x 6 matrix.
pub(super) const MAX_DESTINATIONS: usize = 36;

/// Most steps of a plan: 5 per destination (8 values of at most 8 sources, plain and
/// negated ones in separate steps).
const MAX_STEPS: usize = 5 * MAX_DESTINATIONS;

/// Where a destination's value comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Value {
    /// `+0`.
    Zero,
    /// Value `position` of source `source`.
    Plain(usize, usize),
    /// `0 - ` value `position` of source `source`.
    Negated(usize, usize),
}

/// One two-source permute: values `mask` of the destination become `(a ++ b)[idx[p]]`
/// (`0 - ` it when `neg`).
#[derive(Clone, Copy, Debug)]
pub(super) struct Step {
    /// The first source (values `0..8` of `idx`).
    pub(super) a: u8,
    /// The second source (values `8..16` of `idx`); `a` when the step has one source.
    pub(super) b: u8,
    /// The value of `a ++ b` each position takes.
    pub(super) idx: [u8; 8],
    /// The positions the step writes (bit `p` for position `p`).
    pub(super) mask: u8,
    /// Whether the step writes `0 - ` the values.
    pub(super) neg: bool,
}

/// Every destination's steps: destination `d`'s are `steps[starts[d]..starts[d + 1]]`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Plan {
    /// The steps, destination after destination.
    pub(super) steps: [Step; MAX_STEPS],
    /// Where each destination's steps start (`starts[destinations]` is their count).
    pub(super) starts: [u16; MAX_DESTINATIONS + 1],
    /// The number of destinations.
    pub(super) destinations: usize,
}

const NO_STEP: Step = Step {
    a: 0,
    b: 0,
    idx: [0; 8],
    mask: 0,
    neg: false,
};

impl Plan {
    /// The plan of `destinations` destinations whose value `p` comes from `from[d][p]`,
    /// the sources numbered below `sources`.
    const fn new(
        destinations: usize,
        sources: usize,
        from: &[[Value; 8]; MAX_DESTINATIONS],
    ) -> Plan {
        assert!(destinations <= MAX_DESTINATIONS && sources <= 256);
        let mut plan = Plan {
            steps: [NO_STEP; MAX_STEPS],
            starts: [0; MAX_DESTINATIONS + 1],
            destinations,
        };
        let mut count = 0;
        let mut d = 0;
        while d < destinations {
            plan.starts[d] = count as u16;
            let mut neg = 0;
            while neg < 2 {
                // The sources this kind of value of `d` reads, ascending, two per step.
                let mut pending: Option<usize> = None;
                let mut s = 0;
                while s <= sources {
                    let used = s < sources && reads(&from[d], s, neg == 1);
                    if used && pending.is_none() {
                        pending = Some(s);
                    } else if let Some(a) = pending {
                        if used || s == sources {
                            let b = if used { s } else { a };
                            plan.steps[count] = step(&from[d], a, b, neg == 1);
                            count += 1;
                            pending = None;
                        }
                    }
                    s += 1;
                }
                neg += 1;
            }
            d += 1;
        }
        assert!(count <= MAX_STEPS);
        plan.starts[destinations] = count as u16;
        plan
    }
}

/// Whether a value of `from` is source `s` (negated or not, as `neg`).
const fn reads(from: &[Value; 8], s: usize, neg: bool) -> bool {
    let mut p = 0;
    while p < 8 {
        match from[p] {
            Value::Plain(x, _) if !neg && x == s => return true,
            Value::Negated(x, _) if neg && x == s => return true,
            _ => {}
        }
        p += 1;
    }
    false
}

/// The step that writes the values of `from` taken from sources `a` and `b`.
const fn step(from: &[Value; 8], a: usize, b: usize, neg: bool) -> Step {
    let mut out = Step {
        a: a as u8,
        b: b as u8,
        idx: [0; 8],
        mask: 0,
        neg,
    };
    let mut p = 0;
    while p < 8 {
        let (s, at) = match from[p] {
            Value::Plain(s, at) if !neg => (s, at),
            Value::Negated(s, at) if neg => (s, at),
            _ => (usize::MAX, 0),
        };
        if s == a || s == b {
            out.idx[p] = (if s == a { at } else { 8 + at }) as u8;
            out.mask |= 1 << p;
        }
        p += 1;
    }
    out
}

/// The gather of a field of row width `m` into the lane arrays of its entries `offsets`
/// (`lanes[d][l] = rows[offsets[d] + l m]`): source `j` is `rows[8 j .. 8 j + 8]` of the
/// block's `8 m` values.
pub(super) const fn gather(m: usize, offsets: &[usize]) -> Plan {
    let mut from = [[Value::Zero; 8]; MAX_DESTINATIONS];
    let mut d = 0;
    while d < offsets.len() {
        let mut l = 0;
        while l < 8 {
            let f = offsets[d] + l * m;
            from[d][l] = Value::Plain(f / 8, f % 8);
            l += 1;
        }
        d += 1;
    }
    Plan::new(offsets.len(), m, &from)
}

/// The gather of 8 rows of `n` values into `n` lane arrays (`nu`, velocities).
pub(super) const fn gather_vectors<const N: usize>() -> Plan {
    let mut offsets = [0; N];
    let mut k = 0;
    while k < N {
        offsets[k] = k;
        k += 1;
    }
    gather(N, &offsets)
}

/// The gather of 8 rows of `n x n` matrices into the lane arrays of their entries `U_rc`,
/// `r < c`, in the order of [`BodyState::spin`](crate::BodyState::spin).
pub(super) const fn gather_spins<const N: usize, const S: usize>() -> Plan {
    let pairs = super::pairs::<N, S>();
    let mut offsets = [0; S];
    let mut k = 0;
    while k < S {
        offsets[k] = pairs[k].0 * N + pairs[k].1;
        k += 1;
    }
    gather(N * N, &offsets)
}

/// The scatter of `n` lane arrays into 8 rows of `n` values: destination `d` is
/// `rows[8 d .. 8 d + 8]`.
pub(super) const fn scatter_vectors<const N: usize>() -> Plan {
    let mut from = [[Value::Zero; 8]; MAX_DESTINATIONS];
    let mut d = 0;
    while d < N {
        let mut p = 0;
        while p < 8 {
            let f = 8 * d + p;
            from[d][p] = Value::Plain(f % N, f / N);
            p += 1;
        }
        d += 1;
    }
    Plan::new(N, N, &from)
}

/// The scatter of the `S` lane arrays of compact spins into 8 rows of full skew matrices
/// (`U_rr = +0`, `U_rc` for `r < c`, `U_cr = 0 - U_rc`): destination `d` is
/// `rows[8 d .. 8 d + 8]` of the block's `8 n^2` values.
pub(super) const fn scatter_spins<const N: usize, const S: usize>() -> Plan {
    let pairs = super::pairs::<N, S>();
    let mut from = [[Value::Zero; 8]; MAX_DESTINATIONS];
    let mut d = 0;
    while d < N * N {
        let mut p = 0;
        while p < 8 {
            let f = 8 * d + p;
            let (l, e) = (f / (N * N), f % (N * N));
            let (r, c) = (e / N, e % N);
            let mut k = 0;
            while k < S {
                if pairs[k].0 == r && pairs[k].1 == c {
                    from[d][p] = Value::Plain(k, l);
                } else if pairs[k].0 == c && pairs[k].1 == r {
                    from[d][p] = Value::Negated(k, l);
                }
                k += 1;
            }
            p += 1;
        }
        d += 1;
    }
    Plan::new(N * N, S, &from)
}

/// The plan run on plain arrays, one value at a time: `out[d]` from `sources`, as the
/// permutes do (`+0` first, then each step's values, `0.0 - x` for a negated one).
#[cfg(test)]
pub(super) fn interpret(plan: &Plan, sources: &[[f64; 8]]) -> Vec<[f64; 8]> {
    (0..plan.destinations)
        .map(|d| {
            let mut out = [0.0; 8];
            let steps = &plan.steps[plan.starts[d] as usize..plan.starts[d + 1] as usize];
            for s in steps {
                for (p, x) in out.iter_mut().enumerate() {
                    if s.mask >> p & 1 == 1 {
                        let i = s.idx[p] as usize;
                        let v = sources[if i < 8 { s.a } else { s.b } as usize][i % 8];
                        *x = if s.neg { 0.0 - v } else { v };
                    }
                }
            }
            out
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `m` rows... as the sources of a block of 8 rows of width `m`: value `f` is `f`.
    fn numbered(m: usize) -> Vec<[f64; 8]> {
        (0..m)
            .map(|j| std::array::from_fn(|p| (8 * j + p) as f64 + 1.0))
            .collect()
    }

    fn plans_transpose<const N: usize, const S: usize>() {
        let pairs: Vec<(usize, usize)> = crate::skew_pairs(N).collect();
        // Gathers: lane array d, lane l is row l's entry at offset d.
        let rows = numbered(N);
        let lanes = interpret(&const { gather_vectors::<N>() }, &rows);
        for (d, lane) in lanes.iter().enumerate() {
            for (l, &x) in lane.iter().enumerate() {
                assert_eq!(x, (l * N + d) as f64 + 1.0, "n = {N}: vectors");
            }
        }
        let rows = numbered(N * N);
        let spins = interpret(&const { gather_spins::<N, S>() }, &rows);
        assert_eq!(spins.len(), S);
        for (k, lane) in spins.iter().enumerate() {
            let (r, c) = pairs[k];
            for (l, &x) in lane.iter().enumerate() {
                assert_eq!(x, (l * N * N + r * N + c) as f64 + 1.0, "n = {N}: spins");
            }
        }
        // Scatters back: the velocities' rows, and each spin's full skew matrix.
        let back = interpret(&const { scatter_vectors::<N>() }, &lanes);
        assert_eq!(back.concat(), numbered(N).concat(), "n = {N}: vectors back");
        let back = interpret(&const { scatter_spins::<N, S>() }, &spins).concat();
        for l in 0..8 {
            for r in 0..N {
                for c in 0..N {
                    let x = back[l * N * N + r * N + c];
                    let above = (l * N * N + r * N + c) as f64 + 1.0;
                    let below = (l * N * N + c * N + r) as f64 + 1.0;
                    let want = match r.cmp(&c) {
                        std::cmp::Ordering::Less => above,
                        std::cmp::Ordering::Equal => 0.0,
                        std::cmp::Ordering::Greater => 0.0 - below,
                    };
                    assert_eq!(
                        x.to_bits(),
                        want.to_bits(),
                        "n = {N}: U[{r}][{c}] of row {l}"
                    );
                }
            }
        }
        // Each step reads at most two sources, each destination's plain and negated values
        // each from ceil(sources / 2) steps.
        let plan = const { scatter_spins::<N, S>() };
        for d in 0..plan.destinations {
            let steps = (plan.starts[d + 1] - plan.starts[d]) as usize;
            assert!(steps <= 5, "n = {N}: {steps} steps for one destination");
        }
    }

    #[test]
    fn plans_transpose_blocks_of_eight_rows() {
        plans_transpose::<2, 1>();
        plans_transpose::<3, 3>();
        plans_transpose::<4, 6>();
        plans_transpose::<5, 10>();
        plans_transpose::<6, 15>();
    }

    #[test]
    fn a_destination_of_two_sources_takes_one_permute() {
        // n = 2: each lane array of `nu` is the even or odd values of two vectors.
        let plan = const { gather_vectors::<2>() };
        assert_eq!(plan.starts[..3], [0, 1, 2]);
        assert_eq!(plan.steps[0].idx, [0, 2, 4, 6, 8, 10, 12, 14]);
        assert_eq!(
            (plan.steps[0].a, plan.steps[0].b, plan.steps[0].mask),
            (0, 1, 0xff)
        );
    }
}
