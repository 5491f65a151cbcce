//! Static bounds: one rounding-error bound for every input in a regime's box.
//!
//! Each regime of the report ([`Regime`]) has a *static box*: an interval per kernel input
//! that holds most of the cases the regime samples. Over it the generator's bound
//! ([`noslip_codegen::bound::KernelBound::analyse_split`], the same rules as a case's bound,
//! evaluated on intervals) gives, per output component, a bound on the absolute error that
//! holds for **every** input in the box, sampled or not. The figure is the largest such
//! bound over the movable bodies' components, in eps of the format (the states' entries are
//! O(1) in most boxes; where a regime scales them, the bound scales with them). The report
//! prints it beside the largest absolute component error measured over the regime's cases
//! that lie in the box, and fails if one exceeds it.
//!
//! The typical box (`g = 2/n`): per body `inv_mass in [1/4, 4]`, `radius in [1/2, 2]`,
//! `gamma2 in [g/8, g]` (a box reaching `gamma2_1 = gamma2_2 = 0` contains `D = 0` and has
//! no finite bound, so it stops at `g/8`, where the typical regime samples `(0, g]`), every
//! entry of `U_i` and `u_i` in `[-1, 1]`, every component of `nu` in `[-1, 1]` (a box cannot
//! say `|nu| = 1`). Each regime changes what its sampling changes ([`StaticBox::about`]).
//! Every parameter range is cut into geometric pieces ([`pieces`]), since the rules lose the
//! correlation between a quotient's numerator and divisor over a wide interval, and the
//! bound is by the rules alone ([`KernelBound::analyse_split_rules`]): over a box the
//! mean-value bound gives nothing tighter, at three times the cost.

use crate::regime::Regime;
use noslip_codegen::bound::{Format, InputRange, KernelBound};
use noslip_codegen::Variant;

/// A regime's box for one kernel: per body its parameter ranges and its states' half-widths.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StaticBox {
    /// The kernel the box's cases dispatch to (`Fixed`: body 1 immovable).
    pub variant: Variant,
    /// `[lo, hi]` of `inv_mass` per body.
    pub inv_mass: [(f64, f64); 2],
    /// `[lo, hi]` of the radius per body.
    pub radius: [(f64, f64); 2],
    /// `[lo, hi]` of `gamma2` per body.
    pub gamma2: [(f64, f64); 2],
    /// Every entry of `u_i` in `[-w, w]`.
    pub velocity: [f64; 2],
    /// Every entry of `U_i` in `[-w, w]`.
    pub spin: [f64; 2],
}

/// The number of geometric pieces a `gamma2` range `[lo, hi]` is cut into: one per factor 4
/// of `hi / lo`, at least 4 (the typical box's range, a factor 8, gets 4), at most 32; 1 for
/// a point. The other parameters get 4 pieces: measured on the report's boxes at n = 3,
/// more pieces of the mass ratio's and radius ratio's wide ranges (21, 22) left their bounds
/// the same, where the small-gamma box's bound grows 3.6x at one piece per factor 16 of
/// `gamma2` and 1500x at 4 pieces (its quotients `1 / gamma2`-like over the whole range).
pub fn pieces(lo: f64, hi: f64) -> usize {
    if lo >= hi {
        return 1;
    }
    if lo <= 0.0 {
        return 4;
    }
    ((hi / lo).log2() / 2.0).ceil().clamp(4.0, 32.0) as usize
}

impl StaticBox {
    /// The typical box of dimension `n` (module docs), for the `free` kernel.
    pub fn typical(n: usize) -> StaticBox {
        let g = 2.0 / n as f64;
        StaticBox {
            variant: Variant::Free,
            inv_mass: [(0.25, 4.0); 2],
            radius: [(0.5, 2.0); 2],
            gamma2: [(g / 8.0, g); 2],
            velocity: [1.0; 2],
            spin: [1.0; 2],
        }
    }

