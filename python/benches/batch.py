"""collide_batch against the copy floor, the Rust batch path and a vectorised NumPy peer.

    python python/benches/batch.py [--rows 1000000] [--dims 2 3] [--rounds 5]
        [--threads] [--validated] [--compare OTHER/_native.abi3.so]

On the same random contacts (both bodies free, float64, C-contiguous), in ns per contact,
medians with min-max over `rounds` alternated rounds: every round runs each contender once
in turn, so that a change of the shared machine's load hits them alike. Ratios are the
median (min-max) of the ratios within each round.

- `copy`, `copy new`: the copy floor, in Rust: every input element read once and every
  output element written once (each body's states copied from its input), into reused
  output arrays, or into new ones allocated as NumPy allocates a large array (anonymous
  `mmap` advised for huge pages), which pays the first touch of new pages as a call
  returning new arrays must;
- `np copy`, `np copy new`: the same floor written with NumPy (`np.copyto` into the reused
  arrays, `np.array(..., copy=True)` for new ones, all four returned together as
  `collide_batch` returns its outputs, `sum` of the rest);
- `kernel`: `Exec::free` alone on the rows already in its blocked layout;
- `steps`: the Rust batch path before issue 30: chunks of 512 rows gathered into a
  `FreeBatch` (`fill_from_rows`), run by `Exec::free`, scattered by `write_rows`;
- `rust rows`, `rust rows new`: the Rust batch path, `Exec::free_rows` (a few blocks at a
  time gathered, run and scattered, each step compiled for the run-time ISA), into reused
  outputs (the reference of `out=`) or new ones (the reference of new arrays);
- `out=`, `new`: `noslip.collide_batch(..., validate=False)` into reused arrays or
  returning new ones (the unvalidated path the targets are about);
- `numpy`: the closed form of docs/derivation.md section 8 written with NumPy array
  operations (checked against the package first), new arrays;
- `--validated`: `collide_batch` with validation (each row through `collide`), `out=`;
- `--compare`: another build's native module (e.g. the wheel before a change), its
  `collide_batch` timed in the same rounds (`before out=`, `before new`).

The default is one thread for everything, timed in CPU seconds of the calling thread
(CLOCK_THREAD_CPUTIME_ID: time.thread_time here, clock_gettime in Rust): on a shared, loaded
machine these move far less than the wall clock. `--threads` runs the package and the Rust
references on rayon's default pool instead (wall clock).
"""

from __future__ import annotations

import argparse
import importlib.machinery
import importlib.util
import time
from types import ModuleType
from typing import Any, Callable

import numpy as np

import noslip
from noslip.batch import _body_arrays, _parse_body, reference_seconds

Bodies = list[dict[str, np.ndarray]]


def contacts(rng: np.random.Generator, rows: int, n: int) -> tuple[np.ndarray, Bodies]:
    """Random approaching contacts of two free balls, one per row."""
    nu = rng.normal(size=(rows, n))
    nu /= np.linalg.norm(nu, axis=1, keepdims=True)
    bodies = []
    for _ in range(2):
        a = rng.uniform(-1, 1, size=(rows, n, n))
        bodies.append({
            "angular_velocity": a - a.transpose(0, 2, 1),
            "velocity": rng.uniform(-1, 1, size=(rows, n)),
            "inv_mass": rng.uniform(0.25, 4.0, size=rows),
            "radius": rng.uniform(0.5, 2.0, size=rows),
            "gamma2": rng.uniform(0.01, 2.0 / n, size=rows),
        })
    dn = np.einsum("ij,ij->i", bodies[1]["velocity"] - bodies[0]["velocity"], nu)
    nu[dn > 0] *= -1
    return nu, bodies


