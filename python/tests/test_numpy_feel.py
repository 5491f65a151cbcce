"""The package as NumPy users expect it (issue 29): inputs cast as ufuncs cast them, arrays
out, one vocabulary of body keys, one shape message, ``__version__``, ``Scene`` equality and
reprs, paths, docstrings."""

import inspect
import pickle
import re
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest

import noslip

ROOT = Path(__file__).resolve().parents[2]


def bits(a):
    a = np.asarray(a, dtype=np.float64)
    return a.view(np.uint64)


def batch(rng, rows, n, dtype=np.float64):
    """Approaching contacts of two free bodies, in the collide vocabulary (mass, lambda)."""
    nu = rng.normal(size=(rows, n))
    nu /= np.linalg.norm(nu, axis=1, keepdims=True)

    def body():
        a = rng.normal(size=(rows, n, n))
        return {
            "angular_velocity": (a - a.transpose(0, 2, 1)).astype(dtype),
            "velocity": rng.uniform(-1, 1, (rows, n)).astype(dtype),
            "mass": 2.0,
            "radius": 0.5,
            "lambda": 0.02,
        }

    b1, b2 = body(), body()
    away = np.einsum("ij,ij->i", b2["velocity"] - b1["velocity"], nu) > 0
    nu[away] *= -1
    return nu.astype(dtype), [b1, b2]


# --- collide_batch: casting ----------------------------------------------------------------


def test_int_inputs_run_in_float64_as_true_divide_makes_them():
    nu = np.array([[0, 1]])
    ball = {"angular_velocity": np.zeros((1, 2, 2), dtype=np.int64),
            "velocity": np.array([[0, 1]]), "mass": 1, "radius": 1}
    wall = {"angular_velocity": np.zeros((1, 2, 2), dtype=np.int32),
            "velocity": np.array([[0, 0]]), "mass": float("inf"), "radius": 1}
    a, b = noslip.collide_batch(nu, [ball, wall])
    assert a["velocity"].dtype == np.float64
    want = noslip.collide([0.0, 1.0], [
        {"mass": 1, "radius": 1, "angular_velocity": [[0, 0], [0, 0]], "velocity": [0, 1]},
        {"mass": "inf", "radius": 1, "angular_velocity": [[0, 0], [0, 0]], "velocity": [0, 0]},
    ])
    assert np.array_equal(bits(a["velocity"][0]), bits(want[0]["velocity"]))
    assert np.array_equal(bits(a["angular_velocity"][0]), bits(want[0]["angular_velocity"]))


def test_mixed_float32_and_float64_give_float64_and_float32_stays_float32():
    rng = np.random.default_rng(1)
    nu, bodies = batch(rng, 50, 3, np.float32)
    nu32 = nu / np.linalg.norm(nu, axis=1, keepdims=True)  # unit in float32's arithmetic
    a32, _ = noslip.collide_batch(nu32, bodies)
    assert a32["velocity"].dtype == np.float32  # Python scalars (mass, ...) are weak
    # float32 states with a float64 normal run in float64, as a ufunc would: the same as
    # casting every input to float64 first.
    nu64 = nu.astype(np.float64)
    nu64 /= np.linalg.norm(nu64, axis=1, keepdims=True)
    a64, _ = noslip.collide_batch(nu64, bodies)
    assert a64["velocity"].dtype == np.float64
    cast = [{k: (v.astype(np.float64) if isinstance(v, np.ndarray) else v)
             for k, v in b.items()} for b in bodies]
    want, _ = noslip.collide_batch(nu64, cast)
    assert np.array_equal(bits(a64["velocity"]), bits(want["velocity"]))
    assert np.array_equal(bits(a64["angular_velocity"]), bits(want["angular_velocity"]))
    assert noslip.batch.result_dtype([("a", np.float16(1)), ("b", 2.0)]) == np.float32
    assert noslip.batch.result_dtype([("a", np.float32(1)), ("b", np.int64(2))]) == np.float64


@pytest.mark.parametrize("bad", [np.array([[1j, 0]]), np.array([["a", "b"]]),
                                 np.ones((1, 2), dtype=np.longdouble)])
