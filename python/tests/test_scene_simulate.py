"""noslip.Scene and noslip.simulate against `noslip simulate` (the same events log, bit for
bit), scenes from text, files and dicts, pickling, and errors naming the place."""

import csv
import json
import pickle
import subprocess
import sys

import numpy as np
import pytest

import noslip
from conftest import run_cli


def test_scene_from_file_text_and_dict_agree(root):
    path = root / "scenes" / "sinai.toml"
    a = noslip.Scene.from_file(path)
    b = noslip.Scene(path.read_text())
    c = noslip.Scene.from_dict(
        {
            "dim": 2,
            "box": {"size": [1, 1], "boundary": ["periodic", "periodic"]},
            "species": [{"name": "disk", "mass": 1, "radius": "1/20"}],
            "ball": [{"species": 0, "position": ["1/10", "1/10"],
                      "velocity": ["0.6", "0.8"], "angular_velocity": 0}],
            "obstacle": [{"position": ["1/2", "1/2"], "radius": "3/10"}],
            "simulation": {"events": 100000, "orientation": True},
        }
    )
    assert (a.dim, a.balls, b.dim, c.dim) == (2, 1, 2, 2)
    runs = [noslip.simulate(s, events=300, log=True) for s in (a, b, c)]
    for r in runs[1:]:
        assert np.array_equal(
                r.events["post_velocity"], runs[0].events["post_velocity"], equal_nan=True
            )


def test_numpy_values_in_a_dict_are_read_as_their_python_values():
    """np.int64, np.float32, np.bool_, arrays and Decimal in a scene dict are the scene the
    plain values give (a sweep hands its grid's NumPy values over; they were refused as
    "got int64")."""
    from decimal import Decimal

    def scene(count, radius, position, mass, orientation):
        return noslip.Scene.from_dict({
            "dim": 2,
            "box": {"size": [4, 4], "boundary": ["periodic", "periodic"]},
            "species": [{"name": "a", "mass": mass, "radius": radius, "count": count}],
            "obstacle": [{"position": position, "radius": 0.5}],
            "simulation": {"orientation": orientation},
        })

    plain = scene(3, 0.25, [1.0, 2.0], "1.5", True)
    numpy = scene(np.int64(3), np.float32(0.25), np.array([1.0, 2.0]), Decimal("1.5"),
                  np.bool_(True))
    assert numpy == plain
    with pytest.raises(noslip.InputError, match=r"species\[0\]\.mass: .*got complex"):
        scene(3, 0.25, [1.0, 2.0], np.complex128(1), True)


def test_a_scene_pickles_as_its_text(root):
    scene = noslip.Scene.from_file(root / "scenes" / "gas2d.toml")
    back = pickle.loads(pickle.dumps(scene))
    assert back.toml == scene.toml and back.origin == scene.origin
    a = noslip.simulate(scene, events=500)
    b = noslip.simulate(back, events=500)
    assert a.summary["energy_end"] == b.summary["energy_end"]


def test_simulate_gives_the_cli_events_log_bit_for_bit(root, cli, tmp_path):
    path = root / "scenes" / "sinai.toml"
    out = tmp_path / "run"
    run_cli(cli, "simulate", str(path), "--events", "1500", "--quiet",
            "--out", str(out), "--log", str(out / "events.jsonl"))
    lines = [json.loads(line) for line in (out / "events.jsonl").read_text().splitlines()]
    summary = json.loads((out / "summary.json").read_text())
    got = noslip.simulate(noslip.Scene.from_file(path), events=1500, log=True)
    ev = got.events
    assert len(lines) == len(ev["time"]) == 1500
    assert ev["time"].tolist() == [e["time"] for e in lines]
    assert ev["nu"].tolist() == [e["nu"] for e in lines]
    assert ev["kind"].tolist() == [
        ["ball-ball", "ball-wall", "ball-obstacle"].index(e["kind"]) for e in lines
    ]
    assert ev["post_velocity"][:, 0].tolist() == [e["post"][0]["velocity"] for e in lines]
    assert ev["pre_spin"][:, 0].tolist() == [e["pre"][0]["spin"] for e in lines]
    assert ev["obstacle"].tolist() == [e.get("obstacle", -1) for e in lines]
    for key in ("events", "ball_obstacle", "time", "energy_start", "energy_end", "energy_drift"):
        assert got.summary[key] == summary[key], key


