"""noslip.collide_batch: bit for bit the single calls, validation naming the row and field,
only the outputs allocated, and the GIL released."""

import os
import threading
import time
import tracemalloc

import numpy as np
import pytest

import noslip


def random_batch(rng, rows, n, dtype=np.float64, immovable=True, unit_exactly=True):
    """Rows of approaching contacts in R^n; a sixth of them with body 1 immovable and a sixth
    with body 2 immovable. With `unit_exactly`, only normals whose |nu|^2 is 1 exactly in
    f64 (so `collide` renormalises nothing and its result is the kernel's: a normal off by
    an ulp is renormalised by `collide` and not by the batch, docs/python.md)."""
    nu = rng.normal(size=(rows * 3, n))
    nu /= np.linalg.norm(nu, axis=1, keepdims=True)
    if unit_exactly:
        # |nu|^2 summed left to right, as collide's check does (einsum may pair terms).
        nu = nu[[sum(x * x for x in row.tolist()) == 1.0 for row in nu]]
    nu = nu[:rows]
    assert len(nu) == rows
    bodies = []
    for _ in range(2):
        a = rng.uniform(-1, 1, size=(rows, n, n))
        bodies.append(
            {
                "angular_velocity": a - a.transpose(0, 2, 1),
                "velocity": rng.uniform(-1, 1, size=(rows, n)),
                "inv_mass": rng.uniform(0.25, 4.0, size=rows),
                "radius": rng.uniform(0.5, 2.0, size=rows),
                "gamma2": rng.uniform(0.01, 2.0 / n, size=rows),
            }
        )
    dn = np.einsum("ij,ij->i", bodies[1]["velocity"] - bodies[0]["velocity"], nu)
    nu[dn > 0] *= -1
    if immovable:
        who = rng.integers(0, 6, size=rows)
        for b in range(2):
            bodies[b]["inv_mass"][who == b] = 0.0
    out_bodies = [{k: v.astype(dtype) for k, v in b.items()} for b in bodies]
    return nu.astype(dtype), out_bodies


def single(nu, bodies, i):
    case_bodies = []
    for b in bodies:
        w = float(b["inv_mass"][i])
        case_bodies.append(
            {
                "mass": "inf" if w == 0 else 1.0 / w,
                "radius": float(b["radius"][i]),
                "gamma2": float(b["gamma2"][i]),
                "angular_velocity": b["angular_velocity"][i].tolist(),
                "velocity": b["velocity"][i].tolist(),
            }
        )
    return noslip.collide(nu[i].tolist(), case_bodies)


def same_bits(a, b):
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    return a.shape == b.shape and np.array_equal(a.view(np.uint64), b.view(np.uint64))


@pytest.mark.parametrize("n", [2, 3, 4, 5, 6])
def test_batch_equals_single_calls_bit_for_bit(n):
    """`collide` takes the mass and computes inv_mass = 1/m; the batch takes inv_mass. The
    rows use inv_mass whose 1/(1/w) round trips to w, so both run on the same parameters."""
    rng = np.random.default_rng(n)
    nu, bodies = random_batch(rng, 203, n)
    for b in bodies:
        w = b["inv_mass"]
        ok = (w == 0) | (1.0 / (1.0 / np.where(w == 0, 1, w)) == w)
        b["inv_mass"] = np.where(ok, w, 1.0)
    after = noslip.collide_batch(nu, bodies)
    for i in range(len(nu)):
        want = single(nu, bodies, i)
        for b in range(2):
            assert same_bits(after[b]["angular_velocity"][i], want[b]["angular_velocity"]), (n, i, b)
            assert same_bits(after[b]["velocity"][i], want[b]["velocity"]), (n, i, b)


def test_shared_parameters_and_strided_inputs_give_the_same_rows():
    rng = np.random.default_rng(7)
    nu, bodies = random_batch(rng, 300, 3, immovable=False)
    for b in bodies:
        b["radius"][:] = 0.75
        b["gamma2"][:] = 0.4
    shared = [dict(b, radius=0.75, gamma2=0.4) for b in bodies]
    # A Fortran-ordered copy and a strided view: read in place, same results.
    strided = [dict(b, velocity=np.asfortranarray(b["velocity"])) for b in shared]
    nu_view = np.repeat(nu, 2, axis=0)[::2]
    a = noslip.collide_batch(nu, bodies)
    for other in (noslip.collide_batch(nu, shared), noslip.collide_batch(nu_view, strided)):
        for b in range(2):
            for k in ("angular_velocity", "velocity"):
                assert same_bits(a[b][k], other[b][k])


