"""A batch of collisions on NumPy arrays: :func:`collide_batch`."""

from __future__ import annotations

from typing import Any, Dict, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

from noslip import _native
from noslip._native import DIMS, InputError

__all__ = ["collide_batch", "isa", "BODY_KEYS"]

#: The keys of a body in :func:`collide_batch`, those of :func:`noslip.collide`: the states,
#: ``radius``, one of ``mass`` / ``inv_mass`` and at most one of ``lambda`` / ``gamma2`` /
#: ``distribution`` (uniform when none is given).
BODY_KEYS = (
    "angular_velocity",
    "velocity",
    "mass",
    "inv_mass",
    "radius",
    "lambda",
    "gamma2",
    "distribution",
)

#: The keys of which a body gives exactly one (the mass), and at most one (the inertia).
_MASS_KEYS = ("mass", "inv_mass")
_INERTIA_KEYS = ("lambda", "gamma2", "distribution")

_Array = npt.NDArray[Any]
_BodyArrays = Tuple[_Array, _Array, _Array, _Array, _Array]


def _shape_text(shape: Tuple[Union[int, str], ...]) -> str:
    """A shape as NumPy prints it: ``(5, 3)``, ``(5,)``."""
    if len(shape) == 1:
        return f"({shape[0]},)"
    return "(" + ", ".join(str(k) for k in shape) + ")"


def _shape_error(field: str, expected: str, got: Tuple[int, ...]) -> InputError:
    """The package's one shape message: ``field: expected shape (5, 3), got (6, 3)``."""
    return InputError(f"{field}: expected shape {expected}, got {_shape_text(got)}")


def _numeric(x: Any, field: str) -> Any:
    """``x`` as :func:`numpy.result_type` takes it: an ndarray or NumPy scalar as it is, a
    Python int or float as it is (a "weak" scalar: it takes the arrays' float type, as in
    ufuncs), anything else (lists, nested sequences) through :func:`numpy.asarray`; the
    mass ``"inf"`` (as :func:`noslip.collide` spells it) is ``inf``."""
    if isinstance(x, str) and field.endswith(".mass") and x.strip().lower() == "inf":
        return float("inf")
    if isinstance(x, (np.ndarray, np.generic)) or (
        isinstance(x, (int, float)) and not isinstance(x, bool)
    ):
        return x
    try:
        a = np.asarray(x)
    except (TypeError, ValueError) as e:
        raise InputError(f"{field}: expected numbers, got {type(x).__name__} ({e})") from None
    return a


def _check_kind(x: Any, field: str) -> None:
    """Refuse a value no float type holds (naming the field): complex, text, objects, and
    ``longdouble`` (the kernels run in float64 at most; casting would round it)."""
    dt = np.asarray(x).dtype if not isinstance(x, (int, float)) else np.dtype(type(x))
    if dt.kind not in "biuf" or (dt.kind == "f" and dt.itemsize > 8):
        raise InputError(
            f"{field}: dtype {dt} cannot be cast to float64 or float32 without loss (give "
            "real numbers: bools, ints or floats up to float64)"
        )


def result_dtype(values: Sequence[Tuple[str, Any]]) -> np.dtype[Any]:
    """The float type a batch of these inputs runs in, as a ufunc casts them: the
    :func:`numpy.result_type` of every input (Python scalars are "weak": they take the
    arrays' type), then ``float32`` if that is ``float32`` or ``float16``, else ``float64``
    (ints and bools, as ``np.true_divide`` makes them ``float64``; mixed ``float32`` and
    ``float64`` give ``float64``)."""
    for field, x in values:
        _check_kind(x, field)
    common = np.result_type(*(x for _, x in values))
    if common.kind == "f" and common.itemsize <= 4:
        return np.dtype(np.float32)
    return np.dtype(np.float64)