def test_conserve_energy_is_the_cli_flag_and_removes_the_drift(root, cli, tmp_path):
    """``conserve_energy=True`` is ``noslip simulate --conserve-energy``, contact for contact,
    and it removes the kernel's energy drift on ``disk_between_walls``: over 10^5 contacts
    the uncorrected kernel gains about +0.008 eps of the energy per contact (800 eps in all,
    docs/accuracy.md), where a random walk of the per-contact changes (standard deviation
    about 0.28 eps there) spreads by about 89 eps. The corrected end must be within 4 of
    those (356 eps), the uncorrected one outside them (the test's power)."""
    path = root / "scenes" / "disk_between_walls.toml"
    out = tmp_path / "run"
    run_cli(cli, "simulate", str(path), "--events", "2000", "--quiet", "--conserve-energy",
            "--out", str(out), "--log", str(out / "events.jsonl"))
    lines = [json.loads(line) for line in (out / "events.jsonl").read_text().splitlines()]
    assert json.loads((out / "summary.json").read_text())["conserve_energy"] is True
    scene = noslip.Scene.from_file(path)
    got = noslip.simulate(scene, events=2000, log=True, conserve_energy=True)
    plain = noslip.simulate(scene, events=2000, log=True)
    assert got.summary["conserve_energy"] is True and plain.summary["conserve_energy"] is False
    post = got.events["post_velocity"][:, 0].tolist()
    assert post == [e["post"][0]["velocity"] for e in lines]
    assert post != plain.events["post_velocity"][:, 0].tolist()
    band = 4 * 0.28 * 1e5**0.5 * np.finfo(float).eps
    corrected = noslip.simulate(scene, events=100_000, conserve_energy=True)
    uncorrected = noslip.simulate(scene, events=100_000)
    assert corrected.summary["energy_drift"] < band
    assert uncorrected.summary["energy_drift"] > band


def test_energy_is_conserved_event_by_event():
    """Each contact of a ball with the fixed obstacle keeps the ball's energy
    m (|u|^2 + lambda U_12^2 * 2) / 2 up to f64 rounding (a few eps of the energy)."""
    run = noslip.simulate(noslip.tables.sinai(0.5, 0.3), events=2000, log=True)
    ev = run.events
    lam = 0.5 * (1 / 20) ** 2 / 2  # gamma2 R^2 / 2

    def energy(spin, velocity):
        return 0.5 * ((velocity**2).sum(axis=1) + lam * 2 * (spin**2).sum(axis=1))

    e_pre = energy(ev["pre_spin"][:, 0], ev["pre_velocity"][:, 0])
    e_post = energy(ev["post_spin"][:, 0], ev["post_velocity"][:, 0])
    assert np.abs(e_post - e_pre).max() < 16 * np.finfo(float).eps * e_pre.max()
    assert run.energy["drift"].shape == run.energy["events"].shape
    assert abs(run.summary["energy_drift"]) < 1e-12


def test_bad_scenes_and_limits_name_the_place():
    with pytest.raises(noslip.InputError, match="line 1"):
        noslip.Scene("dim = ")
    with pytest.raises(noslip.InputError, match=r"species\[0\]"):
        noslip.Scene.from_dict({
            "dim": 2, "box": {"size": [1, 1], "boundary": ["periodic", "periodic"]},
            "species": [{"mass": -1, "radius": 0.1}],
        })
    with pytest.raises(noslip.InputError, match=r"^time: must be positive"):
        noslip.simulate(noslip.tables.sinai(0.5, 0.3), time=-1.0)
    with pytest.raises(noslip.InputError, match=r"^events: must be at least 1"):
        noslip.simulate(noslip.tables.sinai(0.5, 0.3), events=0)