def test_serial_and_threaded_batches_are_identical():
    rng = np.random.default_rng(11)
    nu, bodies = random_batch(rng, 5000, 4, unit_exactly=False)
    a = noslip.collide_batch(nu, bodies, parallel=True)
    b = noslip.collide_batch(nu, bodies, parallel=False)
    for body in range(2):
        for k in ("angular_velocity", "velocity"):
            assert same_bits(a[body][k], b[body][k])


@pytest.mark.parametrize("n", [2, 3])
def test_unvalidated_runs_of_rows_give_the_bits_of_short_batches(n):
    """Without validation the serial path takes row-major arrays in runs of 32768 rows (then
    reruns the rows with an immovable body by `fixed`): over two whole runs and a part of a
    third, at n = 2 and 3 (the AVX-512 permutes of the gather and scatter where the CPU has
    them), serial and split, every row is what a batch of 1000 rows (one short run) gives.
    New arrays are written from the last rows to the first, arrays given as `out` from the
    first to the last: both give these bits."""
    rng = np.random.default_rng(40 + n)
    rows = 2 * 32768 + 4099
    nu, bodies = random_batch(rng, rows, n, unit_exactly=False)
    parts = []
    for i in range(0, rows, 1000):
        part = [{k: v[i : i + 1000] for k, v in b.items()} for b in bodies]
        parts.append(noslip.collide_batch(nu[i : i + 1000], part, validate=False))
    want = [{k: np.concatenate([p[b][k] for p in parts]) for k in parts[0][b]} for b in range(2)]
    for parallel in (False, True):
        got = noslip.collide_batch(nu, bodies, validate=False, parallel=parallel)
        out = [{k: np.full_like(v, np.nan) for k, v in b.items()} for b in want]
        into = noslip.collide_batch(nu, bodies, validate=False, parallel=parallel, out=out)
        for b in range(2):
            for k in ("angular_velocity", "velocity"):
                assert same_bits(got[b][k], want[b][k]), (n, b, k, parallel)
                assert same_bits(into[b][k], want[b][k]), (n, b, k, parallel, "out")


def test_float32_is_the_float64_map_up_to_f32_rounding():
    """The same f32 inputs, computed in f32 and in f64: the kernel's error is a few eps per
    body in its energy norm for typical inputs (docs/accuracy.md bounds it by 16 eps), and
    these states and results are O(1) with masses within 16x, so 1e-5 (84 eps of f32) per
    component is a bound with room, and 1e-7 would not hold for f32 rounding alone."""
    rng = np.random.default_rng(3)
    nu32, bodies32 = random_batch(rng, 1000, 3, dtype=np.float32, unit_exactly=False)
    nu32 /= np.linalg.norm(nu32.astype(np.float64), axis=1, keepdims=True).astype(np.float32)
    bodies64 = [{k: v.astype(np.float64) for k, v in b.items()} for b in bodies32]
    a = noslip.collide_batch(nu32, bodies32)
    b = noslip.collide_batch(nu32.astype(np.float64), bodies64, validate=False)
    assert a[0]["velocity"].dtype == np.float32
    for body in range(2):
        for k in ("angular_velocity", "velocity"):
            err = np.abs(a[body][k].astype(np.float64) - b[body][k]).max()
            assert 1e-9 < err < 1e-5, (body, k, err)


