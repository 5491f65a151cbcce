"""noslip.collide_batch with a contact law of the rough-ball family (issue 27): validated rows
bit for bit `noslip.collide(..., contact=...)`, unvalidated rows bit for bit the same kernel
row by row, a law per row or one shared, and bad laws refused naming the row and field."""

import numpy as np
import pytest

import noslip
from test_batch import random_batch, same_bits


def round_trip_masses(bodies):
    """inv_mass values whose 1/(1/w) is w, so that `collide` (which takes the mass) runs on
    the batch's parameters (as test_batch does)."""
    for b in bodies:
        w = b["inv_mass"]
        ok = (w == 0) | (1.0 / (1.0 / np.where(w == 0, 1, w)) == w)
        b["inv_mass"] = np.where(ok, w, 1.0)


def single(nu, bodies, i, contact):
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
    return noslip.collide(nu[i].tolist(), case_bodies, contact=contact)


def laws(rng, rows, kind):
    """Per-row laws: the family's ends among uniform draws."""
    e = rng.uniform(0, 1, rows)
    e[:4] = [0.0, 1.0, 1.0, 0.5]
    if kind == "rough":
        beta = rng.uniform(-1, 1, rows)
        beta[:4] = [-1.0, 1.0, -1.0, 0.0]
        return {"e": e, "beta": beta}
    mu = rng.uniform(0, 2, rows) * rng.integers(0, 2, rows)
    beta0 = rng.uniform(-1, 1, rows)
    return {"e": e, "mu": mu, "beta0": beta0}


def row_law(law, i):
    return {k: float(np.asarray(v).reshape(-1)[i if np.ndim(v) else 0]) for k, v in law.items()}


@pytest.mark.parametrize("kind", ["rough", "walton"])
@pytest.mark.parametrize("n", [2, 3, 4, 5, 6])
def test_validated_rows_are_collide_with_their_law_bit_for_bit(n, kind):
    rng = np.random.default_rng(27 + n)
    nu, bodies = random_batch(rng, 41, n)
    round_trip_masses(bodies)
    law = laws(rng, 41, kind)
    after = noslip.collide_batch(nu, bodies, contact=law)
    for i in range(41):
        want = single(nu, bodies, i, row_law(law, i))
        for b in range(2):
            for key in ("angular_velocity", "velocity"):
                assert same_bits(after[b][key][i], want[b][key]), (n, kind, i, b, key)


@pytest.mark.parametrize("kind", ["rough", "walton"])
@pytest.mark.parametrize("n", [2, 3, 6])
def test_unvalidated_rows_are_the_kernel_under_each_rows_law(n, kind):
    """Each row of a batch with a law per row has the bits of that row alone under its law
    as a shared scalar law (the shared-law kernel), C-contiguous or strided, serial or not."""
    rng = np.random.default_rng(270 + n)
    rows = 1100  # more than a pass and a split
    nu, bodies = random_batch(rng, rows, n)
    law = laws(rng, rows, kind)
    after = noslip.collide_batch(nu, bodies, contact=law, validate=False)
    serial = noslip.collide_batch(nu, bodies, contact=law, validate=False, parallel=False)
    # Strided inputs (every other row of a twice longer array) take the row-by-row path.
    wide_nu = np.repeat(nu, 2, axis=0)[::2]
    wide = [{k: np.repeat(v, 2, axis=0)[::2] for k, v in b.items()} for b in bodies]
    strided = noslip.collide_batch(wide_nu, wide, contact=law, validate=False)
    for i in list(range(40)) + list(range(rows - 9, rows)):
        one = [{k: v[i : i + 1] for k, v in b.items()} for b in bodies]
        want = noslip.collide_batch(nu[i : i + 1], one, contact=row_law(law, i), validate=False)
        for got in (after, serial, strided):
            for b in range(2):
                for key in ("angular_velocity", "velocity"):
                    assert same_bits(got[b][key][i], want[b][key][0]), (n, kind, i, b, key)


@pytest.mark.parametrize("n", [2, 4])
def test_the_elastic_ends_are_the_no_slip_and_smooth_maps(n):
    rng = np.random.default_rng(2700 + n)
    nu, bodies = random_batch(rng, 300, n)
    no_slip = noslip.collide_batch(nu, bodies, validate=False)
    ends = noslip.collide_batch(nu, bodies, contact={"e": 1, "beta": 1}, validate=False)
    smooth = noslip.collide_batch(nu, bodies, contact="smooth", validate=False)
    rough_smooth = noslip.collide_batch(nu, bodies, contact={"e": 1, "beta": -1}, validate=False)
    for b in range(2):
        for key in ("angular_velocity", "velocity"):
            assert same_bits(ends[b][key], no_slip[b][key])
            assert same_bits(smooth[b][key], rough_smooth[b][key])
    # The smooth map leaves every spin as it was.
    for b in range(2):
        assert same_bits(smooth[b]["angular_velocity"], bodies[b]["angular_velocity"])


