"""Seeded collision cases in the JSON case format, as Python values: every dimension with
generated kernels, the 2D and 3D spin shorthands, immovable bodies, point masses, and each
way of giving the inertia."""

from __future__ import annotations

import random
from fractions import Fraction

import numpy as np


def skew(rng: random.Random, n: int) -> list[list[Fraction]]:
    m = [[Fraction(0)] * n for _ in range(n)]
    for r in range(n):
        for c in range(r + 1, n):
            x = Fraction(rng.randint(-40, 40), rng.randint(1, 9))
            m[r][c], m[c][r] = x, -x
    return m


def unit_normal(rng: random.Random, n: int) -> list[Fraction]:
    """A rational unit vector: the inverse stereographic projection of a rational point."""
    y = [Fraction(rng.randint(-9, 9), rng.randint(1, 5)) for _ in range(n - 1)]
    s = sum(t * t for t in y)
    return [2 * t / (1 + s) for t in y] + [(s - 1) / (1 + s)]


def case(rng: random.Random, n: int) -> dict:
    """One approaching case in R^n with exact (Fraction) numbers."""
    nu = unit_normal(rng, n)
    bodies = []
    for b in range(2):
        body: dict = {
            "mass": Fraction(rng.randint(1, 30), rng.randint(1, 7)),
            "radius": Fraction(rng.randint(1, 20), rng.randint(1, 9)),
            "angular_velocity": skew(rng, n),
            "velocity": [Fraction(rng.randint(-30, 30), rng.randint(1, 8)) for _ in range(n)],
        }
        pick = rng.randrange(4)
        if pick == 0:
            body["lambda"] = body["radius"] ** 2 / n * Fraction(rng.randint(0, 10), 10)
        elif pick == 1:
            body["gamma2"] = Fraction(2, n) * Fraction(rng.randint(1, 10), 10)
        elif pick == 2:
            body["distribution"] = rng.choice(["uniform", "shell"])
        bodies.append(body)
    if rng.random() < 0.25:
        bodies[rng.randrange(2)]["mass"] = "inf"
    if n == 2 and rng.random() < 0.5:
        for body in bodies:
            body["angular_velocity"] = body["angular_velocity"][1][0]
    if n == 3 and rng.random() < 0.5:
        for body in bodies:
            u = body["angular_velocity"]
            body["angular_velocity"] = [u[2][1], u[0][2], u[1][0]]
    dn = sum((bodies[1]["velocity"][k] - bodies[0]["velocity"][k]) * nu[k] for k in range(n))
    if dn > 0:  # make them approach
        nu = [-x for x in nu]
    return {"dim": n, "normal": nu, "bodies": bodies}


def cases(seed: int, per_dim: int) -> list[dict]:
    rng = random.Random(seed)
    return [case(rng, n) for n in range(2, 7) for _ in range(per_dim)]


def floats(x):
    """The case with every Fraction as the nearest float (correctly rounded)."""
    if isinstance(x, dict):
        return {k: floats(v) for k, v in x.items()}
    if isinstance(x, list):
        return [floats(v) for v in x]
    if isinstance(x, Fraction):
        return float(x)
    return x


def json_text(x) -> object:
    """The case as the command line reads it: Fractions as "p/q", floats as their repr."""
    if isinstance(x, dict):
        return {k: json_text(v) for k, v in x.items()}
    if isinstance(x, list):
        return [json_text(v) for v in x]
    if isinstance(x, Fraction):
        return f"{x.numerator}/{x.denominator}"
    if isinstance(x, float):
        return repr(x)
    return x


def bits(x: float) -> int:
    return int(np.float64(x).view(np.uint64))
