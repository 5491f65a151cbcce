"""The granular observables (``docs/granular.md``): ``noslip.simulate(..., observables=DT)``
returns the rows ``noslip simulate --observables DT`` writes, bit for bit, both as its CSV and
as its Parquet table (read by ``noslip.read_observables``); a bad interval raises naming
``observables``; the rows count against ``max_memory``."""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import pytest

import noslip
from conftest import run_cli

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "scenes" / "granular3d.toml"
COLUMNS = [
    "time",
    "contacts",
    "T_tr",
    "T_rot",
    "energy",
    "collision_frequency",
    "lost_ball_ball",
    "lost_ball_wall",
    "lost_ball_obstacle",
    "lost_ball_boundary",
    "injected",
    "pressure",
    "a2",
    "msd",
    "msd_cm",
]


@pytest.fixture(scope="module")
def written(cli: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The CLI's output set of the granular gas to t = 3, sampled every 0.5."""
    out = tmp_path_factory.mktemp("observables") / "run"
    run_cli(
        cli,
        "simulate",
        str(SCENE),
        "--quiet",
        "--time",
        "3",
        "--observables",
        "0.5",
        "--out",
        str(out),
    )
    return out


def test_the_rows_equal_the_cli_csv_and_parquet_bit_for_bit(written: Path) -> None:
    got = noslip.simulate(SCENE, time=3, observables=0.5).observables
    assert list(got) == COLUMNS
    assert got["contacts"].dtype == np.int64 and got["time"].dtype == np.float64
    with open(written / "observables.csv", newline="") as f:
        rows = list(csv.reader(f))
    assert [h.split(" [")[0] for h in rows[0]] == COLUMNS
    body = rows[1:]
    # The start and the first contact after each of t = 0.5 .. 2.5 (none after 3: the run
    # stops there).
    assert len(body) == len(got["time"]) == 6
    for k, name in enumerate(COLUMNS):
        text = np.array([float(r[k]) for r in body])
        ours = np.asarray(got[name], dtype=np.float64)
        # Shortest round-trip decimals parse back to the same doubles (the bits compared,
        # so -0.0 is not 0.0); NaN (the first row's frequency) where the CSV has NaN.
        assert np.array_equal(np.isnan(ours), np.isnan(text)), name
        ok = ~np.isnan(text)
        assert np.array_equal(ours[ok].view(np.int64), text[ok].view(np.int64)), name
    frame = noslip.read_observables(written / "observables.parquet")
    assert list(frame.columns) == COLUMNS
    assert frame["contacts"].dtype == np.int64
    for name in COLUMNS:
        np.testing.assert_array_equal(frame[name].to_numpy(), got[name], err_msg=name)
    assert frame.attrs["units"]["T_tr"] == "M L^2 T^-2"
    assert frame.attrs["units"]["collision_frequency"] == "T^-1"
    assert frame.attrs["dim"] == 3


def test_other_tables_are_told_apart(written: Path) -> None:
    with pytest.raises(ValueError, match=r"is not a noslip events log.*read_observables"):
        noslip.read_log(written / "observables.parquet")


@pytest.mark.parametrize("dt", [0.0, -1.0, float("nan"), float("inf")])
def test_a_bad_interval_names_observables(dt: float) -> None:
    with pytest.raises(noslip.InputError, match="observables: the interval must be positive"):
        noslip.simulate(SCENE, events=10, observables=dt)


def test_the_rows_count_against_max_memory() -> None:
    # A row at every contact (the interval far below the time between contacts), 648 bytes
    # each with one species (simulate's docstring): 3600 bytes hold 5 rows.
    with pytest.raises(noslip.InputError, match=r"time: .*observables=1e-12.*max_memory = 3600"):
        noslip.simulate(SCENE, time=1, observables=1e-12, max_memory=3600)
    small = noslip.simulate(SCENE, events=5, observables=1e-12, max_memory=6 * 648)
    assert len(small.observables["time"]) == 6  # the start and each contact
    with pytest.raises(noslip.InputError, match=r"max_memory = 3887 bytes after 4 contacts"):
        noslip.simulate(SCENE, events=5, observables=1e-12, max_memory=6 * 648 - 1)
    # A mixture's rows hold its species' and pairs' columns too: 72 bytes a species and 48 a
    # pair, 648 + 2 * 72 + 3 * 48 = 936 for the two species (three pairs) of the mixture.
    mixture = ROOT / "scenes" / "mixture2d.toml"
    small = noslip.simulate(mixture, events=5, observables=1e-12, max_memory=6 * 936)
    assert len(small.observables["time"]) == 6
    with pytest.raises(noslip.InputError, match=r"max_memory = 5615 bytes after 4 contacts"):
        noslip.simulate(mixture, events=5, observables=1e-12, max_memory=6 * 936 - 1)


def test_pair_correlation_equals_the_cli_csv(cli: Path, tmp_path: Path) -> None:
    """g(r) of the CLI's pair-correlation.csv, bit for bit; bad radii and a missing
    interval named."""
    scene = ROOT / "scenes" / "gas3d.toml"
    out = tmp_path / "run"
    run_cli(cli, "simulate", str(scene), "--quiet", "--events", "3000", "--observables",
            "0.5", "--pair-correlation", "2", "--pair-bins", "20", "--out", str(out))
    with open(out / "pair-correlation.csv", newline="") as f:
        rows = list(csv.reader(f))
    assert rows[0] == ["r [L]", "g [1]"]
    text = np.array([[float(x) for x in r] for r in rows[1:]])
    got = noslip.simulate(scene, events=3000, observables=0.5, pair_correlation=2,
                          pair_bins=20).pair_correlation
    assert got["r"].shape == got["g"].shape == (20,)
    for k, name in enumerate(["r", "g"]):
        assert np.array_equal(got[name].view(np.int64), text[:, k].view(np.int64)), name
    with pytest.raises(noslip.InputError, match="pair_correlation: "):
        noslip.simulate(scene, events=10, observables=0.5, pair_correlation=1e6)
    with pytest.raises(noslip.InputError, match="pair_correlation: .*give observables"):
        noslip.simulate(scene, events=10, pair_correlation=2)
    # The bins' bound is enforced: -1 panicked (read as i32), 2**30 asked for 8 GiB.
    for bins in [-1, 0, 2**20 + 1, 2**30, -(2**32)]:
        with pytest.raises(noslip.InputError, match=r"pair_bins: must be an integer in 1..=1048576"):
            noslip.simulate(scene, events=10, observables=0.5, pair_correlation=2,
                            pair_bins=bins)


def test_self_diffusion_equals_the_cli_csv(cli: Path, tmp_path: Path) -> None:
    """The self-diffusion blocks of the CLI's self-diffusion.csv, bit for bit, and the
    estimate their mean and standard error; bad blocks and a missing interval named."""
    scene = ROOT / "scenes" / "driven3d.toml"
    out = tmp_path / "run"
    run_cli(cli, "simulate", str(scene), "--quiet", "--time", "40", "--observables",
            "0.5", "--self-diffusion", "8", "--self-diffusion-from", "4", "--out", str(out))
    with open(out / "self-diffusion.csv", newline="") as f:
        rows = list(csv.reader(f))
    assert rows[0] == ["block [1]", "start [T]", "end [T]", "D [L^2 T^-1]"]
    text = np.array([[float(x) for x in r] for r in rows[1:]])
    got = noslip.simulate(scene, time=40.0, observables=0.5, self_diffusion=8.0,
                          self_diffusion_from=4.0).self_diffusion
    # Blocks from the first row at or after 4 on the grid 4 + 8 k: four finished by t = 40.
    assert got["D"].shape == (4,)
    for k, name in enumerate(["start", "end", "D"], start=1):
        assert np.array_equal(got[name].view(np.int64), text[:, k].view(np.int64)), name
    assert got["mean"] == pytest.approx(np.mean(got["D"]), rel=1e-15)
    assert got["standard_error"] == pytest.approx(np.std(got["D"], ddof=1) / 2.0, rel=1e-12)
    assert np.all(got["start"][1:] == got["end"][:-1]) and got["start"][0] >= 4.0
    with pytest.raises(noslip.InputError, match=r"self_diffusion: the block \(1\) must be"):
        noslip.simulate(scene, time=5.0, observables=0.5, self_diffusion=1.0)
    with pytest.raises(noslip.InputError, match="self_diffusion: .*give observables"):
        noslip.simulate(scene, time=5.0, self_diffusion=8.0)
    assert noslip.simulate(scene, time=1.0, observables=0.5).self_diffusion == {}