def _cast(x: Any, dtype: np.dtype[Any], field: str, scalar: bool = False) -> _Array:
    """``x`` as an array of ``dtype``: the same array when it already is one (read in place,
    no copy), else a converted copy; a finite value beyond float32's range is named, not
    made infinite, and so is an integer beyond any float's. ``scalar``: a ball parameter,
    whose nonzero value may not become 0 in float32 (a state entry may: it is measured
    against the others, as the checked ``collide`` measures a subnormal one)."""
    if isinstance(x, np.ndarray) and x.dtype == dtype:
        return x
    try:
        with np.errstate(over="ignore", invalid="ignore", under="ignore"):
            a = np.asarray(x).astype(dtype)
    except OverflowError:
        # A Python int beyond every float (10**400): named, not NumPy's bare OverflowError.
        raise InputError(
            f"{field}: an integer beyond the range of {np.dtype(dtype).name} (at most about "
            f"{float(np.finfo(dtype).max):.3g})"
        ) from None
    if dtype == np.float32:
        wide = np.asarray(x, dtype=np.float64)
        beyond = np.isinf(a) & np.isfinite(wide)
        if np.any(beyond):
            raise InputError(
                f"{field}: {float(wide[beyond].flat[0])!r} is beyond the range of float32 (the "
                "inputs' common type)"
            )
        # A nonzero value that float32 cannot hold (1e-50 became 0): named as such, not as
        # the 0 a later check would see.
        lost = (a == 0) & (wide != 0)
        if scalar and np.any(lost):
            raise InputError(
                f"{field}: {float(wide[lost].flat[0])!r} is below the range of float32 (it would "
                "be 0; the inputs' common type)"
            )
    return a


def _parse_body(body: Any, b: int) -> Dict[str, Any]:
    """Body ``b``'s keys checked (a mapping; no unknown key; the states, ``radius`` and a
    mass present; at most one mass and one inertia key) and its numbers as
    :func:`_numeric` makes them (``distribution`` kept as text)."""
    if not isinstance(body, Mapping):
        raise InputError(f"bodies[{b}]: expected a mapping with keys {', '.join(BODY_KEYS)}")
    unknown = [k for k in body if k not in BODY_KEYS]
    if unknown:
        raise InputError(
            f"bodies[{b}].{unknown[0]}: unknown key (the keys are: {', '.join(BODY_KEYS)})"
        )
    for key in ("angular_velocity", "velocity", "radius"):
        if key not in body:
            raise InputError(f"bodies[{b}].{key}: missing (required)")
    masses = [k for k in _MASS_KEYS if k in body]
    if not masses:
        raise InputError(f"bodies[{b}].mass: missing (give mass, or inv_mass = 1/mass)")
    if len(masses) > 1:
        raise InputError(f"bodies[{b}].inv_mass: conflicts with mass: give one of them")
    inertia = [k for k in _INERTIA_KEYS if k in body]
    if len(inertia) > 1:
        raise InputError(
            f"bodies[{b}].{inertia[1]}: conflicts with {inertia[0]}: give at most one of "
            "lambda, gamma2, distribution"
        )
    out: Dict[str, Any] = {}
    for key, x in body.items():
        if key == "distribution":
            if not isinstance(x, str):
                raise InputError(
                    f"bodies[{b}].distribution: expected \"uniform\" or \"shell\", got "
                    f"{type(x).__name__}"
                )
            out[key] = x
        else:
            out[key] = _numeric(x, f"bodies[{b}].{key}")
    return out


#: The number of dimensions of each array a body needs, per row.
_ROW_NDIM = {"angular_velocity": 2, "velocity": 1}


def _body_arrays(
    body: Dict[str, Any], b: int, dtype: np.dtype[Any], rows: int, n: int, single: bool
) -> _BodyArrays:
    """Body ``b``'s five arrays in the native order (``angular_velocity``, ``velocity``,
    ``inv_mass``, ``radius``, ``gamma2``), each of ``dtype`` with the dimensions its key
    needs; ``mass``, ``lambda`` and ``distribution`` turned into ``inv_mass`` and ``gamma2``
    by :func:`noslip.collide`'s ball constructor (natively, row by row). ``single``: one
    contact (a 1-D normal), the states without their row axis."""
    lead: Tuple[int, ...] = () if single else (rows,)
    lead_text: Tuple[Union[int, str], ...] = () if single else (rows,)
    states = []
    for key in ("angular_velocity", "velocity"):
        field = f"bodies[{b}].{key}"
        a = _cast(body[key], dtype, field)
        want = lead + (n,) * _ROW_NDIM[key]
        if a.ndim != len(want):
            raise _shape_error(field, _shape_text(lead_text + (n,) * _ROW_NDIM[key]), a.shape)
        states.append(a if not single else a.reshape((1,) + a.shape))
    params: Dict[str, _Array] = {}
    for key in ("mass", "inv_mass", "radius", "lambda", "gamma2"):
        if key not in body:
            continue
        field = f"bodies[{b}].{key}"
        a = _cast(body[key], dtype, field, scalar=True)
        if a.ndim == 0:
            a = a.reshape(1)
        elif single or a.ndim != 1 or len(a) not in (1, rows):
            expected = "a scalar" if single else f"({rows},) or a scalar"
            raise _shape_error(field, expected, a.shape)
        params[key] = a
    needs_ball = "mass" in body or "lambda" in body or "gamma2" not in body
    if needs_ball:
        convert = _native.batch_params_f64 if dtype == np.float64 else _native.batch_params_f32
        distribution = body.get("distribution")
        if "lambda" not in body and "gamma2" not in body and distribution is None:
            distribution = "uniform"
        inv_mass, gamma2 = convert(
            n, b, params.get("mass"), params["radius"], params.get("lambda"), distribution
        )
        if inv_mass is not None:
            params["inv_mass"] = inv_mass
        if gamma2 is not None:
            params["gamma2"] = gamma2
    return (
        states[0],
        states[1],
        params["inv_mass"],
        params["radius"],
        params["gamma2"],
    )