def test_inputs_no_float_type_holds_are_refused_naming_the_field(bad):
    if bad.dtype == np.longdouble and np.finfo(np.longdouble).bits == 64:
        pytest.skip("longdouble is float64 here")
    ball = {"angular_velocity": np.zeros((1, 2, 2)), "velocity": bad, "mass": 1,
            "radius": 1}
    wall = {"angular_velocity": np.zeros((1, 2, 2)), "velocity": np.zeros((1, 2)),
            "inv_mass": 0, "radius": 1}
    with pytest.raises(noslip.InputError, match=r"^bodies\[0\]\.velocity: dtype"):
        noslip.collide_batch(np.array([[0.0, 1.0]]), [ball, wall])


# --- collide_batch: one contact, one vocabulary, dimensions --------------------------------


def test_a_1d_normal_is_one_contact_with_unbatched_results():
    rng = np.random.default_rng(2)
    nu, bodies = batch(rng, 1, 3)
    one = [{k: (v[0] if isinstance(v, np.ndarray) else v) for k, v in b.items()}
           for b in bodies]
    a, b = noslip.collide_batch(nu[0], one)
    assert a["velocity"].shape == (3,) and a["angular_velocity"].shape == (3, 3)
    full, _ = noslip.collide_batch(nu, bodies)
    assert np.array_equal(bits(a["velocity"]), bits(full["velocity"][0]))
    out = ({"angular_velocity": np.empty((3, 3)), "velocity": np.empty(3)},
           {"angular_velocity": np.empty((3, 3)), "velocity": np.empty(3)})
    got = noslip.collide_batch(nu[0], one, out=out)
    assert got[0]["velocity"] is out[0]["velocity"]
    assert np.array_equal(bits(out[1]["velocity"]), bits(b["velocity"]))


@pytest.mark.parametrize("n", [2, 3, 6])
def test_collide_keys_give_collides_results_bit_for_bit(n):
    """mass, lambda and distribution (collide's keys) against noslip.collide row by row."""
    rng = np.random.default_rng(n)
    nu, bodies = batch(rng, 40, n)
    bodies[1]["distribution"] = "shell"
    del bodies[1]["lambda"]
    bodies[1]["mass"] = np.where(rng.uniform(size=40) < 0.3, np.inf, 3.0)
    a, b = noslip.collide_batch(nu, bodies)
    for i in range(40):
        case = [{"mass": float(bodies[0]["mass"]), "radius": 0.5, "lambda": 0.02,
                 "angular_velocity": bodies[0]["angular_velocity"][i].tolist(),
                 "velocity": bodies[0]["velocity"][i].tolist()},
                {"mass": "inf" if bodies[1]["mass"][i] == np.inf else 3.0, "radius": 0.5,
                 "distribution": "shell",
                 "angular_velocity": bodies[1]["angular_velocity"][i].tolist(),
                 "velocity": bodies[1]["velocity"][i].tolist()}]
        want = noslip.collide(nu[i].tolist(), case)
        assert np.array_equal(bits(a["velocity"][i]), bits(want[0]["velocity"]))
        assert np.array_equal(bits(a["angular_velocity"][i]), bits(want[0]["angular_velocity"]))
        assert np.array_equal(bits(b["velocity"][i]), bits(want[1]["velocity"]))


def test_key_errors_name_the_key_given():
    rng = np.random.default_rng(3)
    nu, bodies = batch(rng, 5, 2)
    bad = [dict(bodies[0]), bodies[1]]
    bad[0]["lambda"] = 1.0  # above R^2/n = 0.125
    with pytest.raises(noslip.InputError, match=r"^bodies\[0\]\.lambda: "):
        noslip.collide_batch(nu, bad)
    bad[0]["lambda"] = np.full(5, 0.02)
    bad[0]["lambda"][3] = -1.0
    with pytest.raises(noslip.InputError, match=r"^row 3: bodies\[0\]\.lambda: "):
        noslip.collide_batch(nu, bad, validate=False)
    bad = [dict(bodies[0]), bodies[1]]
    bad[0]["mass"] = -1.0
    with pytest.raises(noslip.InputError, match=r"^bodies\[0\]\.mass: must be positive"):
        noslip.collide_batch(nu, bad)
    bad[0]["inv_mass"] = 1.0
    with pytest.raises(noslip.InputError, match=r"^bodies\[0\]\.inv_mass: conflicts with mass"):
        noslip.collide_batch(nu, bad)
    bad = [dict(bodies[0]), bodies[1]]
    bad[0]["gamma2"] = 0.1
    with pytest.raises(noslip.InputError, match=r"^bodies\[0\]\.gamma2: conflicts with lambda"):
        noslip.collide_batch(nu, bad)
    bad = [dict(bodies[0]), bodies[1]]
    del bad[0]["mass"]
    with pytest.raises(noslip.InputError, match=r"^bodies\[0\]\.mass: missing"):
        noslip.collide_batch(nu, bad)


