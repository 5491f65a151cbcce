//! The proven rounding-error bound of the generated float kernels
//! ([`noslip_codegen::bound`]) for one case, in the figure the report measures: per movable
//! body, `|computed - exact|_E / |exact|_E` in its energy norm, in units of the format's
//! epsilon.
//!
//! A case's inputs are a point box, each input passed exactly (the report's truth is the
//! rational map at the float inputs), so the bound is the running error bound of that call:
//! `measured <= bound` must hold for every case, and `bound / measured` is the tightness.
//! Cases are dispatched as `collide_unchecked` dispatches them: `free` with both bodies
//! movable, `fixed(nu, R_1, ball 2, ..)` with body 1 immovable, `fixed(-nu, R_2, ball 1,
//! state 2, state 1)` with body 2 immovable.

use crate::case::Case;
use crate::method::Method;
use crate::static_box::StaticBox;
use noslip_codegen::bound::{Format, InputRange, KernelBound};
use noslip_codegen::{Arith, Variant};

/// Where a kernel input comes from in a case (after the dispatch's relabelling).
#[derive(Clone, Copy, Debug)]
enum Slot {
    Nu(usize),
    Spin(usize, usize),
    Velocity(usize, usize),
    Radius(usize),
    InvMass(usize),
    Gamma2(usize),
}

/// The input named `name` ([`noslip_codegen::model::names`]) in dimension `n`; bodies 0, 1.
fn slot(n: usize, name: &str) -> Slot {
    let body = |s: &str| s.parse::<usize>().expect("body number") - 1;
    if let Some(k) = name.strip_prefix("nu_") {
        Slot::Nu(k.parse().expect("component"))
    } else if let Some(b) = name.strip_prefix("radius") {
        Slot::Radius(body(b))
    } else if let Some(b) = name.strip_prefix("inv_mass") {
        Slot::InvMass(body(b))
    } else if let Some(b) = name.strip_prefix("gamma2_") {
        Slot::Gamma2(body(b))
    } else if let Some(rest) = name.strip_prefix('U') {
        let (b, ij) = rest.split_once('_').expect("U{b}_{ij}");
        let ij: Vec<usize> = ij.bytes().map(|c| usize::from(c - b'0')).collect();
        let k = noslip_codegen::model::skew_pairs(n)
            .iter()
            .position(|&p| p == (ij[0], ij[1]))
            .expect("a skew pair");
        Slot::Spin(body(b), k)
    } else if let Some(rest) = name.strip_prefix('u') {
        let (b, k) = rest.split_once('_').expect("u{b}_{k}");
        Slot::Velocity(body(b), k.parse().expect("component"))
    } else {
        panic!("unknown kernel input {name}")
    }
}

/// One kernel's bound with its inputs located in a case.
#[derive(Debug)]
struct Located {
    kernel: KernelBound,
    slots: Vec<Slot>,
}

impl Located {
    fn new(n: usize, variant: Variant, arith: Arith, format: Format) -> Located {
        let kernel = KernelBound::of(n, variant, arith, format);
        let slots = kernel.inputs().iter().map(|s| slot(n, s)).collect();
        Located { kernel, slots }
    }
}

/// The bounds of one float method's kernels in dimension `N`.
#[derive(Debug)]
pub struct ProvenBound {
    format: Format,
    free: Located,
    fixed: Located,
}

impl ProvenBound {
    /// The bounds of `method`'s kernels (`F64`, `F64Fma`, `F32`; `None` for the others).
    pub fn of(n: usize, method: Method) -> Option<ProvenBound> {
        let (arith, format) = match method {
            Method::F64 | Method::Batch => (Arith::Plain, Format::F64),
            Method::F64Fma => (Arith::Fma, Format::F64),
            Method::F32 => (Arith::Plain, Format::F32),
            _ => return None,
        };
        Some(ProvenBound::of_kernel(n, arith, format))
    }

    /// The bounds of the kernels `arith` in `format`, whether or not a report method runs
    /// them (the `f32` FMA kernels: the certified companions' tightness is measured against
    /// them, `accuracy/tests/proven.rs`).
    pub fn of_kernel(n: usize, arith: Arith, format: Format) -> ProvenBound {
        ProvenBound {
            format,
            free: Located::new(n, Variant::Free, arith, format),
            fixed: Located::new(n, Variant::Fixed, arith, format),
        }
    }

    /// The format the kernels run in.
    pub fn format(&self) -> Format {
        self.format
    }

