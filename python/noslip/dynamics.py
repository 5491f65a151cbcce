"""Lyapunov exponents of a scene: :func:`lyapunov`."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from noslip import _native
from noslip._native import InputError, Scene

__all__ = ["LyapunovResult", "lyapunov"]


@dataclass(frozen=True)
class LyapunovResult:
    """The Lyapunov exponents of a run (as ``noslip lyapunov`` writes ``spectrum.json`` and
    ``running.csv``).

    Attributes
    ----------
    method : str
        ``"qr"`` or ``"two-trajectory"``.
    contact : str
        The contact law: ``"no-slip"`` or ``"smooth"``.
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


def _scene(scene: Scene | str | dict) -> Scene:
    if isinstance(scene, str):
        return Scene(scene)
    if isinstance(scene, dict):
        return Scene.from_dict(scene)
    if not isinstance(scene, Scene):
        raise InputError(f"scene: expected a Scene, TOML text or a dict, got {type(scene).__name__}")
    return scene


def lyapunov(
    scene: Scene | str | dict,
    events: int = 100_000,
    *,
    k: int | None = None,
    method: str = "qr",
    seed: int = 1,
    blocks: int = 10,
    every: int | None = None,
    contact: str = "no-slip",
) -> LyapunovResult:
    """Lyapunov exponents of a scene's dynamics, as ``noslip lyapunov`` computes them (the
    same numbers, bit for bit, for the same arguments).

    The phase space is the balls' centres, velocities and spins (orientations never feed
    back). ``method="qr"``: the ``k`` largest exponents (default all) from tangent vectors
    carried by the exact flight and contact tangent maps along the engine's trajectory,
    re-orthonormalised (Gram-Schmidt) every ``every`` contacts (default: every contact for
    one ball, ``balls/4`` for a gas); exponent ``i`` is the mean growth rate of the i-th
    diagonal entry of ``R``. ``method="two-trajectory"``: the largest exponent from a second
    run kept ``1e-9`` away (Benettin), an independent check with no tangent map (``k=1``).

    ``events`` contacts are run: the first of ``blocks + 1`` equal parts is a warm-up, the
    other ``blocks`` give the standard errors. ``contact="smooth"`` makes every contact
    specular (spins untouched): the classical billiard, the Hamiltonian control.
    See ``docs/dynamics.md``.

    Raises
    ------
    InputError
        A bad scene (naming the place) or argument (naming it), or a run that cannot be
        measured (no contact, a singular tangent map at a grazing contact).
    """
    out = _native.lyapunov(_scene(scene), events, k, method, seed, blocks, every, contact)
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
