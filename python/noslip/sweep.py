"""Parameter sweeps on Dask: :func:`sweep`."""

from __future__ import annotations

import hashlib
import importlib
import itertools
import json
import math
import numbers
import os
from fractions import Fraction
from pathlib import Path
from typing import (
    TYPE_CHECKING,
    Any,
    Callable,
    Dict,
    Iterable,
    List,
    Mapping,
    Optional,
    Sequence,
    TypeVar,
    Union,
)

import numpy as np

from noslip._args import is_integer, is_real
from noslip._native import InputError

if TYPE_CHECKING:
    import pandas as pd

T = TypeVar("T")

__all__ = ["sweep", "grid_points", "point_key"]

#: The column of a store that identifies a grid point (its parameters keyed by value).
POINT = "_point"

Grid = Union[Mapping[str, Iterable[Any]], Sequence[Mapping[str, Any]]]
Row = Dict[str, Any]


def grid_points(grid: Grid) -> List[Dict[str, Any]]:
    """The points of a grid: the Cartesian product of a mapping ``name -> values`` (the last
    name varying fastest), or a sequence of points (mappings ``name -> value``) as given.

    Raises
    ------
    InputError
        A grid that is not one of these, has no point, or names a parameter with no value
        (naming ``grid`` or ``grid[name]``).
    """
    if isinstance(grid, Mapping):
        if not grid:
            raise InputError("grid: empty: give at least one parameter and its values")
        names = list(grid)
        values = []
        for name in names:
            if not isinstance(name, str):
                raise InputError(f"grid: parameter names must be strings, got {name!r}")
            v = grid[name]
            if isinstance(v, (str, bytes)) or not isinstance(v, Iterable):
                raise InputError(
                    f"grid[{name!r}]: expected the parameter's values (a list or an array), "
                    f"got {type(v).__name__}"
                )
            v = list(v)
            if not v:
                raise InputError(f"grid[{name!r}]: no values (the grid would have no point)")
            values.append(v)
        return [dict(zip(names, point)) for point in itertools.product(*values)]
    if isinstance(grid, (str, bytes)) or not isinstance(grid, Sequence):
        raise InputError(
            "grid: expected a mapping name -> values or a sequence of points, got "
            f"{type(grid).__name__}"
        )
    if not grid:
        raise InputError("grid: empty: give at least one point")
    points = []
    for i, p in enumerate(grid):
        if not isinstance(p, Mapping):
            raise InputError(f"grid[{i}]: expected a mapping name -> value, got {type(p).__name__}")
        points.append(dict(p))
    return points


def _value_key(x: Any) -> str:
    """A parameter value as text that is equal for equal values: numbers by their exact
    value (``1``, ``1.0``, ``np.int64(1)`` and ``np.float64(1.0)`` alike; ``0.1`` and
    ``np.float32(0.1)`` differ, as their values do), sequences and arrays element by
    element, strings and others by their JSON or ``repr`` text."""
    if x is None or isinstance(x, (bool, np.bool_, str)):
        return json.dumps(x.item() if isinstance(x, np.bool_) else x)
    if isinstance(x, np.integer):
        return str(int(x))
    if isinstance(x, numbers.Rational):
        return str(Fraction(int(x.numerator), int(x.denominator)))
    if isinstance(x, (float, np.floating)):
        if math.isfinite(x):
            p, q = x.as_integer_ratio()
            return str(Fraction(int(p), int(q)))
        return repr(float(x))
    if isinstance(x, np.ndarray):
        return "[" + ",".join(_value_key(v) for v in x.tolist()) + "]"
    if isinstance(x, (list, tuple)):
        return "[" + ",".join(_value_key(v) for v in x) + "]"
    return f"{type(x).__name__}:{x!r}"


def point_key(point: Mapping[str, Any]) -> str:
    """The key of a grid point in a store: its parameters sorted by name, each keyed by value
    (see :func:`_value_key`), so a grid from ``np.arange`` and the same grid of Python ints
    are the same points."""
    return "{" + ",".join(f"{json.dumps(k)}:{_value_key(point[k])}" for k in sorted(point)) + "}"


def run_points(function: Callable[..., Any], points: Sequence[Mapping[str, Any]]) -> List[Row]:
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
        rows.append({POINT: point_key(point), **point, **result})
    return rows