def numpy_peer(nu: np.ndarray, bodies: Bodies) -> tuple[dict[str, np.ndarray], ...]:
    """The closed form (docs/derivation.md section 8), vectorised over rows:
    c = R1 U1 nu + R2 U2 nu, d_n = (u2 - u1).nu, t = u2 - u1 - d_n nu - c,
    D = w1 g2 (1 + g1) + w2 g1 (1 + g2), P = d_n/(w1 + w2) nu + g1 g2/D t,
    u1+ = u1 + 2 w1 P, u2+ = u2 - 2 w2 P,
    U1+ = U1 + 2 w1 g2/(R1 D) nu^t, U2+ = U2 + 2 w2 g1/(R2 D) nu^t,
    with a^b = b a^T - a b^T (section 2)."""
    b1, b2 = bodies
    U1, U2 = b1["angular_velocity"], b2["angular_velocity"]
    u1, u2 = b1["velocity"], b2["velocity"]
    w1, w2 = b1["inv_mass"][:, None], b2["inv_mass"][:, None]
    R1, R2 = b1["radius"][:, None], b2["radius"][:, None]
    g1, g2 = b1["gamma2"][:, None], b2["gamma2"][:, None]
    c = R1 * np.einsum("rij,rj->ri", U1, nu) + R2 * np.einsum("rij,rj->ri", U2, nu)
    du = u2 - u1
    dn = np.einsum("ri,ri->r", du, nu)[:, None]
    t = du - dn * nu - c
    D = w1 * g2 * (1 + g1) + w2 * g1 * (1 + g2)
    P = dn / (w1 + w2) * nu + g1 * g2 / D * t
    wedge = t[:, :, None] * nu[:, None, :] - nu[:, :, None] * t[:, None, :]
    return (
        {"angular_velocity": U1 + (2 * w1 * g2 / (R1 * D))[:, :, None] * wedge,
         "velocity": u1 + 2 * w1 * P},
        {"angular_velocity": U2 + (2 * w2 * g1 / (R2 * D))[:, :, None] * wedge,
         "velocity": u2 - 2 * w2 * P},
    )


def numpy_copy(nu: np.ndarray, bodies: Bodies, out: Any = None) -> tuple[float, list[Any]]:
    """The copy floor in NumPy: the normals and parameters summed, each body's states copied
    into `out` (reused arrays) or into new arrays, which are returned, all four alive at
    once as `collide_batch`'s are (a copy dropped before the next is made lets glibc's
    `malloc` hand the same pages back at n = 2, where the arrays are under its 32 MiB `mmap`
    threshold, so that floor never paid the first touch `collide_batch` pays)."""
    total = float(nu.sum())
    new = []
    for b in range(2):
        for key in ("inv_mass", "radius", "gamma2"):
            total += float(bodies[b][key].sum())
        for key in ("angular_velocity", "velocity"):
            if out is None:
                new.append(np.array(bodies[b][key], copy=True))
            else:
                np.copyto(out[b][key], bodies[b][key])
    return total, new


def load_native(path: str) -> ModuleType:
    """Another build's native module (`_native.abi3.so`), under a name of its own."""
    loader = importlib.machinery.ExtensionFileLoader("_native", path)
    spec = importlib.util.spec_from_file_location("_native", path, loader=loader)
    assert spec is not None
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module


