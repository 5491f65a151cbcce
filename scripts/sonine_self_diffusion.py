#!/usr/bin/env python3
"""Chapman-Enskog's Sonine approximations ``[D]_P`` of the self-diffusion coefficient of a
dilute gas of equal smooth elastic hard balls in R^n, computed exactly from first principles.

The theory (docs/granular.md, "Self-diffusion against Chapman-Enskog", derives it). A tagged
ball among identical gas balls, the gas Maxwellian at temperature ``T``: in reduced
velocities ``c = v / sqrt(2 T / m)`` the tagged ball's distribution is
``n_1 f_M(c) (1 - B(c) . grad ln n_1)`` with ``B(c) = c b(c^2)``, and ``B`` solves
``L B = v``, where ``L`` is the linear (Lorentz-like) operator of a ball against a Maxwellian
gas of number density ``rho``,

    L[psi](c_1) = rho sigma^(n-1) sqrt(2 T / m) <int_{g.k > 0} (g . k) (psi(c_1) - psi(c_1')) dk>,

the average over the partner's ``c_2`` (Maxwellian ``pi^(-n/2) exp(-c_2^2)``), ``g = c_1 - c_2``,
``k`` a unit vector (the contact normal), ``c_1' = c_1 - (g . k) k``. (For mechanically identical
balls this is exact at any tagged fraction: the tagged and untagged perturbations cancel in
the partner's term.) Expanding ``b = sum_q b_q S_q(c^2)`` in the Sonine (Laguerre) polynomials
``S_q = L_q^(n/2)``, the Galerkin equations are ``sum_q a_pq b_q = delta_p0 n / 2`` (only
``S_0`` has a component along ``c^2``), with the matrix elements

    a_pq = <int_{g.k > 0} (g . k) [c_1 S_p(c_1^2)] . [c_1 S_q(c_1^2) - c_1' S_q(c_1'^2)] dk>

(the average over both balls' Maxwellians), and ``D = (2 T / m)^(1/2) n (a^-1)_00 / (4 rho
sigma^(n-1))``. So ``[D]_P / [D]_1 = a_00 (a_P^-1)_00`` with ``a_P`` the leading ``P x P`` block
(Cramer's rule: ``det a_P / det`` of its lower ``(P-1) x (P-1)`` block, times ``a_00``).

How ``a_pq`` is computed exactly. With ``G = (c_1 + c_2) / 2`` and ``g``, the weight is
``pi^-n exp(-2 G^2 - g^2 / 2)``: ``G`` normal with variance ``1/4`` a component, ``g`` with
variance 1. Take ``g = r e_1`` and ``k = cos(th) e_1 + sin(th) e_2`` (the ``G`` average leaves a
function of ``r`` and ``th`` only), so ``c_1 = G + (r/2) e_1`` and ``c_1' = G + (r/2) (1 - 2
cos^2 th, -2 cos th sin th)``. The integrand is a polynomial in ``G_1, G_2, R2 = |G|^2 - G_1^2
- G_2^2, r, cos th, sin th``; its ``G`` moments are ``<G_i^(2j)> = (2j - 1)!! / 4^j`` and ``<R2^j>
= 2^-j Gamma((n-2)/2 + j) / Gamma((n-2)/2)``; then ``sin^2 th = 1 - cos^2 th``, the half sphere
``int_{cos th > 0} cos^j th dk = pi^((n-1)/2) Gamma((j+1)/2) / Gamma((j+n)/2)``, and ``<r^a> =
2^(a/2) Gamma((a+n)/2) / Gamma(n/2)``. Each of these is a rational times a power of
``sqrt(2)`` and of ``sqrt(pi)``; the script keeps that form (class ``Surd``) and checks that all
terms of a dimension share the same powers, so every ratio below is an exact rational.

Usage::

    scripts/sonine_self_diffusion.py [--dims 2,3] [--orders 8] [--check-quadrature N]

prints, per dimension, ``a_00`` in closed form, the matrix ``a_pq / a_00`` (exact rationals, for
the smallest orders) and ``[D]_P / [D]_1`` for ``P = 1..orders`` as exact fractions and decimals,
with the successive differences. ``--check-quadrature N`` cross-checks ``a_pq`` (``p, q < 3``)
against a Monte Carlo estimate from ``N`` sampled collisions (seeded), with its standard error.
Standard library only.
"""

from __future__ import annotations

import argparse
import math
import random
import sys
from dataclasses import dataclass
from fractions import Fraction

