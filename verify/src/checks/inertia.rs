//! The inertia parameter from radial densities, exactly:
//! `lambda = int_0^R x^(n+1) P(x) dx / (n int_0^R x^(n-1) P(x) dx)`.
//! Polynomial densities integrate term by term; layered (piecewise-constant) densities
//! layer by layer. A density must be non-negative on `[0, R]` and not identically zero.

use collision_core::{Exact, Scalar as _};
use num_traits::{One, Zero};

/// A radial density on `[0, R]`.
#[derive(Clone, Debug)]
pub enum Density {
    /// `P(x) = sum_j c_j x^j`.
    Polynomial(Vec<Exact>),
    /// `(outer radius, density)` per layer, from the centre out; the last radius is `R`.
    Layered(Vec<(Exact, Exact)>),
}

fn pow(x: &Exact, k: usize) -> Exact {
    (0..k).fold(Exact::one(), |acc, _| acc * x)
}

fn moment(d: &Density, radius: &Exact, m: usize) -> Exact {
    match d {
        // int_0^R x^m c_j x^j dx = c_j R^(m+j+1) / (m+j+1)
        Density::Polynomial(c) => c
            .iter()
            .enumerate()
            .map(|(j, cj)| cj * pow(radius, m + j + 1) / Exact::from_ratio((m + j + 1) as i64, 1))
            .sum(),
        Density::Layered(layers) => {
            let mut inner = Exact::zero();
            let mut total = Exact::zero();
            for (outer, rho) in layers {
                total += rho * (pow(outer, m + 1) - pow(&inner, m + 1))
                    / Exact::from_ratio(m as i64 + 1, 1);
                inner = outer.clone();
            }
            total
        }
    }
}

fn eval(c: &[Exact], x: &Exact) -> Exact {
    c.iter().rev().fold(Exact::zero(), |acc, cj| acc * x + cj)
}

/// Bernstein coefficients of `P` on `[a, b]`: `P(a + (b - a) s) = sum_k beta_k C(d,k) s^k (1-s)^(d-k)`.
fn bernstein(c: &[Exact], a: &Exact, b: &Exact) -> Vec<Exact> {
    let d = c.len().saturating_sub(1);
    // Taylor shift to a, scale by (b - a): coefficients q_j of P(a + h s) in s.
    let mut shifted = c.to_vec();
    for i in 0..d {
        for j in (i..d).rev() {
            let t = &shifted[j + 1] * a;
            shifted[j] += t;
        }
    }
    let h = b - a;
    let q: Vec<Exact> = shifted
        .iter()
        .enumerate()
        .map(|(j, x)| x * pow(&h, j))
        .collect();
    let binom = |n: usize, k: usize| -> Exact {
        (0..k).fold(Exact::one(), |acc, i| {
            acc * Exact::from_integer((n - i) as i64) / Exact::from_integer((i + 1) as i64)
        })
    };
    (0..=d)
        .map(|k| (0..=k).map(|j| &q[j] * binom(k, j) / binom(d, j)).sum())
        .collect()
}

/// `Ok` if `P >= 0` on `[0, R]` (certified by Bernstein coefficients, subdividing up to
/// depth 24); `Err` with a point where it is negative, or that it could not be certified
/// (a density that touches zero inside `(0, R)`, e.g. `(x - 1/3)^2`, cannot be certified
/// this way and is refused with that message).
fn nonnegative(c: &[Exact], radius: &Exact) -> Result<(), String> {
    let mut stack = vec![(Exact::zero(), radius.clone(), 0u32)];
    while let Some((a, b, depth)) = stack.pop() {
        for x in [&a, &b] {
            let v = eval(c, x);
            if v < Exact::zero() {
                return Err(format!("the density is negative at x = {x}: P(x) = {v}"));
            }
        }
        if bernstein(c, &a, &b).iter().all(|x| *x >= Exact::zero()) {
            continue;
        }
        if depth == 24 {
            return Err(format!("could not certify P >= 0 near x = {a}"));
        }
        let mid = (&a + &b) / Exact::from_ratio(2, 1);
        stack.push((a, mid.clone(), depth + 1));
        stack.push((mid, b, depth + 1));
    }
    Ok(())
}

/// `lambda` of a density in R^n on a ball of radius `R`, after validating the density.
pub fn lambda(n: usize, radius: &Exact, d: &Density) -> Result<Exact, String> {
    match d {
        Density::Polynomial(c) => nonnegative(c, radius)?,
        Density::Layered(layers) => {
            let mut inner = Exact::zero();
            for (k, (outer, rho)) in layers.iter().enumerate() {
                if *rho < Exact::zero() {
                    return Err(format!("layer {k} has negative density {rho}"));
                }
                if *outer <= inner {
                    return Err(format!("layer {k}: radii must increase"));
                }
                inner = outer.clone();
            }
            if inner != *radius {
                return Err("the last layer must end at R".into());
            }
        }
    }
    let mass = moment(d, radius, n - 1);
    if mass.is_zero() {
        return Err("the density is zero: no mass".into());
    }
    Ok(moment(d, radius, n + 1) / (Exact::from_ratio(n as i64, 1) * mass))
}