def collide_batch(
    normal: npt.ArrayLike,
    bodies: Sequence[Mapping[str, Any]],
    *,
    contact: Union[str, Mapping[str, Any], None] = None,
    validate: bool = True,
    parallel: bool = True,
    out: Optional[Sequence[Mapping[str, _Array]]] = None,
) -> Tuple[Dict[str, _Array], Dict[str, _Array]]:
    """The no-slip collision map (or another law of the rough-ball family) on every row of a
    batch.

    Row ``k`` is one contact: ``xi_k+ = 2 P_G(q_k) xi_k - xi_k`` (see :func:`noslip.collide`).
    With ``validate`` (the default) every row goes through :func:`noslip.collide`'s own
    checked path (the checks and the rounding allowance, the kernel run with an unbounded
    exponent, the results rounded back or refused when they do not fit): each row is
    accepted or refused as ``collide`` does it and its result is ``collide``'s bit for bit.
    Without it the
    generated batch kernels run the rows (blocks of 8 contacts, vectorised with the
    instruction set chosen at run time, :func:`isa`): each row is bit for bit the scalar
    kernel's result (``collide_unchecked`` in Rust), which is ``collide``'s only where the
    row needs no rounding allowance (``|nu|^2 = 1`` in the batch's float type, ``gamma2``
    in ``[0, 2/n]``, not grazing within 8 eps, ``U`` exactly skew) and no intermediate
    leaves the float type's range (a velocity of 1e308 against an immovable body gives
    ``-inf`` there, ``collide`` the finite ``3.3e307``). A row with an immovable body
    (``inv_mass = 0``) runs the ``fixed`` kernel, as ``collide`` does; that body comes back
    unchanged. The validated rows cost about 1 µs each (``collide``'s unbounded-exponent
    arithmetic), the unvalidated ones 15 to 150 ns (``docs/python.md``).

    The arrays are read in place (any strides; no copy, no per-row Python object), the GIL
    is released, and with ``parallel`` the rows are shared between the calling thread and
    rayon's other threads (from 513 rows on; the caller never waits for a thread to wake).
    C-contiguous arrays (NumPy's default) are gathered straight into the kernels' lane arrays
    and the results scattered straight into the outputs, in chunks of 512 rows; other strides
    go row by row. Memory beyond the new output arrays is a scratch of one chunk (15 to
    130 kB) per running thread, which that thread keeps for its next call.

    **Types**: the inputs are cast as a ufunc casts them. The batch runs in ``float32`` when
    :func:`numpy.result_type` of every input is ``float32`` (or ``float16``), else in
    ``float64`` (ints and bools, or ``float32`` mixed with ``float64``); Python scalars take
    the arrays' type. Arrays already of that type are read in place; others are converted
    (a copy). Complex, text, object and ``longdouble`` inputs are refused, naming the field.

    Parameters
    ----------
    normal : array_like, shape (N, n) or (n,)
        The unit normals ``nu``, from body 1's centre to body 2's; n in 2..6 (the
        dimensions with batch kernels; :func:`noslip.collide` takes n up to 16). A 1-D
        normal is one contact: the states are then ``(n, n)`` and ``(n,)``, the parameters
        scalars, and so are the results.
    bodies : two mappings
        The keys of :func:`noslip.collide`: ``angular_velocity``, ``(N, n, n)`` skew
        matrices ``U``; ``velocity``, ``(N, n)``; ``radius`` ``R > 0``; ``mass`` (``inf``
        for an immovable body) or ``inv_mass`` (``1/m``, 0 immovable); at most one of
        ``lambda`` (in ``[0, R^2/n]``), ``gamma2 = 2 lambda / R^2`` (in ``[0, 2/n]``;
        ``I/(m R^2)`` in 3D) or ``distribution`` (``"uniform"``, the default, ``2/(n+2)``;
        ``"shell"``, ``2/n``). Each parameter is ``(N,)`` or a scalar shared by all rows.
        ``mass``, ``lambda`` and ``distribution`` are turned into the kernels' ``inv_mass``
        and ``gamma2`` row by row by the constructor :func:`noslip.collide` builds its balls
        with (``Ball::new``: the same numbers, bit for bit, and the same checks, with or
        without ``validate``).
    contact : str or mapping, optional
        The contact law, as :func:`noslip.collide` takes it: ``"no-slip"`` (the default),
        ``"smooth"`` (``(e, beta) = (1, -1)``), ``{"e": e, "beta": beta}`` (the rough-ball
        law) or ``{"e": e, "mu": mu, "beta0": beta0}`` (the Walton law); here each number is
        a scalar shared by every row or an ``(N,)`` array, one law per row (``e`` in
        ``[0, 1]``, ``beta`` and ``beta0`` in ``[-1, 1]``, ``mu >= 0``, no NaN: a refused
        value names the row and the field, ``row 3: contact.e: ...``). With a law other than
        no-slip, ``validate`` runs each row through ``collide_rough`` / ``collide_walton``
        (Rust; :func:`noslip.collide`'s checks and rounding under that row's law) on the
        calling thread, and without it the rows go through ``Exec::rough_free_rows``: the
        scalar family kernel's bits on every row (docs/batch.md, "Laws as columns"); such a
        batch is not interrupted by Ctrl-C.
    validate : bool
        Check every row as :func:`noslip.collide` does (finite; unit normal; valid balls;
        skew ``U``; approaching, ``(u_2 - u_1) . nu <= 0``; a result that fits the float
        type), within the rounding allowance, by calling ``collide``'s own code. Without it, a bad row's outputs are garbage, not always visibly (NaN or infinities
        from a non-finite input, but finite, wrong numbers from others, such as a zero
        normal); the other rows' outputs are unaffected.
    parallel : bool
        Split the rows across rayon's threads (``False``: the calling thread only; the GIL
        is released either way).
    out : two mappings of arrays, optional
        Arrays to write the results into instead of new ones, as NumPy's ``out=``: per body
        ``angular_velocity`` ``(N, n, n)`` and ``velocity`` ``(N, n)`` (``(n, n)`` and
        ``(n,)`` for one contact) of the batch's dtype,
        C-contiguous, writeable, sharing no memory with the inputs or each other (a loop
        that keeps them allocates nothing and skips the first touch of new memory). On an
        error they may hold some rows' results.

    Returns
    -------
    (dict, dict)
        Per body, ``angular_velocity`` ``(N, n, n)`` and ``velocity`` ``(N, n)`` (one
        contact: ``(n, n)`` and ``(n,)``), of the batch's dtype: new arrays, or those of
        ``out``.

    Raises
    ------
    InputError
        A wrong shape or dtype (naming the field, ``out[1].velocity`` for an output), or
        with ``validate`` the first bad row: ``row 17: bodies[1].gamma2: ...``.
    KeyboardInterrupt
        Ctrl-C (SIGINT): Python's signals are looked at before each run of 4096 rows (once
        50 ms have passed); the new arrays are discarded, and arrays given as ``out`` hold
        the results of the runs done before it and are unchanged elsewhere.
    """
    nu = _numeric(normal, "normal")
    if np.ndim(nu) not in (1, 2):
        raise _shape_error("normal", "(N, n) or (n,)", np.shape(nu))
    single = np.ndim(nu) == 1
    rows, n = (1, np.shape(nu)[0]) if single else np.shape(nu)
    if n not in DIMS:
        raise InputError(
            f"normal: expected shape (N, n) with n in {DIMS[0]}..={DIMS[-1]} (the dimensions "
            "with batch kernels; noslip.collide takes n up to 16), got "
            f"{_shape_text(np.shape(nu))}"
        )
    if isinstance(bodies, (str, bytes, Mapping)) or not isinstance(bodies, Sequence):
        raise InputError("bodies: expected two bodies (a sequence of two mappings)")
    if len(bodies) != 2:
        raise InputError(f"bodies: expected two bodies, got {len(bodies)}")
    parsed = [_parse_body(bodies[b], b) for b in range(2)]
    law = _parse_contact(contact)
    dtype = result_dtype(
        [("normal", nu)]
        + [
            (f"bodies[{b}].{k}", x)
            for b, body in enumerate(parsed)
            for k, x in body.items()
            if k != "distribution"
        ]
        + ([] if law is None else [(f"contact.{k}", x) for k, x in law[1].items()])
    )
    nu = _cast(nu, dtype, "normal")
    if single:
        nu = nu.reshape(1, n)
    b1, b2 = (_body_arrays(parsed[b], b, dtype, rows, n, single) for b in range(2))
    arrays = None if out is None else _out(out, dtype, rows, n, single)
    if law is None:
        run = _native.collide_batch_f64 if dtype == np.float64 else _native.collide_batch_f32
        s1, v1, s2, v2 = run(nu, b1, b2, validate, parallel, arrays)
    else:
        kind, values = law
        columns = [_law_column(x, dtype, f"contact.{k}", rows, single) for k, x in values.items()]
        run_law = (
            _native.collide_batch_law_f64 if dtype == np.float64 else _native.collide_batch_law_f32
        )
        s1, v1, s2, v2 = run_law(nu, b1, b2, kind, columns, validate, parallel, arrays)
    if out is not None:
        return (
            {"angular_velocity": out[0]["angular_velocity"], "velocity": out[0]["velocity"]},
            {"angular_velocity": out[1]["angular_velocity"], "velocity": out[1]["velocity"]},
        )
    if single:
        s1, v1, s2, v2 = s1[0], v1[0], s2[0], v2[0]
    return (
        {"angular_velocity": s1, "velocity": v1},
        {"angular_velocity": s2, "velocity": v2},
    )