def test_a_bad_row_is_named_with_its_field():
    rng = np.random.default_rng(5)
    nu, bodies = random_batch(rng, 3000, 2, immovable=False)
    bodies[1]["gamma2"][2049] = 1.5  # above 2/n = 1
    # Later bad rows in the same chunk of 512 rows and in later ones (run by whichever thread
    # takes them first): the first bad row is named, split or not.
    bodies[0]["radius"][[2500, 2600, 2999]] = -1.0
    # Repeated: which run reports first depends on timing, the row named must not.
    for parallel in (True, False) * 10:
        with pytest.raises(noslip.InputError, match=r"^row 2049: bodies\[1\]\.gamma2"):
            noslip.collide_batch(nu, bodies, parallel=parallel)
    bodies[1]["gamma2"][2049] = 0.5
    bodies[0]["angular_velocity"][17, 0, 1] += 1.0  # no longer skew
    with pytest.raises(noslip.InputError, match=r"^row 17: bodies\[0\]\.angular_velocity"):
        noslip.collide_batch(nu, bodies)
    bodies[0]["angular_velocity"][17, 0, 1] -= 1.0
    nu[9] *= 1.001
    with pytest.raises(noslip.InputError, match=r"^row 9: normal: must be a unit vector"):
        noslip.collide_batch(nu, bodies)


def test_a_failed_call_leaves_nothing_for_the_next():
    """Each thread keeps its chunk scratches between calls: calls stopped by a bad row (in
    the row-major path, after the gather, and in the strided path, half-way through filling
    the scratch), and calls of the same type with fewer rows and of other types in between,
    must not change a later call's bits; sampled rows are checked against `collide` too."""
    rng = np.random.default_rng(12)
    nu, bodies = random_batch(rng, 3000, 3)
    for b in bodies:  # inv_mass that round-trips through collide's mass (see above)
        w = b["inv_mass"]
        ok = (w == 0) | (1.0 / (1.0 / np.where(w == 0, 1, w)) == w)
        b["inv_mass"] = np.where(ok, w, 1.0)
    want = noslip.collide_batch(nu, bodies, parallel=False)
    for i in (0, 1, 511, 512, 1500, 2999):
        row = single(nu, bodies, i)
        for b in range(2):
            for k in ("angular_velocity", "velocity"):
                assert same_bits(want[b][k][i], row[b][k]), (i, b, k)
    bad = [dict(b) for b in bodies]
    bad[0] = dict(bad[0], radius=bad[0]["radius"].copy())
    bad[0]["radius"][[100, 1500, 2900]] = -1.0
    strided_bad = [dict(bad[0], velocity=np.asfortranarray(bad[0]["velocity"])), bad[1]]
    fewer_nu, fewer = random_batch(rng, 700, 3, unit_exactly=False)
    other_nu, other = random_batch(rng, 700, 5, unit_exactly=False)
    for parallel in (True, False):
        for stopped in (bad, strided_bad):
            with pytest.raises(noslip.InputError, match=r"^row 100: bodies\[0\]\.radius"):
                noslip.collide_batch(nu, stopped, parallel=parallel)
        noslip.collide_batch(fewer_nu, fewer, parallel=parallel)
        noslip.collide_batch(other_nu, other, parallel=parallel)
        noslip.collide_batch(
            other_nu.astype(np.float32),
            [{k: v.astype(np.float32) for k, v in b.items()} for b in other],
            validate=False,
            parallel=parallel,
        )
        got = noslip.collide_batch(nu, bodies, parallel=parallel)
        for b in range(2):
            for k in ("angular_velocity", "velocity"):
                assert same_bits(got[b][k], want[b][k]), (parallel, b, k)


def test_without_validation_a_bad_row_spoils_only_itself():
    rng = np.random.default_rng(6)
    nu, bodies = random_batch(rng, 40, 3, immovable=False)
    good = noslip.collide_batch(nu, bodies)
    bodies[0]["velocity"][13, 0] = np.nan
    bad = noslip.collide_batch(nu, bodies, validate=False)
    rows = np.isnan(bad[0]["velocity"]).any(axis=1) | np.isnan(bad[1]["velocity"]).any(axis=1)
    assert rows.tolist() == [i == 13 for i in range(40)]
    keep = ~rows
    assert same_bits(bad[1]["velocity"][keep], good[1]["velocity"][keep])


