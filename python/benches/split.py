"""collide_batch on one thread and split across rayon's threads, for small to mid batches.

    python python/benches/split.py [--dims 3 6] [--rows 513 1024 ... 65536] [--rounds 7]

For each `n` and number of rows: random approaching contacts (batch.py's `contacts`, seeded by
`n` and the rows, so that two installs see the same data), validated, into reused outputs
(`out=`). Each round times at least 20 calls (and about 2 10^6 rows) with `parallel=False`,
then as many with `parallel=True`; the wall clock, median of the rounds, µs per call. The
batch is split from 513 rows on (more than one chunk of 512): this measures what the split
costs or gains where a call takes tens of µs. Compare within a line: the share of rows that
the cheap check sends to `collide`'s full checks depends on the data.
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np
from batch import contacts

import noslip


def per_call_us(
    nu: np.ndarray,
    bodies: list[dict[str, np.ndarray]],
    out: tuple[dict[str, np.ndarray], dict[str, np.ndarray]],
    parallel: bool,
    calls: int,
) -> float:
    """Mean wall-clock µs of `calls` calls of `collide_batch` into `out`.

    Parameters
    ----------
    nu, bodies
        The batch, as `noslip.collide_batch` takes it.
    out
        Output arrays from an earlier call, written again.
    parallel
        Passed to `collide_batch`.
    calls
        Number of calls timed together.

    Returns
    -------
    float
        Microseconds per call.
    """
    start = time.perf_counter()
    for _ in range(calls):
        noslip.collide_batch(nu, bodies, parallel=parallel, out=out)
    return (time.perf_counter() - start) / calls * 1e6


def main() -> None:
    """Print one table line per `n` and number of rows."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--dims", type=int, nargs="+", default=[3, 6])
    parser.add_argument(
        "--rows", type=int, nargs="+", default=[513, 1024, 2048, 4096, 16384, 65536]
    )
    parser.add_argument("--rounds", type=int, default=7)
    args = parser.parse_args()
    print(f"isa {noslip.isa()}, wall clock, median of {args.rounds} rounds, µs per call")
    print("| n | rows | serial | parallel | serial / parallel |")
    print("|---:|---:|---:|---:|---:|")
    for n in args.dims:
        for rows in args.rows:
            nu, bodies = contacts(np.random.default_rng([n, rows]), rows, n)
            serial = noslip.collide_batch(nu, bodies, parallel=False)
            split = noslip.collide_batch(nu, bodies, parallel=True)
            for b in range(2):
                for key in serial[b]:
                    assert np.array_equal(serial[b][key], split[b][key]), (n, rows, key)
            calls = max(20, 2_000_000 // rows)
            times: dict[bool, list[float]] = {False: [], True: []}
            for _ in range(args.rounds):
                for parallel in (False, True):
                    times[parallel].append(per_call_us(nu, bodies, serial, parallel, calls))
            one, two = (statistics.median(times[p]) for p in (False, True))
            print(f"| {n} | {rows} | {one:.1f} | {two:.1f} | {one / two:.2f} |")


if __name__ == "__main__":
    main()
