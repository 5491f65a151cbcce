"""A batch of collisions on NumPy arrays: :func:`collide_batch`."""

from __future__ import annotations

from typing import Any, Mapping, Sequence

import numpy as np

from noslip import _native
from noslip._native import InputError

__all__ = ["collide_batch", "isa", "BODY_KEYS"]

#: The keys of a body in :func:`collide_batch`: its states and the kernel's parameters.
BODY_KEYS = ("angular_velocity", "velocity", "inv_mass", "radius", "gamma2")


def _shapes(shape: tuple[int, ...]) -> dict[str, str]:
    """The expected shape of each body key, as text, for ``normal``'s shape ``(N, n)``."""
    rows, n = shape if len(shape) == 2 else ("N", "n")
    return {
        "angular_velocity": f"({rows}, {n}, {n})",
        "velocity": f"({rows}, {n})",
        "inv_mass": f"({rows},) or a scalar",
        "radius": f"({rows},) or a scalar",
        "gamma2": f"({rows},) or a scalar",
    }


#: The number of dimensions of each body key's array (a scalar parameter made 1-D).
_NDIM = {"angular_velocity": 3, "velocity": 2, "inv_mass": 1, "radius": 1, "gamma2": 1}


def _body(body: Mapping[str, Any], b: int, dtype: np.dtype, shape: tuple[int, ...]) -> tuple:
    """Body ``b``'s five arrays in the native order, each of ``dtype`` (``normal``'s) and
    with the number of dimensions its key needs; ``shape`` is ``normal``'s, for the
    message (the sizes are checked natively, naming the field too).

    Raises
    ------
    InputError
        A missing or unknown key, a wrong dtype or a wrong number of dimensions, naming
        ``bodies[b].key``.
    """
    if not isinstance(body, Mapping):
        raise InputError(f"bodies[{b}]: expected a mapping with keys {', '.join(BODY_KEYS)}")
    unknown = [k for k in body if k not in BODY_KEYS]
    if unknown:
        raise InputError(
            f"bodies[{b}].{unknown[0]}: unknown key (the keys are: {', '.join(BODY_KEYS)})"
        )
    arrays = []
    for key in BODY_KEYS:
        if key not in body:
            raise InputError(f"bodies[{b}].{key}: missing (required)")
        x = body[key]
        if isinstance(x, np.ndarray) and x.ndim > 0:
            a = x
        else:
            a = np.asarray(x)
            if a.ndim == 0:
                # A scalar parameter, shared by every row: rounded once to the batch's dtype
                # (a finite number beyond float32's range is named, not made infinite).
                with np.errstate(over="ignore"):
                    a = a.astype(dtype).reshape(1)
                if a.dtype.kind == "f" and np.isinf(a[0]) and np.isfinite(np.asarray(x, float)):
                    raise InputError(f"bodies[{b}].{key}: {x!r} is beyond the range of {dtype}")
        if a.dtype != dtype:
            raise InputError(
                f"bodies[{b}].{key}: dtype {a.dtype}, expected {dtype} (the dtype of normal; "
                "arrays are read in place, never converted)"
            )
        if a.ndim != _NDIM[key]:
            got = "a scalar" if np.ndim(x) == 0 else str(a.shape)
            raise InputError(f"bodies[{b}].{key}: expected shape {_shapes(shape)[key]}, got {got}")
        arrays.append(a)
    return tuple(arrays)


