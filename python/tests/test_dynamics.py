"""noslip.lyapunov against `noslip lyapunov` (the same spectrum and running estimate, bit
for bit), both methods and both contact laws, and errors naming the argument."""

import csv
import json

import numpy as np
import pytest

import noslip
from conftest import run_cli


def cli_spectrum(cli, scene, out, *args):
    run_cli(cli, "lyapunov", str(scene), "--out", str(out), *args)
    summary = json.loads((out / "spectrum.json").read_text())
    with open(out / "running.csv") as f:
        rows = list(csv.reader(f))
    return summary, rows


@pytest.mark.parametrize(
    "method, contact, extra",
    [("qr", "no-slip", []), ("two-trajectory", "smooth", ["--k", "1"])],
)
def test_lyapunov_gives_the_cli_spectrum_bit_for_bit(root, cli, tmp_path, method, contact, extra):
    path = root / "scenes" / "sinai.toml"
    summary, rows = cli_spectrum(
        cli, path, tmp_path / "run", "--events", "3000", "--blocks", "5",
        "--method", method, "--contact", contact, "--seed", "7", *extra,
    )
    got = noslip.lyapunov(
        noslip.Scene.from_file(path), 3000, blocks=5, method=method, contact=contact, seed=7,
        k=1 if extra else None,
    )
    assert got.method == summary["method"] == method
    assert got.contact == summary["law"] == contact
    for key in ("dimension", "contacts", "warmup", "every", "time"):
        assert getattr(got, key) == summary[key], key
    # The JSON and CSV floats are shortest round-trip text: equal means the same f64.
    assert got.per_time.tolist() == [e["value"] for e in summary["per_time"]]
    assert got.per_time_error.tolist() == [e["error"] for e in summary["per_time"]]
    assert got.per_contact.tolist() == [e["value"] for e in summary["per_contact"]]
    assert (got.sum, got.sum_error) == (summary["sum"]["value"], summary["sum"]["error"])
    header, body = rows[0], rows[1:]
    assert header == ["contacts", "time"] + [f"lambda_{i + 1}" for i in range(len(got.per_time))]
    assert got.running_contacts.tolist() == [int(r[0]) for r in body]
    assert got.running_time.tolist() == [float(r[1]) for r in body]
    assert got.running.tolist() == [[float(x) for x in r[2:]] for r in body]
    assert got.running.shape == (len(body), len(got.per_time)) and len(body) > 0
    assert got.largest == got.per_time[0] > 0  # the Sinai table is chaotic


def test_the_full_spectrum_of_the_sinai_table_has_the_phase_space_dimension(root):
    """One disk in 2D: centre (2), velocity (2), spin (1): five exponents, largest first."""
    got = noslip.lyapunov(noslip.Scene.from_file(root / "scenes" / "sinai.toml"), 2200, blocks=10)
    assert got.dimension == 5 and got.per_time.shape == (5,)
    assert np.all(np.diff(got.per_time) <= 0)


@pytest.mark.parametrize(
    "kwargs, message",
    [
        ({"k": 9}, r"^k: must be in 1\.\.=5"),
        ({"method": "svd"}, r"^method: must be"),
        ({"contact": "sticky"}, r"^contact: must be"),
        ({"events": 5}, r"^events: 5 contacts cannot make a warm-up"),
        ({"every": 0}, r"^every: must be at least 1"),
        ({"method": "two-trajectory", "k": 2}, r"^k: two-trajectory gives the largest"),
    ],
)
def test_bad_arguments_are_named(root, kwargs, message):
    scene = noslip.Scene.from_file(root / "scenes" / "sinai.toml")
    with pytest.raises(noslip.InputError, match=message):
        noslip.lyapunov(scene, **{"events": 1000, **kwargs})
