"""Parameter sweeps on Dask: :func:`sweep`."""

from __future__ import annotations

import hashlib
import itertools
import json
import math
import os
from pathlib import Path
from typing import Any, Callable, Iterable, Mapping, Sequence, Union

__all__ = ["sweep", "grid_points"]

#: The column of a store that identifies a grid point (its parameters as sorted JSON).
POINT = "_point"

Grid = Union[Mapping[str, Iterable[Any]], Sequence[Mapping[str, Any]]]


def grid_points(grid: Grid) -> list[dict[str, Any]]:
    """The points of a grid: the Cartesian product of a mapping ``name -> values`` (the last
    name varying fastest), or a sequence of points (mappings ``name -> value``) as given."""
    if isinstance(grid, Mapping):
        names = list(grid)
        return [dict(zip(names, values)) for values in itertools.product(*grid.values())]
    return [dict(p) for p in grid]


def _key(point: Mapping[str, Any]) -> str:
    return json.dumps(point, sort_keys=True, default=str)


def run_points(function: Callable[..., Any], points: Sequence[Mapping[str, Any]]) -> list[dict]:
    """One task: ``function(**point)`` for each point; a row per point with the parameters,
    the results (a mapping's items, or ``value``) and the point's key."""
    rows = []
    for point in points:
        result = function(**point)
        if not isinstance(result, Mapping):
            result = {"value": result}
        clash = set(result) & (set(point) | {POINT})
        if clash:
            raise ValueError(f"result names {sorted(clash)} clash with the parameters")
        rows.append({POINT: _key(point), **point, **result})
    return rows


def _write_part(store: Path, rows: list[dict]) -> None:
    """Write one task's rows as ``part-<hash>.csv``, atomically (a temporary file renamed
    into place): a part is in the store whole or not at all."""
    import pandas as pd

    name = hashlib.sha1("\n".join(r[POINT] for r in rows).encode()).hexdigest()[:16]
    tmp = store / f".part-{name}.{os.getpid()}.tmp"
    pd.DataFrame(rows).to_csv(tmp, index=False)
    os.replace(tmp, store / f"part-{name}.csv")


def _read_store(store: Path):
    import pandas as pd

    parts = sorted(store.glob("part-*.csv"))
    if not parts:
        return None
    # Floats are written by repr and must read back as the same float: pandas before 3
    # rounds unless asked for "round_trip" (pandas 3 reads round-trip by default).
    exact = {"float_precision": "round_trip"} if int(pd.__version__.split(".")[0]) < 3 else {}
    frames = [pd.read_csv(p, keep_default_na=False, na_values=[""], **exact) for p in parts]
    return pd.concat(frames, ignore_index=True).drop_duplicates(POINT, keep="first")


def _batches(todo: list, size: int) -> list[list]:
    return [todo[i : i + size] for i in range(0, len(todo), size)]


def sweep(
    function: Callable[..., Any],
    grid: Grid,
    client: Any = None,
    store: str | os.PathLike | None = None,
    *,
    points_per_task: int | None = None,
    retries: int = 2,
):
    """Run ``function(**point)`` over every point of ``grid`` as Dask tasks.

    Several grid points form one task (``points_per_task``; by default about four tasks per
    worker, at most 64 points each). With ``store``, each task's rows are written to
    ``store/part-<hash>.csv`` as soon as the task completes (by this process, atomically), so
    a re-run with the same store computes only the points not there yet, and a lost worker
    or an interrupted sweep loses no finished result; Dask recomputes the tasks a lost worker
    held.

    Parameters
    ----------
    function : callable
        Called as ``function(**point)`` on a worker; returns a mapping ``name -> scalar`` (or
        a scalar, stored as ``value``). It must be deterministic for re-runs to be
        meaningful, and picklable (a module-level function; Dask's cloudpickle also ships a
        user's functions by value).
    grid : mapping or sequence
        ``{"gamma2": [...], "radius": [...]}`` (the Cartesian product, see
        :func:`grid_points`) or a sequence of points.
    client : dask.distributed.Client, "serial" or None
        A user's client runs the tasks on their cluster unchanged (LocalCluster,
        dask-jobqueue on SLURM, Kubernetes, ...). ``None`` starts a local cluster of
        processes, one single-threaded worker per core, for this call. ``"serial"`` runs the
        points in this process, without Dask.
    store : path, optional
        A directory for the results (created if missing).

    Returns
    -------
    pandas.DataFrame
        One row per grid point, in grid order: the parameters, then the results (a
        DataFrame: named, typed columns of parameters and results, ready for ``pivot`` and
        plots; with a store it is read back from the store, so a fresh and a resumed sweep
        give the same frame).
    """
    import pandas as pd

    points = grid_points(grid)
    keys = [_key(p) for p in points]
    path = Path(store) if store is not None else None
    if path is not None:
        path.mkdir(parents=True, exist_ok=True)
        stored = _read_store(path)
        finished = set(stored[POINT]) if stored is not None else set()
    else:
        finished = set()
    todo = [p for p, k in zip(points, keys) if k not in finished]
    rows: list[dict] = []

    def completed(task_rows: list[dict]) -> None:
        if path is not None:
            _write_part(path, task_rows)
        else:
            rows.extend(task_rows)

    if todo and client == "serial":
        size = points_per_task or len(todo)
        for batch in _batches(todo, size):
            completed(run_points(function, batch))
    elif todo:
        from dask.distributed import Client, LocalCluster, as_completed

        own = client is None
        if own:
            cluster = LocalCluster(
                n_workers=os.cpu_count() or 1, threads_per_worker=1, processes=True
            )
            client = Client(cluster)
        try:
            workers = max(1, len(client.scheduler_info().get("workers", {})))
            size = points_per_task or min(64, max(1, math.ceil(len(todo) / (4 * workers))))
            futures = [
                client.submit(run_points, function, batch, pure=False, retries=retries)
                for batch in _batches(todo, size)
            ]
            for future in as_completed(futures):
                completed(future.result())
                future.release()
        finally:
            if own:
                client.close()
                cluster.close()

    if path is not None:
        frame = _read_store(path)
        if frame is None:
            return pd.DataFrame()
    else:
        frame = pd.DataFrame(rows)
    order = {k: i for i, k in enumerate(keys)}
    frame = frame[frame[POINT].isin(order)].copy()
    frame["_order"] = frame[POINT].map(order)
    frame = frame.sort_values("_order").drop(columns=["_order", POINT])
    return frame.reset_index(drop=True)