def test_dimensions_beyond_the_batch_kernels_are_a_clear_error():
    nu = np.zeros((2, 7))
    nu[:, 0] = 1
    body = {"angular_velocity": np.zeros((2, 7, 7)), "velocity": np.zeros((2, 7)),
            "mass": 1, "radius": 1}
    with pytest.raises(noslip.InputError,
                       match=r"^normal: expected shape \(N, n\) with n in 2\.\.=6 .*"
                             r"noslip\.collide takes n up to 16\), got \(2, 7\)$"):
        noslip.collide_batch(nu, [body, body])


def test_one_style_of_shape_message():
    """NumPy's tuples everywhere: `expected shape (5, 3), got (6, 3)`."""
    rng = np.random.default_rng(4)
    nu, bodies = batch(rng, 5, 3)
    bad = [dict(bodies[0]), bodies[1]]
    bad[0]["velocity"] = np.zeros((6, 3))
    with pytest.raises(noslip.InputError,
                       match=r"^bodies\[0\]\.velocity: expected shape \(5, 3\), got \(6, 3\)$"):
        noslip.collide_batch(nu, bad)
    bad[0]["velocity"] = np.zeros(3)
    with pytest.raises(noslip.InputError,
                       match=r"^bodies\[0\]\.velocity: expected shape \(5, 3\), got \(3,\)$"):
        noslip.collide_batch(nu, bad)
    bad = [dict(bodies[0]), bodies[1]]
    bad[0]["radius"] = np.ones(4)
    with pytest.raises(noslip.InputError,
                       match=r"^bodies\[0\]\.radius: expected shape \(5,\) or a scalar, got \(4,\)$"):
        noslip.collide_batch(nu, bad)
    out = noslip.collide_batch(nu, bodies)
    out[1]["velocity"] = np.zeros((4, 3))
    with pytest.raises(noslip.InputError,
                       match=r"^out\[1\]\.velocity: expected shape \(5, 3\), got \(4, 3\)$"):
        noslip.collide_batch(nu, bodies, out=out)


# --- collide: arrays out -------------------------------------------------------------------


def test_collide_returns_arrays_where_results_are_arrays():
    ball = {"mass": 1, "radius": 1, "angular_velocity": 0.5, "velocity": [0.0, -1.0]}
    wall = {"mass": "inf", "radius": 1, "angular_velocity": 0, "velocity": [0, 0]}
    after = noslip.collide([0, -1], [ball, wall])
    assert isinstance(after[0]["velocity"], np.ndarray)
    assert after[0]["velocity"].dtype == np.float64 and after[0]["velocity"].shape == (2,)
    assert isinstance(after[0]["angular_velocity"], float)  # the 2D number form, as given
    three = noslip.collide([0, 0, 1], [
        {"mass": 1, "radius": 1, "angular_velocity": np.zeros((3, 3)), "velocity": [0, 0, 1]},
        {"mass": 1, "radius": 1, "angular_velocity": [1, 2, 3], "velocity": [0, 0, 0]}])
    assert three[0]["angular_velocity"].shape == (3, 3)
    assert three[1]["angular_velocity"].shape == (3,)
    exact = noslip.collide([0, -1], [ball, wall] if False else [
        dict(ball, angular_velocity=Fraction(1, 2), velocity=[0, -1]), wall], exact=True)
    assert all(isinstance(x, Fraction) for x in exact[0]["velocity"])


# --- version, Scene ------------------------------------------------------------------------


def test_version_is_the_packages():
    text = (ROOT / "python" / "pyproject.toml").read_text()
    declared = re.search(r'^version = "([^"]+)"', text, re.M).group(1)
    cargo = re.search(r'^version = "([^"]+)"', (ROOT / "python" / "Cargo.toml").read_text(),
                      re.M).group(1)
    assert noslip.__version__ == declared == cargo