def test_shapes_and_dtypes_are_checked_naming_the_field():
    rng = np.random.default_rng(8)
    nu, bodies = random_batch(rng, 10, 3)
    wrong = [dict(bodies[0]), dict(bodies[1], velocity=bodies[1]["velocity"][:, :2])]
    with pytest.raises(noslip.InputError, match=r"^bodies\[1\]\.velocity: expected shape \(10, 3\)"):
        noslip.collide_batch(nu, wrong)
    # Types are cast as ufuncs cast them (test_numpy_feel.py); what no float type holds is
    # refused, naming the field.
    with pytest.raises(noslip.InputError, match=r"^normal: dtype complex128"):
        noslip.collide_batch(nu.astype(complex), bodies)
    with pytest.raises(noslip.InputError, match=r"^bodies\[0\]\.spin: unknown key"):
        noslip.collide_batch(nu, [dict(bodies[0], spin=1.0), bodies[1]])
    with pytest.raises(noslip.InputError, match=r"^bodies\[0\]\.inv_mass: conflicts with mass"):
        noslip.collide_batch(nu, [dict(bodies[0], mass=1.0), bodies[1]])
    with pytest.raises(noslip.InputError, match=r"normal: expected shape \(N, n\) with n in"):
        noslip.collide_batch(np.zeros((4, 7)), bodies)


def test_values_no_float_type_holds_are_named():
    """An int beyond every float is named (it was NumPy's bare OverflowError); in float32 a
    ball parameter that would become 0 is named as such, and the range error quotes the
    number, not its NumPy repr."""
    rng = np.random.default_rng(9)

    def with_mass(bodies, mass):
        b0 = {k: v for k, v in bodies[0].items() if k != "inv_mass"}
        return [dict(b0, mass=mass), bodies[1]]

    nu, bodies = random_batch(rng, 4, 3, immovable=False)
    with pytest.raises(noslip.InputError, match=r"^bodies\[0\]\.mass: an integer beyond"):
        noslip.collide_batch(nu, with_mass(bodies, 10**400))
    with pytest.raises(noslip.InputError, match=r"^bodies\[0\]\.radius: an integer beyond"):
        noslip.collide_batch(nu, [dict(bodies[0], radius=10**400), bodies[1]])
    nu32, b32 = random_batch(rng, 4, 3, dtype=np.float32, immovable=False, unit_exactly=False)
    with pytest.raises(noslip.InputError,
                       match=r"^bodies\[0\]\.mass: 1e-50 is below the range of float32"):
        noslip.collide_batch(nu32, with_mass(b32, 1e-50))
    with pytest.raises(noslip.InputError,
                       match=r"^bodies\[0\]\.radius: 1e\+300 is beyond the range of float32"):
        noslip.collide_batch(nu32, [dict(b32[0], radius=1e300), b32[1]])


def test_only_the_outputs_are_allocated():
    """NumPy reports its allocations to tracemalloc: the peak during the call is the output
    arrays (2 bodies x (n^2 + n) float64 per row) and nothing per row besides."""
    rng = np.random.default_rng(9)
    rows, n = 200_000, 3
    nu, bodies = random_batch(rng, rows, n, immovable=False, unit_exactly=False)
    outputs = 2 * rows * (n * n + n) * 8
    tracemalloc.start()
    try:
        tracemalloc.reset_peak()
        base = tracemalloc.get_traced_memory()[0]
        after = noslip.collide_batch(nu, bodies)
        peak = tracemalloc.get_traced_memory()[1] - base
    finally:
        tracemalloc.stop()
    assert after[0]["velocity"].shape == (rows, n)
    assert outputs <= peak < outputs + 64 * 1024, (peak, outputs)


@pytest.mark.parametrize("n", [2, 3, 6])
def test_out_arrays_receive_the_same_bits_and_are_returned(n):
    rng = np.random.default_rng(20 + n)
    nu, bodies = random_batch(rng, 1000, n, unit_exactly=False)
    want = noslip.collide_batch(nu, bodies)
    out = [{k: np.full_like(v, np.nan) for k, v in b.items()} for b in want]
    for parallel in (True, False):
        got = noslip.collide_batch(nu, bodies, parallel=parallel, out=out)
        for b in range(2):
            for k in ("angular_velocity", "velocity"):
                assert got[b][k] is out[b][k]
                assert same_bits(got[b][k], want[b][k]), (n, b, k, parallel)
        for b in out:
            for v in b.values():
                v[:] = np.nan


def test_out_allocates_nothing():
    rng = np.random.default_rng(12)
    nu, bodies = random_batch(rng, 200_000, 3, immovable=False, unit_exactly=False)
    out = noslip.collide_batch(nu, bodies)
    tracemalloc.start()
    try:
        tracemalloc.reset_peak()
        base = tracemalloc.get_traced_memory()[0]
        noslip.collide_batch(nu, bodies, out=out)
        peak = tracemalloc.get_traced_memory()[1] - base
    finally:
        tracemalloc.stop()
    assert peak < 64 * 1024, peak


