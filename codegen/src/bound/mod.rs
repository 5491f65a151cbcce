//! Proven rounding-error bounds of the generated kernels, derived from the same lowered
//! program the back ends emit ([`crate::program::Program`]: the schedule, the fusion, the
//! operation order).
//!
//! **Model.** Every operation of a float kernel is correctly rounded to nearest in its format
//! ([`Format`]): `fl(a op b) = a op b + r`, `|r| <= u 2^floor(log2 |a op b|)` (half the
//! spacing of the floats there, which is at most `u |a op b|`, the standard model's
//! `(1 + delta)`, `|delta| <= u`), and `|r| <= u 2^e_min` below the normal range, so gradual
//! underflow is covered; a fused multiply-add rounds once. Overflow is not assumed away: an
//! operation whose result could reach the largest finite value makes its bound infinite.
//!
//! **What is bounded.** Given a box of real inputs (an interval per input) and, per input,
//! the relative error of the float the caller passes (0 for an input taken as given; for a
//! normal or a `gamma2` rounded from an exact value, the rounding), [`KernelBound::analyse`]
//! returns for every output an interval holding its exact value (the kernel's rational map on
//! the real inputs) and a number `E` with `|computed - exact| <= E` for every input point of
//! the box. The rules are in [`propagate`]'s docs; each output's `E` is the smaller of
//! theirs and a second bound, the mean value theorem along the roundings with the adjoints
//! enclosed over the box (`bound/adjoint.rs`, whose docs derive it). A point box is a running
//! error bound for one call.
//!
//! **Its own arithmetic** is `f64` rounded to nearest and moved one float outward after every
//! operation ([`round`]), so rounding in the bound can only raise it.
//!
//! The bound of a body in its kinetic-energy norm, the figure `noslip report` measures, is
//! [`BodyBound::relative_energy_error`].

mod adjoint;
pub mod format;
pub mod gappa;
pub mod propagate;
pub mod round;

pub use format::Format;
pub use propagate::Enclosed;
pub use round::Interval;

use crate::arith::Arith;
use crate::model::{self, Variant};
use crate::program::Program;
use propagate::Compiled;
use round::{add_up, div_up, mul_up, pow2_floor, sqrt_down, sqrt_up};

/// One input of a box: the interval of its real value, and the relative error of the float
/// the kernel is given (`|x^ - x| <= relative_error |x|`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InputRange {
    /// Holds the real input.
    pub value: Interval,
    /// Relative error of the float passed to the kernel (0: the float is the input).
    pub relative_error: f64,
}

impl InputRange {
    /// Exactly the float `x`.
    pub fn point(x: f64) -> InputRange {
        InputRange {
            value: Interval::point(x),
            relative_error: 0.0,
        }
    }

    /// Any real in `[lo, hi]`, passed exactly.
    pub fn range(lo: f64, hi: f64) -> InputRange {
        InputRange {
            value: Interval::new(lo, hi),
            relative_error: 0.0,
        }
    }

    /// The same range, passed with a relative error of at most `relative_error`.
    pub fn rounded(self, relative_error: f64) -> InputRange {
        InputRange {
            relative_error,
            ..self
        }
    }
}

/// The bounds of one returned body.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyBound {
    /// 1 or 2.
    pub body: usize,
    /// The compact skew entries of `U+`.
    pub spin: Vec<Enclosed>,
    /// The centre velocity `u+`.
    pub velocity: Vec<Enclosed>,
}

impl BodyBound {
    /// Every output of the body: spin entries, then velocity components.
    pub fn components(&self) -> impl Iterator<Item = &Enclosed> {
        self.spin.iter().chain(&self.velocity)
    }

    /// An upper bound of `|computed - exact|_E`, the body's error in the norm
    /// `|x|_E^2 = 2 lambda sum_{i<j} U_ij^2 + |u|^2` (its kinetic-energy norm divided by the
    /// mass), from the componentwise bounds.
    pub fn energy_error(&self, lambda: f64) -> f64 {
        weighted_norm_up(lambda, self.spin.iter(), self.velocity.iter(), |e| e.error)
    }

    /// A lower bound of the exact body's `|x|_E` over the box (0 if it can vanish).
    pub fn energy_norm_lower(&self, lambda: f64) -> f64 {
        let parts =
            |it: std::slice::Iter<'_, Enclosed>| it.map(|e| e.value.mig()).collect::<Vec<_>>();
        let (s, v) = (parts(self.spin.iter()), parts(self.velocity.iter()));
        weighted_norm_down(2.0 * lambda, &s, &v)
    }

    /// An upper bound of `|computed - exact|_E / |exact|_E`, the normwise error `noslip report`
    /// measures (the mass cancels); infinite when the exact body can vanish in the box, 0 when
    /// the computed body is exact.
    pub fn relative_energy_error(&self, lambda: f64) -> f64 {
        let err = self.energy_error(lambda);
        if err == 0.0 {
            return 0.0;
        }
        let norm = self.energy_norm_lower(lambda);
        if norm > 0.0 {
            div_up(err, norm)
        } else {
            f64::INFINITY
        }
    }
}