def test_out_and_float32_with_a_law():
    rng = np.random.default_rng(5)
    nu, bodies = random_batch(rng, 50, 3, dtype=np.float32)
    law = {"e": np.float32(0.9), "mu": np.full(50, 0.3, dtype=np.float32), "beta0": 0.5}
    got = noslip.collide_batch(nu, bodies, contact=law, validate=False)
    assert got[0]["velocity"].dtype == np.float32
    out = [
        {"angular_velocity": np.empty((50, 3, 3), np.float32), "velocity": np.empty((50, 3), np.float32)}
        for _ in range(2)
    ]
    back = noslip.collide_batch(nu, bodies, contact=law, validate=False, out=out)
    for b in range(2):
        assert back[b]["velocity"] is out[b]["velocity"]
        assert same_bits(out[b]["velocity"], got[b]["velocity"])
        assert same_bits(out[b]["angular_velocity"], got[b]["angular_velocity"])


@pytest.mark.parametrize("kind", ["rough", "walton"])
def test_new_arrays_over_many_passes_are_out_and_short_batches(kind):
    """Without validation, new arrays under a law are written from the last rows to the first
    (`Exec::last_rows_first`), arrays given as `out` from the first to the last: over many
    passes (20000 rows at n = 3, out of the L2 cache) and a law per row, serial and split,
    both give the bits of batches of 1000 rows (one short call each)."""
    rng = np.random.default_rng(31 if kind == "rough" else 32)
    rows = 20000
    nu, bodies = random_batch(rng, rows, 3, unit_exactly=False)
    law = laws(rng, rows, kind)
    parts = []
    for i in range(0, rows, 1000):
        part = [{k: v[i : i + 1000] for k, v in b.items()} for b in bodies]
        part_law = {k: v[i : i + 1000] for k, v in law.items()}
        parts.append(noslip.collide_batch(nu[i : i + 1000], part, contact=part_law, validate=False))
    want = [{k: np.concatenate([p[b][k] for p in parts]) for k in parts[0][b]} for b in range(2)]
    for parallel in (False, True):
        got = noslip.collide_batch(nu, bodies, contact=law, validate=False, parallel=parallel)
        out = [{k: np.full_like(v, np.nan) for k, v in b.items()} for b in want]
        into = noslip.collide_batch(
            nu, bodies, contact=law, validate=False, parallel=parallel, out=out
        )
        for b in range(2):
            for k in ("angular_velocity", "velocity"):
                assert same_bits(got[b][k], want[b][k]), (kind, b, k, parallel)
                assert same_bits(into[b][k], want[b][k]), (kind, b, k, parallel, "out")


@pytest.mark.parametrize("validate", [True, False])
def test_bad_laws_name_the_row_and_the_field(validate):
    rng = np.random.default_rng(9)
    nu, bodies = random_batch(rng, 6, 3)
    e = np.full(6, 0.5)
    e[2] = 1.5
    cases = [
        ({"e": e, "beta": 0.0}, "row 2: contact.e: must be in [0, 1], got 1.5"),
        ({"e": 0.5, "beta": np.array([0, 0, 0, 0, 0, -1.01])}, "row 5: contact.beta"),
        # A value every row shares names the field alone.
        ({"e": 0.5, "beta": np.nan}, "contact.beta: must be in [-1, 1], got NaN"),
        ({"e": 1.0, "mu": np.array([0.1, 0.1, 0.1, -0.1, 0.1, 0.1]), "beta0": 0}, "row 3: contact.mu"),
        ({"e": 1.0, "mu": 0.1, "beta0": 2}, "contact.beta0: must be in [-1, 1], got 2.0"),
        ({"e": np.full(5, 0.5), "beta": 0.0}, "contact.e: expected shape (6,) or a scalar, got (5,)"),
        ({"e": np.full((6, 1), 0.5), "beta": 0.0}, "contact.e: expected shape"),
        ({"e": 0.5}, "contact: expected the keys e, beta"),
        ({"e": 0.5, "beta": 0, "mu": 1}, "contact: expected the keys"),
        ("rough", 'contact: expected "no-slip", "smooth"'),
        (3, "contact: expected"),
        ({"e": "x", "beta": 0}, "contact.e: dtype"),
    ]
    for contact, message in cases:
        with pytest.raises(noslip.InputError) as err:
            noslip.collide_batch(nu, bodies, contact=contact, validate=validate)
        assert str(err.value).startswith(message), (contact, str(err.value))