def test_bad_out_arrays_are_named():
    rng = np.random.default_rng(13)
    nu, bodies = random_batch(rng, 10, 3)
    good = noslip.collide_batch(nu, bodies)

    def out_with(b, key, value):
        out = [dict(good[0]), dict(good[1])]
        out[b][key] = value
        return out

    cases = [
        (out_with(1, "velocity", np.zeros((10, 2))), r"^out\[1\]\.velocity: expected shape"),
        (
            out_with(0, "angular_velocity", np.zeros((10, 3, 3), np.float32)),
            r"^out\[0\]\.angular_velocity: dtype float32",
        ),
        (
            out_with(0, "velocity", np.zeros((3, 10)).T),
            r"^out\[0\]\.velocity: must be C-contiguous",
        ),
        (out_with(1, "velocity", [[0.0] * 3] * 10), r"^out\[1\]\.velocity: expected a NumPy array"),
        (out_with(0, "spin", good[0]["velocity"]), r"^out\[0\]\.spin: unknown key"),
        ([good[0]], r"^out: expected two mappings"),
    ]
    read_only = np.zeros((10, 3))
    read_only.setflags(write=False)
    cases.append((out_with(1, "velocity", read_only), r"^out\[1\]\.velocity: must be writeable"))
    # An output that is an input, or the same array twice: refused, nothing computed in place.
    cases.append(
        (out_with(0, "velocity", bodies[0]["velocity"]), r"^out\[0\]\.velocity: shares memory")
    )
    cases.append(
        (out_with(1, "velocity", good[0]["velocity"]), r"^out\[1\]\.velocity: shares memory")
    )
    for out, message in cases:
        with pytest.raises(noslip.InputError, match=message):
            noslip.collide_batch(nu, bodies, out=out)


def test_the_gil_is_released_during_a_batch():
    """While a serial batch runs in one thread, this thread keeps running Python: with the
    GIL held it could not advance at all during the call."""
    rng = np.random.default_rng(10)
    nu, bodies = random_batch(rng, 400_000, 4, immovable=False, unit_exactly=False)
    done = threading.Event()
    started = threading.Event()

    def work():
        started.set()
        noslip.collide_batch(nu, bodies, parallel=False)
        done.set()

    t = threading.Thread(target=work)
    t.start()
    started.wait()
    ticks = 0
    while not done.is_set():
        ticks += 1
        time.sleep(0)
    t.join()
    assert ticks > 100, ticks


def boundary_rows(n):
    """One-row batches on and around each bound of the checks, in units of eps (the
    rounding allowance is 8 eps of the scale): |nu|^2 - 1, gamma2 - 2/n, U_ij + U_ji, U_ii,
    the normal relative velocity (approaching to grazing to separating); and magnitudes far
    from 1 (huge velocities, tiny normal components, subnormal and zero velocities)."""
    eps = np.finfo(np.float64).eps
    rng = np.random.default_rng(100 + n)
    base_nu, base = random_batch(rng, 1, n, immovable=False)
    cases = []

    def case(edit):
        nu = base_nu.copy()
        bodies = [{k: v.copy() for k, v in b.items()} for b in base]
        edit(nu, bodies)
        cases.append((nu, bodies))

    ks = [-40, -20, -12, -9, -8, -7, -6, -5, -4, -3, -2, -1, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 12, 20]
    for k in ks:
        case(lambda nu, b, k=k: nu.__imul__(np.sqrt(1 + k * eps)))
        case(lambda nu, b, k=k: b[1]["gamma2"].__setitem__(0, 2.0 / n * (1 + k * eps)))
        case(lambda nu, b, k=k: b[0]["gamma2"].__setitem__(0, k * eps))
        case(lambda nu, b, k=k: b[0]["angular_velocity"][0].__setitem__(
            (1, 0), -b[0]["angular_velocity"][0, 0, 1] * (1 + k * eps)))
        case(lambda nu, b, k=k: b[1]["angular_velocity"][0].__setitem__((0, 0), k * eps))

        def graze(nu, b, k=k):
            # u_2 - u_1 = t + dn nu with t perpendicular to nu, dn = k eps |t|.
            t = b[1]["velocity"][0] - b[0]["velocity"][0]
            t -= (t @ nu[0]) * nu[0]
            b[1]["velocity"][0] = b[0]["velocity"][0] + t + k * eps * np.linalg.norm(t) * nu[0]

        case(graze)
    case(lambda nu, b: [x["velocity"].__imul__(1e300) for x in b])
    case(lambda nu, b: [x["velocity"].__imul__(1e-310) for x in b])
    case(lambda nu, b: [x["velocity"].__imul__(0.0) for x in b])
    case(lambda nu, b: b[1]["velocity"].__setitem__(0, b[0]["velocity"][0]))

    def tiny_component(nu, b):
        nu[0, 0] = 1e-170
        nu[0, 1:] /= np.linalg.norm(nu[0, 1:])

    case(tiny_component)
    return cases