def parameter_types(points: Sequence[Mapping[str, Any]]) -> Dict[str, "np.dtype[Any]"]:
    """The column type of each parameter over the whole grid, so that every part of a store
    has the same schema (a reader of the directory unifies them): ``int64`` when every value
    is an int, ``float64`` when every value is a real number (ints mixed with floats: the
    docs' ``[0, 0.25, 0.5, 1]``), nothing for others (kept as pandas infers them)."""
    types: Dict[str, "np.dtype[Any]"] = {}
    names = {k for p in points for k in p}
    for name in names:
        values = [p.get(name) for p in points]
        if all(is_integer(v) for v in values):
            types[name] = np.dtype(np.int64)
        elif all(is_real(v) for v in values):
            types[name] = np.dtype(np.float64)
    return types


def _write_part(store: Path, rows: List[Row], types: Mapping[str, "np.dtype[Any]"]) -> None:
    """Write one task's rows as ``part-<hash>.parquet`` (pyarrow: typed columns, the
    parameters in the grid's ``types``, arrays as list columns), atomically (a hidden
    temporary file renamed into place, which Parquet readers of the directory skip): a
    part is in the store whole or not at all."""
    import pandas as pd

    name = hashlib.sha1("\n".join(r[POINT] for r in rows).encode()).hexdigest()[:16]
    tmp = store / f".part-{name}.{os.getpid()}.tmp"
    try:
        frame = pd.DataFrame(rows)
        for column, dtype in types.items():
            if column in frame:
                frame[column] = frame[column].astype(dtype)
        frame.to_parquet(tmp, engine="pyarrow", index=False)
    except (ValueError, TypeError, OverflowError, NotImplementedError) as e:
        # pyarrow's ArrowInvalid (a 2-D array), ArrowNotImplementedError (a complex value),
        # an int beyond 64 bits: what a Parquet column cannot hold, named with the store.
        tmp.unlink(missing_ok=True)
        raise InputError(
            f"store: the rows of {rows[0][POINT]} ... cannot be Parquet columns: {e} (a result "
            "or parameter must be a number, a string, a bool or a 1-D array of them)"
        ) from None
    os.replace(tmp, store / f"part-{name}.parquet")


def _read_store(store: Path) -> Optional["pd.DataFrame"]:
    import pandas as pd

    parts = sorted(store.glob("part-*.parquet"))
    if not parts:
        return None
    frames = [pd.read_parquet(p, engine="pyarrow") for p in parts]
    return pd.concat(frames, ignore_index=True).drop_duplicates(POINT, keep="first")


def _batches(todo: List[T], size: int) -> List[List[T]]:
    return [todo[i : i + size] for i in range(0, len(todo), size)]


def _check_arguments(
    function: Any, client: Any, store: Any, points_per_task: Any, retries: Any
) -> None:
    """The arguments of :func:`sweep` other than the grid, each refused with an
    :class:`InputError` naming it."""
    if not callable(function):
        raise InputError(f"function: expected a callable, got {type(function).__name__}")
    if isinstance(client, str) and client != "serial":
        raise InputError(
            f"client: {client!r} is not a client: give None (a local cluster of processes "
            "for this call), \"serial\" (this process, no Dask) or a dask.distributed.Client"
        )
    if client is not None and not isinstance(client, str) and not hasattr(client, "submit"):
        raise InputError(
            f"client: expected None, \"serial\" or a dask.distributed.Client, got "
            f"{type(client).__name__}"
        )
    if store is not None and not isinstance(store, (str, os.PathLike)):
        raise InputError(
            f"store: expected a directory (str or os.PathLike), got {type(store).__name__}"
        )
    for name, value, least in (("points_per_task", points_per_task, 1), ("retries", retries, 0)):
        if value is None and name == "points_per_task":
            continue
        if not is_integer(value):
            raise InputError(f"{name}: expected an int >= {least}, got {type(value).__name__}")
        if value < least:
            raise InputError(f"{name}: must be at least {least}, got {value}")