#: The keys of each law of the family in ``contact``, in the native order of its columns.
_LAW_KEYS = {"rough": ("e", "beta"), "walton": ("e", "mu", "beta0")}


def _parse_contact(contact: Any) -> Optional[Tuple[str, Dict[str, Any]]]:
    """``contact`` as ``(kind, {key: number or array})`` (``"rough"`` or ``"walton"``, the keys
    in their native order), or ``None`` for the no-slip map; a bad law names ``contact``."""
    if contact is None or (isinstance(contact, str) and contact == "no-slip"):
        return None
    if isinstance(contact, str):
        if contact == "smooth":
            return ("rough", {"e": 1, "beta": -1})
        raise InputError(
            f'contact: expected "no-slip", "smooth", {{"e", "beta"}} or {{"e", "mu", "beta0"}}, '
            f"got {contact!r}"
        )
    if not isinstance(contact, Mapping):
        raise InputError(
            f'contact: expected "no-slip", "smooth" or a mapping, got {type(contact).__name__}'
        )
    keys = set(contact)
    for kind, wanted in _LAW_KEYS.items():
        if keys == set(wanted):
            return (kind, {k: _numeric(contact[k], f"contact.{k}") for k in wanted})
    raise InputError(
        "contact: expected the keys e, beta (the rough-ball law) or e, mu, beta0 (the Walton "
        f"law), got {', '.join(sorted(str(k) for k in keys)) or 'none'}"
    )