@pytest.mark.parametrize("n", [2, 3, 6])
def test_the_fast_check_accepts_only_what_collide_checks_accept(n):
    """Row-major arrays go through a cheap check in f64 that passes the clearly valid rows and
    sends the others to `collide`'s checks; strided arrays go through `collide`'s checks
    alone. Around every bound the two give the same verdict and the same message, and the
    rows near the bounds do occur on both sides (the cases are not all valid or all bad)."""
    verdicts = []
    for nu, bodies in boundary_rows(n):
        # Every second column of a wider array: strided, so every row takes the slow path.
        strided_nu = np.repeat(nu, 2, axis=1)[:, ::2]
        assert not strided_nu.flags.c_contiguous and np.array_equal(strided_nu, nu)
        results = []
        for args in ((nu, bodies), (strided_nu, bodies)):
            try:
                out = noslip.collide_batch(*args)
                results.append(("ok", out[0]["velocity"].tobytes(), out[1]["velocity"].tobytes()))
            except noslip.InputError as e:
                results.append(("error", str(e)))
        assert results[0] == results[1]
        verdicts.append(results[0][0])
    assert verdicts.count("ok") > 10 and verdicts.count("error") > 10, verdicts


def test_arrays_with_the_wrong_number_of_dimensions_are_named():
    """A column (N, 1) where (N,) is expected once gave PyO3's `TypeError: argument 'body1':
    'ndarray' object cannot be cast as 'ndarray'`; now the field and the expected shape."""
    rng = np.random.default_rng(14)
    nu, bodies = random_batch(rng, 10, 3)
    cases = [
        (0, "gamma2", np.full((10, 1), 0.4),
         r"^bodies\[0\]\.gamma2: expected shape \(10,\) or a scalar, got \(10, 1\)$"),
        (1, "velocity", np.zeros((10, 3, 1)),
         r"^bodies\[1\]\.velocity: expected shape \(10, 3\), got \(10, 3, 1\)$"),
        (0, "angular_velocity", 0.0,
         r"^bodies\[0\]\.angular_velocity: expected shape \(10, 3, 3\), got \(\)$"),
    ]
    for b, key, value, message in cases:
        given = [dict(body) for body in bodies]
        given[b][key] = value
        with pytest.raises(noslip.InputError, match=message):
            noslip.collide_batch(nu, given)
    out = noslip.collide_batch(nu, bodies)
    out[1]["velocity"] = np.zeros(10)
    message = r"^out\[1\]\.velocity: expected shape \(10, 3\), got \(10,\)$"
    with pytest.raises(noslip.InputError, match=message):
        noslip.collide_batch(nu, bodies, out=out)


def test_an_inverse_mass_error_names_inv_mass():
    """The batch takes `inv_mass` (collide takes `mass`): its errors name the key given."""
    rng = np.random.default_rng(15)
    nu, bodies = random_batch(rng, 10, 3, immovable=False)
    bodies[0]["inv_mass"][4] = -1.0
    message = r"^row 4: bodies\[0\]\.inv_mass: inverse mass must be >= 0$"
    with pytest.raises(noslip.InputError, match=message):
        noslip.collide_batch(nu, bodies)
    bodies[0]["inv_mass"][4] = 1.0
    bodies[1]["inv_mass"] = np.inf
    message = r"^row 0: bodies\[1\]\.inv_mass: must be a finite number"
    with pytest.raises(noslip.InputError, match=message):
        noslip.collide_batch(nu, bodies)