/// `sqrt(2 lambda sum s_k^2 + sum v_k^2)` of `f` over the entries, rounded upward, scaled
/// by a power of two so that it neither overflows nor underflows before the end.
fn weighted_norm_up<'a>(
    lambda: f64,
    spin: impl Iterator<Item = &'a Enclosed> + Clone,
    velocity: impl Iterator<Item = &'a Enclosed> + Clone,
    f: impl Fn(&Enclosed) -> f64,
) -> f64 {
    let w = 2.0 * lambda; // exact
    let scale = spin
        .clone()
        .chain(velocity.clone())
        .map(&f)
        .fold(0.0, f64::max);
    if scale == 0.0 || !scale.is_finite() {
        return scale;
    }
    let s = pow2_floor(scale);
    let sq = |x: f64| {
        let y = div_up(x, s);
        mul_up(y, y)
    };
    let total = spin
        .map(|e| mul_up(w, sq(f(e))))
        .chain(velocity.map(|e| sq(f(e))))
        .fold(0.0, add_up);
    mul_up(sqrt_up(total), s)
}

/// `sqrt(w sum s_k^2 + sum v_k^2)`, rounded downward (scaled like [`weighted_norm_up`]).
fn weighted_norm_down(w: f64, spin: &[f64], velocity: &[f64]) -> f64 {
    let scale = spin.iter().chain(velocity).copied().fold(0.0, f64::max);
    if scale == 0.0 || !scale.is_finite() {
        return if scale.is_finite() { 0.0 } else { f64::MAX };
    }
    let s = pow2_floor(scale);
    let down = round::down;
    let sq = |x: f64| {
        let y = down(x / s).max(0.0);
        down(y * y).max(0.0)
    };
    let total = spin
        .iter()
        .map(|&x| down(w * sq(x)).max(0.0))
        .chain(velocity.iter().map(|&x| sq(x)))
        .fold(0.0, |acc, x| down(acc + x));
    down(sqrt_down(total) * s).max(0.0)
}

/// The bounds of one kernel's outputs over one box.
#[derive(Clone, Debug, PartialEq)]
pub struct Bounds {
    /// The returned bodies, in the kernel's output order.
    pub bodies: Vec<BodyBound>,
}

impl Bounds {
    /// The bounds over the union of two boxes: per output, the larger error bounds and the
    /// hull of the enclosures.
    pub fn join(&self, other: &Bounds) -> Bounds {
        let one = |a: &Enclosed, b: &Enclosed| Enclosed {
            value: Interval::new(a.value.lo.min(b.value.lo), a.value.hi.max(b.value.hi)),
            error: a.error.max(b.error),
            relative: a.relative.max(b.relative),
        };
        let bodies = self
            .bodies
            .iter()
            .zip(&other.bodies)
            .map(|(a, b)| BodyBound {
                body: a.body,
                spin: a.spin.iter().zip(&b.spin).map(|(x, y)| one(x, y)).collect(),
                velocity: a
                    .velocity
                    .iter()
                    .zip(&b.velocity)
                    .map(|(x, y)| one(x, y))
                    .collect(),
            })
            .collect();
        Bounds { bodies }
    }
}

/// `r` cut into `k` adjacent pieces (see [`KernelBound::analyse_split`]).
fn split(r: InputRange, k: usize) -> Vec<InputRange> {
    let (lo, hi) = (r.value.lo, r.value.hi);
    if k == 1 || lo >= hi {
        return vec![r];
    }
    let at = |i: usize| {
        if i == 0 {
            lo
        } else if i == k {
            hi
        } else if lo > 0.0 {
            lo * (hi / lo).powf(i as f64 / k as f64)
        } else {
            lo + (hi - lo) * (i as f64 / k as f64)
        }
    };
    (0..k)
        .map(|i| InputRange {
            value: Interval::new(at(i), at(i + 1)),
            relative_error: r.relative_error,
        })
        .collect()
}

/// One kernel (dimension, variant, plain or fused, format), ready to bound over any box.
#[derive(Clone, Debug)]
pub struct KernelBound {
    /// The dimension `n`.
    pub dim: usize,
    /// Which bodies move.
    pub variant: Variant,
    /// Plain or fused arithmetic.
    pub arith: Arith,
    /// The format it runs in.
    pub format: Format,
    compiled: Compiled,
}

impl KernelBound {
    /// The kernel the generator emits for `dim`, `variant` and `arith`, run in `format`.
    pub fn of(dim: usize, variant: Variant, arith: Arith, format: Format) -> KernelBound {
        KernelBound::new(&Program::lower(&model::build(dim, variant), arith), format)
    }