    /// The boxes of `regime` in dimension `n` for a kernel in `format`: one, or two where the
    /// regime picks a body at random (the bound is the larger of the two, a case counts if
    /// it lies in either). Only the extreme scales' box depends on the format: `f32` holds
    /// states to `1e30` of its `3.4e38`, not `1e100`.
    pub fn of(regime: Regime, n: usize, format: Format) -> Vec<StaticBox> {
        let typical = StaticBox::typical(n);
        let each_body = |change: &dyn Fn(&mut StaticBox, usize)| {
            (0..2)
                .map(|b| {
                    let mut x = typical;
                    change(&mut x, b);
                    x
                })
                .collect()
        };
        let one = |change: &dyn Fn(&mut StaticBox)| {
            let mut x = typical;
            change(&mut x);
            vec![x]
        };
        let g = 2.0 / n as f64;
        match regime {
            Regime::Typical => vec![typical],
            // The heavy body's inverse mass: the other's over 10^3..10^15.
            Regime::MassRatio => each_body(&|x, heavy| x.inv_mass[heavy] = (0.25e-15, 4e-3)),
            // Either body immovable: `collide` runs `fixed` with the immovable body first.
            Regime::Immovable => one(&|x| {
                x.variant = Variant::Fixed;
                x.inv_mass[0] = (0.0, 0.0);
                x.gamma2[0] = (0.0, 0.0);
            }),
            Regime::SmallGamma => one(&|x| x.gamma2 = [(g * 1e-15, g); 2]),
            Regime::PointMass => each_body(&|x, b| x.gamma2[b] = (0.0, 0.0)),
            Regime::RadiusRatio => one(&|x| x.radius[0] = (0.5e-6, 2e6)),
            Regime::Scale => one(&|x| {
                let w = if format == Format::F32 { 1e30 } else { 1e100 };
                x.velocity = [w; 2];
                x.spin = [w; 2];
            }),
            Regime::SpinDominated => one(&|x| x.spin = [1e12; 2]),
            // Body 2's velocity moved along the normal by `-dn + 1e-12 |t|`, with
            // `|dn| <= |u_2 - u_1| <= 2 sqrt(n)`.
            Regime::Grazing => one(&|x| x.velocity[1] = 1.0 + 2.0 * (n as f64).sqrt() + 1e-6),
        }
    }