def test_without_validation_a_zero_normal_gives_finite_garbage():
    """docs/python.md: without validation a bad row's outputs are garbage, not always NaN; a
    zero normal gives finite numbers (not the input state, not a collision), the other
    rows are untouched."""
    rng = np.random.default_rng(16)
    nu, bodies = random_batch(rng, 40, 3, immovable=False)
    good = noslip.collide_batch(nu, bodies)
    nu[7] = 0.0
    with pytest.raises(noslip.InputError, match=r"^row 7: normal"):
        noslip.collide_batch(nu, bodies)
    bad = noslip.collide_batch(nu, bodies, validate=False)
    for b in range(2):
        for key in ("angular_velocity", "velocity"):
            assert np.isfinite(bad[b][key]).all()
            keep = np.arange(40) != 7
            assert same_bits(bad[b][key][keep], good[b][key][keep])


def collide_or_error(nu, bodies, i, masses):
    """`noslip.collide` on row `i`, the bodies' masses given as `masses[b][i]` (the batch
    takes their inverses): its result, or None if it refuses the row."""
    case_bodies = []
    for b, body in enumerate(bodies):
        m = masses[b][i]
        case_bodies.append({
            "mass": "inf" if m == np.inf else float(m),
            "radius": float(body["radius"][i]),
            "gamma2": float(body["gamma2"][i]),
            "angular_velocity": body["angular_velocity"][i].tolist(),
            "velocity": body["velocity"][i].tolist(),
        })
    try:
        return noslip.collide(nu[i].tolist(), case_bodies)
    except noslip.InputError:
        return None


def batch_or_error(nu, bodies, i):
    """The validated batch on row `i` alone: its two bodies, or None if it refuses the row."""
    row = [{k: v[i:i + 1] for k, v in b.items()} for b in bodies]
    try:
        return noslip.collide_batch(nu[i:i + 1], row)
    except noslip.InputError:
        return None


def test_validated_rows_at_the_range_limits_are_collides():
    """Issue 26: a velocity of 1e308 against an immovable body came back -inf from the
    validated batch (the f64 kernel's 2 P overflowed) where `collide` returns the finite
    [3.33e307, -1e308]; a velocity of 5e-324 came back subnormal where `collide` refuses
    it. The validated rows now go through `collide` itself."""
    def row(speed):
        nu = np.array([[0.0, 1.0]])
        bodies = [
            {"angular_velocity": np.zeros((1, 2, 2)), "velocity": np.array([[speed, speed]]),
             "inv_mass": np.array([1.0]), "radius": np.array([1.0]),
             "gamma2": np.array([0.5])},
            {"angular_velocity": np.zeros((1, 2, 2)), "velocity": np.zeros((1, 2)),
             "inv_mass": np.array([0.0]), "radius": np.array([1.0]),
             "gamma2": np.array([0.5])},
        ]
        return nu, bodies, [[1.0], [np.inf]]

    nu, bodies, masses = row(1e308)
    want = collide_or_error(nu, bodies, 0, masses)
    got = batch_or_error(nu, bodies, 0)
    assert want is not None and got is not None
    assert np.isfinite(got[0]["velocity"]).all(), got[0]["velocity"]
    assert same_bits(got[0]["velocity"][0], want[0]["velocity"])
    assert want[0]["velocity"][1] == -1e308 and 3.3e307 < want[0]["velocity"][0] < 3.4e307
    nu, bodies, masses = row(5e-324)
    assert collide_or_error(nu, bodies, 0, masses) is None
    with pytest.raises(noslip.InputError, match=r"^row 0: bodies\[0\]\.velocity: .* below the "
                       r"normal range of f64"):
        noslip.collide_batch(nu, bodies)


