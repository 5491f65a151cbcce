#!/usr/bin/env python3
"""The fourth cumulant ``a_2`` of the homogeneous cooling state of smooth inelastic hard balls
in R^d, first Sonine approximation, computed exactly from the collision integrals and checked
against van Noije & Ernst's closed form (Granular Matter 1, 57 (1998)),

    a_2 = 16 (1 - e) (1 - 2 e^2) / (9 + 24 d - e (41 - 8 d) + 30 (1 - e) e^2).

The theory (docs/granular.md, "The cooling state's a_2"). In the cooling state the scaled
distribution ``phi(c)``, ``c = v / sqrt(2 T / m)``, is stationary, and the moments of the
Boltzmann equation give ``zeta p <c^p> / 2 = K mu_p`` for every ``p``, ``mu_p = <int_{g.k > 0}
(g . k) (c_1^p - c_1'^p) dk>`` the collisional loss of ``c^p`` (``c_1' = c_1 - ((1 + e) / 2)
(g . k) k``, the average over both balls' ``phi``). With ``<c^2> = d / 2`` and ``<c^4> = d (d +
2) (1 + a_2) / 4``, ``p = 2`` and ``p = 4`` give ``mu_4 = (d + 2) (1 + a_2) mu_2``. The first
Sonine approximation takes ``phi = phi_M (1 + a_2 S_2(c^2))``, ``S_2 = L_2^(d/2 - 1)``, keeps
``mu_p = mu_p0 + a_2 mu_p1`` to first order and drops ``a_2^2``:

    a_2 = (mu_40 - (d + 2) mu_20) / ((d + 2) (mu_20 + mu_21) - mu_41).

The second Sonine approximation adds ``a_3 S_3`` and the balance at ``p = 6``, ``mu_6 <c^2> = 3
mu_2 <c^6>``, both linear in ``(a_2, a_3)`` (products dropped): a 2 x 2 system. Its change to
``a_2`` is the first order's estimated error (``sim/tests/boltzmann.rs`` holds the DSMC to it).

The ``mu`` are computed with ``scripts/sonine_self_diffusion.py``'s exact polynomial
bookkeeping (``G`` and ``g`` averages, half sphere, radial moments), at a rational ``e``: the
result is an exact rational, compared with the closed form. Standard library only.

Usage::

    scripts/sonine_cooling_a2.py [--dims 2,3] [--e 1/2,7/10,9/10]
"""

from __future__ import annotations

import argparse
import math
import sys
from fractions import Fraction
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import sonine_self_diffusion as s  # noqa: E402  (the script beside this one)


def van_noije_ernst(dim: int, e: Fraction) -> Fraction:
    """The closed form of the module docs."""
    numerator = 16 * (1 - e) * (1 - 2 * e * e)
    return numerator / (9 + 24 * dim - e * (41 - 8 * dim) + 30 * (1 - e) * e * e)


def as_integers(coefficients: list[Fraction]) -> tuple[list[int], int]:
    """``(integers, scale)`` with ``coefficients = integers / scale``."""
    scale = math.lcm(*(c.denominator for c in coefficients))
    return [int(c * scale) for c in coefficients], scale


def polynomial_of(x: s.Poly, coefficients: list[int]) -> s.Poly:
    """``sum_j coefficients[j] x^j`` for a polynomial ``x``."""
    out: s.Poly = {}
    power = s.const(1)
    for j, c in enumerate(coefficients):
        if j:
            power = s.mul(power, x)
        out = s.add(out, s.scale(power, c))
    return out


class Moments:
    """The collisional moments ``mu_p = <int_{g.k > 0} (g . k) (c_1^p - c_1'^p) dk w>`` of
    smooth balls with restitution ``e`` in R^d, for the weights ``w = 1`` and ``w = S_k(c_1^2)
    + S_k(c_2^2)``, ``S_k = L_k^(d/2 - 1)``, each divided by the collision frequency
    ``<int_{g.k > 0} (g . k) dk>`` (one common surd), so exact rationals.
    """

    def __init__(self, dim: int, e: Fraction) -> None:
        self.dim = dim
        self.den = e.denominator
        den, num = e.denominator, e.numerator
        var, add, mul, scale = s.var, s.add, s.mul, s.scale
        cc = mul(var(s.COS), var(s.COS))
        # c_1 = G + h e_1, c_2 = G - h e_1 (h = r / 2, g . k = 2 h cos th);
        # den c_1' = den c_1 - (den + num) h cos th (cos th, sin th).
        x1, y1 = add(var(s.G1), var(s.RR)), var(s.G2)
        x2 = add(var(s.G1), scale(var(s.RR), -1))
        x1p = add(scale(x1, den), scale(mul(var(s.RR), cc), -(den + num)))
        y1p = add(scale(y1, den), scale(mul(var(s.RR), mul(var(s.COS), var(s.SIN))), -(den + num)))
        rest = var(s.R2)
        self.c1sq = add(mul(x1, x1), mul(y1, y1), rest)
        self.c2sq = add(mul(x2, x2), mul(y1, y1), rest)
        # den^2 c_1'^2 (the R2 part scales too)
        self.c1psq = add(mul(x1p, x1p), mul(y1p, y1p), scale(rest, den * den))
        self.unit = self.mean(s.const(1))

    def mean(self, p: s.Poly) -> s.Surd:
        """``<int_{g.k > 0} (g . k) p dk>``."""
        return s.collision_mean(s.reduce_over_g_mean(p, self.dim), self.dim)

    def mu(self, p: int, k: int | None) -> Fraction:
        """``mu_p`` (``p`` even) with the weight ``1`` (``k = None``) or ``S_k(c_1^2) +
        S_k(c_2^2)``."""
        half = p // 2
        d2h: int = self.den ** (2 * half)
        gain = polynomial_of(self.c1psq, [0] * half + [1])
        loss = s.add(s.scale(polynomial_of(self.c1sq, [0] * half + [1]), d2h), s.scale(gain, -1))
        scale = 1
        if k is not None:
            coefficients, scale = as_integers(s.laguerre(k, Fraction(self.dim - 2, 2)))
            weight = s.add(
                polynomial_of(self.c1sq, coefficients), polynomial_of(self.c2sq, coefficients)
            )
            loss = s.mul(loss, weight)
        q = self.mean(loss) / self.unit
        if q.q and (q.two, q.pi_half) != (0, 0):
            raise ValueError("unlike surds")
        return q.q / (d2h * scale)