def sweep(
    function: Callable[..., Any],
    grid: Grid,
    client: Any = None,
    store: Union[str, "os.PathLike[str]", None] = None,
    *,
    points_per_task: Optional[int] = None,
    retries: int = 2,
) -> "pd.DataFrame":
    """Run ``function(**point)`` over every point of ``grid`` as Dask tasks.

    Several grid points form one task (``points_per_task``; by default about four tasks per
    worker, at most 64 points each). With ``store``, each task's rows are written to
    ``store/part-<hash>.parquet`` as soon as the task completes (by this process,
    atomically), so a re-run with the same store computes only the points not there yet,
    and a lost worker or an interrupted sweep loses no finished result; Dask recomputes the
    tasks a lost worker held.

    Points are the same when their parameters are equal by value: ``np.arange(3)`` and
    ``[0, 1, 2]`` give the same points, as do ``1`` and ``1.0``; floats are compared by their
    exact binary value (``np.float32(0.1)`` is not ``0.1``).

    The store is a directory of Parquet files (pyarrow), one per task: typed columns, the
    parameters, the results (an array result as a list column, read back as an array) and
    ``_point``, the point's key. Any Parquet reader reads it whole, without noslip:
    ``pandas.read_parquet(store)``, ``polars.read_parquet(f"{store}/*.parquet")``,
    ``dask.dataframe.read_parquet(store)``.

    Parameters
    ----------
    function : callable
        Called as ``function(**point)`` on a worker; returns a mapping ``name -> value`` (a
        number, a string or an array), or a value, stored as ``value``. It must be
        deterministic for re-runs to be meaningful, and picklable (a module-level function;
        Dask's cloudpickle also ships a user's functions by value).
    grid : mapping or sequence
        ``{"gamma2": [...], "radius": [...]}`` (the Cartesian product, see
        :func:`grid_points`) or a sequence of points.
    client : dask.distributed.Client, "serial" or None
        A user's client runs the tasks on their cluster unchanged (LocalCluster,
        dask-jobqueue on SLURM, Kubernetes, ...). ``None`` starts a local cluster of
        processes, one single-threaded worker per core, for this call: in a script, call
        ``sweep`` under ``if __name__ == "__main__":``, since the workers are spawned
        processes that import the script's module. ``"serial"`` runs the points in this
        process, without Dask.
    store : str or os.PathLike, optional
        A directory for the results (created if missing).
    points_per_task : int, optional
        Grid points per task (at least 1).
    retries : int
        How many times Dask retries a failed task (at least 0).

    Returns
    -------
    pandas.DataFrame
        One row per grid point, in grid order: the parameters, then the results (named,
        typed columns, ready for ``pivot`` and plots; with a store it is read back from the
        store, so a fresh and a resumed sweep give the same frame).

    Raises
    ------
    InputError
        A bad argument, naming it: ``client="local"``, an empty grid or a parameter without
        values, ``points_per_task`` below 1, a store that is not a path, ...
    """
    import pandas as pd

    _check_arguments(function, client, store, points_per_task, retries)
    points = grid_points(grid)
    keys = [point_key(p) for p in points]
    types = parameter_types(points)
    path = Path(store) if store is not None else None
    if path is not None:
        if path.exists() and not path.is_dir():
            raise InputError(f"store: {path} is a file; the store is a directory of parts")
        path.mkdir(parents=True, exist_ok=True)
        stored = _read_store(path)
        finished = set(stored[POINT]) if stored is not None else set()
    else:
        finished = set()
    todo = [p for p, k in zip(points, keys) if k not in finished]
    rows: List[Row] = []

    def completed(task_rows: List[Row]) -> None:
        if path is not None:
            _write_part(path, task_rows, types)
        else:
            rows.extend(task_rows)

    if todo and client == "serial":
        size = points_per_task or len(todo)
        for batch in _batches(todo, size):
            completed(run_points(function, batch))
    elif todo:
        # dask.distributed is untyped (its stubs vary by version): used through Any.
        distributed: Any = importlib.import_module("dask.distributed")

        own = client is None
        cluster = None
        if own:
            cluster = distributed.LocalCluster(
                n_workers=os.cpu_count() or 1, threads_per_worker=1, processes=True
            )
            client = distributed.Client(cluster)
        try:
            workers = max(1, len(client.scheduler_info().get("workers", {})))
            size = points_per_task or min(64, max(1, math.ceil(len(todo) / (4 * workers))))
            futures = [
                client.submit(run_points, function, batch, pure=False, retries=retries)
                for batch in _batches(todo, size)
            ]
            for future in distributed.as_completed(futures):
                completed(future.result())
                future.release()
        finally:
            if own:
                client.close()
                if cluster is not None:
                    cluster.close()

    if path is not None:
        stored = _read_store(path)
        if stored is None:
            return pd.DataFrame()
        frame = stored
    else:
        frame = pd.DataFrame(rows)
        for column, dtype in types.items():
            if column in frame:
                frame[column] = frame[column].astype(dtype)
    order = {k: i for i, k in enumerate(keys)}
    frame = frame[frame[POINT].isin(list(order))].copy()
    frame["_order"] = frame[POINT].map(order)
    frame = frame.sort_values("_order").drop(columns=["_order", POINT])
    return frame.reset_index(drop=True)
