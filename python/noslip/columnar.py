"""The Parquet outputs of ``noslip simulate``, read without text: :func:`read_log`,
:func:`read_boundary_map` and :func:`read_observables`.

``noslip simulate SCENE --log FILE.parquet --boundary-map FILE.parquet --observables DT``
writes the events log, the boundary map and (``observables.parquet`` in its output
directory) the granular observables as Apache Parquet (the crate ``noslip-columnar``): typed
columns, and in the file's metadata ``noslip.units`` (column name to unit: ``L`` the scene's length
unit, ``T`` its time unit, ``1`` none), ``noslip.table`` (what a row is) and ``noslip.dim``.
These functions return the table as a pandas DataFrame with those in ``DataFrame.attrs``.

pyarrow and pandas are imported on the first call (they are the ``sweep`` extra:
``pip install "noslip[sweep]"``); the base install stays NumPy only.
"""

from __future__ import annotations

import importlib
import json
import os
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["read_log", "read_boundary_map", "read_observables"]

#: A column each table has and the others have not: how a file is told apart.
_MARKS = {"events log": "ball_0", "boundary map": "coordinate", "observables": "T_tr"}

#: The function that reads each table.
_READERS = {
    "events log": "read_log",
    "boundary map": "read_boundary_map",
    "observables": "read_observables",
}


def _parquet() -> Any:
    """``pyarrow.parquet``, or an ``ImportError`` saying how to install it."""
    try:
        return importlib.import_module("pyarrow.parquet")
    except ImportError as e:
        raise ImportError(
            "reading noslip's Parquet outputs needs pyarrow and pandas: "
            'pip install "noslip[sweep]" (or pip install pyarrow pandas)'
        ) from e


def _read(path: str | os.PathLike[str], what: str) -> pd.DataFrame:
    """The table ``what`` in the Parquet file ``path``, with its metadata in ``attrs``."""
    if not isinstance(path, (str, os.PathLike)):
        raise TypeError(
            f"path: expected a file name (str or os.PathLike), got {type(path).__name__}"
        )
    pq = _parquet()
    name = os.fspath(path)
    try:
        table = pq.read_table(name)
    except FileNotFoundError:
        raise
    except Exception as e:  # pyarrow's errors: not Parquet, truncated, ...
        raise ValueError(f"path: {name} is not a readable Parquet file: {e}") from e
    meta = {
        k.decode(): v.decode() for k, v in (table.schema.metadata or {}).items()
    }
    columns = set(table.column_names)
    if "noslip.units" not in meta or _MARKS[what] not in columns:
        other = next(
            (o for o, mark in _MARKS.items() if "noslip.units" in meta and mark in columns),
            None,
        )
        hint = (
            f" (it is a noslip {other}: read it with noslip.{_READERS[other]})" if other else ""
        )
        raise ValueError(f"path: {name} is not a noslip {what} written by noslip simulate{hint}")
    frame: pd.DataFrame = table.to_pandas()
    frame.attrs["units"] = json.loads(meta["noslip.units"])
    frame.attrs["table"] = meta.get("noslip.table", "")
    frame.attrs["dim"] = int(meta.get("noslip.dim", "0"))
    return frame


def read_log(path: str | os.PathLike[str]) -> pd.DataFrame:
    """Read the events log ``noslip simulate --log FILE.parquet`` wrote.

    Parameters
    ----------
    path : str or os.PathLike
        The Parquet file.

    Returns
    -------
    pandas.DataFrame
        One row per contact, the JSON lines log's fields as typed columns: ``event``
        (from 1), ``time``, ``kind`` (``ball-ball``, ``ball-wall``, ``ball-obstacle``,
        ``ball-boundary``), ``ball_0``, ``ball_1``, ``axis``, ``side``, ``obstacle``,
        ``boundary`` (missing where they do not apply), ``nu_k``, ``position_b_k``,
        ``pre_b_spin_j``, ``pre_b_velocity_k``, ``post_b_spin_j``, ``post_b_velocity_k``
        (``b`` the slot, 0 or 1; slot 1 missing unless ball-ball). ``attrs["units"]`` maps
        each column to its unit, ``attrs["dim"]`` is ``n``, ``attrs["table"]`` says what a
        row is.

    Raises
    ------
    ImportError
        pyarrow or pandas is not installed.
    FileNotFoundError
        No such file.
    ValueError
        The file is not Parquet, or not an events log of ``noslip simulate`` (the message
        names ``path``).

    Examples
    --------
    >>> log = noslip.read_log("out/sinai/events.parquet")  # doctest: +SKIP
    >>> log["time"].to_numpy(), log.attrs["units"]["time"]  # doctest: +SKIP
    """
    return _read(path, "events log")


def read_boundary_map(path: str | os.PathLike[str]) -> pd.DataFrame:
    """Read the boundary map ``noslip simulate --boundary-map FILE.parquet`` wrote.

    Parameters
    ----------
    path : str or os.PathLike
        The Parquet file.

    Returns
    -------
    pandas.DataFrame
        One row per contact of a ball with an immovable body, the CSV's columns typed:
        ``event``, ``time``, ``ball``, ``kind``, ``id``, ``q0`` .. ``q{n-1}``,
        ``coordinate``, ``incidence``, ``reflection``, ``normal_velocity``,
        ``tangential_velocity``, ``tangential_velocity_post``, ``spin``, ``spin_post``,
        ``scaled_spin``, ``scaled_spin_post`` (``docs/tables.md``). ``attrs`` as
        :func:`read_log`'s.

    Raises
    ------
    ImportError
        pyarrow or pandas is not installed.
    FileNotFoundError
        No such file.
    ValueError
        The file is not Parquet, or not a boundary map of ``noslip simulate`` (the message
        names ``path``).
    """
    return _read(path, "boundary map")


def read_observables(path: str | os.PathLike[str]) -> pd.DataFrame:
    """Read the granular observables ``noslip simulate --observables DT`` wrote.

    Parameters
    ----------
    path : str or os.PathLike
        The Parquet file, ``observables.parquet`` in the run's output directory.

    Returns
    -------
    pandas.DataFrame
        One row per sample, the CSV's columns typed: ``time``, ``contacts`` (int64),
        ``T_tr``, ``T_rot``, ``energy``, ``collision_frequency``, ``lost_ball_ball``,
        ``lost_ball_wall``, ``lost_ball_obstacle``, ``lost_ball_boundary``, ``injected``, ``pressure``,
        ``a2``, ``msd``, ``msd_cm`` and, in a mixture, ``T_tr_s``, ``T_rot_s`` and
        ``msd_cm_s`` per species, ``lost_ball_ball_A-B`` and ``contacts_A-B`` (int64) per pair
        of species (``docs/granular.md``; the same as :attr:`SimulationResult.observables`).
        ``attrs`` as :func:`read_log`'s (units in the scene's ``M``, ``L``, ``T``).

    Raises
    ------
    ImportError
        pyarrow or pandas is not installed.
    FileNotFoundError
        No such file.
    ValueError
        The file is not Parquet, or not observables of ``noslip simulate`` (the message
        names ``path``).
    """
    return _read(path, "observables")
