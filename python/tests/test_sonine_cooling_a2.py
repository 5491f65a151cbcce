"""``scripts/sonine_cooling_a2.py``: the cooling state's ``a_2`` of smooth inelastic balls at
the first Sonine order, from the collision integrals in exact rationals, is van Noije &
Ernst's closed form (2D to 4D, several ``e``), vanishes at ``e = 1`` to every order, and the
second-order values that ``sim/tests/boltzmann.rs`` holds the DSMC to are the script's. About
2 s."""

from __future__ import annotations

import re
from fractions import Fraction

import pytest
from repo_scripts import ROOT, load

S = load("sonine_cooling_a2")


@pytest.mark.parametrize("dim", [2, 3, 4])
def test_first_order_is_van_noije_ernsts(dim: int) -> None:
    for e in (Fraction(0), Fraction(1, 3), Fraction(1, 2), Fraction(7, 10), Fraction(9, 10)):
        assert S.first_sonine_a2(dim, e) == S.van_noije_ernst(dim, e), (dim, e)
    # a_2 changes sign at e = 1 / sqrt(2): positive below, negative above.
    assert S.first_sonine_a2(dim, Fraction(7, 10)) > 0 > S.first_sonine_a2(dim, Fraction(71, 100))


def test_elastic_is_maxwellian_and_the_rust_constants() -> None:
    for dim in (2, 3):
        assert S.first_sonine_a2(dim, Fraction(1)) == 0
        assert S.second_sonine(dim, Fraction(1)) == (0, 0)
    rust = (ROOT / "sim" / "tests" / "boltzmann.rs").read_text()
    table = re.findall(r"\((\d), (0\.\d+), (-?[0-9._]+)\)", rust)
    assert len(table) == 4
    for dim, e, value in table:
        a2, _ = S.second_sonine(int(dim), Fraction(e))
        assert abs(float(a2) - float(value.replace("_", ""))) < 5e-7, (dim, e, value)
