"""`noslip.collide(..., exact=True)` on one case, per call, by the path it takes.

    python python/benches/collide_exact.py [--calls 300] [--rounds 5]

The case of `examples/case.json` (3D, matrix spins, short numbers: a *plain* case, which
`collide_case` runs on the command's direct path) and the same case with its default law
written out, ``contact="no-slip"`` (the same collision and the same Python work, but not
plain, so it takes the one-pass reader and the general path), in alternated rounds; µs per
call (wall clock), median (min-max) over the rounds. The two answers are checked equal
first.
"""

from __future__ import annotations

import argparse
import json
import statistics
import time
from pathlib import Path
from typing import Any, Dict, List

import noslip


def per_call(case: Dict[str, Any], calls: int) -> float:
    """µs per call of ``noslip.collide(**case, exact=True)`` over ``calls`` calls."""
    start = time.perf_counter()
    for _ in range(calls):
        noslip.collide(**case, exact=True)
    return (time.perf_counter() - start) / calls * 1e6


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--calls", type=int, default=300)
    parser.add_argument("--rounds", type=int, default=5)
    args = parser.parse_args()
    root = Path(__file__).resolve().parents[2]
    plain = json.loads((root / "examples" / "case.json").read_text())
    general = {**plain, "contact": "no-slip"}
    assert noslip.collide(**plain, exact=True) == noslip.collide(**general, exact=True)
    times: Dict[str, List[float]] = {"plain (direct path)": [], "contact given (general)": []}
    for _ in range(args.rounds):
        times["plain (direct path)"].append(per_call(plain, args.calls))
        times["contact given (general)"].append(per_call(general, args.calls))
    for name, t in times.items():
        print(f"{name}: {statistics.median(t):.1f} ({min(t):.1f}-{max(t):.1f}) us per call")


if __name__ == "__main__":
    main()
