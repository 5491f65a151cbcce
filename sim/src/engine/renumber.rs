//! The balls renumbered in cell order at every re-basing (and at the start), so that the
//! records of balls in one cell, and of neighbouring cells along a row, lie together in
//! memory: a scan's partners (their counters, read when one of them becomes the best
//! contact) and a contact's two balls are then near each other.
//!
//! Internal only: the engine's index of a ball (its place in `balls`) changes, its number
//! as the caller knows it (`id`, kept in its record) does not. The log, the contact's
//! bodies (body 1 the lower id), the keys that order simultaneous events
//! (`canonical::key`, [`super::record::key_of`]) and every public method use ids; so the
//! log is the same bytes with or without renumbering (the reference tests compare it with
//! the all-pairs reference's, which never renumbers).

use super::Simulation;
use crate::queue::Slot;
use crate::PairKernels;

impl<const N: usize, const S: usize, K: PairKernels<f64, N, S>> Simulation<N, S, K> {
    /// Renumbers the balls in the order of the slab (cell after cell; call right after
    /// `Residents::compact`): ball `q` becomes the `q`-th record of the slab. The pending
    /// events are dropped (every ball is predicted again next). `O(balls)`, in place: the
    /// records are moved along the permutation's cycles.
    pub(super) fn renumber(&mut self) {
        // order[q]: the present index of the ball that becomes q.
        let mut order: Vec<u32> = self.motion.in_cell_order().map(|b| b as u32).collect();
        self.queue.clear();
        for record in &mut self.balls {
            record.slot = Slot::EMPTY;
        }
        if order.iter().enumerate().all(|(q, &p)| q == p as usize) {
            return;
        }
        // Along each cycle q0 <- order[q0] <- order[order[q0]] ... (a done place is marked
        // u32::MAX).
        for start in 0..order.len() {
            if order[start] == u32::MAX || order[start] as usize == start {
                continue;
            }
            let held = self.balls[start].clone();
            let mut q = start;
            loop {
                let p = std::mem::replace(&mut order[q], u32::MAX) as usize;
                if p == start {
                    self.balls[q] = held;
                    break;
                }
                self.balls[q] = self.balls[p].clone();
                q = p;
            }
        }
        for (q, record) in self.balls.iter().enumerate() {
            self.index[record.id as usize] = q as u32;
        }
        self.motion.renumber(self.balls.as_slice());
    }
}

#[cfg(test)]
mod tests {
    use crate::{Body, GenericKernels, Setup, Simulation, Step};
    use collision_core::{Ball, BodyState};

    const DISK: Ball<f64> = Ball {
        inv_mass: 1.0,
        radius: 0.5,
        gamma2: 0.5,
    };

    /// 64 disks on an 8 x 8 lattice of a periodic square of side 24, numbered from the top
    /// right corner down (against the cells' order), with distinct velocities.
    fn gas() -> Simulation<2, 1, GenericKernels<f64>> {
        let bodies = (0..64)
            .map(|b| {
                let (x, y) = (7 - b % 8, 7 - b / 8);
                Body {
                    species: 0,
                    position: [3.0 * x as f64 + 1.5, 3.0 * y as f64 + 1.5],
                    state: BodyState {
                        spin: [0.01 * b as f64],
                        velocity: [((b * 37) % 11) as f64 - 5.0, ((b * 53) % 7) as f64 - 3.0],
                    },
                }
            })
            .collect::<Vec<_>>();
        let setup = Setup {
            size: [24.0, 24.0],
            periodic: [true, true],
            species: vec![DISK],
            obstacles: vec![],
            bodies,
            orientation: false,
            table: crate::Table::boxed(),
        };
        let kernels = GenericKernels {
            species: vec![DISK],
        };
        Simulation::new(setup, kernels).unwrap()
    }

    /// The numbering is consistent: `index` inverts the records' ids, every ball is in its
    /// cell's list under its place; and, right after a renumbering, the balls lie in cell
    /// order.
    fn check_numbering(sim: &Simulation<2, 1, GenericKernels<f64>>, in_cell_order: bool) {
        let cells: Vec<usize> = sim.balls.iter().map(|r| sim.grid.flat(&r.cell())).collect();
        for (p, record) in sim.balls.iter().enumerate() {
            assert_eq!(sim.index[record.id as usize] as usize, p);
            let list = sim.motion.cell(cells[p]);
            assert!(list.iter().any(|r| r.ball as usize == p), "ball {p}");
        }
        if in_cell_order {
            assert!(cells.windows(2).all(|w| w[0] <= w[1]), "{cells:?}");
        }
    }

    #[test]
    fn balls_are_renumbered_in_cell_order_and_named_by_their_ids() {
        let sim = gas();
        // Renumbered at the start (the ids ran against the cells' order) ...
        assert!(sim.index.iter().enumerate().any(|(i, &p)| i != p as usize));
        check_numbering(&sim, true);
        // ... and every public method still answers by the caller's numbers.
        for b in 0..64usize {
            let (x, y) = (7 - b % 8, 7 - b / 8);
            assert_eq!(
                sim.position(b),
                [3.0 * x as f64 + 1.5, 3.0 * y as f64 + 1.5]
            );
            assert_eq!(sim.state(b).spin, [0.01 * b as f64]);
        }
        // Through contacts and re-basings (each renumbers again): body 1 the lower id, and
        // each contact's positions those of the balls it names.
        let mut sim = gas();
        let rebases = sim.rebases();
        for _ in 0..3000 {
            let Step::Contact(event) = sim.step(f64::INFINITY) else {
                panic!("a gas keeps colliding")
            };
            if let crate::Contact::Ball { i, j } = event.contact {
                assert!(i < j && j < 64);
                assert_eq!(sim.position(i), event.position[0]);
                assert_eq!(sim.position(j), event.position[1]);
                assert_eq!(sim.state(j), &event.post[1]);
            }
        }
        assert!(sim.rebases() > rebases);
        // (The balls moved on since the last renumbering.)
        check_numbering(&sim, false);
    }
}