def extreme_rows(rng, rows, n):
    """Random rows whose magnitudes span f64's range, its ends included: each number is
    zero or `±m 10^e` with `e` from the subnormals to 308; normals unit in floats (some a
    few ulps off), `gamma2` up to a few eps beyond 2/n, masses from 1e-300 to 1e300 or
    immovable, some rows grazing or separating. About half are valid."""
    exps = np.array([-323, -315, -308, -300, -200, -150, -30, -1, 0, 1, 30, 150, 200, 300,
                     306, 307, 308])
    scale = rng.choice(exps, size=rows)

    def magnitudes(shape):
        """Per row, numbers within 10^-3 of the row's scale 10^e (at most 1.7e308)."""
        e = (scale.reshape((rows,) + (1,) * (len(shape) - 1))
             - rng.integers(0, 3, size=shape) * (rng.random(size=shape) < 0.5))
        x = rng.uniform(1, 1.7, size=shape) * 10.0 ** e
        x *= rng.choice([-1.0, 1.0], size=shape)
        x[rng.random(size=shape) < 0.15] = 0.0
        return x

    nu = rng.normal(size=(rows, n))
    nu /= np.linalg.norm(nu, axis=1, keepdims=True)
    off = rng.random(rows) < 0.2
    nu[off] *= 1 + rng.integers(-6, 7, size=(off.sum(), 1)) * np.finfo(float).eps
    small = rng.random(rows) < 0.1
    nu[small, 0] = 1e-200
    nu[small, 1:] /= np.linalg.norm(nu[small, 1:], axis=1, keepdims=True)
    bodies, masses = [], []
    for _ in range(2):
        a = magnitudes((rows, n, n))
        spin = np.triu(a, 1) - np.triu(a, 1).transpose(0, 2, 1)
        m = 10.0 ** rng.uniform(-300, 300, size=rows)
        bodies.append({
            "angular_velocity": spin,
            "velocity": magnitudes((rows, n)),
            "radius": np.where(rng.random(rows) < 0.5, rng.uniform(0.5, 2, size=rows),
                               10.0 ** rng.choice(exps, size=rows)),
            "gamma2": np.minimum(rng.uniform(0, 2.0 / n * (1 + 1e-15), size=rows), 2.0 / n + 4e-16),
        })
        masses.append(m)
    fixed = rng.integers(0, 5, size=rows)
    for b in range(2):
        masses[b] = np.where(fixed == b, np.inf, masses[b])
        bodies[b]["inv_mass"] = 1.0 / masses[b]
    # Approaching, mostly: flip the normal where the bodies separate, except in a tenth.
    with np.errstate(over="ignore", invalid="ignore"):
        dn = np.einsum("ij,ij->i", bodies[1]["velocity"] - bodies[0]["velocity"], nu)
    nu[(dn > 0) & (rng.random(rows) < 0.9)] *= -1
    return nu, bodies, masses


@pytest.mark.parametrize("n", [2, 3, 6])
def test_validated_rows_are_accepted_refused_and_rounded_as_collide_does(n):
    """Property: on random rows spanning f64's range, each row alone is refused by the
    validated batch exactly when `collide` refuses it, and otherwise gives `collide`'s
    result bit for bit; the accepted rows together in one batch (threads, chunks of 512)
    give the same bits."""
    rng = np.random.default_rng(260 + n)
    # NOSLIP_BATCH_ROWS rows per n for a longer local run (1200 in the suite).
    rows = int(os.environ.get("NOSLIP_BATCH_ROWS", "1200"))
    nu, bodies, masses = extreme_rows(rng, rows, n)
    accepted = []
    for i in range(len(nu)):
        want = collide_or_error(nu, bodies, i, masses)
        got = batch_or_error(nu, bodies, i)
        assert (got is None) == (want is None), (n, i)
        if want is not None:
            accepted.append(i)
            for b in range(2):
                assert same_bits(got[b]["angular_velocity"][0], want[b]["angular_velocity"]), (n, i)
                assert same_bits(got[b]["velocity"][0], want[b]["velocity"]), (n, i)
    assert len(nu) // 8 < len(accepted) < len(nu) - len(nu) // 8, len(accepted)
    keep = np.array(accepted)
    together = noslip.collide_batch(nu[keep], [{k: v[keep] for k, v in b.items()} for b in bodies])
    for j, i in enumerate(accepted):
        got = batch_or_error(nu, bodies, i)
        for b in range(2):
            assert same_bits(together[b]["velocity"][j], got[b]["velocity"][0]), (n, i)
            assert same_bits(together[b]["angular_velocity"][j], got[b]["angular_velocity"][0])
