//! One collision's inputs in a given number type, and the conversions between types.

use collision_core::{Ball, BodyState, Exact, Scalar};

/// The inputs of one collision: the normal, both balls, both states.
#[derive(Clone, Debug, PartialEq)]
pub struct Case<T, const N: usize, const S: usize> {
    /// The unit contact normal `nu`, from body 1 to body 2.
    pub nu: [T; N],
    /// Body 1's and body 2's parameters.
    pub balls: [Ball<T>; 2],
    /// Body 1's and body 2's states `(U, u)`.
    pub states: [BodyState<T, N, S>; 2],
}

impl<T, const N: usize, const S: usize> Case<T, N, S> {
    /// Every input through `f`.
    pub fn map<U>(&self, mut f: impl FnMut(&T) -> U) -> Case<U, N, S> {
        let mut ball = |b: &Ball<T>| Ball {
            inv_mass: f(&b.inv_mass),
            radius: f(&b.radius),
            gamma2: f(&b.gamma2),
        };
        let balls = [ball(&self.balls[0]), ball(&self.balls[1])];
        let mut state = |s: &BodyState<T, N, S>| BodyState {
            spin: std::array::from_fn(|k| f(&s.spin[k])),
            velocity: std::array::from_fn(|k| f(&s.velocity[k])),
        };
        let states = [state(&self.states[0]), state(&self.states[1])];
        Case {
            nu: std::array::from_fn(|k| f(&self.nu[k])),
            balls,
            states,
        }
    }

    /// Both balls by reference, as `collide` takes them.
    pub fn ball_refs(&self) -> [&Ball<T>; 2] {
        [&self.balls[0], &self.balls[1]]
    }

    /// Both states by reference, as `collide` takes them.
    pub fn state_refs(&self) -> [&BodyState<T, N, S>; 2] {
        [&self.states[0], &self.states[1]]
    }
}

impl<T: Scalar, const N: usize, const S: usize> Case<T, N, S> {
    /// The same (finite, binary float) inputs, exactly.
    pub fn to_exact(&self) -> Case<Exact, N, S> {
        self.map(|x| Exact::from_float(x.to_f64()).expect("sampled inputs are finite"))
    }
}

impl<const N: usize, const S: usize> Case<f64, N, S> {
    /// The inputs rounded to `f32`, or why they cannot be: a value that overflows, or a
    /// non-zero value that becomes zero or subnormal (the regime then is not an `f32`
    /// regime at that point).
    pub fn to_f32(&self) -> Result<Case<f32, N, S>, &'static str> {
        let mut why = None;
        let case = self.map(|&x| {
            let y = x as f32;
            if !y.is_finite() {
                why = Some("inputs overflow f32");
            } else if x != 0.0 && !y.is_normal() {
                why = Some("inputs underflow f32");
            }
            y
        });
        match why {
            Some(w) => Err(w),
            None => Ok(case),
        }
    }
}

/// Post-collision states as one coordinate vector `[U_1, u_1, U_2, u_2]`.
pub fn flatten<T: Clone, const N: usize, const S: usize>(
    states: &[BodyState<T, N, S>; 2],
) -> Vec<T> {
    states
        .iter()
        .flat_map(|s| s.spin.iter().chain(&s.velocity).cloned())
        .collect()
}

/// The names of the coordinates of [`flatten`]: `U1_01`, .., `u2_{n-1}`.
pub fn component_names(n: usize) -> Vec<String> {
    (1..=2)
        .flat_map(|b| {
            collision_core::skew_pairs(n)
                .map(move |(i, j)| format!("U{b}_{i}{j}"))
                .chain((0..n).map(move |k| format!("u{b}_{k}")))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_follow_the_coordinate_order() {
        assert_eq!(
            component_names(2),
            ["U1_01", "u1_0", "u1_1", "U2_01", "u2_0", "u2_1"]
        );
        assert_eq!(component_names(3).len(), 12);
    }

    #[test]
    fn f32_conversion_refuses_what_f32_cannot_hold() {
        let mut case = Case::<f64, 2, 1> {
            nu: [1.0, 0.0],
            balls: [
                Ball::immovable(2, 1.0),
                Ball {
                    inv_mass: 1.0,
                    radius: 1.0,
                    gamma2: 0.5,
                },
            ],
            states: [BodyState::zero(), BodyState::zero()],
        };
        assert!(case.to_f32().is_ok());
        case.states[1].velocity[0] = 1e100;
        assert_eq!(case.to_f32().unwrap_err(), "inputs overflow f32");
        case.states[1].velocity[0] = 1e-100;
        assert_eq!(case.to_f32().unwrap_err(), "inputs underflow f32");
    }
}
