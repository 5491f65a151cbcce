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


def test_orbits_give_the_cli_report_bit_for_bit(root, cli, tmp_path):
    """A rational start (the CLI's --from) and a grid: the same orbits, eigenvalues and
    exact characteristic polynomial as `noslip orbits` writes into orbits.json."""
    path = root / "scenes" / "sinai.toml"
    out = tmp_path / "orbits"
    run_cli(cli, "orbits", str(path), "--period", "2", "--from", "17/20,1/2,1,0,0",
            "--grid", "2", "--out", str(out))
    want = json.loads((out / "orbits.json").read_text())
    from fractions import Fraction as F

    got = noslip.orbits(noslip.Scene.from_file(path), 2, starts=[[F(17, 20), 0.5, 1, 0, "0"]],
                        grid=2)
    assert (got.period, got.starts, got.misses) == (want["period"], want["starts"], want["misses"])
    assert len(got.orbits) == len(want["orbits"]) > 0
    for o, w in zip(got.orbits, want["orbits"]):
        assert o.boundaries == w["boundaries"] and o.verdict == w["verdict"]
        assert o.start.tolist() == w["start"] and o.states.tolist() == w["states"]
        assert o.residual == w["residual"] and o.found_from == w["found_from"]
        assert [(z.real, z.imag) for z in o.eigenvalues] == [tuple(e) for e in w["eigenvalues"]]
    assert len(got.exact) == 1
    e, w = got.exact[0], want["exact"][0]
    assert e is not None and e.charpoly == w["charpoly"] and e.periodic == w["periodic"]
    assert e.coefficients == [F(x) for x in w["coefficients"]]
    assert e.end == [F(x) for x in w["end"]]


def test_the_bouncing_orbit_is_hyperbolic_when_smooth_and_elliptic_when_no_slip():
    """The disk bouncing along y = 1/2 between the obstacle (radius 3/10 at the centre) and
    its periodic image: a period-2 orbit of the boundary map (the same obstacle twice) whose
    exact return map brings the rational start back exactly. Between convex scatterers the
    smooth (classical) bouncing orbit is hyperbolic (Sinai); under no-slip contacts the
    period-2 orbits are linearly stable, elliptic (Cox and Feres, no-slip billiards)."""
    scene = noslip.tables.sinai(0.5, "3/10")
    # Just after a contact at the obstacle's rightmost point: centre at x = 1/2 + 3/10 +
    # 1/20, moving right at unit speed, no spin.
    start = ["17/20", "1/2", 1, 0, 0]
    for contact, verdict in (("smooth", "hyperbolic"), ("no-slip", "elliptic")):
        got = noslip.orbits(scene, 2, starts=[start], contact=contact)
        assert [o.verdict for o in got.orbits] == [verdict], contact
        assert got.orbits[0].boundaries == [0, 0]
        assert got.exact[0] is not None and got.exact[0].periodic
        assert np.allclose(got.orbits[0].start, [0.85, 0.5, 1, 0, 0], atol=1e-12)