def test_a_ball_leaving_its_container_is_an_input_error_naming_it(root):
    # An inelastic collapse against the circle's wall (e = 1/2, no TC model) ends with the
    # ball's normal velocity rounded to 0 or out: the run cannot go on (docs/granular.md).
    text = (root / "scenes" / "circle.toml").read_text()
    collapsing = text.replace("radius = 1\n", "radius = 1\ncontact = { e = 0.5, beta = -1 }\n", 1)
    with pytest.raises(noslip.InputError, match=r"ball 0 left the table through container\[0\]"):
        noslip.simulate(noslip.Scene(collapsing), events=1000)
    # With the TC model the collapse ends and the run goes on.
    run = noslip.simulate(noslip.Scene(collapsing + '[contact]\ntc = "1e-3"\n'), events=1000)
    assert run.summary["events"] == 1000 and run.summary["left_table"] is None
    # Contacts at one instant without end (the wedge's walls at e = 0 drive the disk into
    # the apex): an InputError naming the ball, where simulate(time=...) never returned.
    apex = (root / "scenes" / "wedge.toml").read_text().replace(
        "[table.wedge]", "[table]\ncontact = { e = 0, beta = -1 }\n[table.wedge]")
    with pytest.raises(noslip.InputError, match=r"inelastic collapse at t = 2\.57845.*\(ball 0, their centres not moving\)"):
        noslip.simulate(noslip.Scene(apex), time=10.0)
    # At e = 0 the scene itself is refused, naming e.
    with pytest.raises(noslip.InputError, match=r"container\[0\]\.contact\.e: must be > 0"):
        noslip.Scene(text.replace("radius = 1\n", "radius = 1\ncontact = { e = 0, beta = 0 }\n", 1))


@pytest.mark.parametrize("scene, events", [("sinai.toml", 800), ("sector.toml", 800),
                                           ("wedge.toml", 50), ("cube3d.toml", 400)])
def test_the_boundary_map_is_the_cli_csv_bit_for_bit(root, cli, tmp_path, scene, events):
    """`simulate(...).boundary_map` against `noslip simulate --boundary-map`: the same
    columns, in the same order, and the same numbers (the CSV's floats are shortest
    round-trip text), for an obstacle (Sinai), a 2D table's boundaries (sector, wedge) and a
    3D box."""
    path = root / "scenes" / scene
    out = tmp_path / "run"
    csv_path = tmp_path / "map.csv"
    run_cli(cli, "simulate", str(path), "--events", str(events), "--quiet",
            "--out", str(out), "--boundary-map", str(csv_path))
    with open(csv_path) as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    got = noslip.simulate(noslip.Scene.from_file(path), events=events, boundary_map=True).boundary_map
    assert list(got) == header
    assert len(body) > 0 and all(len(got[c]) == len(body) for c in header)
    for k, column in enumerate(header):
        if column == "kind":
            assert got[column].tolist() == [r[k] for r in body]
        elif column in ("event", "ball", "id"):
            assert got[column].tolist() == [int(r[k]) for r in body], column
        else:
            assert got[column].tolist() == [float(r[k]) for r in body], column


def test_the_boundary_map_keeps_the_disk_energy_at_each_contact(root):
    """The no-slip map at an immovable boundary keeps the energy: in the map's coordinates
    u_n^2 + u_t^2 + (gamma R c)^2 is the same before and after each contact (2D), to a few
    eps of it; the normal velocity is reversed and the tangential part and the scaled spin
    are reflected together (an orthogonal map on (u_t, gamma R c))."""
    run = noslip.simulate(noslip.Scene.from_file(root / "scenes" / "sector.toml"), events=500,
                          boundary_map=True)
    m = run.boundary_map
    before = m["normal_velocity"] ** 2 + m["tangential_velocity"] ** 2 + m["scaled_spin"] ** 2
    after = m["normal_velocity"] ** 2 + m["tangential_velocity_post"] ** 2 \
        + m["scaled_spin_post"] ** 2
    assert len(before) > 100
    # The map reverses u_n exactly in exact arithmetic, so (u_t, gamma R c) keeps its length.
    # In f64 the kernel is within 16 eps of the state in its energy norm (docs/accuracy.md),
    # 32 eps of the energy, and the map's columns add a few roundings: 64 eps.
    assert np.all(np.abs(after - before) <= 64 * np.finfo(float).eps * before)
    assert np.all(np.abs(m["incidence"]) < np.pi / 2) and np.all(np.abs(m["reflection"]) < np.pi / 2)


def sinai_dict(**changes):
    """The Sinai scene as a dict, with `changes` to its species (one disk)."""
    return {
        "dim": 2,
        "box": {"size": [1, 1], "boundary": ["periodic", "periodic"]},
        "species": [{"name": "disk", "mass": 1, "radius": "1/20", **changes}],
        "ball": [{"species": 0, "position": ["1/10", "1/10"], "velocity": ["0.6", "0.8"]}],
        "obstacle": [{"position": ["1/2", "1/2"], "radius": "3/10"}],
    }


