//! A ball's free flight in one record: what the neighbour scan reads of every ball it meets.

/// Ball `i`'s centre `a_i` at its own time `t_i`, its velocity `u_i` (a copy of its state's,
/// kept equal by the engine) and its radius `R_i`: the flight `a_i + (t - t_i) u_i` and the
/// contact distance `R_i + R_j`: `2n + 2` numbers read together, in this order (`repr(C)`: the
/// 3D lanes load them four at a time, `engine/lanes3.rs`).
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub(crate) struct Motion<const N: usize> {
    /// The centre `a_i` at time `since`.
    pub pos: [f64; N],
    /// The local time `t_i` of `pos`.
    pub since: f64,
    /// The velocity `u_i`.
    pub velocity: [f64; N],
    /// The radius `R_i`.
    pub radius: f64,
}

impl<const N: usize> Motion<N> {
    /// The centre at local time `now`: `a_i + (now - t_i) u_i`.
    #[inline]
    pub(crate) fn at(&self, now: f64) -> [f64; N] {
        let dt = now - self.since;
        std::array::from_fn(|k| self.pos[k] + self.velocity[k] * dt)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_flight_moves_along_its_velocity() {
        let m = Motion {
            pos: [1.0, 2.0, 3.0],
            since: 0.5,
            velocity: [2.0, 0.0, -1.0],
            radius: 0.5,
        };
        assert_eq!(m.at(1.5), [3.0, 2.0, 2.0]);
        assert_eq!(m.at(0.5), m.pos);
    }
}
