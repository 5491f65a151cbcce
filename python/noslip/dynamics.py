"""Lyapunov exponents of a scene, :func:`lyapunov`, and periodic orbits of a one-ball
table, :func:`orbits`."""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from fractions import Fraction
from numbers import Rational
from typing import Any, List, Sequence

import numpy as np
import numpy.typing as npt

from noslip import _native
from noslip._args import SceneLike, as_scene
from noslip._native import InputError

__all__ = ["ExactReturn", "LyapunovResult", "Orbit", "OrbitsResult", "lyapunov", "orbits"]


@dataclass(frozen=True)
class LyapunovResult:
    """The Lyapunov exponents of a run (as ``noslip lyapunov`` writes ``spectrum.json`` and
    ``running.csv``).

    Attributes
    ----------
    method : str
        ``"qr"`` or ``"two-trajectory"``.
    contact : str
        The override of every contact's law, ``"no-slip"`` or ``"smooth"``, or ``"scene"``
        when each contact followed its own kind in the scene.
    dimension : int
        The phase-space dimension ``balls (2n + S)`` (centres, velocities, spins;
        ``S = n(n-1)/2``).
    contacts, warmup, every : int
        Contacts run, of them the unmeasured warm-up block, and contacts between
        re-orthonormalisations.
    time : float
        The simulated time of the measured part.
    per_time, per_time_error : ndarray (k,)
        The exponents per unit time, largest first, ``lambda_i = lim (1/t) log sigma_i``
        (``sigma_i`` the growth of the i-th Gram-Schmidt direction), and their standard
        errors (the spread of the blocks' estimates over ``sqrt(blocks)``).
    per_contact, per_contact_error : ndarray (k,)
        The same per contact (all contacts of the scene).
    sum, sum_error : float
        The sum of the exponents computed, per unit time (0 for the full spectrum of a
        volume-preserving flow).
    running_contacts, running_time : ndarray (R,)
        The running estimate's rows: contacts so far (warm-up included), time so far.
    running : ndarray (R, k)
        The exponents per unit time over the measured part so far.
    """

    method: str
    contact: str
    dimension: int
    contacts: int
    warmup: int
    every: int
    time: float
    per_time: np.ndarray
    per_time_error: np.ndarray
    per_contact: np.ndarray
    per_contact_error: np.ndarray
    sum: float
    sum_error: float
    running_contacts: np.ndarray = field(repr=False)
    running_time: np.ndarray = field(repr=False)
    running: np.ndarray = field(repr=False)

    @property
    def largest(self) -> float:
        """The largest exponent per unit time, ``per_time[0]``."""
        return float(self.per_time[0])


def lyapunov(
    scene: SceneLike,
    events: int = 100_000,
    *,
    k: int | None = None,
    method: str = "qr",
    seed: int = 1,
    blocks: int = 10,
    every: int | None = None,
    contact: str | None = None,
) -> LyapunovResult:
    """Lyapunov exponents of a scene's dynamics, as ``noslip lyapunov`` computes them (the
    same numbers, bit for bit, for the same arguments).

    The phase space is the balls' centres, velocities and spins (orientations never feed
    back). ``method="qr"``: the ``k`` largest exponents (default: all when they fit 64 MiB
    of tangent vectors and ``2e9`` multiply-adds of Gram-Schmidt over the run, else the
    largest ``k`` that fits; a ``k`` needing over 1 GiB is refused) from tangent vectors
    carried by the exact flight and contact tangent maps along the engine's trajectory,
    re-orthonormalised (Gram-Schmidt) every ``every`` contacts (default: every contact for
    one ball, ``balls/4`` for a gas, shortened to a block's contacts; a longer ``every`` is
    refused, as it would leave blocks without an estimate); exponent ``i`` is the mean growth rate of the i-th
    diagonal entry of ``R``. ``method="two-trajectory"``: the largest exponent from a second
    run kept ``1e-9`` away (Benettin), an independent check with no tangent map (``k=1``).

    ``events`` contacts are run: the first of ``blocks + 1`` equal parts is a warm-up, the
    other ``blocks`` give the standard errors. By default each contact follows its own kind in
    the scene (``contact = "no-slip"`` or ``"smooth"`` per boundary and for ball pairs);
    ``contact="smooth"`` or ``"no-slip"`` overrides every contact, as ``noslip lyapunov
    --contact`` does (``"smooth"``: the classical billiard, the Hamiltonian control).
    See ``docs/dynamics.md``.

    Raises
    ------
    InputError
        A bad scene (naming the place) or argument (naming it), or a run that cannot be
        measured (no contact, a singular tangent map at a grazing contact).
    KeyboardInterrupt
        Ctrl-C (SIGINT) during the run: Python's signals are looked at before every contact
        (every 256, once 50 ms have passed); the partial run is discarded.
    """
    out = _native.lyapunov(as_scene(scene), events, k, method, seed, blocks, every, contact)
    per_time, per_time_error = out["per_time"]
    per_contact, per_contact_error = out["per_contact"]
    s, s_error = out["sum"]
    return LyapunovResult(
        method=out["method"],
        contact=out["contact"],
        dimension=out["dimension"],
        contacts=out["contacts"],
        warmup=out["warmup"],
        every=out["every"],
        time=out["time"],
        per_time=per_time,
        per_time_error=per_time_error,
        per_contact=per_contact,
        per_contact_error=per_contact_error,
        sum=s,
        sum_error=s_error,
        running_contacts=out["running_contacts"],
        running_time=out["running_time"],
        running=out["running_exponents"],
    )


