//! The range rule of specialised kernels: every folded constant must have a finite `f32`
//! and `f64` literal (the kernels are generic over both; see [`crate::literal`]). A scene
//! that breaks it is refused, naming the species field at fault.

use super::build;
use crate::schedule::schedule;
use noslip_scene::Pair;
use noslip_scene::PairSet;
use num_rational::BigRational;
use num_traits::ToPrimitive;
use std::fmt;

/// A scene whose specialised kernel needs a constant beyond the `f32` or `f64` range.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ConstantOutOfRange {
    /// The species field at fault, `species[i].mass` (or `species[i]` when no single field
    /// is: only the combination overflows).
    pub field: String,
    /// The field's value, approximately.
    pub value: String,
    /// The kernel that needs the constant.
    pub kernel: String,
    /// The constant, approximately.
    pub constant: String,
    /// `"f32"` or `"f64"`.
    pub format: &'static str,
}

impl fmt::Display for ConstantOutOfRange {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let max = if self.format == "f32" {
            format!("{:e}", f32::MAX)
        } else {
            format!("{:e}", f64::MAX)
        };
        write!(
            f,
            "{}: {} makes the specialised kernel `{}` fold the constant {}, beyond the {} range \
             (|x| <= {max}); specialised kernels run in f32 and f64 alike: rescale the scene's \
             units (the map is homogeneous in mass and length)",
            self.field, self.value, self.kernel, self.constant, self.format
        )
    }
}

impl std::error::Error for ConstantOutOfRange {}

/// Why [`super::generate`] refused a pair set.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum GenerateError {
    /// The runtime crate's path is not a Rust path.
    CratePath(String),
    /// A folded constant has no finite `f32` or `f64` literal.
    OutOfRange(ConstantOutOfRange),
}

impl fmt::Display for GenerateError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            GenerateError::CratePath(p) => write!(f, "crate path: {p:?} is not a Rust path"),
            GenerateError::OutOfRange(e) => e.fmt(f),
        }
    }
}

impl std::error::Error for GenerateError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            GenerateError::OutOfRange(e) => Some(e),
            GenerateError::CratePath(_) => None,
        }
    }
}

/// `x` for a message: `2.5e-7`, or `~1e400` beyond the f64 range (from the digit counts).
fn approx(x: &BigRational) -> String {
    let zero = BigRational::from_integer(0.into());
    match x.to_f64() {
        _ if x == &zero => "0".to_string(),
        Some(f) if f.is_finite() && f != 0.0 => {
            let s = format!("{f:.3e}");
            let (mantissa, exponent) = s.split_once('e').expect("exponent form");
            let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
            format!("{mantissa}e{exponent}")
        }
        _ => {
            let digits = |n: &num_bigint::BigInt| n.magnitude().to_string().len() as i64;
            let sign = if x < &zero { "-" } else { "" };
            format!("{sign}~1e{}", digits(x.numer()) - digits(x.denom()))
        }
    }
}

/// The first live constant of `pair`'s kernel with no finite literal: `(value, format)`.
fn overflowing_constant(set: &PairSet, pair: Pair) -> Option<(BigRational, &'static str)> {
    let kernel = build(set, pair);
    let roots = kernel
        .outputs
        .iter()
        .flat_map(|o| o.spin.iter().chain(&o.velocity).copied());
    let sched = schedule(&kernel.graph, roots);
    sched.constants.iter().find_map(|&id| {
        let c = kernel.graph.as_const(id).expect("a constant");
        crate::literal::overflows(c).map(|format| (c.clone(), format))
    })
}

/// Check that every kernel of `set` has finite literals; else name the species field at
/// fault: the first field (mass, then radius, of each species of the pair) that, set to 1
/// alone, brings every constant of the kernel back into range.
pub fn check_ranges(set: &PairSet) -> Result<(), ConstantOutOfRange> {
    for pair in set.all() {
        let Some((constant, format)) = overflowing_constant(set, pair) else {
            continue;
        };
        let species = match pair {
            Pair::BallBall(a, b) if a != b => vec![a, b],
            Pair::BallBall(a, _) | Pair::BallWall(a, ..) | Pair::BallObstacle(a) => vec![a],
        };
        let one = BigRational::from_integer(1.into());
        let mut field = None;
        'search: for &s in &species {
            for name in ["mass", "radius"] {
                let mut trial = set.clone();
                let sp = &mut trial.species[s];
                let value = if name == "mass" {
                    let v = sp.mass.clone();
                    sp.mass = one.clone();
                    sp.inv_mass = one.clone();
                    v
                } else {
                    let v = sp.radius.clone();
                    sp.radius = one.clone();
                    v
                };
                if overflowing_constant(&trial, pair).is_none() {
                    field = Some((format!("species[{s}].{name}"), approx(&value)));
                    break 'search;
                }
            }
        }
        let (field, value) = field.unwrap_or_else(|| {
            let s = species[0];
            let sp = &set.species[s];
            (
                format!("species[{s}]"),
                format!("mass {}, radius {}", approx(&sp.mass), approx(&sp.radius)),
            )
        });
        return Err(ConstantOutOfRange {
            field,
            value,
            kernel: pair.fn_name(),
            constant: approx(&constant),
            format,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use noslip_scene::Scene;

    /// A walled 2D box with one species of two balls.
    fn set(mass: &str, radius: &str) -> PairSet {
        let text = format!(
            "dim = 2\n[box]\nsize = [1000, 1000]\nboundary = [\"wall\", \"wall\"]\n\
             [[species]]\nmass = \"{mass}\"\nradius = \"{radius}\"\ncount = 2\n"
        );
        Scene::from_toml(&text, "range.toml").unwrap().pairs()
    }

    #[test]
    fn in_range_scenes_pass_and_extreme_ones_name_their_field() {
        assert_eq!(check_ranges(&set("1", "1/2")), Ok(()));
        // Radius 1e-7: constants near 1e14, finite in f32.
        assert_eq!(check_ranges(&set("1", "1e-7")), Ok(()));
        let cases = [
            ("1e-39", "1/10", "species[0].mass", "f32"), // 2/m = 2e39
            ("1e39", "1/10", "species[0].mass", "f32"),  // m/2 = 5e38
            ("1e400", "1/10", "species[0].mass", "f64"),
            ("1", "1e-40", "species[0].radius", "f32"),
        ];
        for (mass, radius, field, format) in cases {
            let e = check_ranges(&set(mass, radius)).unwrap_err();
            assert_eq!((e.field.as_str(), e.format), (field, format), "{e}");
            assert_eq!(e.kernel, "ball_ball_0_0");
        }
    }

    #[test]
    fn approximations_read_like_the_input() {
        let q = |s: &str| noslip_scene::parse_exact(s).unwrap();
        assert_eq!(approx(&q("1e-39")), "1e-39");
        assert_eq!(approx(&q("2.5e7")), "2.5e7");
        assert_eq!(approx(&q("1e400")), "~1e400");
        assert_eq!(approx(&q("-1e-400")), "-~1e-400");
        assert_eq!(approx(&q("0")), "0");
    }
}
