//! The report's batch variant: cases run through the batch kernels the way `collide`
//! dispatches them, so that every result is `collide_unchecked`'s bit for bit.
//!
//! `collide` runs `free` when both bodies move, `fixed` when body 1 is immovable, and `fixed`
//! with the bodies swapped and `nu` negated when body 2 is. The batch `free` kernel with
//! `inv_mass = 0` computes the same rational map with other roundings (docs/batch.md), so
//! the cases are split into one `free` batch and one `fixed` batch.

use crate::case::Case;
use collision_core::batch::{
    BatchKernel, Contact, Exec, FixedBatch, FreeBatch, PairBatch, StateBatch,
};
use collision_core::{BodyState, Generated};

/// Where a case's result comes from.
#[derive(Clone, Copy, Debug)]
enum Slot {
    /// Item `k` of the `free` batch.
    Free(usize),
    /// Item `k` of the `fixed` batch; `swapped`: body 2 is the immovable one.
    Fixed { k: usize, swapped: bool },
}

/// The cases as batches, with the outputs of the last run.
pub struct Batched<const N: usize, const S: usize> {
    free: FreeBatch<f64, N, S>,
    fixed: FixedBatch<f64, N, S>,
    slots: Vec<Slot>,
    free_out: PairBatch<f64, N, S>,
    fixed_out: StateBatch<f64, N, S>,
}

impl<const N: usize, const S: usize> Batched<N, S>
where
    Generated: BatchKernel<f64, N, S>,
{
    /// The cases as batches: free contacts in one, contacts with an immovable body in the other
    /// (swapped so that body 1 is the immovable one).
    pub fn new(cases: &[Case<f64, N, S>]) -> Self {
        let (mut free, mut fixed) = (FreeBatch::new(), FixedBatch::new());
        let slots = cases
            .iter()
            .map(|c| {
                let [b1, b2] = &c.balls;
                let [s1, s2] = &c.states;
                if b1.is_immovable() || b2.is_immovable() {
                    let swapped = !b1.is_immovable();
                    let item = if swapped {
                        let contact = Contact {
                            nu: c.nu.map(|x| -x),
                            states: [s2.clone(), s1.clone()],
                        };
                        (contact, b2.radius, b1.clone())
                    } else {
                        let contact = Contact {
                            nu: c.nu,
                            states: [s1.clone(), s2.clone()],
                        };
                        (contact, b1.radius, b2.clone())
                    };
                    fixed.push(item);
                    Slot::Fixed {
                        k: fixed.len() - 1,
                        swapped,
                    }
                } else {
                    let contact = Contact {
                        nu: c.nu,
                        states: c.states.clone(),
                    };
                    free.push((contact, c.balls.clone()));
                    Slot::Free(free.len() - 1)
                }
            })
            .collect();
        Batched {
            free,
            fixed,
            slots,
            free_out: PairBatch::new(),
            fixed_out: StateBatch::new(),
        }
    }

    /// Run both batches on `exec` (the timed part).
    pub fn run(&mut self, exec: &Exec) {
        exec.free(&self.free, &mut self.free_out);
        exec.fixed(&self.fixed, &mut self.fixed_out);
    }

    /// Case `i`'s result of the last run: `[body 1+, body 2+]`, an immovable body unchanged.
    pub fn result(&self, i: usize, cases: &[Case<f64, N, S>]) -> Option<[BodyState<f64, N, S>; 2]> {
        let [s1, s2] = &cases.get(i)?.states;
        Some(match *self.slots.get(i)? {
            Slot::Free(k) => self.free_out.get(k)?,
            Slot::Fixed { k, swapped: false } => [s1.clone(), self.fixed_out.get(k)?],
            Slot::Fixed { k, swapped: true } => [self.fixed_out.get(k)?, s2.clone()],
        })
    }
}