    /// The kernel `case` dispatches to, its inputs (widened exactly to `f64`, in the
    /// kernel's order), and which case body each returned body is.
    fn dispatch<const N: usize, const S: usize>(
        &self,
        case: &Case<f64, N, S>,
    ) -> (&KernelBound, Vec<f64>, [usize; 2]) {
        let immovable = |b: usize| case.balls[b].inv_mass == 0.0;
        // The kernel's body k is the case's body order[k]; `sign` multiplies the normal.
        let (located, order, sign) = match (immovable(0), immovable(1)) {
            (false, false) => (&self.free, [0, 1], 1.0),
            (true, _) => (&self.fixed, [0, 1], 1.0),
            (false, true) => (&self.fixed, [1, 0], -1.0),
        };
        let value = |s: Slot| match s {
            Slot::Nu(k) => sign * case.nu[k],
            Slot::Spin(b, k) => case.states[order[b]].spin[k],
            Slot::Velocity(b, k) => case.states[order[b]].velocity[k],
            Slot::Radius(b) => case.balls[order[b]].radius,
            Slot::InvMass(b) => case.balls[order[b]].inv_mass,
            Slot::Gamma2(b) => case.balls[order[b]].gamma2,
        };
        let inputs = located.slots.iter().map(|&s| value(s)).collect();
        (&located.kernel, inputs, order)
    }

    /// The kernel's bounds at `case` (inputs as the kernel receives them, widened exactly
    /// to `f64`), and which case body each returned body is.
    fn analyse<const N: usize, const S: usize>(
        &self,
        case: &Case<f64, N, S>,
    ) -> (noslip_codegen::bound::Bounds, [usize; 2]) {
        let (kernel, inputs, order) = self.dispatch(case);
        let points: Vec<InputRange> = inputs.into_iter().map(InputRange::point).collect();
        (kernel.analyse(&points), order)
    }

    /// The static bound over `boxes` ([`StaticBox::bound_eps`] of the kernel each box
    /// names, in this bound's format), the largest over them: in eps, `+inf` where the
    /// rules give no finite bound.
    pub fn static_bound(&self, boxes: &[StaticBox]) -> f64 {
        boxes
            .iter()
            .map(|b| {
                let located = match b.variant {
                    Variant::Free => &self.free,
                    Variant::Fixed => &self.fixed,
                };
                b.bound_eps(&located.kernel)
            })
            .fold(0.0, f64::max)
    }

    /// Whether `case`, as `collide_unchecked` dispatches it, lies in one of `boxes`.
    pub fn in_box<const N: usize, const S: usize>(
        &self,
        case: &Case<f64, N, S>,
        boxes: &[StaticBox],
    ) -> bool {
        let (kernel, inputs, _) = self.dispatch(case);
        boxes.iter().any(|b| b.contains(kernel, &inputs))
    }

    /// Per body of `case`, the proven bound of its normwise error in eps, with `lambda[b]`
    /// the weight of its norm (as the report measures it); `None` for an immovable body
    /// (returned unchanged).
    pub fn body_bounds<const N: usize, const S: usize>(
        &self,
        case: &Case<f64, N, S>,
        lambda: [f64; 2],
    ) -> [Option<f64>; 2] {
        let (bounds, order) = self.analyse(case);
        let mut out = [None, None];
        for body in &bounds.bodies {
            let b = order[body.body - 1];
            out[b] = Some(body.relative_energy_error(lambda[b]) / self.format.epsilon());
        }
        out
    }

    /// The proven bound of the absolute error of every output component, in
    /// [`crate::case::flatten`] order (`0` for an immovable body's, returned unchanged).
    pub fn component_bounds<const N: usize, const S: usize>(
        &self,
        case: &Case<f64, N, S>,
    ) -> Vec<f64> {
        let (bounds, order) = self.analyse(case);
        let mut out = vec![0.0; 2 * (S + N)];
        for body in &bounds.bodies {
            let b = order[body.body - 1];
            for (k, e) in body.components().enumerate() {
                out[b * (S + N) + k] = e.error;
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn input_names_locate_their_slots() {
        assert!(matches!(slot(3, "nu_2"), Slot::Nu(2)));
        assert!(matches!(slot(3, "U2_12"), Slot::Spin(1, 2)));
        assert!(matches!(slot(4, "U1_03"), Slot::Spin(0, 2)));
        assert!(matches!(slot(3, "u1_0"), Slot::Velocity(0, 0)));
        assert!(matches!(slot(3, "radius2"), Slot::Radius(1)));
        assert!(matches!(slot(3, "inv_mass1"), Slot::InvMass(0)));
        assert!(matches!(slot(3, "gamma2_2"), Slot::Gamma2(1)));
    }
}