def test_scene_equality_pickle_and_repr():
    scene = noslip.Scene.from_file(ROOT / "scenes" / "sinai.toml")
    again = pickle.loads(pickle.dumps(scene))
    assert again == scene and hash(again) == hash(scene)
    assert scene != noslip.Scene(scene.toml)  # another origin
    assert noslip.Scene(scene.toml) == noslip.Scene(scene.toml)
    assert scene != scene.toml
    text = repr(scene)
    assert "dim=2" in text and "balls=1" in text and scene.description in text


def test_result_reprs_show_their_content():
    run = noslip.simulate(ROOT / "scenes" / "sinai.toml", events=100, log=True)
    text = repr(run)
    assert "events=100" in text and "events log rows=100" in text and "energy_drift=" in text


def test_paths_are_taken_wherever_a_scene_is():
    path = ROOT / "scenes" / "sinai.toml"
    by_path = noslip.simulate(path, events=200)
    by_scene = noslip.simulate(noslip.Scene.from_file(path), events=200)
    assert by_path.summary["time"] == by_scene.summary["time"]
    assert noslip.lyapunov(path, 2200, k=1).per_time[0] == \
        noslip.lyapunov(noslip.Scene.from_file(path), 2200, k=1).per_time[0]
    with pytest.raises(noslip.InputError, match="scene: expected a Scene, TOML text, a path"):
        noslip.simulate(3, events=1)


def test_a_dict_without_species_blames_species():
    scene = {"dim": 2, "box": {"size": [1, 1], "boundary": ["periodic", "periodic"]}}
    with pytest.raises(noslip.InputError, match=r"^<dict>: species: missing"):
        noslip.Scene.from_dict(scene)
    del scene["box"]["boundary"]
    with pytest.raises(noslip.InputError, match=r"^<dict>: box\.boundary: missing"):
        noslip.Scene.from_dict(scene)


def test_orbits_take_a_numpy_array_of_starts(root):
    scene = root / "scenes" / "disk_between_walls.toml"
    if not scene.exists():
        pytest.skip("no disk_between_walls scene")
    listed = noslip.orbits(scene, 2, starts=[[1, 0.5, 0, 1, 0]])
    array = noslip.orbits(scene, 2, starts=np.array([[1, 0.5, 0, 1, 0]]))
    assert len(array.orbits) == len(listed.orbits) == 1
    assert np.array_equal(array.orbits[0].start, listed.orbits[0].start)


# --- docstrings ----------------------------------------------------------------------------


def _public():
    yield "Scene", noslip.Scene
    for name in ("from_file", "from_dict", "toml", "origin", "dim", "description", "balls"):
        yield f"Scene.{name}", getattr(noslip.Scene, name)
    for name in noslip.__all__:
        obj = getattr(noslip, name)
        if callable(obj) or inspect.ismodule(obj):
            yield name, obj
    for name in dir(noslip._native):
        obj = getattr(noslip._native, name)
        if callable(obj) and not name.startswith("_"):
            yield f"_native.{name}", obj


@pytest.mark.parametrize("name,obj", list(_public()))
def test_docstrings_are_numpy_style_without_rustdoc_markup(name, obj):
    doc = inspect.getdoc(obj)
    assert doc, f"{name} has no docstring"
    assert "](" not in doc and "[`" not in doc, f"{name}: a rustdoc link"
    # Single backticks as rustdoc writes code; Sphinx roles (:func:`x`) are NumPy style.
    single = re.findall(r"(?<![`\w:])`[^`\n]+`(?![`_])", doc)
    assert not single, f"{name}: rustdoc code spans {single} (NumPy style writes ``x``)"


def test_native_signatures_have_no_ellipsis():
    assert str(inspect.signature(noslip.Scene)) == "(text, origin='<string>')"
    assert str(inspect.signature(noslip.Scene.from_dict)) == "(scene, origin='<dict>')"
    for name in dir(noslip._native):
        obj = getattr(noslip._native, name)
        if callable(obj) and not isinstance(obj, type):
            try:
                sig = str(inspect.signature(obj))
            except (ValueError, TypeError):
                continue
            assert "Ellipsis" not in sig and "..." not in sig, (name, sig)
