#!/usr/bin/env python3
"""Run two `noslip` binaries on the same generated collide cases and compare every byte.

    scripts/collide_compare.py BEFORE AFTER [--cases 400] [--seed 1] [--keep DIR]

Writes `--cases` random cases (and examples/case.json) to a temporary directory, runs
`BINARY collide FILE` and `BINARY collide --exact FILE` with both binaries, and compares
stdout, stderr and the exit code of each pair. Prints the counts (answers, errors) and every
difference; exits 1 if there is one.

The cases: 2..7 dimensions; fixed (a mass "inf") and free; numbers spelled as JSON integers
and floats, short ratio and decimal strings (the forms `--exact`'s direct path reads), 17-
and 20-digit decimals, exponents, 3-decimal strings, zeros; normals exactly unit (the
stereographic image of a rational point) or rounded; `lambda`, `gamma2` in and out of range,
`distribution`, or none; the omega (3D) and scalar (2D) spin forms; velocities approaching
or separating. Every tenth case has a negative mass, every tenth a broken normal (not unit),
every tenth a spin entry that is not skew, every tenth is an array of two cases, every
twentieth a key given twice, every twentieth a truncated text.
"""

import argparse
import json
import random
import subprocess
import sys
import tempfile
from fractions import Fraction
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


# Whether the case being written spells its numbers only in the short forms (integers,
# ratio and short decimal strings, JSON floats): half the cases, so that `--exact`'s direct
# path reads many of them whole.
PLAIN = {"on": False}


def spell(x: Fraction, rng: random.Random, form: int | None = None) -> str:
    """A JSON value for the rational x, in one of the format's spellings (`form`, else drawn)."""
    if form is None:
        form = draw_form(rng)
    if form == 0 and x.denominator == 1:
        return str(x.numerator)
    if form == 1:
        return repr(float(x))
    if form == 2:
        return json.dumps(f"{float(x):.17g}")
    if form == 3:
        return json.dumps(f"{float(x):.20f}")
    if form == 4:
        return json.dumps(f"{float(x):e}")
    if form == 5:
        return json.dumps(f"{float(x):.3f}")
    if form == 6 and x == 0:
        return json.dumps("0/7")
    d = x.denominator
    while d % 2 == 0:
        d //= 2
    while d % 5 == 0:
        d //= 5
    if form == 7 and d == 1:
        # A finite decimal, exactly.
        return json.dumps(str(float(x)) if len(str(float(x))) < 17 else str(x))
    return json.dumps(str(x))


def draw_form(rng: random.Random) -> int:
    return rng.choice([0, 1, 6, 7, 8, 9]) if PLAIN["on"] else rng.randrange(10)


def small(rng: random.Random, top: int) -> Fraction:
    return Fraction(rng.randint(-top, top), rng.choice([1, 2, 3, 4, 5, 7, 10]))


def normal(dim: int, rng: random.Random) -> list[Fraction]:
    y = [Fraction(rng.randint(-30, 30), rng.choice([7, 11, 13])) for _ in range(dim - 1)]
    y2 = sum((v * v for v in y), Fraction(0))
    return [2 * v / (y2 + 1) for v in y] + [(y2 - 1) / (y2 + 1)]


