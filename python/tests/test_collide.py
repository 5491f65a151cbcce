"""noslip.collide against the command line (`noslip collide`), bit for bit in f64 and
equal in exact rationals, and the conservation laws in exact arithmetic."""

import collections
import json
from fractions import Fraction

import numpy as np
import pytest

import noslip
from cases import bits, case, cases, floats, json_text
from conftest import run_cli

CASES = cases(seed=13, per_dim=6)


def flat(x):
    if hasattr(x, "tolist"):  # collide's float results are NumPy arrays
        x = x.tolist()
    if isinstance(x, list):
        return [y for v in x for y in flat(v)]
    if isinstance(x, dict):
        return [y for k in sorted(x) for y in flat(x[k])]
    return [x]


def test_floats_equal_the_cli_bit_for_bit(cli):
    float_cases = [floats(c) for c in CASES]
    expected = json.loads(run_cli(cli, "collide", stdin=json.dumps(json_text(float_cases))))
    for c, want in zip(float_cases, expected):
        got = noslip.collide(c["normal"], c["bodies"])
        got_flat, want_flat = flat(got), flat(want["bodies"])
        assert len(got_flat) == len(want_flat) > 0
        assert [bits(x) for x in got_flat] == [bits(x) for x in want_flat], c


def test_exact_equals_the_cli(cli):
    expected = json.loads(
        run_cli(cli, "collide", "--exact", stdin=json.dumps(json_text(CASES)))
    )
    for c, want in zip(CASES, expected):
        got = noslip.collide(c["normal"], c["bodies"], exact=True)
        assert all(isinstance(x, Fraction) for x in flat(got))
        assert flat(got) == [Fraction(x) for x in flat(want["bodies"])]


def test_fractions_in_float_mode_round_once_as_the_cli_does(cli):
    c = CASES[7]
    want = json.loads(run_cli(cli, "collide", stdin=json.dumps(json_text(c))))
    got = noslip.collide(c["normal"], c["bodies"])
    assert [bits(x) for x in flat(got)] == [bits(x) for x in flat(want["bodies"])]


def full_matrix(spin, n):
    if n == 2 and not isinstance(spin, list):
        return [[0, -spin], [spin, 0]]
    if n == 3 and not isinstance(spin[0], list):
        w = spin
        return [[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]]
    return spin


def inertia(body, n):
    """lambda = (1/(n m)) int |b|^2 dmu from the body's keys (uniform: R^2/(n+2))."""
    r = body["radius"]
    if "lambda" in body:
        return body["lambda"]
    if "gamma2" in body:
        return body["gamma2"] * r * r / 2
    if body.get("distribution") == "shell":
        return r * r / n
    return r * r / (n + 2)


def test_exact_results_conserve_energy_and_momentum():
    """First principles, exactly: E = sum m (|u|^2 + lambda |U|_F^2) / 2 and, with both
    bodies free, p = sum m u are unchanged; the contact velocity along nu is reversed
    (V_2(Q) - V_1(Q)) . nu -> -(...), with V_i(Q) = U_i (x_Q - a_i) + u_i."""
    checked = 0
    for c in CASES:
        if any(b["mass"] == "inf" for b in c["bodies"]):
            continue
        n, nu = c["dim"], c["normal"]
        after = noslip.collide(nu, c["bodies"], exact=True)

        def energy(states):
            e = Fraction(0)
            for body, (spin, u) in zip(c["bodies"], states):
                m, lam = body["mass"], inertia(body, n)
                big_u = full_matrix(spin, n)
                e += m * (sum(x * x for x in u) + lam * sum(x * x for row in big_u for x in row))
            return e / 2

        def normal_speed(states):
            (s1, u1), (s2, u2) = states
            r1, r2 = c["bodies"][0]["radius"], c["bodies"][1]["radius"]
            m1, m2 = full_matrix(s1, n), full_matrix(s2, n)
            v1 = [sum(m1[i][k] * r1 * nu[k] for k in range(n)) + u1[i] for i in range(n)]
            v2 = [sum(m2[i][k] * (-r2) * nu[k] for k in range(n)) + u2[i] for i in range(n)]
            return sum((v2[i] - v1[i]) * nu[i] for i in range(n))

        before = [(b["angular_velocity"], b["velocity"]) for b in c["bodies"]]
        post = [(b["angular_velocity"], b["velocity"]) for b in after]
        assert energy(post) == energy(before)
        for k in range(n):
            assert sum(b["mass"] * s[1][k] for b, s in zip(c["bodies"], post)) == sum(
                b["mass"] * s[1][k] for b, s in zip(c["bodies"], before)
            )
        assert normal_speed(post) == -normal_speed(before)
        checked += 1
    assert checked >= 15