# Monomials in (G1, G2, R2, h, cos th, sin th), ``h = r / 2``, each an exponent tuple; with
# ``h`` for ``r / 2`` every coefficient before the averages is an integer (fast products).
Exponents = tuple[int, int, int, int, int, int]
Poly = dict[Exponents, int]

G1, G2, R2, RR, COS, SIN = range(6)


def var(index: int, coefficient: int = 1) -> Poly:
    """The monomial ``coefficient * x_index``.

    Parameters
    ----------
    index : int
        Which variable (``G1, G2, R2, RR, COS, SIN``).
    coefficient : int
        Its coefficient.

    Returns
    -------
    Poly
        The one-term polynomial.
    """
    e = [0] * 6
    e[index] = 1
    return {(e[0], e[1], e[2], e[3], e[4], e[5]): coefficient}


def const(value: int) -> Poly:
    """The constant polynomial ``value``."""
    return {(0, 0, 0, 0, 0, 0): value} if value else {}


def add(*terms: Poly) -> Poly:
    """The sum of polynomials, zero coefficients dropped."""
    out: Poly = {}
    for p in terms:
        for e, c in p.items():
            out[e] = out.get(e, 0) + c
    return {e: c for e, c in out.items() if c}


def scale(p: Poly, factor: int) -> Poly:
    """``factor * p``."""
    return {e: c * factor for e, c in p.items()} if factor else {}


def mul(p: Poly, q: Poly) -> Poly:
    """The product ``p q``."""
    out: Poly = {}
    for e1, c1 in p.items():
        for e2, c2 in q.items():
            e = (
                e1[0] + e2[0],
                e1[1] + e2[1],
                e1[2] + e2[2],
                e1[3] + e2[3],
                e1[4] + e2[4],
                e1[5] + e2[5],
            )
            out[e] = out.get(e, 0) + c1 * c2
    return {e: c for e, c in out.items() if c}


@dataclass(frozen=True)
class Surd:
    """The number ``q * sqrt(2)^two * sqrt(pi)^pi_half``, ``q`` rational.

    Sums are kept only between equal powers (``add`` raises otherwise): every matrix element
    of one dimension carries the same powers, which is what makes the ratios rational.
    """

    q: Fraction
    two: int = 0
    pi_half: int = 0

    def __mul__(self, other: Surd) -> Surd:
        return Surd(self.q * other.q, self.two + other.two, self.pi_half + other.pi_half).norm()

    def __truediv__(self, other: Surd) -> Surd:
        return Surd(self.q / other.q, self.two - other.two, self.pi_half - other.pi_half).norm()

    def norm(self) -> Surd:
        """The same number with ``sqrt(2)^two`` reduced to ``two`` in {0, 1}."""
        whole, rest = divmod(self.two, 2)
        return Surd(self.q * Fraction(2) ** whole, rest, self.pi_half)

    def add(self, other: Surd) -> Surd:
        """``self + other``; both must carry the same powers of ``sqrt(2)``, ``sqrt(pi)``."""
        if self.q == 0:
            return other
        if other.q == 0:
            return self
        if (self.two, self.pi_half) != (other.two, other.pi_half):
            raise ValueError(f"unlike surds: {self} + {other}")
        return Surd(self.q + other.q, self.two, self.pi_half)

    def __float__(self) -> float:
        return float(self.q) * math.sqrt(2) ** self.two * math.sqrt(math.pi) ** self.pi_half

    def __str__(self) -> str:
        parts = [str(self.q)]
        if self.two:
            parts.append(f"sqrt(2)^{self.two}" if self.two != 1 else "sqrt(2)")
        if self.pi_half:
            p = self.pi_half
            parts.append("sqrt(pi)" if p == 1 else f"pi^({p}/2)" if p % 2 else f"pi^{p // 2}")
        return " ".join(parts)