    /// Any lowered program (a specialised kernel, say), run in `format`.
    pub fn new(program: &Program, format: Format) -> KernelBound {
        KernelBound {
            dim: program.dim,
            variant: program.variant,
            arith: program.arith,
            format,
            compiled: Compiled::new(program, format),
        }
    }

    /// The inputs the kernel reads, by name ([`crate::model::names`]), in the order
    /// [`KernelBound::analyse`] takes their ranges.
    pub fn inputs(&self) -> &[String] {
        &self.compiled.inputs
    }

    /// The bounds over the box `inputs` (one range per [`KernelBound::inputs`], in order).
    pub fn analyse(&self, inputs: &[InputRange]) -> Bounds {
        self.analyse_with(inputs, true)
    }

    /// [`KernelBound::analyse`] by the rules alone, without the mean-value bound: the
    /// same or a larger bound, about a third of the time. Over a wide box the mean-value
    /// bound's adjoints are enclosed over the whole box and give nothing tighter.
    pub fn analyse_rules(&self, inputs: &[InputRange]) -> Bounds {
        self.analyse_with(inputs, false)
    }

    fn analyse_with(&self, inputs: &[InputRange], mean_value: bool) -> Bounds {
        let given: Vec<Enclosed> = inputs
            .iter()
            .map(|r| {
                let error = if r.relative_error == 0.0 {
                    0.0
                } else {
                    mul_up(r.value.mag(), r.relative_error)
                };
                Enclosed::new(r.value, error, r.relative_error)
            })
            .collect();
        let mut values = self.compiled.run(self.format, &given);
        // Per output, the smaller of the rules' bound and the mean-value one (adjoint.rs).
        if mean_value {
            let outputs = self.compiled.output_indices();
            let second = adjoint::bounds(&self.compiled, self.format, &given, &outputs);
            for (&k, &e) in outputs.iter().zip(&second) {
                if e < values[k].error {
                    values[k] = Enclosed::new(values[k].value, e, values[k].relative);
                }
            }
        }
        let bodies = self
            .compiled
            .outputs
            .iter()
            .map(|(body, spin, velocity)| BodyBound {
                body: *body,
                spin: spin.iter().map(|&k| values[k]).collect(),
                velocity: velocity.iter().map(|&k| values[k]).collect(),
            })
            .collect();
        Bounds { bodies }
    }

    /// The bounds over the box `inputs`, split into sub-boxes: input `k` into `pieces[k]`
    /// intervals (geometric when the range is positive, else of equal width; adjacent
    /// pieces share their float end, so they cover the range). Per output, the largest
    /// error and the hull of the enclosures over the sub-boxes: a bound over the whole box,
    /// tighter than [`KernelBound::analyse`] where the rules lose the correlation between
    /// inputs (the kernels' quotients of parameters).
    pub fn analyse_split(&self, inputs: &[InputRange], pieces: &[usize]) -> Bounds {
        self.split_with(inputs, pieces, |sub| self.analyse(sub))
    }

    /// [`KernelBound::analyse_split`] by the rules alone ([`KernelBound::analyse_rules`]).
    pub fn analyse_split_rules(&self, inputs: &[InputRange], pieces: &[usize]) -> Bounds {
        self.split_with(inputs, pieces, |sub| self.analyse_rules(sub))
    }

    /// `analyse` over every sub-box of the split, joined.
    fn split_with(
        &self,
        inputs: &[InputRange],
        pieces: &[usize],
        analyse: impl Fn(&[InputRange]) -> Bounds,
    ) -> Bounds {
        assert_eq!(inputs.len(), pieces.len(), "one piece count per input");
        let parts: Vec<Vec<InputRange>> = inputs
            .iter()
            .zip(pieces)
            .map(|(r, &k)| split(*r, k.max(1)))
            .collect();
        let mut index = vec![0usize; parts.len()];
        let mut joined: Option<Bounds> = None;
        loop {
            let sub: Vec<InputRange> = index.iter().zip(&parts).map(|(&i, p)| p[i]).collect();
            let b = analyse(&sub);
            joined = Some(match joined {
                None => b,
                Some(j) => j.join(&b),
            });
            // The next index, odometer-style.
            let mut k = 0;
            loop {
                if k == index.len() {
                    return joined.expect("at least one sub-box");
                }
                index[k] += 1;
                if index[k] < parts[k].len() {
                    break;
                }
                index[k] = 0;
                k += 1;
            }
        }
    }

    /// The bounds over the box given by name (`range(name)` for each input).
    pub fn analyse_named(&self, range: impl Fn(&str) -> InputRange) -> Bounds {
        let inputs: Vec<InputRange> = self.inputs().iter().map(|n| range(n)).collect();
        self.analyse(&inputs)
    }
}

#[cfg(test)]
mod tests;