@dataclass(frozen=True)
class Orbit:
    """A periodic orbit of the boundary map, found by Newton's method.

    Attributes
    ----------
    boundaries : list of int
        The boundaries touched, in order (walls ``2k`` and ``2k + 1`` at ``x_k = 0`` and
        ``L_k`` for each walled axis ``k`` in order, then the obstacles); the start is on the
        last.
    start : ndarray (2n + S,)
        The start ``[x, u, U]``: the centre on its boundary, the velocity just after the
        contact, the spin entries ``U_ij``, ``i < j``.
    states : ndarray (K, 2n + S)
        The section states after each contact (the last is the start again).
    residual : float
        ``|P^K(z) - z| / (1 + |z|)`` at the start; ``residuals`` the same before each
        Newton step and at the end.
    eigenvalues : ndarray (2n + S - 1,), complex
        The eigenvalues of the linearised section map (the flow direction's 0 removed).
    verdict : str
        ``"elliptic"`` (all on the unit circle, some non-real), ``"parabolic"`` (all at
        ``+-1``) or ``"hyperbolic"`` (some off the unit circle), with tolerance ``1e-6``;
        ``"undetermined"`` when the eigenvalue iteration did not converge (``eigenvalues``
        is then empty).
    found_from : int
        How many starts converged to it.
    """

    boundaries: list[int]
    start: np.ndarray
    states: np.ndarray
    residual: float
    residuals: np.ndarray
    eigenvalues: np.ndarray
    verdict: str
    found_from: int


@dataclass(frozen=True)
class ExactReturn:
    """The return map of a rational start on a table with rational contact times, in exact
    rationals: the boundaries touched, whether ``P^K(z) = z`` exactly, ``P^K(z)``, and the
    characteristic polynomial ``det(l I - DP^K) / l`` of the section map (as text, highest
    power first, and its coefficients from the constant term up)."""

    boundaries: list[int]
    periodic: bool
    end: list[Fraction]
    charpoly: str
    coefficients: list[Fraction]


@dataclass(frozen=True)
class OrbitsResult:
    """The periodic orbits of period ``period`` found from ``starts`` starts (``tried`` of
    them tried before the search's bound of contacts, ``misses`` of those did not converge),
    each once; ``contacts``: the contacts the search followed; ``stopped``: why it stopped
    before trying every start (``None`` if it tried them all); ``exact``: per given start,
    its :class:`ExactReturn` or ``None`` (a contact time or the start's projection is
    irrational)."""

    period: int
    starts: int
    misses: int
    orbits: list[Orbit]
    exact: list[ExactReturn | None]
    tried: int
    contacts: int
    stopped: str | None


def _shape_text(shape: tuple[int, ...]) -> str:
    return f"({shape[0]},)" if len(shape) == 1 else "(" + ", ".join(map(str, shape)) + ")"


def _number(x: object, where: str) -> str:
    if isinstance(x, (bool, np.bool_)):
        raise InputError(f"{where}: expected a number, got {x!r}")
    if isinstance(x, Rational):
        return f"{x.numerator}/{x.denominator}"
    if isinstance(x, np.floating):
        x = float(x)
    if isinstance(x, float):
        # Its shortest decimal, read exactly as the command reads it (0.1 is 1/10).
        return repr(x)
    if isinstance(x, str):
        return x
    raise InputError(f"{where}: expected a number, got {type(x).__name__}")