def gamma_half(twice: int) -> Surd:
    """``Gamma(twice / 2)`` for a positive integer ``twice``: ``(k-1)!`` at ``k``, and
    ``Gamma(k + 1/2) = (2k)! / (4^k k!) sqrt(pi)``.

    Parameters
    ----------
    twice : int
        Twice the argument, positive.

    Returns
    -------
    Surd
        The exact value.
    """
    if twice <= 0:
        raise ValueError(f"Gamma({twice}/2): the argument must be positive")
    if twice % 2 == 0:
        return Surd(Fraction(math.factorial(twice // 2 - 1)))
    k = (twice - 1) // 2
    return Surd(Fraction(math.factorial(2 * k), 4**k * math.factorial(k)), 0, 1)


def laguerre(p: int, alpha: Fraction) -> list[Fraction]:
    """The coefficients of ``L_p^(alpha)(x) = sum_k (-1)^k C(p + alpha, p - k) x^k / k!``.

    Parameters
    ----------
    p : int
        The order.
    alpha : Fraction
        The index.

    Returns
    -------
    list of Fraction
        ``[s_0, ..., s_p]``, the coefficient of ``x^k`` at ``k``.
    """
    out = []
    for k in range(p + 1):
        binom = Fraction(1)
        for i in range(1, p - k + 1):
            binom *= (alpha + k + i) / i
        out.append((-1) ** k * binom / math.factorial(k))
    return out


def sonine(p: int, dim: int) -> list[Fraction]:
    """The coefficients of ``S_p(x) = L_p^(n/2)(x)`` (:func:`laguerre` at ``alpha = n/2``).

    Parameters
    ----------
    p : int
        The order.
    dim : int
        The dimension ``n`` (the polynomial's index is ``n/2``).

    Returns
    -------
    list of Fraction
        ``[s_0, ..., s_p]``, the coefficient of ``x^k`` at ``k``.
    """
    return laguerre(p, Fraction(dim, 2))


def reduce_over_g_mean(p: Poly, dim: int) -> dict[tuple[int, int, int], Fraction]:
    """Average a polynomial over ``G`` (normal, variance ``1/4`` a component) and put
    ``sin^2 th = 1 - cos^2 th``.

    Parameters
    ----------
    p : Poly
        A polynomial in ``(G1, G2, R2, h, cos th, sin th)``, ``h = r / 2``.
    dim : int
        The dimension (``R2`` is the squared norm of ``G``'s other ``n - 2`` components).

    Returns
    -------
    dict
        ``{(h power, cos power, 0): coefficient}``: the average, a polynomial in ``h = r / 2``
        and ``cos th``.

    Raises
    ------
    ValueError
        If an odd power of ``sin th`` survives (it cannot: reflecting ``e_2`` maps the
        integrand to itself with ``G_2 -> -G_2``, ``sin th -> -sin th``).
    """

    def g_moment(j: int) -> Fraction:
        if j % 2:
            return Fraction(0)
        double_factorial = math.prod(range(j - 1, 0, -2)) if j > 1 else 1
        return Fraction(double_factorial, 4 ** (j // 2))

    def r2_moment(j: int) -> Fraction:
        out = Fraction(1)
        for i in range(j):
            out *= (Fraction(dim - 2, 2) + i) / 2
        return out

    out: dict[tuple[int, int, int], Fraction] = {}
    for (a, b, k, r, c, s), coef in p.items():
        m = g_moment(a) * g_moment(b) * r2_moment(k)
        if not m:
            continue
        if s % 2:
            raise ValueError("an odd power of sin th survived the average over G")
        # sin^(2h) = (1 - cos^2)^h
        h = s // 2
        for i in range(h + 1):
            key = (r, c + 2 * i, 0)
            out[key] = out.get(key, Fraction(0)) + coef * m * math.comb(h, i) * (-1) ** i
    return {e: c for e, c in out.items() if c}


def collision_mean(p: dict[tuple[int, int, int], Fraction], dim: int) -> Surd:
    """``<int_{cos th > 0} (r cos th) p(r, cos th) dk>`` over ``g`` normal with unit variance.

    Half sphere: ``int cos^j th dk = pi^((n-1)/2) Gamma((j+1)/2) / Gamma((j+n)/2)``;
    radial: ``<r^a> = 2^(a/2) Gamma((a+n)/2) / Gamma(n/2)``.

    Parameters
    ----------
    p : dict
        ``{(h power, cos power, 0): coefficient}`` from ``reduce_over_g_mean``, ``h = r / 2``.
    dim : int
        The dimension ``n``.

    Returns
    -------
    Surd
        The exact value.
    """
    total = Surd(Fraction(0))
    for (h, c, _), coef in p.items():
        a, j = h + 1, c + 1  # h^h = r^h / 2^h, and the rate's factor g . k = r cos th
        sphere = Surd(Fraction(1), 0, dim - 1) * gamma_half(j + 1) / gamma_half(j + dim)
        radial = Surd(Fraction(1), a, 0) * gamma_half(a + dim) / gamma_half(dim)
        total = total.add(Surd(coef / 2**h) * sphere * radial)
    return total


def matrix(dim: int, orders: int) -> list[list[Surd]]:
    """The exact matrix ``a_pq``, ``p, q < orders`` (module docs).

    It is built from the moments ``M_kl = <(g.k) [c_1^2 (c_1^2)^(k+l) - (c_1^2)^k (c_1'^2)^l
    (c_1 . c_1')]>``, ``a_pq = sum_kl s_pk s_ql M_kl`` with ``s`` the Sonine coefficients.

    Parameters
    ----------
    dim : int
        The dimension ``n >= 2``.
    orders : int
        ``P``.

    Returns
    -------
    list of list of Surd
        ``a_pq``.
    """
    x1 = add(var(G1), var(RR))  # c_1's components: G + h e_1, h = r / 2
    y1 = var(G2)
    cc = mul(var(COS), var(COS))
    # c_1' = G + h (1 - 2 cos^2, -2 cos sin)
    x1p = add(var(G1), var(RR), scale(mul(var(RR), cc), -2))
    y1p = add(var(G2), scale(mul(var(RR), mul(var(COS), var(SIN))), -2))
    rest = var(R2)
    c1sq = add(mul(x1, x1), mul(y1, y1), rest)
    c1psq = add(mul(x1p, x1p), mul(y1p, y1p), rest)
    c1dot = add(mul(x1, x1p), mul(y1, y1p), rest)
    powers = [const(1)]
    powers_p = [const(1)]
    for _ in range(2 * orders):
        powers.append(mul(powers[-1], c1sq))
        powers_p.append(mul(powers_p[-1], c1psq))
    moments = [[Surd(Fraction(0))] * orders for _ in range(orders)]
    for k in range(orders):
        for l in range(k, orders):
            gain = mul(mul(powers[k], powers_p[l]), c1dot)
            if k != l:  # M_kl + M_lk: the loss terms are equal, the gain terms differ
                gain = add(gain, mul(mul(powers[l], powers_p[k]), c1dot))
            loss = scale(powers[k + l + 1], 2 if k != l else 1)
            both = collision_mean(reduce_over_g_mean(add(loss, scale(gain, -1)), dim), dim)
            # M is symmetric (the operator is self-adjoint), so M_kl = (M_kl + M_lk) / 2
            half_sum = both * Surd(Fraction(1, 2) if k != l else Fraction(1))
            moments[k][l] = moments[l][k] = half_sum
    s = [sonine(p, dim) for p in range(orders)]
    a = [[Surd(Fraction(0))] * orders for _ in range(orders)]
    for p in range(orders):
        for q in range(orders):
            total = Surd(Fraction(0))
            for k, sk in enumerate(s[p]):
                for l, sl in enumerate(s[q]):
                    total = total.add(Surd(sk * sl) * moments[k][l])
            a[p][q] = total
    return a


def determinant(m: list[list[Fraction]]) -> Fraction:
    """The determinant of a square matrix of rationals (exact Gaussian elimination)."""
    m = [row[:] for row in m]
    n = len(m)
    det = Fraction(1)
    for i in range(n):
        pivot = next((r for r in range(i, n) if m[r][i]), None)
        if pivot is None:
            return Fraction(0)
        if pivot != i:
            m[i], m[pivot] = m[pivot], m[i]
            det = -det
        det *= m[i][i]
        for r in range(i + 1, n):
            f = m[r][i] / m[i][i]
            for c in range(i, n):
                m[r][c] -= f * m[i][c]
    return det


def ratios(a: list[list[Surd]]) -> list[Fraction]:
    """``[D]_P / [D]_1 = a_00 (a_P^-1)_00 = a_00 det(a_P minus row and column 0) / det a_P``.

    Parameters
    ----------
    a : list of list of Surd
        The matrix, all elements with the same surd part.

    Returns
    -------
    list of Fraction
        ``P = 1..len(a)``.
    """
    unit = a[0][0]
    quotients = [[x / unit for x in row] for row in a]
    if any((x.two, x.pi_half) != (0, 0) for row in quotients for x in row if x.q):
        raise ValueError("a_pq / a_00 is not rational: the elements carry unlike surds")
    r = [[x.q for x in row] for row in quotients]
    out = []
    for p in range(1, len(a) + 1):
        block = [row[:p] for row in r[:p]]
        minor = [row[1:p] for row in r[1:p]]
        out.append(determinant(minor) / determinant(block))
    return out


def monte_carlo(dim: int, p: int, q: int, samples: int, seed: int) -> tuple[float, float]:
    """A Monte Carlo estimate of ``a_pq`` and its standard error (the cross-check).

    ``c_1, c_2`` drawn with variance 1 a component, twice the Maxwellian's ``pi^(-n/2)
    exp(-c^2)`` (importance sampling: the integrand grows like ``|c|^(2p + 2q + 3)``, and with
    the Maxwellian's own spread its rare large values would dominate), each weighted by the
    densities' ratio ``2^(n/2) exp(-c^2 / 2)``; ``k`` uniform on the unit sphere, and
    ``int_{g.k > 0} (g.k) F dk = |S^(n-1)| <(g.k)^+ F>_k``.

    Parameters
    ----------
    dim : int
        The dimension.
    p, q : int
        The element.
    samples : int
        How many collisions.
    seed : int
        The generator's seed.

    Returns
    -------
    tuple of float
        ``(estimate, standard error)``.
    """
    rng = random.Random(seed)
    sp, sq = sonine(p, dim), sonine(q, dim)
    area = 2 * math.pi ** (dim / 2) / math.gamma(dim / 2)
    weight_scale = 2.0 ** (dim / 2)

    def s_at(coefs: list[Fraction], x: float) -> float:
        return sum(float(c) * x**i for i, c in enumerate(coefs))

    total = total_sq = 0.0
    for _ in range(samples):
        c1 = [rng.gauss(0, 1) for _ in range(dim)]
        c2 = [rng.gauss(0, 1) for _ in range(dim)]
        k = [rng.gauss(0, 1) for _ in range(dim)]
        norm = math.sqrt(sum(x * x for x in k))
        k = [x / norm for x in k]
        gk = sum((x - y) * z for x, y, z in zip(c1, c2, k))
        value = 0.0
        if gk > 0:
            c1p = [x - gk * z for x, z in zip(c1, k)]
            x1 = sum(x * x for x in c1)
            x1p = sum(x * x for x in c1p)
            dot = sum(x * y for x, y in zip(c1, c1p))
            x2 = sum(x * x for x in c2)
            weight = weight_scale**2 * math.exp(-(x1 + x2) / 2)
            value = weight * area * gk * s_at(sp, x1) * (x1 * s_at(sq, x1) - dot * s_at(sq, x1p))
        total += value
        total_sq += value * value
    mean = total / samples
    var = (total_sq / samples - mean * mean) / (samples - 1)
    return mean, math.sqrt(var)


def main(argv: list[str]) -> int:
    """The command line (module docs)."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--dims", default="2,3", help="dimensions, comma-separated (>= 2)")
    parser.add_argument("--orders", type=int, default=8, help="the largest P (>= 1)")
    parser.add_argument(
        "--check-quadrature", type=int, default=0, metavar="N", help="Monte Carlo samples"
    )
    args = parser.parse_args(argv)
    try:
        dims = [int(d) for d in args.dims.split(",")]
    except ValueError:
        parser.error(f"--dims: not a comma-separated list of integers: {args.dims!r}")
    if any(d < 2 for d in dims):
        parser.error(f"--dims: each dimension must be at least 2: {args.dims!r}")
    if args.orders < 1:
        parser.error(f"--orders: must be at least 1: {args.orders}")
    if args.check_quadrature < 0:
        parser.error(f"--check-quadrature: must not be negative: {args.check_quadrature}")
    for dim in dims:
        a = matrix(dim, args.orders)
        r = ratios(a)
        print(f"n = {dim}: a_00 = {a[0][0]}")
        shown = min(3, args.orders)
        for p in range(shown):
            row = ", ".join(str((a[p][q] / a[0][0]).q) for q in range(shown))
            print(f"  a_{p}. / a_00 = {row}")
        print("  P   [D]_P / [D]_1             [D]_P - [D]_(P-1)   exact")
        for i, x in enumerate(r):
            diff = float(x - r[i - 1]) if i else float("nan")
            exact = str(x) if len(str(x)) <= 40 else "..."
            print(f"  {i + 1}   {float(x):.12f}   {diff:.3e}   {exact}")
        if args.check_quadrature:
            for p in range(min(3, args.orders)):
                for q in range(p, min(3, args.orders)):
                    est, se = monte_carlo(dim, p, q, args.check_quadrature, 1000 * p + q)
                    exact_value = float(a[p][q])
                    print(
                        f"  a_{p}{q} = {exact_value:.6f}; Monte Carlo {est:.6f} +- {se:.6f} "
                        f"({(est - exact_value) / se:+.2f} standard errors)"
                    )
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