/// The inertia checks for dimension `n`; returns how many densities were checked.
pub fn check(n: usize, seed: u64) -> Result<usize, String> {
    let r = Exact::from_ratio(3, 2);
    let nn = Exact::from_ratio(n as i64, 1);
    let bound = &r * &r / &nn;
    let q = |p: i64, d: i64| Exact::from_ratio(p, d);
    let expect = |what: &str, got: Exact, want: Exact| {
        if got == want {
            Ok(())
        } else {
            Err(format!("{what}: lambda = {got}, expected {want}"))
        }
    };
    expect(
        "uniform",
        lambda(n, &r, &Density::Polynomial(vec![q(1, 1)]))?,
        &r * &r / (&nn + q(2, 1)),
    )?;
    // The extremes are attained in the limit: a thin shell [R (1 - 1/k), R] -> R^2/n and a
    // small core [0, R/k] -> 0, monotonically.
    let (mut last_shell, mut last_core) = (Exact::zero(), bound.clone());
    for k in [2i64, 10, 100, 1000, 10_000] {
        let shell = lambda(
            n,
            &r,
            &Density::Layered(vec![(&r * q(k - 1, k), q(0, 1)), (r.clone(), q(1, 1))]),
        )?;
        let core = lambda(
            n,
            &r,
            &Density::Layered(vec![(&r / q(k, 1), q(1, 1)), (r.clone(), q(0, 1))]),
        )?;
        if !(shell > last_shell && shell < bound && core < last_core && core > Exact::zero()) {
            return Err(format!(
                "shell/core sequence not monotone towards R^2/n and 0 at k = {k}"
            ));
        }
        if (&bound - &shell) * q(k, 1) > bound.clone() * q(2, 1)
            || &core * q(k * k, 1) > bound.clone()
        {
            return Err(format!("shell/core limits converge too slowly at k = {k}"));
        }
        (last_shell, last_core) = (shell, core);
    }
    // Random non-negative densities: polynomial (non-negative coefficients, and squares of
    // polynomials with sign changes) and layered; each lambda in [0, R^2/n].
    let mut rng = collision_core::rng::Rng::new(seed);
    let mut small = |lo: i64, hi: i64| {
        q(
            lo + (rng.next_u64() % (hi - lo + 1) as u64) as i64,
            1 + (rng.next_u64() % 7) as i64,
        )
    };
    let mut count = 3;
    for _ in 0..20 {
        let a: Vec<Exact> = (0..3).map(|_| small(-5, 5)).collect();
        let mut square = vec![Exact::zero(); 5];
        for i in 0..3 {
            for j in 0..3 {
                square[i + j] += &a[i] * &a[j];
            }
        }
        // Strictly positive: a double root inside [0, R] cannot be certified by subdivision
        // (such a density is reported as "could not certify", never accepted wrongly).
        square[0] += q(1, 10);
        let positive: Vec<Exact> = (0..4).map(|_| small(0, 9)).collect();
        let layers: Vec<(Exact, Exact)> = (1..=4).map(|k| (&r * q(k, 4), small(0, 9))).collect();
        for d in [
            Density::Polynomial(square),
            Density::Polynomial(positive),
            Density::Layered(layers),
        ] {
            match lambda(n, &r, &d) {
                Ok(l) if l >= Exact::zero() && l <= bound => count += 1,
                Ok(l) => return Err(format!("{d:?}: lambda = {l} outside [0, R^2/n]")),
                Err(e) if e.contains("no mass") => {}
                Err(e) => return Err(format!("{d:?}: rejected a valid density: {e}")),
            }
        }
    }
    // A density negative somewhere is rejected.
    for bad in [
        Density::Polynomial(vec![q(-1, 2), q(1, 1)]),
        Density::Polynomial(vec![q(1, 1), q(-3, 1), q(1, 1)]),
        Density::Layered(vec![(r.clone(), q(-1, 1))]),
    ] {
        if lambda(n, &r, &bad).is_ok() {
            return Err(format!("{bad:?} is negative somewhere but was accepted"));
        }
    }
    Ok(count)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn negative_densities_are_rejected_with_a_witness() {
        let r = Exact::from_ratio(1, 1);
        let e = lambda(
            3,
            &r,
            &Density::Polynomial(vec![Exact::from_ratio(-1, 2), Exact::from_ratio(1, 1)]),
        )
        .unwrap_err();
        assert_eq!(e, "the density is negative at x = 0: P(x) = -1/2");
        // (x - 1/3)^2 touches zero inside: non-negative, certified or reported, never accepted wrongly.
        let square = vec![
            Exact::from_ratio(1, 9),
            Exact::from_ratio(-2, 3),
            Exact::from_ratio(1, 1),
        ];
        if let Ok(l) = lambda(3, &r, &Density::Polynomial(square)) {
            assert!(l <= Exact::from_ratio(1, 3));
        }
    }

    #[test]
    fn the_bound_holds_in_every_dimension() {
        for n in 2..=6 {
            assert!(check(n, 1).unwrap() > 20);
        }
    }
}
