"""What a NumPy copy into new arrays pays for their first touch, by how long they live.

    python python/benches/first_touch.py [--rows 1000000] [--dims 2 3] [--rounds 7]

The four state arrays of `collide_batch`'s outputs at `--rows` rows, copied from inputs of
the same shapes, in ns per row (CPU time of this thread, page faults included), median
(min-max) over alternated rounds:

- `copyto`: into four arrays allocated once and reused (no first touch);
- `new, one at a time`: `np.array(x, copy=True)` of each input, each dropped before the
  next is made (the copy floor `batch.py` timed for new arrays until 5 December 2026);
- `new, held`: the same four copies alive together, then dropped, as a call that returns
  four new arrays makes them (the floor `batch.py` times now).

An array dropped before the next of the same size is made hands glibc's `malloc` back
pages it can reuse without mapping them again, where the array is under its `mmap`
threshold (32 MiB at most): at n = 2 (32 and 16 MB) `new, one at a time` costs what
`copyto` costs, `new, held` pays the first touch of 96 MB.
"""

from __future__ import annotations

import argparse
import time
from typing import Callable

import numpy as np


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--rows", type=int, default=1_000_000)
    ap.add_argument("--dims", type=int, nargs="+", default=[2, 3])
    ap.add_argument("--rounds", type=int, default=7)
    args = ap.parse_args()
    rows = args.rows
    for n in args.dims:
        rng = np.random.default_rng(n)
        src = [rng.random((rows, n, n)), rng.random((rows, n)),
               rng.random((rows, n, n)), rng.random((rows, n))]
        outs = [np.empty_like(x) for x in src]

        def copyto() -> None:
            for o, x in zip(outs, src):
                np.copyto(o, x)

        def one_at_a_time() -> None:
            for x in src:
                np.array(x, copy=True)

        def held() -> list[np.ndarray]:
            return [np.array(x, copy=True) for x in src]

        cases: dict[str, Callable[[], object]] = {
            "copyto": copyto, "new, one at a time": one_at_a_time, "new, held": held,
        }
        ns: dict[str, list[float]] = {k: [] for k in cases}
        for _ in range(args.rounds):
            for name, f in cases.items():
                t = time.thread_time()
                f()
                ns[name].append((time.thread_time() - t) * 1e9 / rows)
        for name, v in ns.items():
            v.sort()
            print(f"n = {n}, {name}: {v[len(v) // 2]:.1f} ({v[0]:.1f}-{v[-1]:.1f}) ns per row")


if __name__ == "__main__":
    main()