def maxwell_moments(dim: int, p: int, k: int | None) -> Fraction:
    """``<c^p w>`` over the Maxwellian ``pi^(-d/2) exp(-c^2)``, ``w = 1`` or ``S_k(c^2)``:
    ``<x^j> = Gamma(d/2 + j) / Gamma(d/2)``, ``x = c^2``."""

    def x_moment(j: int) -> Fraction:
        return math.prod((Fraction(dim, 2) + i for i in range(j)), start=Fraction(1))

    coefficients = [Fraction(1)] if k is None else s.laguerre(k, Fraction(dim - 2, 2))
    return sum((c * x_moment(p // 2 + j) for j, c in enumerate(coefficients)), start=Fraction(0))


def first_sonine_a2(dim: int, e: Fraction) -> Fraction:
    """``a_2`` at the first Sonine order (module docs)."""
    m = Moments(dim, e)
    m20, m21, m40, m41 = m.mu(2, None), m.mu(2, 2), m.mu(4, None), m.mu(4, 2)
    return (m40 - (dim + 2) * m20) / ((dim + 2) * (m20 + m21) - m41)


def second_sonine(dim: int, e: Fraction) -> tuple[Fraction, Fraction]:
    """``(a_2, a_3)`` at the second Sonine order, linear in both: ``phi = phi_M (1 + a_2 S_2 +
    a_3 S_3)``, the balances ``mu_p <c^2> = (p / 2) mu_2 <c^p>`` for ``p = 4, 6``, products of
    ``a_2, a_3`` dropped; a 2 x 2 linear system.
    """
    m = Moments(dim, e)
    mu = {(p, k): m.mu(p, k) for p in (2, 4, 6) for k in (None, 2, 3)}
    c = {(p, k): maxwell_moments(dim, p, k) for p in (2, 4, 6) for k in (None, 2, 3)}
    rows = []
    for p in (4, 6):
        half = Fraction(p, 2)
        # mu_p <c^2> - (p/2) mu_2 <c^p> = 0, each side linear in (a_2, a_3)
        const = mu[p, None] * c[2, None] - half * mu[2, None] * c[p, None]
        coef = [
            mu[p, k] * c[2, None] - half * (mu[2, k] * c[p, None] + mu[2, None] * c[p, k])
            for k in (2, 3)
        ]
        rows.append((coef, -const))
    (a, b), r1 = rows[0]
    (cc, d), r2 = rows[1]
    det = a * d - b * cc
    return (r1 * d - b * r2) / det, (a * r2 - cc * r1) / det


def main(argv: list[str]) -> int:
    """The command line (module docs)."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--dims", default="2,3", help="dimensions, comma-separated (>= 2)")
    parser.add_argument("--e", default="1/2,7/10,9/10", help="restitutions, rationals in [0, 1]")
    args = parser.parse_args(argv)
    try:
        dims = [int(d) for d in args.dims.split(",")]
        es = [Fraction(x) for x in args.e.split(",")]
    except ValueError:
        parser.error(f"--dims or --e: not a list of numbers: {args.dims!r}, {args.e!r}")
    if any(d < 2 for d in dims):
        parser.error(f"--dims: each dimension must be at least 2: {args.dims!r}")
    if any(not 0 <= e <= 1 for e in es):
        parser.error(f"--e: each restitution must lie in [0, 1]: {args.e!r}")
    for dim in dims:
        for e in es:
            a2 = first_sonine_a2(dim, e)
            closed = van_noije_ernst(dim, e)
            b2, b3 = second_sonine(dim, e)
            print(
                f"d = {dim}, e = {e}: a_2 = {a2} = {float(a2):+.6f}; van Noije & Ernst "
                f"{float(closed):+.6f} ({'equal' if a2 == closed else 'DIFFERENT'}); second "
                f"order a_2 = {float(b2):+.6f}, a_3 = {float(b3):+.6f}"
            )
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
