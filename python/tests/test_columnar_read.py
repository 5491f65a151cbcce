"""``noslip.read_log`` and ``noslip.read_boundary_map``: the Parquet files ``noslip
simulate`` writes, read back as DataFrames, hold exactly the values of the JSON lines log and
the CSV boundary map of the same (deterministic) run; units come from the file's metadata;
bad input raises naming ``path``; pyarrow is imported only when a file is read."""

from __future__ import annotations

import csv
import json
import math
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

import noslip
from conftest import run_cli

ROOT = Path(__file__).resolve().parents[2]


def run(cli: Path, scene: str, out: Path, log: str, bmap: str) -> None:
    """Run ``scene`` for 400 contacts, the log and the map into ``out``."""
    run_cli(
        cli,
        "simulate",
        str(ROOT / "scenes" / scene),
        "--quiet",
        "--events",
        "400",
        "--out",
        str(out),
        "--log",
        str(out / log),
        "--boundary-map",
        str(out / bmap),
    )


@pytest.fixture(scope="module", params=["sinai.toml", "gas2d.toml", "cube3d.toml"])
def outputs(
    request: pytest.FixtureRequest, cli: Path, tmp_path_factory: pytest.TempPathFactory
) -> tuple[Path, Path]:
    """One run of a scene written as text and, again, as Parquet."""
    scene = str(request.param)
    text = tmp_path_factory.mktemp("text")
    columnar = tmp_path_factory.mktemp("parquet")
    run(cli, scene, text, "events.jsonl", "boundary-map.csv")
    run(cli, scene, columnar, "events.parquet", "boundary-map.parquet")
    return text, columnar


def same(a: Any, b: Any) -> bool:
    """Equal values, a missing value (None, NaN) equal only to another."""
    missing = [x is None or (isinstance(x, float) and math.isnan(x)) for x in (a, b)]
    if any(missing):
        return all(missing)
    return bool(a == b)


def test_log_equals_the_json_lines(outputs: tuple[Path, Path]) -> None:
    text, columnar = outputs
    lines = [json.loads(x) for x in (text / "events.jsonl").read_text().splitlines()]
    log = noslip.read_log(columnar / "events.parquet")
    assert len(log) == len(lines) == 400
    n = log.attrs["dim"]
    s = n * (n - 1) // 2
    for row, e in zip(log.to_dict("records"), lines):
        balls = e["balls"] + [None]
        expected: dict[str, Any] = {
            "event": e["event"],
            "time": e["time"],
            "kind": e["kind"],
            "ball_0": balls[0],
            "ball_1": balls[1],
            "axis": e.get("axis"),
            "side": e.get("side"),
            "obstacle": e.get("obstacle"),
            "boundary": e.get("boundary"),
        }
        expected.update({f"nu_{k}": e["nu"][k] for k in range(n)})
        for b in range(2):
            has = b < len(e["positions"])
            for k in range(n):
                expected[f"position_{b}_{k}"] = e["positions"][b][k] if has else None
            for when in ("pre", "post"):
                for j in range(s):
                    expected[f"{when}_{b}_spin_{j}"] = e[when][b]["spin"][j] if has else None
                for k in range(n):
                    expected[f"{when}_{b}_velocity_{k}"] = (
                        e[when][b]["velocity"][k] if has else None
                    )
        # A thermostat's kick columns, null on a contact's row (no thermostat here).
        expected.update({"kick": None, "energy_injected": None})
        assert set(row) == set(expected)
        for key, value in expected.items():
            assert same(row[key], value), (key, row[key], value)
    units = log.attrs["units"]
    assert units["time"] == "T" and units["position_0_0"] == "L"
    assert units["pre_0_velocity_0"] == "L/T" and units["post_0_spin_0"] == "1/T"
    assert log["time"].dtype == "float64" and log["event"].dtype == "int64"


def test_boundary_map_equals_the_csv(outputs: tuple[Path, Path]) -> None:
    text, columnar = outputs
    with open(text / "boundary-map.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    bmap = noslip.read_boundary_map(columnar / "boundary-map.parquet")
    # Every scene here has walls or obstacles: contacts with them in 400.
    assert len(bmap) == len(rows) > 0
    assert list(bmap.columns) == list(rows[0].keys())
    for got, want in zip(bmap.to_dict("records"), rows):
        for key, value in want.items():
            if key == "kind":
                assert got[key] == value
            elif key in ("event", "ball", "id"):
                assert got[key] == int(value)
            else:
                assert got[key] == float(value), (key, got[key], value)
    assert bmap.attrs["units"]["reflection"] == "rad"
    assert bmap.attrs["units"]["q0"] == "L"
    assert bmap.attrs["dim"] in (2, 3)


def test_bad_files_are_refused_naming_path(
    outputs: tuple[Path, Path], tmp_path: Path
) -> None:
    text, columnar = outputs
    not_log = r"path: .*boundary-map.parquet is not a noslip events log.*read_boundary_map"
    with pytest.raises(ValueError, match=not_log):
        noslip.read_log(columnar / "boundary-map.parquet")
    not_map = r"path: .*events.parquet is not a noslip boundary map.*read_log"
    with pytest.raises(ValueError, match=not_map):
        noslip.read_boundary_map(str(columnar / "events.parquet"))
    with pytest.raises(ValueError, match=r"path: .*events.jsonl is not a readable Parquet file"):
        noslip.read_log(text / "events.jsonl")
    with pytest.raises(FileNotFoundError):
        noslip.read_log(tmp_path / "missing.parquet")
    with pytest.raises(TypeError, match="path: expected a file name"):
        noslip.read_log(42)  # type: ignore[arg-type]


def test_pyarrow_is_imported_only_to_read() -> None:
    code = (
        "import sys, noslip; print('pyarrow' in sys.modules);"
        "sys.modules['pyarrow'] = None; sys.modules['pyarrow.parquet'] = None\n"
        "try:\n    noslip.read_log('x.parquet')\nexcept ImportError as e:\n    print(e)"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd="/"
    ).stdout.splitlines()
    assert out[0] == "False"
    assert "pip install" in out[1] and "noslip[sweep]" in out[1]