@pytest.mark.parametrize(
    "scene, message",
    [
        (sinai_dict(mass=float("inf")),
         r"^<dict>: species\[0\]\.mass: must be finite, got inf$"),
        (sinai_dict(radus=0.1), r"^<dict>: species\[0\]\.radus: unknown field `radus`"),
        (sinai_dict(count=-3), r"^<dict>: species\[0\]\.count: invalid value: integer `-3`"),
        ({**sinai_dict(), "dim": 10**30},
         r"^<dict>: dim: integer 1000000000000000000000000000000 is too large for this field"),
        ({**sinai_dict(), "dim": -(10**30)}, r"^<dict>: dim: integer -1\d{30} is too small"),
        ({**sinai_dict(), "box": {"size": [1, 1]}}, r"^<dict>: box.boundary: missing \(a required field\)$"),
        ({"box": sinai_dict()["box"]}, r"^<dict>: dim: missing \(a required field\)$"),
        ({**sinai_dict(), "ball": [{"species": 0, "position": [0.1, "x"], "velocity": [1, 0]}]},
         r"^<dict>: ball\[0\]\.position\[1\]: not a number"),
    ],
)
def test_dict_errors_name_the_dict_path_not_toml_lines(scene, message):
    """The TOML text made from a dict is never seen by the user: errors name the path in the
    dict (`species[0].mass`), never a line and column of that text."""
    with pytest.raises(noslip.InputError, match=message) as e:
        noslip.Scene.from_dict(scene)
    assert "line" not in str(e.value)


BOXED_GAS = """dim = 2
[box]
size = [10, 10]
boundary = ["wall", "wall"]
[[species]]
mass = 1
radius = "1/2"
count = 3
"""


@pytest.mark.parametrize(
    "law_at, field",
    [
        ("[contact]\nballs = {law}\n", "contact.balls"),
        ("[[obstacle]]\nposition = [5, 5]\nradius = 1\ncontact = {law}\n", "obstacle[0].contact"),
        ("[[wall]]\npoint = [0, 1]\nnormal = [0, 1]\ncontact = {law}\n", "wall[0].contact"),
    ],
)
@pytest.mark.parametrize(
    "law, key, says",
    [
        ("{ e = nan, beta = 0 }", "e", "must be finite, got NaN"),
        ("{ e = 0.5, beta = inf }", "beta", "must be finite, got inf"),
        ("{ e = 0.5, mu = 1, beta0 = -nan }", "beta0", "must be finite, got NaN"),
        ("{ e = 1.5, beta = 0 }", "e", "must be in [0, 1], got 3/2"),
        ("{ e = 0.5, beta = -2 }", "beta", "must be in [-1, 1], got -2"),
        ('{ e = 0.5, mu = "-1/4", beta0 = 0 }', "mu", "must be >= 0, got -1/4"),
        ("{ e = 0.5, mu = 1, beta0 = 2 }", "beta0", "must be in [-1, 1], got 2"),
    ],
)
def test_a_bad_contact_law_is_refused_naming_the_field(law_at, field, law, key, says):
    """Issue 27: a NaN, an infinity or an out-of-range number in a contact law (ball-ball,
    obstacle, wall) is an InputError naming the field: after the line and column for what
    the TOML reader refuses, as the place for what validation refuses; from a dict, the dict
    path alone."""
    path = f"{field}.{key}"
    with pytest.raises(noslip.InputError) as e:
        noslip.Scene(BOXED_GAS + law_at.replace("{law}", law))
    text = str(e.value)
    if "finite" in says:
        assert text.startswith("<string>: line ") and f": {path}: {says}" in text, text
    else:
        assert text.startswith(f"<string>: {path}: {says}"), text
    # The same law from a dict (TOML's nan and inf are Python's float ones).
    table = dict(item.split(" = ") for item in law.strip("{} ").split(", "))
    value = {k: {"nan": float("nan"), "-nan": float("nan"), "inf": float("inf")}.get(v, v.strip('"'))
             for k, v in table.items()}
    scene = {"dim": 2, "box": {"size": [10, 10], "boundary": ["wall", "wall"]},
             "species": [{"mass": 1, "radius": "1/2", "count": 3}]}
    if field == "contact.balls":
        scene["contact"] = {"balls": value}
    elif field == "obstacle[0].contact":
        scene["obstacle"] = [{"position": [5, 5], "radius": 1, "contact": value}]
    else:
        scene["wall"] = [{"point": [0, 1], "normal": [0, 1], "contact": value}]
    with pytest.raises(noslip.InputError) as e:
        noslip.Scene.from_dict(scene)
    assert str(e.value).startswith(f"<dict>: {path}: {says}"), str(e.value)


