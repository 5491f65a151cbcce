"""A sweep on Dask: the largest Lyapunov exponent of the no-slip Sinai table over
gamma^2 x obstacle radius, with a plot.

    python examples/python/sinai_sweep.py [--store out/sweep/sinai] [--scheduler ADDRESS]

Each grid point computes the largest Lyapunov exponent per unit time
(noslip.tables.sinai_lyapunov: tangent maps along the simulator's trajectory, QR, for a rough
disk of radius 1/20 in the periodic unit square with a fixed disk obstacle) as part of a Dask
task; results stream into the store, so a re-run computes only the points not there yet.
Without --scheduler a local cluster of processes (one worker per core) runs it; with it, the
cluster at that address (dask-jobqueue, Kubernetes, ...). The plot (needs matplotlib) is
written beside the store.
"""

import argparse
import importlib
from functools import partial
from pathlib import Path
from typing import Any

import numpy as np

import noslip
from noslip.tables import sinai_lyapunov


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--store", default="out/sweep/sinai")
    ap.add_argument("--scheduler", default=None)
    ap.add_argument("--events", type=int, default=20_000)
    args = ap.parse_args()

    grid = {
        "gamma2": np.linspace(0.0, 1.0, 9),
        "radius": np.linspace(0.05, 0.4, 8),
    }
    client: Any = None
    if args.scheduler:
        # dask.distributed and matplotlib are untyped: used through Any.
        distributed: Any = importlib.import_module("dask.distributed")
        client = distributed.Client(args.scheduler)
    exponent = partial(sinai_lyapunov, events=args.events)
    # Grid values as NumPy arrays are fine: points are keyed by value.
    frame = noslip.sweep(exponent, grid, client=client, store=args.store)
    table = frame.pivot(index="gamma2", columns="radius", values="lyapunov")
    print(table.round(3).to_string())
    try:
        matplotlib: Any = importlib.import_module("matplotlib")
        matplotlib.use("Agg")
        plt: Any = importlib.import_module("matplotlib.pyplot")
    except ImportError:
        print("matplotlib is not installed: no plot")
        return
    fig, ax = plt.subplots(figsize=(6, 4.5))
    image = ax.pcolormesh(table.columns, table.index, table.values, shading="nearest")
    ax.set_xlabel("obstacle radius")
    ax.set_ylabel("gamma^2 of the disk")
    ax.set_title("no-slip Sinai table: largest Lyapunov exponent per unit time")
    fig.colorbar(image, ax=ax)
    out = Path(args.store).with_suffix(".png")
    fig.savefig(out, dpi=120, bbox_inches="tight")
    print(f"wrote {out}")


# The guard keeps the local cluster's worker processes (started by spawn, which imports
# this file) from running the sweep themselves.
if __name__ == "__main__":
    main()