@pytest.mark.parametrize(
    "kwargs, message",
    [
        ({"period": 0}, r"^period: must be in 1\.\.=1000"),
        ({"starts": [[1, 2, 3]]}, r"^starts\[0\]: has 3 numbers, expected 2n \+ S = 5"),
        ({"starts": [["0.85", "0.5", 1, 0, "x"]]}, r"^starts\[0\]\[4\]"),
        ({"starts": [["0.85", "0.5", -1, 0, 0]]}, r"^starts\[0\]: the velocity must point"),
        ({"starts": [[1, "1/2", 0, "1e400", 0]]}, r"^starts\[0\]: number 3 is beyond the f64"),
        ({"grid": 0}, r"^grid: must be at least 1"),
        ({"contact": "rough"}, r"^contact: must be"),
        ({"starts": []}, r"^starts: empty: give at least one start"),
    ],
)
def test_bad_orbit_arguments_are_named(root, kwargs, message):
    scene = noslip.Scene.from_file(root / "scenes" / "sinai.toml")
    with pytest.raises(noslip.InputError, match=message):
        noslip.orbits(scene, **{"period": 2, **kwargs})


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda s: noslip.lyapunov(s, -1), r"^events: must be an integer in 1\.\.=\d+, got -1$"),
        (lambda s: noslip.lyapunov(s, 1000, seed=-1),
         r"^seed: must be an integer in 0\.\.=\d+, got -1$"),
        (lambda s: noslip.lyapunov(s, 1000, seed=2**64),
         r"^seed: must be an integer in 0\.\.=18446744073709551615, got 18446744073709551616$"),
        (lambda s: noslip.lyapunov(s, 1000, blocks=-1),
         r"^blocks: must be an integer in 1\.\.=10000, got -1$"),
        (lambda s: noslip.lyapunov(s, 1000, blocks=2**64 - 1),
         r"^blocks: must be in 1\.\.=10000"),
        (lambda s: noslip.lyapunov(s, 2000, blocks=2, every=300),
         r"^every: the tangent vectors stopped being finite between contacts 0 and 300"),
        (lambda s: noslip.lyapunov(s, 2000, every=300),
         r"^every: 300 contacts between re-orthonormalisations would leave blocks without one"),
        (lambda s: noslip.lyapunov(s, 1000, k=-1), r"^k: must be an integer in 1\.\.=\d+, got -1$"),
        (lambda s: noslip.lyapunov(s, 1000, every=-2),
         r"^every: must be an integer in 1\.\.=\d+, got -2$"),
        (lambda s: noslip.orbits(s, -1), r"^period: must be an integer in 1\.\.=\d+, got -1$"),
        (lambda s: noslip.orbits(s, 2, grid=-1),
         r"^grid: must be an integer in 1\.\.=\d+, got -1$"),
    ],
)
def test_negative_and_huge_ints_are_named(root, call, message):
    """An unsigned argument out of its type's range: an InputError naming it and its range,
    not PyO3's bare `OverflowError: can't convert negative int to unsigned`."""
    scene = noslip.Scene.from_file(root / "scenes" / "sinai.toml")
    with pytest.raises(noslip.InputError, match=message):
        call(scene)


BIG_GAS = """dim = 2
[box]
size = [400, 400]
boundary = ["periodic", "periodic"]
[[species]]
mass = 1
radius = "1/2"
count = 12000
[random]
seed = 1
speed = 1
spin = 1
"""


def test_a_spectrum_beyond_the_memory_cap_is_refused_naming_k():
    """12 000 disks (dimension 60 000): the whole spectrum's tangent vectors need 28.8 GB (the
    run aborted on a failed allocation); asked for, it is an InputError naming k, the memory
    and the cap, before any work. By default the 52 largest (the work budget: 12
    re-orthonormalisations, one per block of 9 contacts)."""
    with pytest.raises(noslip.InputError, match=(
            r"^k: 60000 tangent vectors of dimension 60000 need 26\.822 GiB \(28800000000 "
            r"bytes, 8 k d\), beyond the cap of 1\.000 GiB: at most 2236 fit$")):
        noslip.lyapunov(BIG_GAS, 100, k=60000)
    got = noslip.lyapunov(BIG_GAS, 100)
    assert (got.dimension, len(got.per_time)) == (60000, 52)


def test_the_default_k_of_a_gas_keeps_the_run_short(root):
    """gas2d (dimension 3750) over 200 contacts ran the whole spectrum by default (223 s); the
    default is now the 210 largest (2e9 multiply-adds of Gram-Schmidt over 12
    re-orthonormalisations, one per block), as in the CLI."""
    got = noslip.lyapunov(noslip.Scene.from_file(root / "scenes" / "gas2d.toml"), 200)
    assert (got.dimension, len(got.per_time)) == (3750, 210)


def test_the_orbit_search_is_bounded(root):
    """The triangle's period-4 search returns (it never did: an uncapped eigenvalue
    iteration); the native search stops at its bound of contacts and says so."""
    triangle = noslip.Scene.from_file(root / "scenes" / "triangle.toml")
    got = noslip.orbits(triangle, 4, grid=1)
    assert (got.starts, len(got.orbits)) == (3, 3)
    assert (got.tried, got.stopped) == (3, None)
    sector = noslip.Scene.from_file(root / "scenes" / "sector.toml")
    report = noslip.orbits(sector, 4, grid=4, max_contacts=2000)
    assert report.contacts <= 2000 and 0 < report.tried < report.starts == 64
    assert report.stopped.startswith("the search followed ")
    with pytest.raises(noslip.InputError, match=r"^max_contacts: must be at least 1, got 0$"):
        noslip.orbits(sector, 4, grid=4, max_contacts=0)