def summary(values: list[float], digits: int = 1) -> str:
    v = sorted(values)
    return f"{v[len(v) // 2]:.{digits}f} ({v[0]:.{digits}f}-{v[-1]:.{digits}f})"


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--rows", type=int, default=1_000_000)
    ap.add_argument("--dims", type=int, nargs="+", default=[2, 3])
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--threads", action="store_true")
    ap.add_argument("--validated", action="store_true")
    ap.add_argument("--compare", metavar="SO", help="another build's _native.abi3.so")
    args = ap.parse_args()
    parallel = args.threads
    clock = time.perf_counter if parallel else time.thread_time
    other = load_native(args.compare) if args.compare else None

    def seconds(f: Callable[[], Any]) -> float:
        t = clock()
        f()
        return clock() - t

    print(
        f"isa {noslip.isa()}, {args.rows} contacts, {args.rounds} alternated rounds, ns per "
        f"contact, median (min-max), "
        f"{'rayon threads, wall clock' if parallel else 'one thread, CPU time'}"
    )
    times = [
        "copy", "copy new", "np copy", "np copy new", "kernel", "steps", "rust rows",
        "rust rows new", "out=", "new",
    ]
    times += (["before out=", "before new"] if other else []) + ["numpy"]
    times += ["out=, validated"] if args.validated else []
    ratios = {
        "out= / np copy": ("out=", "np copy"),
        "new / np copy new": ("new", "np copy new"),
        "out= / copy": ("out=", "copy"),
        "new / copy new": ("new", "copy new"),
        "out= / rust rows": ("out=", "rust rows"),
        "new / rust rows new": ("new", "rust rows new"),
        "rust rows / copy": ("rust rows", "copy"),
        "numpy / copy": ("numpy", "copy"),
    }
    if other:
        ratios["out= / before out="] = ("out=", "before out=")
        ratios["new / before new"] = ("new", "before new")
    for n in args.dims:
        rng = np.random.default_rng(n)
        nu, bodies = contacts(rng, args.rows, n)
        # The peer is checked against the package first: both compute the same map, in other
        # operation orders, so they agree to rounding (values O(1): 1e-12 is ~5000 eps).
        k = min(args.rows, 10_000)
        sub = [{key: v[:k] for key, v in b.items()} for b in bodies]
        ours, peer = noslip.collide_batch(nu[:k], sub), numpy_peer(nu[:k], sub)
        for b in range(2):
            for key in ("angular_velocity", "velocity"):
                err = np.abs(ours[b][key] - peer[b][key]).max()
                assert err < 1e-12, (n, b, key, err)
        out = noslip.collide_batch(nu, bodies, validate=False)  # touched once, then reused
        batch = noslip.collide_batch
        t: dict[str, list[float]] = {key: [] for key in times}
        native_args = None
        if other:
            f64 = np.dtype(np.float64)
            rows, n_dim = nu.shape
            b1, b2 = (_body_arrays(_parse_body(bodies[b], b), b, f64, rows, n_dim, False)
                      for b in range(2))
            before_out = tuple(np.empty_like(out[b][key]) for b in range(2)
                               for key in ("angular_velocity", "velocity"))
            native_args = (nu, b1, b2)
            # The other build gives the same bits (both are the scalar kernel's).
            got = other.collide_batch_f64(nu, b1, b2, False, parallel)
            want = (out[0]["angular_velocity"], out[0]["velocity"],
                    out[1]["angular_velocity"], out[1]["velocity"])
            assert all(np.array_equal(g, w) for g, w in zip(got, want)), "builds differ"
        for _ in range(args.rounds):
            ref = reference_seconds(nu, bodies, 1, parallel)
            for key, name in [("copy", "copy"), ("copy_new", "copy new"), ("kernel", "kernel"),
                              ("steps", "steps"), ("rows", "rust rows"),
                              ("rows_new", "rust rows new")]:
                t[name] += ref[key]
            t["np copy"].append(seconds(lambda: numpy_copy(nu, bodies, out)))
            t["np copy new"].append(seconds(lambda: numpy_copy(nu, bodies)))
            t["out="].append(seconds(
                lambda: batch(nu, bodies, validate=False, parallel=parallel, out=out)))
            t["new"].append(seconds(lambda: batch(nu, bodies, validate=False, parallel=parallel)))
            if other and native_args:
                t["before out="].append(seconds(lambda: other.collide_batch_f64(
                    *native_args, False, parallel, before_out)))
                t["before new"].append(seconds(
                    lambda: other.collide_batch_f64(*native_args, False, parallel)))
            t["numpy"].append(seconds(lambda: numpy_peer(nu, bodies)))
            if args.validated:
                t["out=, validated"].append(
                    seconds(lambda: batch(nu, bodies, parallel=parallel, out=out)))
        ns = {key: [x * 1e9 / args.rows for x in v] for key, v in t.items()}
        print(f"\nn = {n}")
        print("| " + " | ".join(times) + " |")
        print("|" + "---:|" * len(times))
        print("| " + " | ".join(summary(ns[key]) for key in times) + " |")
        print("| " + " | ".join(ratios) + " |")
        print("|" + "---:|" * len(ratios))
        cells = [
            summary([a / b for a, b in zip(ns[num], ns[den])], 2) for num, den in ratios.values()
        ]
        print("| " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
