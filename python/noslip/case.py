"""One collision: :func:`collide`, in floats or in exact rationals."""

from __future__ import annotations

import json
import math
import numbers
from decimal import Decimal
from fractions import Fraction
from typing import Any, Dict, List, Mapping, Sequence

import numpy as np

from noslip._native import InputError, collide_case

__all__ = ["collide"]


def _number_text(x: Any, path: str, exact: bool) -> Any:
    """A number as the JSON case format spells it: floats as their shortest round-trip
    decimal (so the f64 read back is the same float), ``Fraction`` as ``"p/q"``."""
    if isinstance(x, Fraction):
        return f"{x.numerator}/{x.denominator}"
    if isinstance(x, numbers.Integral):
        return int(x)
    if isinstance(x, Decimal):
        return str(x)
    if isinstance(x, numbers.Real):
        x = float(x)
        if exact and not (path.endswith(".mass") and x == float("inf")):
            raise InputError(
                f"{path}: a float in exact mode (its decimal text is not its value): give an "
                "int, a Fraction or a string such as \"3/5\" (Fraction(x) is the float's "
                "exact binary value)"
            )
        # A finite float as a JSON number: the package reads JSON numbers as the floats
        # whose shortest round-trip text they are (a subnormal is taken as it is); the
        # others as text, for the field's own message.
        return x if math.isfinite(x) else "inf" if x == float("inf") else repr(x)
    raise InputError(f"{path}: expected a number, got {type(x).__name__}")


#: The deepest nesting a case is read to (a case nests at most 5 deep: the bodies, a body,
#: its angular velocity's rows); deeper is a list or dict inside itself, named as such
#: rather than Python's RecursionError.
MAX_CASE_DEPTH = 32


def _to_json(x: Any, path: str, exact: bool, depth: int = 0) -> Any:
    """Python values as the JSON case format: dicts, sequences (lists, tuples, ranges,
    deques, NumPy arrays), numbers, strings (kept as written: ``"3/5"``, ``"inf"``)."""
    if isinstance(x, str):
        try:
            x.encode("utf-8")
        except UnicodeEncodeError:
            raise InputError(
                f"{path or 'case'}: {x!r} is not valid Unicode text (a lone surrogate)"
            ) from None
        return x
    if isinstance(x, bool) or x is None:
        return x
    if depth >= MAX_CASE_DEPTH:
        raise InputError(
            f"{path or 'case'}: nested more than {MAX_CASE_DEPTH} deep (a case nests at most 5 "
            "deep; is a list or dict inside itself?)"
        )
    if isinstance(x, Mapping):
        out: Dict[str, Any] = {}
        for k, v in x.items():
            if not isinstance(k, str):
                raise InputError(f"{path or 'case'}: keys must be strings, got {k!r}")
            out[k] = _to_json(v, f"{path}.{k}" if path else k, exact, depth + 1)
        return out
    if hasattr(x, "tolist") and not isinstance(x, numbers.Number):
        x = x.tolist()
    if isinstance(x, Sequence) and not isinstance(x, (bytes, bytearray)):
        return [_to_json(v, f"{path}[{i}]", exact, depth + 1) for i, v in enumerate(x)]
    return _number_text(x, path, exact)


def _from_json(x: Any, exact: bool) -> Any:
    """The output's numbers: exact ``"p/q"`` strings as ``Fraction``\\ s (lists of them,
    NumPy having no exact rational dtype), floats as ``float64`` arrays where they are
    vectors or matrices (a 2D spin given as a number stays a ``float``)."""
    if isinstance(x, dict):
        return {k: _from_json(v, exact) for k, v in x.items()}
    if exact:
        if isinstance(x, list):
            return [_from_json(v, exact) for v in x]
        return Fraction(x) if isinstance(x, str) else x
    if isinstance(x, list):
        return np.array(x, dtype=np.float64)
    return float(x)


