"""noslip.sweep's arguments and store (issue 29): clear errors, points keyed by value, arrays
stored as arrays in Parquet parts that pandas, polars and Dask read without noslip, and the
sweep of docs/python.md run as a script."""

import re
import subprocess
import sys
from fractions import Fraction
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import noslip
from noslip.sweep import point_key

ROOT = Path(__file__).resolve().parents[2]


def square(x):
    return {"square": x * x}


@pytest.mark.parametrize(
    "kwargs,message",
    [
        ({"client": "local"}, r"^client: 'local' is not a client: give None"),
        ({"client": 3}, r"^client: expected None, \"serial\" or a dask.distributed.Client"),
        ({"grid": {}}, r"^grid: empty"),
        ({"grid": []}, r"^grid: empty"),
        ({"grid": {"x": []}}, r"^grid\['x'\]: no values"),
        ({"grid": {"x": 3}}, r"^grid\['x'\]: expected the parameter's values"),
        ({"grid": [3]}, r"^grid\[0\]: expected a mapping"),
        ({"points_per_task": 0}, r"^points_per_task: must be at least 1, got 0"),
        ({"points_per_task": -1}, r"^points_per_task: must be at least 1, got -1"),
        ({"points_per_task": 1.5}, r"^points_per_task: expected an int >= 1, got float"),
        ({"retries": -1}, r"^retries: must be at least 0, got -1"),
        ({"store": 3}, r"^store: expected a directory"),
        ({"function": 3}, r"^function: expected a callable, got int"),
    ],
)
def test_bad_arguments_are_named(kwargs, message):
    args = {"function": square, "grid": {"x": [1, 2]}, "client": "serial", **kwargs}
    with pytest.raises(noslip.InputError, match=message):
        noslip.sweep(**args)


@pytest.mark.parametrize(
    "function,grid",
    [
        (lambda x: {"m": np.zeros((2, 2))}, {"x": [1]}),  # a 2-D array
        (lambda x: {"big": 2**70}, {"x": [1]}),  # an int beyond 64 bits
        (square, {"x": [1 + 2j]}),  # a complex parameter
    ],
)
def test_what_parquet_cannot_hold_is_named_and_leaves_no_part(tmp_path, function, grid):
    """A result or parameter a Parquet column cannot hold is an InputError naming the store
    (they were pyarrow's and Python's own exceptions), and no part or temporary is left."""
    store = tmp_path / "store"
    with pytest.raises(noslip.InputError, match=r"^store: the rows of .* cannot be Parquet"):
        noslip.sweep(function, grid, client="serial", store=store)
    assert list(store.iterdir()) == []


def test_a_store_that_is_a_file_is_named(tmp_path):
    path = tmp_path / "file"
    path.write_text("not a store")
    with pytest.raises(noslip.InputError, match=r"^store: .* is a file"):
        noslip.sweep(square, {"x": [1]}, client="serial", store=path)
    assert path.read_text() == "not a store"


def test_points_are_keyed_by_value():
    assert point_key({"x": np.int64(1)}) == point_key({"x": 1}) == point_key({"x": 1.0})
    assert point_key({"x": np.float64(0.1)}) == point_key({"x": 0.1})
    # Floats by their exact value: float32's 0.1 is another number than float64's.
    assert point_key({"x": np.float32(0.1)}) != point_key({"x": 0.1})
    assert point_key({"x": np.float32(0.5)}) == point_key({"x": Fraction(1, 2)})
    assert point_key({"a": 1, "b": 2}) == point_key({"b": 2, "a": 1})
    assert point_key({"x": np.arange(3)}) == point_key({"x": [0, 1, 2]})
    assert point_key({"x": "1"}) != point_key({"x": 1})


def test_a_numpy_grid_and_the_same_python_grid_share_a_store(tmp_path):
    calls = []

    def counted(x, y):
        calls.append((x, y))
        return {"sum": float(x + y)}

    store = tmp_path / "store"
    first = noslip.sweep(counted, {"x": np.arange(3), "y": np.array([0.25, 0.5])},
                         client="serial", store=store)
    assert len(calls) == 6 and len(first) == 6
    calls.clear()
    again = noslip.sweep(counted, {"x": [0, 1, 2], "y": [0.25, 0.5]}, client="serial",
                         store=store)
    assert calls == []
    assert len(list(store.glob("part-*.parquet"))) == 1  # no duplicate parts
    assert list(again["sum"]) == list(first["sum"])


def spectrum(n):
    return {"values": np.arange(n, dtype=np.float64) / 3, "label": f"n={n}", "n2": n * n}


def test_arrays_are_stored_as_arrays_and_read_without_noslip(tmp_path):
    store = tmp_path / "store"
    frame = noslip.sweep(spectrum, {"n": [1, 2, 5]}, client="serial", store=store,
                         points_per_task=2)
    assert len(list(store.glob("part-*.parquet"))) == 2
    for n, values in zip(frame["n"], frame["values"]):
        assert isinstance(values, np.ndarray) and values.dtype == np.float64
        assert np.array_equal(values, np.arange(n) / 3)  # the same floats, bit for bit
    # Other readers, in a process without noslip: pandas, polars and Dask if installed.
    script = f"""
import sys, numpy as np
import pandas as pd
store = {str(store)!r}
frame = pd.read_parquet(store).sort_values("n")
assert list(frame["n"]) == [1, 2, 5], frame
assert np.array_equal(np.asarray(frame["values"].iloc[2], dtype=float), np.arange(5) / 3)
print("pandas", len(frame))
try:
    import polars as pl
except ImportError:
    pass
else:
    p = pl.read_parquet(store + "/*.parquet").sort("n")
    assert p["values"].to_list()[2] == (np.arange(5) / 3).tolist()
    print("polars", p.height)
try:
    import dask.dataframe as dd
except ImportError:
    pass
else:
    print("dask", len(dd.read_parquet(store).compute()))
assert "noslip" not in sys.modules
"""
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         cwd=tmp_path, check=False)
    assert out.returncode == 0, out.stderr
    counts = dict(line.split() for line in out.stdout.splitlines())
    assert counts["pandas"] == "3"
    assert all(v == "3" for v in counts.values()), counts


def test_the_docs_sweep_runs_as_a_script(tmp_path):
    """The sweep example of docs/python.md, as written there, run as a script: its local
    cluster's workers are spawned processes that import the script, and its
    ``if __name__ == "__main__":`` guard keeps them from sweeping too."""
    text = (ROOT / "docs" / "python.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    example = [b for b in blocks if "noslip.sweep(" in b and "__main__" in b]
    assert len(example) == 1, "docs/python.md has one sweep example with the guard"
    script = tmp_path / "sweep_example.py"
    script.write_text(example[0])
    out = subprocess.run([sys.executable, str(script)], capture_output=True, text=True,
                         cwd=tmp_path, timeout=600, check=False)
    assert out.returncode == 0, out.stderr[-3000:]
    stored = pd.read_parquet(tmp_path / "out" / "sweep" / "sinai")
    assert len(stored) == 12 and stored["lyapunov"].notna().all()