def test_a_refused_row_names_the_row_under_a_law():
    """With validate, a bad contact row under a law is refused as collide refuses it."""
    rng = np.random.default_rng(10)
    nu, bodies = random_batch(rng, 5, 2)
    bodies[1]["gamma2"][3] = 5.0
    with pytest.raises(noslip.InputError, match="row 3: bodies"):
        noslip.collide_batch(nu, bodies, contact={"e": 0.9, "beta": 0.1})


@pytest.mark.parametrize("kind", ["rough", "walton"])
@pytest.mark.parametrize("n", [2, 3, 5])
def test_rows_with_an_immovable_body_are_the_fixed_kernel(n, kind):
    """The rows with an immovable body (a third of them) take the row path of the `fixed`
    kernel (`Exec::rough_fixed_rows`, body 2 immovable swapped with `-nu`): every row bit for
    bit the row-by-row path of strided inputs (`collide_*_unchecked`), with a law per row
    and one shared, over more rows than the row path's chunk (2048)."""
    rng = np.random.default_rng(2750 + n)
    rows = 2600
    nu, bodies = random_batch(rng, rows, n)
    fixed = (bodies[0]["inv_mass"] == 0) | (bodies[1]["inv_mass"] == 0)
    assert fixed.sum() > rows // 4
    each = laws(rng, rows, kind)
    wide_nu = np.repeat(nu, 2, axis=0)[::2]
    wide = [{k: np.repeat(v, 2, axis=0)[::2] for k, v in b.items()} for b in bodies]
    for law in (each, row_law(each, 7)):
        after = noslip.collide_batch(nu, bodies, contact=law, validate=False)
        strided = noslip.collide_batch(wide_nu, wide, contact=law, validate=False)
        for b in range(2):
            for key in ("angular_velocity", "velocity"):
                assert same_bits(after[b][key], strided[b][key]), (n, kind, b, key)
        # The immovable body keeps its state.
        for b in range(2):
            still = bodies[b]["inv_mass"] == 0
            assert same_bits(after[b]["velocity"][still], bodies[b]["velocity"][still])


@pytest.mark.parametrize("kind", [None, "rough"])
def test_large_out_arrays_streamed_are_the_bits_of_short_batches(kind):
    """Into `out` arrays of at least 16 MiB the results are written with non-temporal
    stores where the CPU has AVX-512 (`Exec::streamed_results`): 100000 rows at n = 3 (19.2
    MB of outputs), no-slip and under a law per row, give the bits of batches of 10000 rows
    (1.9 MB each, ordinary stores) and of new arrays; and the same into arrays starting 8
    bytes past a multiple of 16, which take the ordinary stores."""
    rng = np.random.default_rng(41 if kind is None else 42)
    rows, step = 100000, 10000
    nu, bodies = random_batch(rng, rows, 3, unit_exactly=False)
    law = laws(rng, rows, kind) if kind is not None else None
    extra = {} if law is None else {"contact": law}

    def part_extra(i):
        return {} if law is None else {"contact": {k: v[i : i + step] for k, v in law.items()}}

    parts = []
    for i in range(0, rows, step):
        part = [{k: v[i : i + step] for k, v in b.items()} for b in bodies]
        parts.append(noslip.collide_batch(nu[i : i + step], part, validate=False, **part_extra(i)))
    want = [{k: np.concatenate([p[b][k] for p in parts]) for k in parts[0][b]} for b in range(2)]
    new = noslip.collide_batch(nu, bodies, validate=False, **extra)
    for shift in (0, 1):
        # A buffer one value longer, the array from value `shift` on: 8 bytes off for 1.
        out = []
        for b in range(2):
            arrays = {}
            for k, v in want[b].items():
                buffer = np.full(v.size + 1, np.nan)
                arrays[k] = buffer[shift : shift + v.size].reshape(v.shape)
            out.append(arrays)
        into = noslip.collide_batch(nu, bodies, validate=False, out=out, **extra)
        for b in range(2):
            for k in ("angular_velocity", "velocity"):
                assert same_bits(new[b][k], want[b][k]), (kind, b, k, "new")
                assert same_bits(into[b][k], want[b][k]), (kind, b, k, shift)