def test_a_deep_or_self_referencing_dict_is_an_input_error():
    """A dict inside itself, or nested 10000 deep, once overflowed the stack converting it
    to TOML (Python died with SIGSEGV): now an InputError naming the path where the depth
    limit (64) is passed. Run in a child process, so that a crash fails this test alone."""
    code = """
import noslip
loop = {}; loop["x"] = loop
deep = []; cur = deep
for _ in range(10000):
    nxt = []; cur.append(nxt); cur = nxt
for scene in (loop, {"dim": 2, "x": deep}):
    try:
        noslip.Scene.from_dict(scene)
    except noslip.InputError as e:
        print(str(e))
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0, (out.returncode, out.stderr)
    loop, deep = out.stdout.splitlines()
    assert loop == "<dict>: " + ".".join(["x"] * 64) + ": nested more than 64 deep " \
        "(a scene nests at most 4 deep; is a dict or list inside itself?)"
    assert deep.startswith("<dict>: x" + "[0]" * 63 + ": nested more than 64 deep")
    # A scene's own nesting (4 deep here: table.wedge.directions[0][0]) is far from it.
    with pytest.raises(noslip.InputError, match=r"^<dict>: table\.wedge"):
        noslip.Scene.from_dict({"dim": 2, "table": {"wedge": {"directions": [[1, 0], [0]]}}})


def test_text_that_is_not_unicode_is_an_input_error():
    """A Python string UTF-8 cannot encode (a lone surrogate) anywhere a scene takes text
    is an InputError naming it, not Python's UnicodeEncodeError."""
    scene = {"dim": 2, "box": {"size": [10, 10], "periodic": [True, True]},
             "species": [{"mass": 1, "radius": 0.5, "count": 4}]}
    cases = [
        (lambda: noslip.Scene.from_dict({**scene, "description": "\udc80"}),
         r"^<dict>: description: '\\udc80' is not valid Unicode text \(a lone surrogate\)"),
        (lambda: noslip.Scene.from_dict({**scene, "\udc81": 1}),
         r"^<dict>: scene: a key '\\udc81' is not valid Unicode text"),
        (lambda: noslip.Scene.from_dict(scene, origin="\udc80"),
         r"^origin: not valid Unicode text"),
        (lambda: noslip.Scene("dim = 2 # \udc80"), r"^text: not valid Unicode text"),
        (lambda: noslip.simulate("dim = 2 # \udc80", events=1),
         r"^scene: TOML text that is not valid Unicode \(a lone surrogate at character 10\)"),
    ]
    for make, message in cases:
        with pytest.raises(noslip.InputError, match=message):
            make()


def test_a_file_name_given_as_text_gets_a_hint(root):
    """A path where TOML text is expected fails to parse; the message says to use
    Scene.from_file, for a `.toml` name and for any existing file."""
    hint = r"looks like a file name: read a file with noslip\.Scene\.from_file\("
    with pytest.raises(noslip.InputError, match=r"^<string>: line 1, column 7: .*" + hint):
        noslip.simulate("scenes/sinai.toml")
    with pytest.raises(noslip.InputError, match=hint):
        noslip.Scene(str(root / "README.md"))
    with pytest.raises(noslip.InputError) as e:
        noslip.Scene("dim = ")
    assert "from_file" not in str(e.value)


@pytest.mark.parametrize("events", [-1, 2**64, 10**30])
def test_an_out_of_range_events_is_named(events):
    """Not PyO3's bare `OverflowError: can't convert negative int to unsigned`."""
    message = rf"^events: must be an integer in 1\.\.=18446744073709551615, got {events}$"
    with pytest.raises(noslip.InputError, match=message):
        noslip.simulate(noslip.tables.sinai(0.5, 0.3), events=events)
