//! [`Batch`]: a growable sequence of per-collision items stored as blocks of `LANES`.

use super::lanes::{Lane, Lanewise, LANES};

/// `len` items of `B::Item` in `ceil(len / LANES)` blocks; item `i` is lane `i % LANES` of
/// block `i / LANES`. The lanes of the last block past `len` hold copies of that block's
/// first item (valid inputs, never read back).
#[derive(Clone, Debug, PartialEq)]
pub struct Batch<B> {
    blocks: Vec<B>,
    len: usize,
}

impl<B> Default for Batch<B> {
    fn default() -> Self {
        Batch {
            blocks: Vec::new(),
            len: 0,
        }
    }
}

impl<B: Lanewise> Batch<B> {
    /// An empty batch.
    pub fn new() -> Self {
        Self::default()
    }

    /// An empty batch with room for `contacts` items.
    pub fn with_capacity(contacts: usize) -> Self {
        Batch {
            blocks: Vec::with_capacity(contacts.div_ceil(LANES)),
            len: 0,
        }
    }

    /// Number of items.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether the batch holds no items.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The blocks, `ceil(len / LANES)` of them, for the batch kernels.
    pub fn blocks(&self) -> &[B] {
        &self.blocks
    }

    /// The blocks, mutable (e.g. to update the states in place between steps).
    pub fn blocks_mut(&mut self) -> &mut [B] {
        &mut self.blocks
    }

    /// Empty the batch, keeping its allocation (a scratch batch refilled chunk by chunk
    /// allocates nothing after its first fill).
    pub fn clear(&mut self) {
        self.blocks.clear();
        self.len = 0;
    }

    /// Append one item.
    pub fn push(&mut self, item: B::Item) {
        let l = self.len % LANES;
        if l == 0 {
            self.blocks.push(B::splat(&item));
        } else if let Some(block) = self.blocks.last_mut() {
            block.set_lane(Lane::new(l).expect("l < LANES"), item);
        }
        self.len += 1;
    }

    /// Item `i`, or `None` past the end.
    pub fn get(&self, i: usize) -> Option<B::Item> {
        if i >= self.len {
            return None;
        }
        let lane = Lane::new(i % LANES).expect("i % LANES < LANES");
        Some(self.blocks[i / LANES].lane(lane))
    }

    /// Every item, in order.
    pub fn iter(&self) -> impl Iterator<Item = B::Item> + '_ {
        self.blocks
            .iter()
            .flat_map(|b| Lane::all().map(move |l| b.lane(l)))
            .take(self.len)
    }

    /// Make room for exactly `len` items, reusing the blocks already there and filling new
    /// ones with `fill` (for the outputs of the kernels, which overwrite every lane).
    pub(crate) fn resize_with(&mut self, len: usize, fill: impl FnMut() -> B) {
        self.blocks.resize_with(len.div_ceil(LANES), fill);
        self.len = len;
    }
}

impl<B: Lanewise> FromIterator<B::Item> for Batch<B> {
    fn from_iter<I: IntoIterator<Item = B::Item>>(iter: I) -> Self {
        let mut batch = Batch::new();
        batch.extend(iter);
        batch
    }
}

impl<B: Lanewise> Extend<B::Item> for Batch<B> {
    fn extend<I: IntoIterator<Item = B::Item>>(&mut self, iter: I) {
        for item in iter {
            self.push(item);
        }
    }
}