def test_errors_are_input_errors_naming_the_field():
    c = floats(CASES[0])
    assert issubclass(noslip.InputError, ValueError)
    bad = json.loads(json.dumps(c))
    bad["bodies"][1]["velocity"] = [-x for x in c["bodies"][1]["velocity"]]
    bad["bodies"][0]["velocity"] = [-x for x in c["bodies"][0]["velocity"]]
    with pytest.raises(noslip.InputError, match=r"^bodies\[\*\]\.velocity: .*approach"):
        noslip.collide(bad["normal"], bad["bodies"])
    def gamma2_too_big(b):
        b[1]["gamma2"] = 5.0

    def no_radius(b):
        del b[0]["radius"]

    def short_velocity(b):
        b[0]["velocity"] = [1.0]

    def unknown_key(b):
        b[0]["colour"] = "red"

    def negative_mass(b):
        b[1]["mass"] = -1.0

    def nan_velocity(b):
        b[0]["velocity"] = [float("nan"), 0.0]

    cases_and_messages = [
        (gamma2_too_big, r"^bodies\[1\]\.gamma2: "),
        (no_radius, r"^bodies\[0\]\.radius: missing"),
        (short_velocity, r"^bodies\[0\]\.velocity: expected 2 numbers"),
        (unknown_key, r"^bodies\[0\]\.colour: unknown key"),
        (negative_mass, r"^bodies\[1\]\.mass: must be positive"),
        (nan_velocity, r"^bodies\[0\]\.velocity\[0\]: \"nan\" is not a finite number"),
    ]
    for change, message in cases_and_messages:
        bodies = json.loads(json.dumps(c["bodies"]))
        for b in bodies:
            for k in ("lambda", "gamma2", "distribution"):
                b.pop(k, None)
        change(bodies)
        with pytest.raises(noslip.InputError, match=message):
            noslip.collide(c["normal"], bodies)
    with pytest.raises(noslip.InputError, match=r"^normal: must be a unit vector"):
        noslip.collide([1.0, 1.0], c["bodies"])
    # A normal wrapped once more is named as such, not as a 1D case (it blamed `dim`).
    with pytest.raises(noslip.InputError, match=r"^normal: expected a sequence of n numbers, got a"):
        noslip.collide([c["normal"]], c["bodies"])
    # Any sequence is a sequence: a deque or a range is read as the list it holds.
    normal = c["normal"]
    want = noslip.collide(normal, c["bodies"])
    for seq in (collections.deque(normal), tuple(normal)):
        got = noslip.collide(seq, c["bodies"])
        assert all(np.array_equal(g["velocity"], w["velocity"]) for g, w in zip(got, want))
    with pytest.raises(noslip.InputError, match=r"^dim: must be at least 2, got 1"):
        noslip.collide(range(1, 2), c["bodies"])
    # A string Python holds but UTF-8 cannot encode (a lone surrogate) is named, not
    # Python's UnicodeEncodeError.
    odd = json.loads(json.dumps(c["bodies"]))
    odd[1]["distribution"] = "\udc80"
    with pytest.raises(noslip.InputError,
                       match=r"^bodies\[1\]\.distribution: '\\udc80' is not valid Unicode text"):
        noslip.collide(c["normal"], odd)
    # A list inside itself is named, not Python's RecursionError.
    loop: list = []
    loop.append(loop)
    looped = json.loads(json.dumps(c["bodies"]))
    looped[0]["velocity"] = loop
    with pytest.raises(noslip.InputError,
                       match=r"^bodies\[0\]\.velocity(\[0\])+: nested more than 32 deep"):
        noslip.collide(c["normal"], looped)


def test_floats_are_refused_in_exact_mode_with_the_field():
    c = CASES[0]
    bodies = [dict(b) for b in c["bodies"]]
    bodies[0]["radius"] = 0.5
    with pytest.raises(noslip.InputError, match=r"^bodies\[0\]\.radius: a float in exact mode"):
        noslip.collide(c["normal"], bodies, exact=True)


def test_the_shipped_example_case(root, cli):
    example = json.loads((root / "examples" / "case.json").read_text())
    want = json.loads(run_cli(cli, "collide", "--exact", str(root / "examples" / "case.json")))
    got = noslip.collide(**example, exact=True)
    assert flat(got) == [Fraction(x) for x in flat(want["bodies"])]
