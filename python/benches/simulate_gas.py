"""What a contact costs through ``noslip.simulate`` on a large gas, against another build.

    python python/benches/simulate_gas.py [--dim 2] [--balls 1000000] [--phi 0.2]
        [--events 3000000] [--rounds 3] [--python OTHER/bin/python]

A periodic box of ``--balls`` balls of radius 1/2 (mass 1, no-slip contacts, seeded random
placement) at packing fraction ``--phi``. Each round runs ``simulate`` twice in a fresh
process, for ``E`` and ``2 E`` contacts (``E`` = ``--events``), and prints the difference
of their CPU times over ``E``: µs a contact in steady state, without the setup and the
first contacts. With ``--python``, each round runs that interpreter's ``noslip`` too
(another build installed in another environment), alternated with this one; printed: per
build the median (min-max) over the rounds, and the ratio of the two paired within rounds.
At ``10^6`` balls two runs' setups (their first touches of about 600 MB) vary by more than
``10^6`` contacts cost, hence the default ``E`` of ``3 10^6`` (docs/benchmarks.md, session 58).
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys

from noslip.granular import _ball_volume

# Run in a child process: one `simulate` of `events` contacts, its CPU time printed.
CHILD = """
import json, sys, time
import noslip
scene, events = json.loads(sys.argv[1]), int(sys.argv[2])
start = time.process_time()
noslip.simulate(scene, events=events)
print(time.process_time() - start)
"""


def scene(dim: int, balls: int, phi: float) -> dict[str, object]:
    """The periodic gas: side ``L = (N V_1 / phi)^(1/n)``, ``V_1`` the volume of one ball."""
    side = (balls * _ball_volume(dim) / phi) ** (1 / dim)
    return {
        "dim": dim,
        "box": {"size": [side] * dim, "boundary": ["periodic"] * dim},
        "species": [{"name": "ball", "mass": 1, "radius": "1/2", "count": balls}],
        "random": {"seed": 1, "speed": 1, "spin": 1},
    }


def seconds(python: str, gas: dict[str, object], events: int) -> float:
    """CPU seconds of one ``simulate`` of ``events`` contacts under ``python``."""
    out = subprocess.run(
        [python, "-c", CHILD, json.dumps(gas), str(events)],
        check=True,
        capture_output=True,
        text=True,
    )
    return float(out.stdout.split()[-1])


def per_contact(python: str, gas: dict[str, object], events: int) -> float:
    """µs a contact between ``events`` and ``2 events`` contacts."""
    return (seconds(python, gas, 2 * events) - seconds(python, gas, events)) / events * 1e6


def summary(xs: list[float]) -> str:
    """Median (min-max)."""
    return f"{statistics.median(xs):.3f} ({min(xs):.3f}-{max(xs):.3f})"


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--dim", type=int, default=2)
    ap.add_argument("--balls", type=int, default=1_000_000)
    ap.add_argument("--phi", type=float, default=0.2)
    ap.add_argument("--events", type=int, default=3_000_000)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--python", help="another build's interpreter, alternated with this one")
    args = ap.parse_args()
    gas = scene(args.dim, args.balls, args.phi)
    builds = [sys.executable] + ([args.python] if args.python else [])
    times: list[list[float]] = [[] for _ in builds]
    for r in range(args.rounds):
        for b, python in enumerate(builds):
            times[b].append(per_contact(python, gas, args.events))
        print(f"round {r + 1}: " + "  ".join(f"{t[-1]:.3f}" for t in times), flush=True)
    for python, t in zip(builds, times):
        print(f"{python}: {summary(t)} µs a contact")
    if args.python:
        ratios = [a / b for a, b in zip(times[1], times[0])]
        print(f"other / this, paired within rounds: {summary(ratios)}")


if __name__ == "__main__":
    main()