def orbits(
    scene: SceneLike,
    period: int,
    *,
    starts: Sequence[Sequence[object]] | npt.NDArray[Any] | None = None,
    grid: int | None = None,
    contact: str | None = None,
    max_contacts: int | None = None,
) -> OrbitsResult:
    """Periodic orbits of the ``period``-th return map of the boundary map of a one-ball
    table (a scene with one ball: any of its boundaries, fixed ball obstacles, periodic axes), as
    ``noslip orbits`` finds them (the same ``orbits.json``, bit for bit).

    The section is the state just after a contact, ``[x, u, U]`` (``2n + S`` numbers).
    Orbits are found by Newton's method on ``P^K(z) - z`` with the exact derivative (the
    flight and contact tangent maps, projected onto the section), a least-norm step and the
    energy fixed at the start's. Starts: each of ``starts`` (ints, ``Fraction``s, decimal
    strings or floats, read as their shortest decimal; moved along the normal onto the
    nearest boundary), or ``grid=M`` (2D: ``M`` points on each boundary x ``M`` outgoing
    angles x ``M`` spins, at unit speed), or by default the scene's ball after its first
    contact. ``starts`` may be a ``(K, 2n + S)`` NumPy array. For a rational start on a table with rational contact times (flat walls), the
    return map and the characteristic polynomial of its linearisation are also computed in
    exact rationals. ``max_contacts`` bounds the search's work as ``noslip orbits
    --max-contacts`` does (default 5e7 contacts, a minute or two): at the bound the search
    returns what it found, with ``stopped`` saying how many starts it tried. See
    ``docs/dynamics.md``.

    Raises
    ------
    InputError
        A bad scene (naming the place) or argument (``period``, ``starts[i]``, ``grid``,
        ``contact``, ``max_contacts``).
    KeyboardInterrupt
        Ctrl-C (SIGINT) during the search: Python's signals are looked at before each
        start (its exact return map, then its Newton search); the orbits found so far are
        discarded. One start's work is bounded by ``period`` and Newton's steps.
    """
    if isinstance(starts, np.ndarray):
        # An array of starts, (K, 2n + S): its rows as lists of Python numbers (NumPy's
        # truth value of an array is ambiguous, and its rows are not Sequences).
        if starts.ndim != 2:
            raise InputError(
                f"starts: expected shape (K, 2n + S), got {_shape_text(starts.shape)}"
            )
        starts = starts.tolist()
    if isinstance(starts, (str, bytes)) or not isinstance(starts, (Sequence, type(None))):
        raise InputError(f"starts: expected a sequence of starts, got {type(starts).__name__}")
    if starts is not None and len(starts) == 0 and grid is None:
        # An empty list ran the scene's own start (the default of None) without a word.
        raise InputError(
            "starts: empty: give at least one start, None for the scene's ball, or grid= for "
            "a grid of starts"
        )
    given: List[List[str]] = []
    for i, z in enumerate([] if starts is None else starts):
        if isinstance(z, np.ndarray):
            z = z.tolist()
        if isinstance(z, (str, bytes)) or not isinstance(z, Sequence):
            raise InputError(f"starts[{i}]: expected a sequence of 2n + S numbers")
        given.append([_number(x, f"starts[{i}][{k}]") for k, x in enumerate(z)])
    report = json.loads(
        _native.orbits(as_scene(scene), period, given, grid, contact, max_contacts)
    )
    found = [
        Orbit(
            boundaries=o["boundaries"],
            start=np.array(o["start"], dtype=np.float64),
            states=np.array(o["states"], dtype=np.float64),
            residual=o["residual"],
            residuals=np.array(o["residuals"], dtype=np.float64),
            eigenvalues=np.array([complex(re, im) for re, im in o["eigenvalues"]]),
            verdict=o["verdict"],
            found_from=o["found_from"],
        )
        for o in report["orbits"]
    ]
    exact = [
        None
        if e is None
        else ExactReturn(
            boundaries=e["boundaries"],
            periodic=e["periodic"],
            end=[Fraction(x) for x in e["end"]],
            charpoly=e["charpoly"],
            coefficients=[Fraction(x) for x in e["coefficients"]],
        )
        for e in report["exact"]
    ]
    return OrbitsResult(
        period=report["period"],
        starts=report["starts"],
        misses=report["misses"],
        orbits=found,
        exact=exact,
        tried=report["tried"],
        contacts=report["contacts"],
        stopped=report["stopped"],
    )
