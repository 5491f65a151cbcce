//! Arithmetic that cannot underestimate: `f64` operations rounded to nearest, then moved
//! one float outward ([`up`], [`down`]), and closed intervals built on them.
//!
//! A correctly rounded operation `RN(x)` lies within half a float spacing of the exact `x`;
//! the next float above `RN(x)` is a full spacing away, so `up(RN(x)) >= x` and
//! `down(RN(x)) <= x` for every finite `x`, in the subnormal range too, and an overflow
//! gives `+inf` upward (a true, if useless, upper bound). The bound's own arithmetic is
//! therefore rigorous without changing the FPU's rounding mode, at the cost of one float
//! per operation (relative `2^-52`, negligible against the bounds it computes). A NaN is
//! treated as "no bound": [`up`] maps it to `+inf` and [`down`] to `-inf`.

/// The next float above `x` (`+inf` stays, NaN becomes `+inf`).
pub fn up(x: f64) -> f64 {
    if x.is_nan() {
        return f64::INFINITY;
    }
    if x == f64::INFINITY {
        return x;
    }
    if x == 0.0 {
        return f64::from_bits(1);
    }
    let bits = x.to_bits();
    f64::from_bits(if x > 0.0 { bits + 1 } else { bits - 1 })
}

/// The next float below `x` (`-inf` stays, NaN becomes `-inf`).
pub fn down(x: f64) -> f64 {
    -up(-x)
}

/// Upper bound of `a + b`.
pub fn add_up(a: f64, b: f64) -> f64 {
    up(a + b)
}

/// Upper bound of `a * b` for `a, b >= 0` (`0 * inf` is taken as `+inf`).
pub fn mul_up(a: f64, b: f64) -> f64 {
    up(a * b)
}

/// Upper bound of `a / b` for `a >= 0`, `b > 0`.
pub fn div_up(a: f64, b: f64) -> f64 {
    up(a / b)
}

/// Lower bound of `a - b`.
pub fn sub_down(a: f64, b: f64) -> f64 {
    down(a - b)
}

/// Upper bound of `sqrt(a)`, `a >= 0`.
pub fn sqrt_up(a: f64) -> f64 {
    up(a.sqrt())
}

/// Lower bound of `sqrt(a)`, `a >= 0` (never below 0).
pub fn sqrt_down(a: f64) -> f64 {
    down(a.sqrt()).max(0.0)
}

/// The largest power of two not above `x > 0` (`x` itself for `+inf`; `0` for `x <= 0`).
/// Exact: it reads the exponent bits.
pub fn pow2_floor(x: f64) -> f64 {
    if x.is_nan() {
        return f64::INFINITY;
    }
    if x <= 0.0 {
        return 0.0;
    }
    if x.is_infinite() {
        return x;
    }
    let bits = x.to_bits();
    let exponent = bits >> 52;
    if exponent == 0 {
        // Subnormal: keep the highest set bit of the fraction.
        let top = 63 - bits.leading_zeros();
        return f64::from_bits(1u64 << top);
    }
    f64::from_bits(exponent << 52)
}

/// A closed interval `[lo, hi]` of reals (possibly unbounded).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval {
    /// Lower end.
    pub lo: f64,
    /// Upper end.
    pub hi: f64,
}

impl Interval {
    /// Every real.
    pub const ENTIRE: Interval = Interval {
        lo: f64::NEG_INFINITY,
        hi: f64::INFINITY,
    };

    /// `[lo, hi]`; NaN ends become infinite.
    pub fn new(lo: f64, hi: f64) -> Interval {
        let lo = if lo.is_nan() { f64::NEG_INFINITY } else { lo };
        let hi = if hi.is_nan() { f64::INFINITY } else { hi };
        Interval { lo, hi }
    }

    /// The single point `x`.
    pub fn point(x: f64) -> Interval {
        Interval::new(x, x)
    }

    /// `max |x|` over the interval.
    pub fn mag(self) -> f64 {
        self.lo.abs().max(self.hi.abs())
    }

    /// `min |x|` over the interval (0 if it contains 0).
    pub fn mig(self) -> f64 {
        if self.lo <= 0.0 && self.hi >= 0.0 {
            0.0
        } else {
            self.lo.abs().min(self.hi.abs())
        }
    }

