"""A fuzzer of the package's entry points (Hypothesis): hostile inputs (NaN, infinities,
subnormals, huge and negative numbers, wrong shapes, dtypes and types, malformed dicts and
TOML text) to `collide`, `collide_batch`, `Scene`, `Scene.from_dict`, `simulate`, `verify`,
`report`, `lyapunov` and `orbits`. Every call must either return finite results or raise
the package's `InputError` (or a `TypeError` for an argument of the wrong Python type)
whose message names the argument: never a crash, a non-finite answer or another exception.

Budget: the `ci` profile (the default) runs a few dozen examples per entry point, the whole
file in well under a minute; `NOSLIP_FUZZ_EXAMPLES=N` runs N examples for `collide` and
`collide_batch` and N/100 (at least the CI count) for the slower entry points."""

import math
import os

import numpy as np
import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

import noslip

EXAMPLES = int(os.environ.get("NOSLIP_FUZZ_EXAMPLES", "0"))
settings.register_profile(
    "fuzz", deadline=None, derandomize=EXAMPLES == 0, print_blob=True,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large,
                           HealthCheck.filter_too_much],
)
settings.load_profile("fuzz")

#: Examples per fast entry point (collide, collide_batch) and per slow one (runs).
FAST = max(EXAMPLES, 150)
SLOW = max(EXAMPLES // 100, 12)

#: Floats at and beyond every edge of f64: NaN, infinities, subnormals, the largest.
EDGES = [math.nan, math.inf, -math.inf, 5e-324, -5e-324, 1e-320, 2.2250738585072014e-308,
         1.7976931348623157e308, -1.7976931348623157e308, 1e308, 1e-300, 0.0, -0.0, 1.0,
         -1.0, 0.5, 1e300, 1e-16]
hostile_float = st.one_of(st.sampled_from(EDGES), st.floats(allow_nan=True, allow_infinity=True),
                          st.floats(-10, 10))
hostile_int = st.one_of(st.sampled_from([0, 1, 2, -1, 2**63, 2**64, -2**64, 10**30]),
                        st.integers(-5, 50))
junk = st.one_of(st.none(), st.booleans(), st.text(max_size=8), hostile_float, hostile_int,
                 st.lists(hostile_float, max_size=3), st.dictionaries(st.text(max_size=4),
                                                                     hostile_float, max_size=2))
number = st.one_of(hostile_float, hostile_int, st.sampled_from(["inf", "3/5", "1/0", "x", "nan"]))


def mostly(valid, hostile):
    """`valid` four times in five, `hostile` otherwise: each argument of a call is hostile
    now and then, so that a good share of the calls get past the checks and run."""
    return st.one_of(valid, valid, valid, valid, hostile)


def names_an_argument(message: str, names: list[str]) -> bool:
    """Whether `message` starts with (or, for PyO3's TypeError, quotes) one of `names`."""
    return any(message.startswith(n) or f"'{n}'" in message for n in names)


def outcome(call, names):
    """Run `call`: its result, or None after an InputError (or TypeError) naming one of
    `names`; any other exception fails the test."""
    try:
        out = call()
        event("returned")
        return out
    except noslip.InputError as e:
        event("InputError")
        assert names_an_argument(str(e), names), f"InputError naming nothing known: {e}"
    except TypeError as e:
        event("TypeError")
        assert names_an_argument(str(e), names), f"TypeError naming nothing known: {e}"
    return None


def all_finite(x) -> bool:
    """Every number in a result (nested dicts, lists, arrays) is finite."""
    if isinstance(x, dict):
        return all(all_finite(v) for v in x.values())
    if isinstance(x, (list, tuple)):
        return all(all_finite(v) for v in x)
    if isinstance(x, np.ndarray):
        return x.dtype.kind not in "fc" or bool(np.isfinite(x).all())
    if isinstance(x, float):
        return math.isfinite(x)
    return True


# --- collide -------------------------------------------------------------------------------

def vector(n):
    return st.lists(number, min_size=n, max_size=n)


@st.composite
def collide_args(draw):
    n = draw(st.sampled_from([2, 3, 4, 2, 3, 1, 7]))
    shape_n = draw(st.sampled_from([n, n, n, n - 1, n + 1]))

    def body():
        return draw(st.one_of(
            st.fixed_dictionaries({
                "mass": st.one_of(number, st.none()), "radius": number, "gamma2": number,
                "angular_velocity": st.lists(vector(shape_n), min_size=shape_n,
                                             max_size=shape_n),
                "velocity": vector(shape_n),
            }),
            junk,
        ))

    nu = draw(st.one_of(vector(n), junk))
    bodies = draw(st.one_of(st.tuples(st.just(0)).map(lambda _: [body(), body()]), junk))
    return nu, bodies


@settings(max_examples=FAST)
@given(collide_args())
def test_fuzz_collide(args):
    nu, bodies = args
    out = outcome(lambda: noslip.collide(nu, bodies),
                  ["normal", "nu", "bodies", "dim", "case", "relative velocity", "mass",
                   "radius", "gamma2", "angular_velocity", "velocity"])
    if out is not None:
        assert all_finite(out), out


# --- collide_batch -------------------------------------------------------------------------

@st.composite
def batch_args(draw):
    n = draw(st.sampled_from([2, 3, 6, 1, 7]))
    rows = draw(st.integers(0, 6))
    dtype = draw(st.sampled_from([np.float64, np.float32, np.float64, np.int64, object,
                                  np.complex128]))

    def arr(shape):
        flat = draw(st.lists(hostile_float, min_size=int(np.prod(shape)),
                             max_size=int(np.prod(shape))))
        a = np.array(flat, dtype=np.float64).reshape(shape)
        with np.errstate(all="ignore"):
            return a.astype(dtype) if dtype is not object else a.astype(object)

    def maybe_wrong(shape):
        wrong = draw(st.sampled_from([None, None, None, None, "rank", "len", "scalar"]))
        if wrong == "rank":
            return arr(shape + (1,))
        if wrong == "len":
            return arr((shape[0] + 1,) + shape[1:])
        if wrong == "scalar":
            return draw(hostile_float)
        return arr(shape)

    def body():
        if draw(st.integers(0, 20)) == 0:
            return draw(junk)
        b = {
            "angular_velocity": maybe_wrong((rows, n, n)),
            "velocity": maybe_wrong((rows, n)),
            "inv_mass": draw(st.one_of(hostile_float, st.just(None))) if draw(st.booleans())
            else maybe_wrong((rows,)),
            "radius": maybe_wrong((rows,)) if draw(st.booleans()) else draw(hostile_float),
            "gamma2": maybe_wrong((rows,)) if draw(st.booleans()) else draw(hostile_float),
        }
        if draw(st.integers(0, 10)) == 0:
            b.pop(draw(st.sampled_from(sorted(b))))
        return b

    normal = maybe_wrong((rows, n))
    return normal, [body(), body()], draw(st.booleans())


@settings(max_examples=FAST)
@given(batch_args())
def test_fuzz_collide_batch(args):
    normal, bodies, parallel = args
    out = outcome(lambda: noslip.collide_batch(normal, bodies, parallel=parallel),
                  ["normal", "bodies", "row ", "out"])
    if out is not None:
        assert all_finite(out), out


# --- Scene ---------------------------------------------------------------------------------

BASE = {
    "dim": 2,
    "box": {"size": [1, 1], "boundary": ["periodic", "periodic"]},
    "species": [{"name": "disk", "mass": 1, "radius": "1/20"}],
    "ball": [{"species": 0, "position": ["1/10", "1/10"], "velocity": ["0.6", "0.8"],
              "angular_velocity": 0}],
    "obstacle": [{"position": ["1/2", "1/2"], "radius": "3/10"}],
}
PATHS = [("dim",), ("box", "size", 0), ("box", "boundary", 1), ("species", 0, "mass"),
         ("species", 0, "radius"), ("species", 0, "gamma2"), ("ball", 0, "position", 1),
         ("ball", 0, "velocity", 0), ("ball", 0, "angular_velocity"), ("ball", 0, "species"),
         ("obstacle", 0, "radius"), ("obstacle", 0, "position"), ("simulation",), ("box",)]


@st.composite
def scene_dicts(draw):
    import copy

    d = copy.deepcopy(BASE)
    for _ in range(draw(st.integers(1, 3))):
        path = draw(st.sampled_from(PATHS))
        node = d
        for key in path[:-1]:
            node = node.setdefault(key, {}) if isinstance(node, dict) else node
            if isinstance(node, list):
                break
        value = draw(st.one_of(number, junk, st.sampled_from(["1e-320", "1e400", "-0"])))
        try:
            node[path[-1]] = value
        except (TypeError, IndexError):
            pass
    return d


SINAI = noslip.tables.sinai(0.5, 0.3)
SINAI_TEXT = SINAI.toml
SCENE_NAMES = ["<dict>", "<string>", "line", "scene", "dim", "box", "species", "ball",
               "obstacle", "simulation", "origin", "text", "scenes"]


@settings(max_examples=SLOW * 4)
@given(scene_dicts())
def test_fuzz_scene_from_dict(d):
    scene = outcome(lambda: noslip.Scene.from_dict(d), SCENE_NAMES)
    if scene is not None:
        assert scene.dim == 2


@st.composite
def mutated_toml(draw):
    """The Sinai scene's text with a piece replaced by junk (a number, a bracket, a quote,
    a key, an empty string)."""
    text = SINAI_TEXT
    at = draw(st.integers(0, len(text)))
    cut = draw(st.integers(0, 12))
    piece = draw(st.one_of(st.sampled_from(["1e400", "nan", "inf", "-1", "0", "5e-324", "[",
                                            "]", '"', "=", "\n", "", "1/0", "x = 1\n",
                                            "[[ball]]\n", "1e-320"]),
                           st.text(max_size=5)))
    return text[:at] + piece + text[at + cut:]


@settings(max_examples=SLOW * 4)
@given(st.one_of(mutated_toml(), mutated_toml(), st.text(max_size=200), st.sampled_from([
    "dim = ", "dim = 2\n[box]\nsize = [1e400, 1]", "dim = 2\n" * 3, "[[ball]]\n" * 50,
    "dim = 2\n[box]\nsize = [nan, 1]\nboundary = ['periodic', 'periodic']",
    "a = [[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[1]]]]]]]]]]]",
])))
def test_fuzz_scene_from_toml(text):
    outcome(lambda: noslip.Scene(text), SCENE_NAMES)


# --- simulate, lyapunov, orbits ------------------------------------------------------------

small_count = mostly(st.integers(1, 300),
                     st.one_of(st.sampled_from([0, -1, 2**64, 10**30]), st.none(), junk))


@settings(max_examples=SLOW * 2)
@given(small_count, mostly(st.one_of(st.none(), st.floats(0.5, 10)),
                          st.one_of(st.sampled_from(EDGES), junk)),
       st.booleans(), st.booleans(),
       mostly(st.one_of(st.none(), st.integers(10**5, 10**9)), st.one_of(hostile_int, junk)))
def test_fuzz_simulate(events, time, log, boundary_map, max_memory):
    if events is None:
        # Every run is bounded by its events: a valid time of 1e308 alone would run for ever.
        events = 50
    if isinstance(events, int) and 300 < events < 2**64:
        events = 300  # a valid 2^63 contacts only takes time (not capped, by design)
    kw = {} if max_memory is None else {"max_memory": max_memory}
    run = outcome(lambda: noslip.simulate(SINAI, events, time, log=log,
                                          boundary_map=boundary_map, **kw),
                  ["events", "time", "max_memory", "log", "boundary_map", "scene"])
    if run is not None:
        assert all_finite(run.summary) and all_finite(run.energy)
        assert all_finite(run.boundary_map)
        assert all_finite({k: v for k, v in run.events.items() if k not in
                           ("positions", "pre_spin", "pre_velocity", "post_spin",
                            "post_velocity")})


@settings(max_examples=SLOW)
@given(mostly(st.integers(20, 300), small_count), mostly(st.none(), small_count),
       mostly(st.sampled_from(["qr", "two-trajectory"]), junk),
       mostly(st.integers(0, 5), st.one_of(hostile_int, junk)),
       mostly(st.integers(1, 5), hostile_int),
       mostly(st.one_of(st.none(), st.integers(1, 5)), hostile_int),
       mostly(st.one_of(st.none(), st.sampled_from(["smooth", "no-slip"])),
              st.one_of(st.just("rough"), junk)))
def test_fuzz_lyapunov(events, k, method, seed, blocks, every, contact):
    if isinstance(events, int) and 300 < events < 2**64:
        events = 300
    out = outcome(lambda: noslip.lyapunov(SINAI, events, k=k, method=method, seed=seed,
                                          blocks=blocks, every=every, contact=contact),
                  ["events", "k", "method", "seed", "blocks", "every", "contact", "scene",
                   "the run"])
    if out is not None:
        assert all_finite([out.per_time, out.per_contact, out.sum, out.time])


ONE_BALL = noslip.Scene.from_dict({
    "dim": 2, "box": {"size": [1, 1], "boundary": ["wall", "wall"]},
    "species": [{"mass": 1, "radius": "1/10"}],
    "ball": [{"species": 0, "position": ["1/2", "1/3"], "velocity": ["3/5", "4/5"],
              "angular_velocity": "1/2"}],
})


@settings(max_examples=SLOW)
@given(mostly(st.integers(1, 2), st.one_of(hostile_int, junk)),
       mostly(st.one_of(st.none(), st.lists(st.lists(number, min_size=5, max_size=5),
                                            max_size=2)),
              st.one_of(st.lists(st.lists(number, max_size=6), max_size=2), junk)),
       mostly(st.one_of(st.none(), st.integers(1, 2)), st.one_of(hostile_int, junk)),
       mostly(st.one_of(st.none(), st.sampled_from(["smooth", "no-slip"])), st.just("x")))
def test_fuzz_orbits(period, starts, grid, contact):
    if isinstance(grid, int) and not isinstance(grid, bool) and 3 <= grid < 10**6:
        grid = 2
    if isinstance(period, int) and not isinstance(period, bool) and 3 <= period < 10**6:
        period = 2
    out = outcome(lambda: noslip.orbits(ONE_BALL, period, starts=starts, grid=grid,
                                        contact=contact),
                  ["period", "starts", "grid", "contact", "scene"])
    if out is not None:
        assert all(all_finite([o.start, o.states, o.residual]) for o in out.orbits)


# --- verify, report ------------------------------------------------------------------------

dims_arg = mostly(st.lists(st.sampled_from([2, 3]), min_size=1, max_size=2),
                  st.one_of(st.lists(st.sampled_from([2, 0, 1, 7, -1, 2**64]), max_size=2),
                            junk))


@settings(max_examples=SLOW)
@given(dims_arg, mostly(st.integers(1, 2), st.one_of(hostile_int, junk)))
def test_fuzz_verify(dims, points):
    if isinstance(points, int) and not isinstance(points, bool) and 3 <= points <= 1024:
        points = 2
    out = outcome(lambda: noslip.verify(dims, points), ["dims", "points"])
    if out is not None:
        assert all_finite(out)


@settings(max_examples=SLOW)
@given(dims_arg, mostly(st.integers(1, 5), st.one_of(hostile_int, junk)),
       mostly(st.integers(0, 9), st.one_of(hostile_int, junk)))
def test_fuzz_report(dims, samples, seed):
    if isinstance(samples, int) and not isinstance(samples, bool) and 6 <= samples <= 100000:
        samples = 5
    out = outcome(lambda: noslip.report(dims, samples, seed), ["dims", "samples", "seed"])
    if out is not None:
        assert all_finite(out)