def _law_column(x: Any, dtype: np.dtype[Any], field: str, rows: int, single: bool) -> _Array:
    """One column of the law: ``(rows,)`` or one value, of ``dtype``, C-contiguous."""
    a = _cast(x, dtype, field)
    if a.ndim == 0:
        a = a.reshape(1)
    elif single or a.ndim != 1 or len(a) not in (1, rows):
        expected = "a scalar" if single else f"({rows},) or a scalar"
        raise _shape_error(field, expected, a.shape)
    return np.ascontiguousarray(a)


def _out(
    out: Sequence[Mapping[str, _Array]], dtype: np.dtype[Any], rows: int, n: int, single: bool
) -> Tuple[_Array, _Array, _Array, _Array]:
    """``out``'s four arrays in the native order, each checked to be an ndarray of ``dtype``
    with the number of dimensions its key needs (sizes, layout and overlaps are checked
    natively, naming the field too); for one contact (``single``) each gets its row axis
    back as a view (a C-contiguous array is required first, or the view would be a copy)."""
    if isinstance(out, Mapping) or not isinstance(out, Sequence) or len(out) != 2:
        raise InputError("out: expected two mappings (one per body), as collide_batch returns")
    lead: Tuple[int, ...] = () if single else (rows,)
    arrays = []
    for b, body in enumerate(out):
        if not isinstance(body, Mapping):
            raise InputError(f"out[{b}]: expected a mapping with keys angular_velocity, velocity")
        unknown = [k for k in body if k not in ("angular_velocity", "velocity")]
        if unknown:
            raise InputError(
                f"out[{b}].{unknown[0]}: unknown key (the keys are: angular_velocity, velocity)"
            )
        for key in ("angular_velocity", "velocity"):
            field = f"out[{b}].{key}"
            if key not in body:
                raise InputError(f"{field}: missing (required)")
            a = body[key]
            if not isinstance(a, np.ndarray):
                raise InputError(f"{field}: expected a NumPy array, got {type(a).__name__}")
            if a.dtype != dtype:
                raise InputError(
                    f"{field}: dtype {a.dtype}, expected {dtype} (the batch's dtype, "
                    "np.result_type of the inputs)"
                )
            want = lead + (n,) * _ROW_NDIM[key]
            if a.shape != want:
                raise _shape_error(field, _shape_text(want), a.shape)
            if single:
                if not a.flags.c_contiguous:
                    raise InputError(
                        f"{field}: must be C-contiguous (the rows are written in place)"
                    )
                a = a.reshape((1,) + a.shape)
            arrays.append(a)
    return (arrays[0], arrays[1], arrays[2], arrays[3])