def collide(
    normal: Sequence[Any],
    bodies: Sequence[Mapping[str, Any]],
    *,
    dim: int | None = None,
    exact: bool = False,
    contact: str | Mapping[str, Any] | None = None,
) -> List[Dict[str, Any]]:
    """The post-collision states of two balls in contact.

    By default the no-slip collision map: the state ``xi = (U_1, u_1, U_2, u_2)`` jumps to
    ``xi+ = 2 P_G xi - xi``, its reflection in the kinetic-energy metric across the
    subspace ``G`` of velocities with no slip at the contact point
    ``V_1(Q) = U_1 (R_1 nu) + u_1 = U_2 (-R_2 nu) + u_2``. It conserves the kinetic energy
    ``sum_i m_i (|u_i|^2 + lambda_i |U_i|_F^2) / 2``, the linear momentum and each body's
    angular momentum about the contact point. ``contact`` selects another law of the
    rough-ball family (docs/derivation.md §15): one impulse at the contact point that turns
    the slip's normal part ``dn`` into ``-e dn`` and its tangential part ``t`` into
    ``-beta t``; it conserves both momenta and loses
    ``(1 - e^2) dn^2 / (2 a) + (1 - beta^2) |t|^2 / (2 b)`` of energy.

    Parameters
    ----------
    normal : sequence of n numbers
        The unit contact normal ``nu``, from body 1's centre to body 2's (``|nu|^2 = 1``).
    bodies : two mappings
        As in the JSON case format of ``noslip collide``: ``mass`` (a number ``> 0``, or
        ``"inf"`` / ``float("inf")`` for an immovable body), ``radius`` ``R > 0``, at most one
        of ``lambda`` (``(1/(n m)) int |b|^2 dmu`` in ``[0, R^2/n]``), ``gamma2``
        (``2 lambda / R^2`` in ``[0, 2/n]``) or ``distribution`` (``"uniform"``, the default,
        or ``"shell"``), ``angular_velocity`` (an ``n x n`` skew matrix; in 2D also a number
        ``c`` for ``U = c J``, in 3D also a vector ``omega`` for ``U x = omega x x``) and
        ``velocity`` (``u``, n numbers). Units: any consistent set (velocities in length per
        time, angular velocities in radians per time).
    dim : int, optional
        ``n``; by default ``len(normal)``.
    exact : bool
        Compute in exact rationals: numbers must be ints, ``Fraction``\\ s or strings
        (``"3/5"``, ``"0.1"`` = 1/10); results are ``Fraction``\\ s. Otherwise ``float64``:
        bit for bit what ``noslip collide`` prints for the same case.
    contact : str or mapping, optional
        The contact law, as the case format's ``contact`` key: ``"no-slip"`` (the default),
        ``"smooth"`` (``(e, beta) = (1, -1)``), ``{"e": e, "beta": beta}`` (the rough-ball
        law, ``e`` in ``[0, 1]``, ``beta`` in ``[-1, 1]``) or ``{"e": e, "mu": mu, "beta0":
        beta0}`` (the Walton law, docs/derivation.md §15.1: ``beta = min(beta0, beta_C)``,
        ``beta_C`` the ``beta`` of sliding with ``|J_t| = mu |J_n|``; ``mu >= 0``, ``beta0``
        in ``[-1, 1]``). Numbers as everywhere else (exact mode: no floats). In exact mode a
        sliding Walton contact whose slip ``|t|`` is irrational takes its one square root to
        256 bits (docs/derivation.md §15.1); it is exact wherever ``|t|`` is rational.

    Returns
    -------
    list of two dicts
        Each body's ``angular_velocity`` (in the form given: an ``(n, n)`` matrix, a number
        in 2D, an ``(3,)`` vector ``omega`` in 3D) and ``velocity`` ``(n,)`` after the
        collision: NumPy ``float64`` arrays (a number as a ``float``), or with
        ``exact=True`` ``Fraction``\\ s in lists (NumPy has no exact rational dtype).

    Raises
    ------
    InputError
        A bad case; the message names the field (``bodies[1].gamma2: ...``,
        ``contact.mu: ...``): the bodies must approach or graze, ``(u_2 - u_1) . nu <= 0``;
        ``e`` outside ``[0, 1]``, ``beta`` or ``beta0`` outside ``[-1, 1]``, a negative
        ``mu`` and NaN are refused.
    """
    if dim is None:
        if isinstance(normal, (str, bytes, Mapping)) or not hasattr(normal, "__len__"):
            raise InputError(
                f"normal: expected a sequence of n numbers, got {type(normal).__name__}"
            )
        dim = len(normal)
        if dim == 1 and isinstance(normal, (list, tuple)) and isinstance(normal[0], (list, tuple)):
            # `[[0, -1]]`: a normal wrapped once more, not a 1D case (it said "dim: must be
            # at least 2, got 1", naming an argument the caller did not give).
            raise InputError(
                f"normal: expected a sequence of n numbers, got a sequence holding one "
                f"sequence of {len(normal[0])} (unwrap it)"
            )
    case: Dict[str, Any] = {
        "dim": dim,
        "normal": normal,
        "bodies": bodies,
    }
    if contact is not None:
        case["contact"] = contact
    text = json.dumps(_to_json(case, "", exact), allow_nan=False)
    out = json.loads(collide_case(text, exact))
    return [_from_json(body, exact) for body in out["bodies"]]