def collide_batch(
    normal: np.ndarray,
    bodies: Sequence[Mapping[str, Any]],
    *,
    validate: bool = True,
    parallel: bool = True,
    out: Sequence[Mapping[str, np.ndarray]] | None = None,
) -> tuple[dict[str, np.ndarray], dict[str, np.ndarray]]:
    """The no-slip collision map on every row of a batch.

    Row ``k`` is one contact: ``xi_k+ = 2 P_G(q_k) xi_k - xi_k`` (see :func:`noslip.collide`).
    With ``validate`` (the default) every row goes through :func:`noslip.collide`'s own
    checked path (the checks and the rounding allowance, the kernel run with an unbounded
    exponent, the results rounded back or refused when they do not fit): each row is
    accepted or refused as ``collide`` does it and its result is ``collide``'s bit for bit
    (the batch takes ``inv_mass`` where ``collide`` takes ``mass``). Without it the
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

    Parameters
    ----------
    normal : ndarray, shape (N, n), float64 or float32
        The unit normals ``nu``, from body 1's centre to body 2's; n in 2..6.
    bodies : two mappings of arrays of ``normal``'s dtype
        ``angular_velocity``: ``(N, n, n)`` skew matrices ``U``; ``velocity``: ``(N, n)``;
        the kernel's parameters ``inv_mass`` (``1/m``, 0 for an immovable body), ``radius``
        ``R > 0`` and ``gamma2 = 2 lambda / R^2`` in ``[0, 2/n]`` (``2/(n+2)`` uniform,
        ``2/n`` a shell; ``I/(m R^2)`` in 3D), each ``(N,)`` or a scalar shared by all rows.
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
        ``angular_velocity`` ``(N, n, n)`` and ``velocity`` ``(N, n)`` of ``normal``'s dtype,
        C-contiguous, writeable, sharing no memory with the inputs or each other (a loop
        that keeps them allocates nothing and skips the first touch of new memory). On an
        error they may hold some rows' results.

    Returns
    -------
    (dict, dict)
        Per body, ``angular_velocity`` ``(N, n, n)`` and ``velocity`` ``(N, n)``: new arrays,
        or those of ``out``.

    Raises
    ------
    InputError
        A wrong shape or dtype (naming the field, ``out[1].velocity`` for an output), or
        with ``validate`` the first bad row: ``row 17: bodies[1].gamma2: ...``.
    """
    normal = np.asarray(normal)
    if normal.dtype not in (np.float64, np.float32):
        raise InputError(f"normal: dtype must be float64 or float32, got {normal.dtype}")
    if normal.ndim != 2:
        raise InputError(f"normal: expected shape (N, n), got {normal.shape}")
    if not isinstance(bodies, Sequence) or len(bodies) != 2:
        raise InputError("bodies: expected two bodies (a sequence of two mappings)")
    b1, b2 = (_body(bodies[b], b, normal.dtype, normal.shape) for b in range(2))
    run = _native.collide_batch_f64 if normal.dtype == np.float64 else _native.collide_batch_f32
    arrays = None if out is None else _out(out, normal.dtype, normal.shape)
    s1, v1, s2, v2 = run(normal, b1, b2, validate, parallel, arrays)
    return (
        {"angular_velocity": s1, "velocity": v1},
        {"angular_velocity": s2, "velocity": v2},
    )


def _out(out: Sequence[Mapping[str, np.ndarray]], dtype: np.dtype, shape: tuple[int, ...]) -> tuple:
    """``out``'s four arrays in the native order, each checked to be an ndarray of ``dtype``
    with the number of dimensions its key needs (``shape``, ``normal``'s, is for the
    message; sizes, layout and overlaps are checked natively, naming the field too)."""
    rows, n = shape
    if isinstance(out, Mapping) or not isinstance(out, Sequence) or len(out) != 2:
        raise InputError("out: expected two mappings (one per body), as collide_batch returns")
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
            if key not in body:
                raise InputError(f"out[{b}].{key}: missing (required)")
            a = body[key]
            if not isinstance(a, np.ndarray):
                raise InputError(f"out[{b}].{key}: expected a NumPy array, got {type(a).__name__}")
            if a.dtype != dtype:
                raise InputError(
                    f"out[{b}].{key}: dtype {a.dtype}, expected {dtype} (the dtype of normal)"
                )
            want = [rows, n, n] if key == "angular_velocity" else [rows, n]
            if a.ndim != len(want):
                raise InputError(f"out[{b}].{key}: expected shape {want}, got {list(a.shape)}")
            arrays.append(a)
    return tuple(arrays)


def isa() -> str:
    """The instruction set the batch kernels run on here: ``sse2``, ``avx2`` or ``avx512``."""
    return _native.isa()


def reference_seconds(
    normal: np.ndarray,
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
    normal = np.asarray(normal)
    b1, b2 = (
        _body(bodies[b], b, np.dtype(np.float64), normal.shape) for b in range(2)
    )
    return dict(_native.reference_seconds(normal, b1, b2, repeats, parallel))
