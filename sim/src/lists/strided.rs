//! Short lists, one a row, in one slab: row `r` is `data[r s .. r s + len[r]]` for a stride
//! `s` that doubles (the slab laid out again) when a row outgrows it. The list engine's
//! neighbour lists and its cells' members: rows of a few to a few tens, read whole and often,
//! changed one element at a time, with no allocation once the stride has grown.

/// The rows (module docs).
#[derive(Debug)]
pub(super) struct Strided<T> {
    data: Vec<T>,
    len: Vec<u32>,
    stride: usize,
    /// What fills the unused places.
    fill: T,
}

impl<T: Copy> Strided<T> {
    /// `rows` empty rows with room for `stride` each.
    pub(super) fn new(rows: usize, stride: usize, fill: T) -> Self {
        let stride = stride.max(1);
        Strided {
            data: vec![fill; rows * stride],
            len: vec![0; rows],
            stride,
            fill,
        }
    }

    /// Row `r`.
    #[inline]
    pub(super) fn row(&self, r: usize) -> &[T] {
        let start = r * self.stride;
        &self.data[start..start + self.len[r] as usize]
    }

    /// Row `r`'s length.
    #[inline]
    pub(super) fn len(&self, r: usize) -> usize {
        self.len[r] as usize
    }

    /// Element `k` of row `r`, to change.
    #[inline]
    pub(super) fn get_mut(&mut self, r: usize, k: usize) -> &mut T {
        debug_assert!(k < self.len(r));
        &mut self.data[r * self.stride + k]
    }

    /// Appends `x` to row `r` and returns its index there.
    #[inline]
    pub(super) fn push(&mut self, r: usize, x: T) -> usize {
        let k = self.len(r);
        if k == self.stride {
            self.grow();
        }
        self.data[r * self.stride + k] = x;
        self.len[r] += 1;
        k
    }

    /// Removes element `k` of row `r`, the row's last element moved into its place; returns
    /// that element if one moved (`k` was not the last).
    #[inline]
    pub(super) fn swap_remove(&mut self, r: usize, k: usize) -> Option<T> {
        let last = self.len(r) - 1;
        let start = r * self.stride;
        self.len[r] -= 1;
        if k == last {
            return None;
        }
        let moved = self.data[start + last];
        self.data[start + k] = moved;
        Some(moved)
    }

    /// Empties row `r`.
    #[inline]
    pub(super) fn clear(&mut self, r: usize) {
        self.len[r] = 0;
    }

    /// Requests the first two cache lines of row `r`.
    #[inline]
    pub(super) fn prefetch_row(&self, r: usize) {
        let start = r * self.stride;
        let line = 64 / std::mem::size_of::<T>().max(1);
        collision_core::batch::prefetch(self.data.get(start));
        collision_core::batch::prefetch(self.data.get(start + line));
    }

    /// The bytes of a row's room (the stride).
    pub(super) fn row_bytes(&self) -> usize {
        self.stride * std::mem::size_of::<T>()
    }

    /// Moves row `order[r]` to row `r`, for every `r` (`order` a permutation of the rows).
    pub(super) fn permute_rows(&mut self, order: &[u32]) {
        let s = self.stride;
        let mut data = vec![self.fill; self.data.len()];
        let mut len = vec![0; self.len.len()];
        for (r, &old) in order.iter().enumerate() {
            let (old, n) = (old as usize, self.len[old as usize]);
            data[r * s..r * s + n as usize]
                .copy_from_slice(&self.data[old * s..old * s + n as usize]);
            len[r] = n;
        }
        self.data = data;
        self.len = len;
    }

    /// Calls `f` on every element of every row.
    pub(super) fn for_each_mut(&mut self, mut f: impl FnMut(&mut T)) {
        for (r, &n) in self.len.iter().enumerate() {
            let start = r * self.stride;
            self.data[start..start + n as usize]
                .iter_mut()
                .for_each(&mut f);
        }
    }

    /// Twice the stride, every row copied to its new place.
    #[cold]
    fn grow(&mut self) {
        let stride = 2 * self.stride;
        let mut data = vec![self.fill; self.len.len() * stride];
        for (r, &len) in self.len.iter().enumerate() {
            let len = len as usize;
            data[r * stride..r * stride + len]
                .copy_from_slice(&self.data[r * self.stride..r * self.stride + len]);
        }
        self.data = data;
        self.stride = stride;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Random pushes and removals against a `Vec` per row (growing from a stride of 1): the
    /// same rows, and the element reported moved is the one now at the removed index.
    #[test]
    fn rows_follow_a_vec_each() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let rows = 7;
        let mut strided = Strided::new(rows, 1, u32::MAX);
        let mut want: Vec<Vec<u32>> = vec![Vec::new(); rows];
        for step in 0..20_000u32 {
            let r = rng.random_range(0..rows);
            if want[r].is_empty() || rng.random_bool(0.55) {
                assert_eq!(strided.push(r, step), want[r].len());
                want[r].push(step);
            } else {
                let k = rng.random_range(0..want[r].len());
                want[r].swap_remove(k);
                let moved = strided.swap_remove(r, k);
                assert_eq!(moved, want[r].get(k).copied());
            }
            if let (0, Some(first)) = (step % 97, want[r].first_mut()) {
                *first = step;
                *strided.get_mut(r, 0) = step;
            }
            assert_eq!(strided.row(r), &want[r][..]);
        }
        strided.clear(0);
        assert!(strided.row(0).is_empty());
    }
}
