"""collide_batch against the Rust batch kernel and a vectorised NumPy peer, side by side.

    python python/benches/batch.py [--rows 1000000] [--dims 3] [--repeats 7] [--threads]

On the same random contacts (both bodies free, float64, C-contiguous), in ns per contact,
the median of `repeats` rounds, each round running every contender once in turn (so that a
change of the machine's load hits them alike):
- `rust rows`: the reference, the Rust batch kernel from the same row-major arrays into
  row-major outputs through collision-core's batch API (fill_from_rows, Exec::free,
  write_rows, chunks of 512 rows), timed in Rust (noslip.batch.reference_seconds); its
  outputs are allocated once and reused (`rust rows`, the reference of `out=`) or new on
  each run, allocated as NumPy allocates a large array (`rust rows, new`: the reference of
  new arrays, paying the same first touch);
- `copy floor`: every input element read once and every output element written once, in
  Rust (no implementation on these arrays can do with less memory traffic);
- `rust kernel`: Exec::free alone on the rows already in its blocked layout (the floor: the
  row-major arrays neither read nor written);
- `collide_batch`: noslip.collide_batch on the NumPy arrays, into new arrays (which it must
  allocate and touch for the first time) and into reused arrays (`out=`, as the reference),
  each without and with validation (the default);
- `numpy`: the closed form of docs/derivation.md section 8 written with NumPy array
  operations (checked against the package first), new arrays as collide_batch's default.

The default is one thread for everything, timed in CPU seconds of the calling thread
(CLOCK_THREAD_CPUTIME_ID: time.thread_time here, clock_gettime in Rust): on a shared, loaded machine
these move far less than the wall clock. `--threads` runs the package and the reference on
rayon's default pool instead (wall clock) and adds the time of two Python threads each
running a serial batch on half the rows over the same two calls in sequence (the GIL is
released: about 0.5 with two free cores).
"""

from __future__ import annotations

import argparse
import threading
import time

import numpy as np

import noslip
from noslip.batch import reference_seconds


def contacts(rng, rows, n):
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


def numpy_peer(nu, bodies):
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


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rows", type=int, default=1_000_000)
    ap.add_argument("--dims", type=int, nargs="+", default=[3])
    ap.add_argument("--repeats", type=int, default=7)
    ap.add_argument("--threads", action="store_true")
    args = ap.parse_args()
    parallel = args.threads
    clock = time.perf_counter if parallel else time.thread_time

    def seconds(f):
        t = clock()
        f()
        return clock() - t

    print(
        f"isa {noslip.isa()}, {args.rows} contacts, median of {args.repeats} rounds, "
        f"ns per contact, {'rayon threads, wall clock' if parallel else 'one thread, CPU time'}"
    )
    head = [
        "n", "copy floor", "rust kernel", "rust rows", "rust rows, new", "new", "new, validated",
        "out=", "out=, validated", "numpy peer", "out=, validated / rust rows",
        "new, validated / rust rows, new",
        "numpy / new, validated", "numpy / copy floor",
    ] + (["2 threads / sequential"] if parallel else [])
    print("| " + " | ".join(head) + " |")
    print("|" + "---:|" * len(head))
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
        out = noslip.collide_batch(nu, bodies)  # allocated and touched once, then reused
        half = [{key: v[: args.rows // 2] for key, v in b.items()} for b in bodies]

        def run_half():
            noslip.collide_batch(nu[: args.rows // 2], half, validate=False, parallel=False)

        def sequential():
            run_half()
            run_half()

        def threaded():
            ts = [threading.Thread(target=run_half) for _ in range(2)]
            for th in ts:
                th.start()
            for th in ts:
                th.join()

        keys = (
            "copy", "rows", "rows_new", "kernel", "new", "new_v", "out", "out_v", "numpy",
            "seq", "thr",
        )
        t = {key: [] for key in keys}
        batch = noslip.collide_batch
        for _ in range(args.repeats):
            ref = reference_seconds(nu, bodies, 1, parallel)
            t["rows"] += ref["rows"]
            t["rows_new"] += ref["rows_new"]
            t["kernel"] += ref["kernel"]
            t["copy"] += ref["copy"]
            t["new"].append(seconds(lambda: batch(nu, bodies, validate=False, parallel=parallel)))
            t["new_v"].append(seconds(lambda: batch(nu, bodies, parallel=parallel)))
            t["out"].append(
                seconds(lambda: batch(nu, bodies, validate=False, parallel=parallel, out=out))
            )
            t["out_v"].append(seconds(lambda: batch(nu, bodies, parallel=parallel, out=out)))
            t["numpy"].append(seconds(lambda: numpy_peer(nu, bodies)))
            if parallel:
                t["seq"].append(seconds(sequential))
                t["thr"].append(seconds(threaded))
        m = {key: float(np.median(v)) * 1e9 / args.rows for key, v in t.items() if v}
        cells = [
            f"{n}", f"{m['copy']:.1f}", f"{m['kernel']:.1f}", f"{m['rows']:.1f}",
            f"{m['rows_new']:.1f}",
            f"{m['new']:.1f}",
            f"{m['new_v']:.1f}", f"{m['out']:.1f}", f"{m['out_v']:.1f}", f"{m['numpy']:.0f}",
            f"{m['out_v'] / m['rows']:.2f}", f"{m['new_v'] / m['rows_new']:.2f}",
            f"{m['numpy'] / m['new_v']:.1f}", f"{m['numpy'] / m['copy']:.1f}",
        ] + ([f"{m['thr'] / m['seq']:.2f}"] if parallel else [])
        print("| " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
