"""``scripts/sonine_self_diffusion.py``, the exact Sonine approximations of the hard-ball
self-diffusion coefficient that ``sim/tests/self_diffusion.rs`` holds the engine to
(docs/granular.md, "Self-diffusion against Chapman-Enskog"), checked in exact rationals
against what is derived independently of its polynomial bookkeeping:

- its Sonine polynomials are orthogonal with the weight ``x^(n/2) exp(-x)``;
- ``a_00`` gives the first approximation ``[D]_1`` derived in the docs from the momentum
  balance of a drifting ball (2D and 3D);
- in 3D, ``a_01`` and ``a_11`` are Chapman & Cowling's brackets for mechanically identical
  rigid spheres (their chapter 9's ``[S_1 C_1, C_1]'_12`` and ``[S_1 C_1, S_1 C_1]'_12`` at
  ``M_1 = M_2 = 1/2``, written from memory with the rigid-sphere ``Omega^(l,r)``: that they
  agree exactly with the script's independent computation is the check), so ``[D]_2 / [D]_1 =
  59/58``;
- ``[D]_P / [D]_1`` for ``P <= 4`` increases (each is a variational lower bound over a larger
  space) and equals the fractions in the docs' table, and the tenth order that the Rust test
  uses lies above the fourth by less than the fourth's last difference.

About 1 s (``P <= 4`` in both dimensions)."""

from __future__ import annotations

import math
import re
from fractions import Fraction

import pytest
from repo_scripts import ROOT, load

S = load("sonine_self_diffusion")


@pytest.mark.parametrize("dim", [2, 3])
def test_sonine_polynomials_are_orthogonal(dim: int) -> None:
    # int_0^inf x^k x^a exp(-x) dx = Gamma(k + a + 1) = Gamma(a + 1) (a + 1)_k, a = n/2.
    a = Fraction(dim, 2)

    def moment(k: int) -> Fraction:
        return math.prod((a + 1 + i for i in range(k)), start=Fraction(1))

    for p in range(5):
        for q in range(5):
            sp, sq = S.sonine(p, dim), S.sonine(q, dim)
            inner = sum(
                (x * y * moment(i + j) for i, x in enumerate(sp) for j, y in enumerate(sq)),
                start=Fraction(0),
            )
            # Gamma(p + a + 1) / (p! Gamma(a + 1)) on the diagonal
            expected = moment(p) / math.factorial(p) if p == q else Fraction(0)
            assert inner == expected, (dim, p, q)


def test_a00_is_the_first_approximation() -> None:
    # D = sqrt(2 T / m) n (a^-1)_00 / (4 rho sigma^(n-1)); the docs' [D]_1 is
    # 3 / (8 rho sigma^2) sqrt(T / (pi m)) in 3D and 1 / (2 rho sigma) sqrt(T / (pi m)) in
    # 2D, i.e. a_00 = 2 sqrt(2 pi) and sqrt(2 pi).
    a3 = S.matrix(3, 1)[0][0]
    a2 = S.matrix(2, 1)[0][0]
    assert (a3.q, a3.two, a3.pi_half) == (2, 1, 1)
    assert (a2.q, a2.two, a2.pi_half) == (1, 1, 1)


def test_second_approximation_for_spheres_is_chapman_cowlings() -> None:
    # Rigid spheres: Omega^(l,r) = K (r+1)!/2 (1 - (1 + (-1)^l) / (2 (1 + l))).
    def omega(l: int, r: int) -> Fraction:
        return Fraction(math.factorial(r + 1), 2) * (1 - Fraction(1 + (-1) ** l, 2 * (1 + l)))

    m1 = m2 = Fraction(1, 2)
    c00 = 8 * m2 * omega(1, 1)
    c01 = 8 * m2**2 * (Fraction(5, 2) * omega(1, 1) - omega(1, 2))
    c11 = 8 * m2 * (
        Fraction(5, 4) * (6 * m1**2 + 5 * m2**2) * omega(1, 1)
        - 5 * m2**2 * omega(1, 2)
        + m2**2 * omega(1, 3)
        + 2 * m1 * m2 * omega(2, 2)
    )
    a = S.matrix(3, 2)
    ratio = [[(x / a[0][0]).q for x in row] for row in a]
    # a_01 < 0 here (a fast ball, where S_1 < 0, is slowed most); only its square enters D.
    assert ratio[0][1] == ratio[1][0] == -abs(c01 / c00) == Fraction(-1, 4)
    assert ratio[1][1] == c11 / c00 == Fraction(59, 16)
    assert S.ratios(a)[1] == Fraction(59, 58)


def test_table_and_the_rust_tests_tenth_order() -> None:
    table = {
        2: [Fraction(1), Fraction(43, 42), Fraction(104377, 101688),
            Fraction(1540122905, 1499738736)],
        3: [Fraction(1), Fraction(59, 58), Fraction(237697, 233336),
            Fraction(6653573409, 6530155888)],
    }
    rust = (ROOT / "sim" / "tests" / "self_diffusion.rs").read_text()
    for dim, expected in table.items():
        r = S.ratios(S.matrix(dim, 4))
        assert r == expected, dim
        assert all(x < y for x, y in zip(r, r[1:])), dim
        found = re.search(rf"const SONINE_10_{dim}D: f64 = ([0-9._]+);", rust)
        assert found is not None, dim
        tenth = float(found.group(1).replace("_", ""))
        assert float(r[3]) < tenth < float(r[3] + (r[3] - r[2])), (dim, tenth)