    /// What the regime's boxes change in the typical one, for the report.
    pub fn about(regime: Regime) -> &'static str {
        match regime {
            Regime::Typical => "the typical box",
            Regime::MassRatio => "the heavy body's inv_mass in [0.25e-15, 4e-3] (two boxes)",
            Regime::Immovable => "fixed: body 1 immovable, body 2 typical",
            Regime::SmallGamma => "both gamma2 in [g 1e-15, g]",
            Regime::PointMass => "one gamma2 = 0 (two boxes)",
            Regime::RadiusRatio => "R_1 in [0.5e-6, 2e6]",
            Regime::Scale => "entries of u_i and U_i in [-1e100, 1e100] (f32: [-1e30, 1e30])",
            Regime::SpinDominated => "entries of U_i in [-1e12, 1e12]",
            Regime::Grazing => "entries of u_2 in +-(1 + 2 sqrt(n) + 1e-6)",
        }
    }

    /// The range of the kernel input `name` ([`noslip_codegen::model::names`]) and its
    /// number of pieces: [`pieces`] for `gamma2`; 4 for the other parameters, or 2 in a box
    /// whose `gamma2` ranges take more than 4 (the small-gamma box: 25 x 25 pieces of the
    /// two `gamma2` would make `4^4` times that 40 typical boxes' time, where `2^4` times
    /// costs 2.4 of them for a bound twice as large at n = 3); 1 for the states and the normal.
    pub fn range(&self, name: &str) -> (InputRange, usize) {
        let wide_gamma = self.gamma2.iter().any(|&(lo, hi)| pieces(lo, hi) > 4);
        let other = if wide_gamma { 2 } else { 4 };
        let body = |rest: &str| -> usize {
            let digit = rest.trim_start_matches('_').as_bytes()[0];
            usize::from(digit - b'1')
        };
        let param = |(lo, hi): (f64, f64), k: usize| (InputRange::range(lo, hi), k);
        let state = |w: f64| (InputRange::range(-w, w), 1);
        if name.starts_with("nu_") {
            (InputRange::range(-1.0, 1.0), 1)
        } else if let Some(b) = name.strip_prefix("inv_mass") {
            param(self.inv_mass[body(b)], other)
        } else if let Some(b) = name.strip_prefix("radius") {
            param(self.radius[body(b)], other)
        } else if let Some(b) = name.strip_prefix("gamma2") {
            let (lo, hi) = self.gamma2[body(b)];
            param((lo, hi), pieces(lo, hi))
        } else if let Some(b) = name.strip_prefix('U') {
            state(self.spin[body(b)])
        } else if let Some(b) = name.strip_prefix('u') {
            state(self.velocity[body(b)])
        } else {
            panic!("unknown kernel input {name}")
        }
    }

    /// Whether the kernel inputs `values` (in `kernel.inputs()` order) lie in the box.
    pub fn contains(&self, kernel: &KernelBound, values: &[f64]) -> bool {
        kernel.variant == self.variant
            && kernel.inputs().iter().zip(values).all(|(name, &x)| {
                let r = self.range(name).0.value;
                r.lo <= x && x <= r.hi
            })
    }

    /// The static bound of `kernel` (whose variant must be the box's) over the box: the
    /// largest absolute error bound of a returned body's component, in eps of its format;
    /// `+inf` if the rules cannot bound it (an overflow or a divisor they cannot keep from 0).
    pub fn bound_eps(&self, kernel: &KernelBound) -> f64 {
        assert_eq!(kernel.variant, self.variant, "the box's kernel");
        let (ranges, pieces): (Vec<InputRange>, Vec<usize>) =
            kernel.inputs().iter().map(|name| self.range(name)).unzip();
        let bounds = kernel.analyse_split_rules(&ranges, &pieces);
        let worst = bounds
            .bodies
            .iter()
            .flat_map(|b| b.components())
            .map(|e| e.error)
            .fold(0.0, f64::max);
        worst / kernel.format.epsilon()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use noslip_codegen::Arith;

    #[test]
    fn pieces_follow_the_range() {
        assert_eq!(pieces(1.0, 1.0), 1);
        assert_eq!(pieces(0.25, 4.0), 4);
        assert_eq!(pieces(0.5e-6, 2e6), 21);
        assert_eq!(pieces(0.25e-15, 4e-3), 22);
        assert_eq!(pieces(1e-300, 1.0), 32);
    }

    #[test]
    fn every_kernel_input_has_a_range() {
        for regime in Regime::ALL {
            for b in StaticBox::of(regime, 3, Format::F64) {
                let kernel = KernelBound::of(3, b.variant, Arith::Plain, Format::F64);
                for name in kernel.inputs() {
                    let (r, k) = b.range(name);
                    assert!(r.value.lo <= r.value.hi && k >= 1, "{name}");
                }
            }
        }
    }

    /// The box's bound holds at its corners and centre, against the kernel's own bound
    /// at those points (a point box is a case; the box bound must cover each).
    #[test]
    fn a_box_bound_covers_the_bounds_of_its_points() {
        let b = StaticBox::typical(2);
        let kernel = KernelBound::of(2, Variant::Free, Arith::Plain, Format::F64);
        let whole = b.bound_eps(&kernel);
        assert!(whole.is_finite() && whole > 0.0);
        for pick in [0.0, 0.5, 1.0] {
            let inputs: Vec<InputRange> = kernel
                .inputs()
                .iter()
                .map(|name| {
                    let r = b.range(name).0.value;
                    InputRange::point(r.lo + pick * (r.hi - r.lo))
                })
                .collect();
            let point = kernel
                .analyse(&inputs)
                .bodies
                .iter()
                .flat_map(|b| b.components())
                .map(|e| e.error)
                .fold(0.0, f64::max)
                / f64::EPSILON;
            assert!(point <= whole, "{point} > {whole} at {pick}");
        }
    }
}
