//! `if c { a } else { b }` without a branch, for conditions that are coin tosses from one
//! event to the next: the side a ball moves to along an axis (`v > 0`), the direction of a
//! cell crossing. A branch on them is mispredicted about every second time (over ten cycles
//! each), and the compiler turns a plain `if` on them into such a branch: callgrind's branch
//! simulation counted about 7 mispredictions a contact on the sign of `v` in the crossing times
//! alone (3D, 4000 balls, `phi` 0.1; docs/benchmarks.md, session 56).
//!
//! The value is chosen by a mask of its bits, which the compiler keeps as a select
//! (`std::hint::select_unpredictable` does the same from Rust 1.88; the workspace's MSRV is
//! 1.85). Both values are computed: they must be cheap and have no side effects.

/// A value whose bits a mask can select.
pub(crate) trait Select: Copy {
    /// `if c { a } else { b }`, bit for bit, without a branch.
    fn select(c: bool, a: Self, b: Self) -> Self;
}

/// All ones if `c`, else zero.
#[inline(always)]
fn mask(c: bool) -> u64 {
    u64::from(c).wrapping_neg()
}

impl Select for u64 {
    #[inline(always)]
    fn select(c: bool, a: u64, b: u64) -> u64 {
        let m = mask(c);
        (a & m) | (b & !m)
    }
}

impl Select for f64 {
    #[inline(always)]
    fn select(c: bool, a: f64, b: f64) -> f64 {
        f64::from_bits(u64::select(c, a.to_bits(), b.to_bits()))
    }
}

impl Select for usize {
    #[inline(always)]
    fn select(c: bool, a: usize, b: usize) -> usize {
        u64::select(c, a as u64, b as u64) as usize
    }
}

impl Select for i64 {
    #[inline(always)]
    fn select(c: bool, a: i64, b: i64) -> i64 {
        u64::select(c, a as u64, b as u64) as i64
    }
}

/// `if c { a } else { b }` without a branch ([`Select`]).
#[inline(always)]
pub(crate) fn select<T: Select>(c: bool, a: T, b: T) -> T {
    T::select(c, a, b)
}

#[cfg(test)]
mod tests {
    use super::select;

    #[test]
    fn select_is_the_if_bit_for_bit() {
        let values = [
            0.0,
            -0.0,
            1.5,
            -2.25,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            f64::MIN_POSITIVE / 4.0,
            f64::MAX,
        ];
        for &a in &values {
            for &b in &values {
                for c in [false, true] {
                    let want = if c { a } else { b };
                    assert_eq!(select(c, a, b).to_bits(), want.to_bits());
                }
            }
        }
        for (a, b) in [(0usize, usize::MAX), (7, 3), (usize::MAX, 0)] {
            assert_eq!(select(true, a, b), a);
            assert_eq!(select(false, a, b), b);
        }
        for (a, b) in [(-1i64, 1), (i64::MIN, i64::MAX), (0, -5)] {
            assert_eq!(select(true, a, b), a);
            assert_eq!(select(false, a, b), b);
        }
    }
}