def isa() -> str:
    """The instruction set the batch kernels run on here: ``sse2``, ``avx2`` or ``avx512``."""
    return _native.isa()


def reference_seconds(
    normal: npt.ArrayLike,
    bodies: Sequence[Mapping[str, Any]],
    repeats: int = 5,
    parallel: bool = True,
) -> dict[str, list[float]]:
    """The benchmark's Rust references on the same float64 rows (C-contiguous, every body
    moving: ``inv_mass > 0``), timed in Rust; the seconds of each of ``repeats`` runs: with
    ``parallel`` on rayon's threads, in wall-clock seconds; else on the calling thread, in
    its CPU seconds (Linux; a loaded machine disturbs them far less).

    Returns
    -------
    dict of str to list of float
        - ``"rows"``: collision-core's batch path from the same row-major arrays into
          row-major outputs, ``Exec::free_rows`` (a few blocks at a time gathered, run by the
          kernel and scattered, each step compiled for the run-time ISA); no validation.
          The outputs are allocated and touched once before the timed runs and reused: the
          reference of ``collide_batch(..., out=)``.
        - ``"rows_new"``: the same into new output memory on each run, allocated as NumPy
          allocates a large array (``mmap``, advised for huge pages): it pays the first
          touch, as ``collide_batch`` does when it returns new arrays.
        - ``"steps"``: the three steps before ``free_rows``: chunks of 512 rows gathered
          into a ``FreeBatch`` (``fill_from_rows``), run by ``Exec::free`` and scattered
          (``PairBatch::write_rows``), into reused outputs.
        - ``"copy"``: the copy floor of any implementation on these arrays: every input
          element read once and every output element written once (each body's states
          copied from its input), in one pass, into reused outputs.
        - ``"copy_new"``: the same into new output memory on each run (as ``"rows_new"``).
        - ``"kernel"``: ``Exec::auto().free`` alone on the rows laid out once, untimed, in
          its blocked batch: the kernel without the row-major arrays.
    """
    nu = np.asarray(normal, dtype=np.float64)
    rows, n = nu.shape
    f64 = np.dtype(np.float64)
    b1, b2 = (
        _body_arrays(_parse_body(bodies[b], b), b, f64, rows, n, False) for b in range(2)
    )
    return dict(_native.reference_seconds(nu, b1, b2, repeats, parallel))