    /// Whether every end is finite.
    pub fn is_bounded(self) -> bool {
        self.lo.is_finite() && self.hi.is_finite()
    }
}

impl std::ops::Add for Interval {
    type Output = Interval;
    /// `{a + b}`, outward.
    fn add(self, b: Interval) -> Interval {
        Interval::new(down(self.lo + b.lo), up(self.hi + b.hi))
    }
}

impl std::ops::Sub for Interval {
    type Output = Interval;
    /// `{a - b}`, outward.
    fn sub(self, b: Interval) -> Interval {
        Interval::new(down(self.lo - b.hi), up(self.hi - b.lo))
    }
}

impl std::ops::Neg for Interval {
    type Output = Interval;
    /// `{-a}` (exact).
    fn neg(self) -> Interval {
        Interval::new(-self.hi, -self.lo)
    }
}

impl std::ops::Mul for Interval {
    type Output = Interval;
    /// `{a b}`, outward; unbounded operands give [`Interval::ENTIRE`].
    fn mul(self, b: Interval) -> Interval {
        if !self.is_bounded() || !b.is_bounded() {
            return Interval::ENTIRE;
        }
        let p = [
            self.lo * b.lo,
            self.lo * b.hi,
            self.hi * b.lo,
            self.hi * b.hi,
        ];
        let lo = p.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = p.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        Interval::new(down(lo), up(hi))
    }
}

impl std::ops::Div for Interval {
    type Output = Interval;
    /// `{a / b}`, outward; [`Interval::ENTIRE`] when `b` contains 0 or an operand is
    /// unbounded.
    fn div(self, b: Interval) -> Interval {
        if !self.is_bounded() || !b.is_bounded() || b.mig() == 0.0 {
            return Interval::ENTIRE;
        }
        let p = [
            self.lo / b.lo,
            self.lo / b.hi,
            self.hi / b.lo,
            self.hi / b.hi,
        ];
        let lo = p.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = p.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        Interval::new(down(lo), up(hi))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outward_steps_bracket_the_exact_result() {
        // 0.1 + 0.2 rounds up to 0.30000000000000004; the exact sum of the two floats lies
        // between its neighbours.
        let s = 0.1f64 + 0.2;
        assert!(down(s) < s && s < up(s));
        assert_eq!(up(0.0), f64::from_bits(1));
        assert_eq!(down(0.0), -f64::from_bits(1));
        assert_eq!(up(-f64::from_bits(1)), -0.0);
        assert_eq!(up(f64::MAX), f64::INFINITY);
        assert_eq!(up(f64::NAN), f64::INFINITY);
        assert_eq!(up(1.0), 1.0 + f64::EPSILON);
        assert_eq!(down(1.0), 1.0 - f64::EPSILON / 2.0);
    }

    #[test]
    fn pow2_floor_reads_the_exponent() {
        assert_eq!(pow2_floor(1.0), 1.0);
        assert_eq!(pow2_floor(1.999), 1.0);
        assert_eq!(pow2_floor(3.0), 2.0);
        assert_eq!(pow2_floor(0.75), 0.5);
        assert_eq!(pow2_floor(f64::from_bits(5)), f64::from_bits(4));
        assert_eq!(pow2_floor(0.0), 0.0);
        assert_eq!(pow2_floor(f64::INFINITY), f64::INFINITY);
    }

    #[test]
    fn intervals_enclose_their_sets() {
        let a = Interval::new(-1.0, 2.0);
        let b = Interval::new(3.0, 4.0);
        let p = a * b;
        assert!(p.lo <= -4.0 && p.hi >= 8.0);
        let q = a / b;
        assert!(q.lo <= -1.0 / 3.0 && q.hi >= 0.5);
        assert_eq!(b / a, Interval::ENTIRE);
        assert_eq!(a.mag(), 2.0);
        assert_eq!(a.mig(), 0.0);
        assert_eq!(b.mig(), 3.0);
        let d = b - a;
        assert!(d.lo <= 1.0 && d.hi >= 5.0);
    }
}
