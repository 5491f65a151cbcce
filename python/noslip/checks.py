"""The exact verification and the accuracy report: :func:`verify`, :func:`report`."""

from __future__ import annotations

import json
from typing import Any, Dict, Iterable

from noslip import _native
from noslip._native import InputError

__all__ = ["verify", "report"]


def _dims(dims: Iterable[int]) -> list[int]:
    """``dims`` as a list, or an :class:`InputError` naming it (a bare ``TypeError: 'NoneType'
    object is not iterable`` before)."""
    if isinstance(dims, (str, bytes)) or not isinstance(dims, Iterable):
        raise InputError(f"dims: expected a sequence of dimensions, got {type(dims).__name__}")
    return list(dims)


def verify(dims: Iterable[int] = (2, 3, 4, 5, 6), points: int = 16) -> dict[str, Any]:
    """Prove the generated kernels exact, as ``noslip verify`` does.

    For every n and both variants (``free``, ``fixed``), identities from the definitions are
    checked in exact rational arithmetic at ``points`` random points each: the reflection
    across the no-slip subspace, conservation of energy, momentum and each body's angular
    momentum about the contact point, ``C o C = id``, the ``m_1 -> inf`` and point-mass limits;
    the decomposition ``T_qM = G_q (+) Ebar_q (+) R n_q`` with its exact ranks; the inertia
    bound ``0 <= lambda <= R^2/n``. An identity of degree ``d`` that passes ``K`` points is
    false with probability at most ``(d / 2^20)^K`` (Schwartz-Zippel).

    Returns
    -------
    dict
        ``verify.json``'s content: ``results`` (one dict per check: ``dim``, ``variant``,
        ``check``, ``passed``, ``detail``, its proof and bound), ``seed``, ``points``,
        ``seconds``; and ``passed``, whether every check passed.

    Raises
    ------
    KeyboardInterrupt
        Ctrl-C (SIGINT): Python's signals are looked at before each point of each identity
        check (once 50 ms have passed); the partial results are discarded.
    """
    out: Dict[str, Any] = json.loads(_native.verify(_dims(dims), points))
    out["passed"] = all(r["passed"] for r in out["results"])
    return out


def report(dims: Iterable[int] = (2, 3), samples: int = 200, seed: int = 1) -> dict[str, Any]:
    """Measure the error and run time of every kernel variant, as ``noslip report`` does.

    Errors are against exact rational ground truth, in nine regimes (typical, mass ratios to
    1e15, an immovable body, gamma^2 to 0, radius ratios to 1e6, scales 1e-100..1e100,
    spin-dominated, near-grazing), as bits ``log2(ulps + 1)`` per component and per body in
    its kinetic-energy norm in units of eps; and the rough-ball family's kernels (``rough``
    and ``walton``) in seven regimes of their laws (ends of ``e`` and ``beta``, an immovable
    body, near grazing, near the Walton switch), in the same normwise measure.

    Returns
    -------
    dict
        ``report.json``'s content (``dims``: per dimension, per regime, per variant, the
        errors and timings, and ``family``: per family regime the same for the rough-ball
        kernels; ``options``; ``provenance``).

    Raises
    ------
    KeyboardInterrupt
        Ctrl-C (SIGINT): Python's signals are looked at before each case and each variant's
        timing (once 50 ms have passed); the partial results are discarded.
    """
    out: Dict[str, Any] = json.loads(_native.report(_dims(dims), samples, seed))
    return out
