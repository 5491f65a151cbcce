"""``collide(..., contact=...)``: the rough-ball and Walton laws (docs/derivation.md §15,
§15.1) on a ball falling onto a wall, against outcomes derived by hand, and their bad
parameters refused naming the field."""

from __future__ import annotations

from fractions import Fraction as F
from typing import Any, List

import numpy as np
import pytest

import noslip

ZERO = [[0, 0, 0], [0, 0, 0], [0, 0, 0]]


def falling(exact: bool = True) -> List[dict[str, Any]]:
    """Body 1 an immovable wall below (``nu = (0, 1, 0)``); body 2 a uniform ball (``m = 1``,
    ``R = 1``, ``lambda = 1/5``: ``b/a = 1 + 1/g = 7/2``) falling without spin at
    ``u = (3, -4, 0)``: ``dn = -4``, slip ``t = (3, 0, 0)``."""
    one = 1 if exact else 1.0
    return [
        {"mass": "inf", "radius": one, "gamma2": F(2, 5) if exact else 0.4,
         "angular_velocity": ZERO, "velocity": [0, 0, 0]},
        {"mass": one, "radius": one, "lambda": F(1, 5) if exact else 0.2,
         "angular_velocity": ZERO, "velocity": [3, -4, 0]},
    ]


def slip(body: dict[str, Any]) -> List[F]:
    """The slip of body 2's contact point on the wall: ``u - R U nu`` with ``R = 1``."""
    u, U = body["velocity"], body["angular_velocity"]
    return [u[i] - U[i][1] for i in range(3)]


def test_rough_law_scales_the_normal_and_tangential_slip():
    e, beta = F(1, 2), F(-1, 3)
    _, after = noslip.collide([0, 1, 0], falling(), exact=True,
                              contact={"e": e, "beta": beta})
    s = slip(after)
    assert s[1] == -e * (-4)  # dn+ = -e dn
    assert [s[0], s[2]] == [-beta * 3, 0]  # t+ = -beta t


def test_two_point_masses_meet_under_a_smooth_law_only():
    """Two point masses (``gamma2 = 0``) were refused under every law; under a smooth one
    (``beta = -1``) their contact is the specular map: ``dn`` becomes ``-e dn``, spins kept.
    A law with a tangential part still refuses them, naming the bodies; a validated batch
    agrees with ``collide``."""
    def body(mass: Any, u: List[Any]) -> dict[str, Any]:
        return {"mass": mass, "radius": 1, "gamma2": 0, "angular_velocity": [[0, 2], [-2, 0]],
                "velocity": u}

    bodies = [body(1, [0, -1]), body(3, [F(1, 2), 0])]
    for contact, e in [("smooth", F(1)), ({"e": F(1, 2), "beta": -1}, F(1, 2))]:
        a, b = noslip.collide([0, -1], bodies, exact=True, contact=contact)
        dn_before = (0 - (-1)) * -1
        dn_after = (b["velocity"][1] - a["velocity"][1]) * -1
        assert dn_after == -e * dn_before
        assert a["angular_velocity"] == b["angular_velocity"] == [[0, 2], [-2, 0]]
    with pytest.raises(noslip.InputError, match=r"^bodies: both bodies are point masses"):
        noslip.collide([0, -1], bodies, contact={"e": 0.5, "beta": 0})
    floats = [dict(body(1.0, [0.0, -1.0])), dict(body(3.0, [0.5, 0.0]))]
    single = noslip.collide([0.0, -1.0], floats, contact="smooth")
    batch = noslip.collide_batch(np.array([0.0, -1.0]), [
        {k: np.asarray(v, dtype=np.float64) for k, v in b.items()} for b in floats
    ], contact="smooth", validate=True)
    for k in range(2):
        assert np.array_equal(batch[k]["velocity"], single[k]["velocity"])


def test_walton_slides_on_the_coulomb_bound_and_sticks_as_the_rough_law():
    # Sticking would take the tangential impulse (1 + beta0)|t|/b = (4/3) 3 / (7/2) = 8/7;
    # the normal one is (1 + e)|dn| = 6. mu = 1/10 allows 6/10: it slides, u_x drops by 6/10.
    law = {"e": F(1, 2), "mu": F(1, 10), "beta0": F(1, 3)}
    _, after = noslip.collide([0, 1, 0], falling(), exact=True, contact=law)
    assert after["velocity"] == [F(12, 5), F(2), F(0)]
    _, floats = noslip.collide([0, 1, 0], falling(False), contact={"e": 0.5, "mu": 0.1, "beta0": 1 / 3})
    # A few roundings of order-1 numbers (one square root among them): 1e-15 is some ulps.
    assert np.max(np.abs(floats["velocity"] - [2.4, 2.0, 0.0])) < 1e-15
    sticking = noslip.collide([0, 1, 0], falling(), exact=True, contact={**law, "mu": 1})
    rough = noslip.collide([0, 1, 0], falling(), exact=True,
                           contact={"e": F(1, 2), "beta": F(1, 3)})
    assert sticking == rough


@pytest.mark.parametrize(
    "contact, field",
    [
        ({"e": 1.5, "beta": 0.0}, "contact.e"),
        ({"e": 0.5, "beta": -2.0}, "contact.beta"),
        ({"e": 0.5, "mu": -0.1, "beta0": 0.0}, "contact.mu"),
        ({"e": 0.5, "mu": float("nan"), "beta0": 0.0}, "contact.mu"),
        ({"e": 0.5, "mu": 0.1, "beta0": 2.0}, "contact.beta0"),
        ({"e": 0.5, "mu": 0.1}, "contact.beta0"),
        # With beta it is the rough form: mu and beta0 are unknown keys (the first named).
        ({"e": 0.5, "mu": 0.1, "beta0": 0.0, "beta": 0.0}, r"contact\.(mu|beta0): unknown key"),
        ("rough", "contact"),
    ],
)
def test_bad_contact_parameters_name_the_field(contact: Any, field: str):
    pattern = field if "\\" in field else field.replace(".", r"\.")
    with pytest.raises(noslip.InputError, match=pattern):
        noslip.collide([0, 1, 0], falling(False), contact=contact)


def test_floats_are_refused_in_exact_mode_with_the_contact_field():
    with pytest.raises(noslip.InputError, match=r"contact\.mu"):
        noslip.collide([0, 1, 0], falling(), exact=True,
                       contact={"e": 1, "mu": 0.1, "beta0": 0})