def body(
    dim: int, rng: random.Random, immovable: bool, spoil_mass: bool, spoil_skew: bool
) -> dict[str, str]:
    radius = Fraction(rng.randint(1, 30), rng.choice([1, 2, 3, 10]))
    mass = '"inf"' if immovable else spell(Fraction(rng.randint(1, 30), rng.choice([1, 2, 3])), rng)
    if spoil_mass:
        mass = spell(Fraction(-rng.randint(0, 5), 1), rng)
    b = {"mass": mass, "radius": spell(radius, rng)}
    t = rng.choice([Fraction(0), Fraction(1, 3), Fraction(1, 2), Fraction(1), Fraction(11, 10)])
    kind = rng.randrange(4)
    if kind == 1:
        b["lambda"] = spell(t * radius * radius / dim, rng)
    elif kind == 2:
        b["gamma2"] = spell(t * 2 / dim, rng)
    elif kind == 3:
        b["distribution"] = json.dumps(rng.choice(["uniform", "shell"] * 5 + ["solid"]))
    form = rng.randrange(6)
    if dim == 2 and form == 0:
        b["angular_velocity"] = spell(small(rng, 5), rng)
    elif dim == 3 and form == 0:
        b["angular_velocity"] = "[" + ", ".join(spell(small(rng, 5), rng) for _ in range(3)) + "]"
    else:
        # Each entry and its opposite spelled in one form (x and -x then read as exact
        # opposites in both modes).
        upper = {(i, j): small(rng, 5) for i in range(dim) for j in range(i + 1, dim)}
        forms = {key: draw_form(rng) for key in upper}
        rows = []
        for i in range(dim):
            row = []
            for j in range(dim):
                if i == j:
                    row.append(spell(Fraction(0), rng))
                elif i < j:
                    row.append(spell(upper[(i, j)], rng, forms[(i, j)]))
                else:
                    x = -upper[(j, i)] + (Fraction(1, 9) if spoil_skew else 0)
                    row.append(spell(x, rng, forms[(j, i)]))
            rows.append("[" + ", ".join(row) + "]")
        b["angular_velocity"] = "[" + ", ".join(rows) + "]"
    return b


def case(k: int, rng: random.Random) -> str:
    dim = rng.randint(2, 7)
    PLAIN["on"] = rng.randrange(2) == 0
    nu = normal(dim, rng)
    if k % 10 == 1:
        nu[0] += Fraction(1, 1000)
    u = [[small(rng, 20) for _ in range(dim)] for _ in range(2)]
    dn = sum(n * (b - a) for n, a, b in zip(nu, u[0], u[1]))
    if dn > 0 and rng.randrange(5) > 0:
        u.reverse()
    fixed = rng.randrange(3)
    bodies = [
        body(dim, rng, fixed == 1 and b == 0, k % 10 == 3 and b == 0, k % 10 == 5 and b == 1)
        for b in range(2)
    ]
    for b in range(2):
        bodies[b]["velocity"] = "[" + ", ".join(spell(x, rng) for x in u[b]) + "]"
    if fixed == 2:
        bodies[1]["mass"] = '"inf"'
    texts = []
    for members_of in bodies:
        members = [f'"{key}": {value}' for key, value in members_of.items()]
        if k % 20 == 7:
            members.append(f'"radius": {members_of["radius"]}')
        texts.append("{" + ", ".join(members) + "}")
    exact_normal = rng.randrange(10) < 7
    normal_text = "[" + ", ".join(
        json.dumps(str(x)) if exact_normal else spell(x, rng) for x in nu
    ) + "]"
    text = f'{{"dim": {dim}, "normal": {normal_text}, "bodies": [{texts[0]}, {texts[1]}]}}'
    if k % 10 == 9:
        text = f"[{text}, {text}]"
    if k % 20 == 13:
        text = text[: rng.randrange(len(text))]
    return text


def run(binary: str, exact: bool, path: Path) -> tuple[bytes, bytes, int]:
    args = [binary, "collide"] + (["--exact"] if exact else []) + [str(path)]
    p = subprocess.run(args, capture_output=True, timeout=600)
    return p.stdout, p.stderr, p.returncode


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("before")
    ap.add_argument("after")
    ap.add_argument("--cases", type=int, default=400)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--keep", help="write the cases into this directory and keep them")
    a = ap.parse_args()
    rng = random.Random(a.seed)
    tmp = tempfile.TemporaryDirectory()
    out = Path(a.keep) if a.keep else Path(tmp.name)
    out.mkdir(parents=True, exist_ok=True)
    files = [ROOT / "examples" / "case.json"]
    for k in range(a.cases):
        f = out / f"case{k:04}.json"
        f.write_text(case(k, rng))
        files.append(f)
    answers = errors = differ = 0
    for f in files:
        for exact in (False, True):
            before = run(a.before, exact, f)
            after = run(a.after, exact, f)
            if before != after:
                differ += 1
                print(f"DIFFER {f} exact={exact}\n  before {before}\n  after  {after}")
            if before[2] == 0:
                answers += 1
            else:
                errors += 1
    print(
        f"{len(files)} inputs, {2 * len(files)} runs each binary: {answers} answers, "
        f"{errors} errors (before); {differ} runs differ in stdout, stderr or exit code"
    )
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
