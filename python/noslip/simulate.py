"""Scenes and the event-driven simulator: :func:`simulate`."""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from noslip import _native
from noslip._native import InputError, Scene

__all__ = ["SimulationResult", "simulate", "KINDS"]

#: The contact kinds of :attr:`SimulationResult.events` ``["kind"]``, by code.
KINDS = ("ball-ball", "ball-wall", "ball-obstacle")


@dataclass(frozen=True)
class SimulationResult:
    """A run of a scene.

    Attributes
    ----------
    summary : dict
        The simulator's summary (as ``noslip simulate`` writes ``summary.json``): ``events``,
        ``ball_ball``, ``ball_wall``, ``ball_obstacle``, ``time``, ``seconds``,
        ``energy_start`` ``E_0``, ``energy_end``, ``energy_drift`` ``|E - E_0| / E_0``,
        ``momentum_drift``, ``angular_momentum_drift``, ``stopped``, ...
    energy : dict of ndarray
        Samples over the run (up to 2000): ``events`` (contacts done), ``drift``
        ``(E - E_0) / E_0`` and ``energy`` ``E = E_0 (1 + drift)``, with
        ``E = sum_i m_i (|u_i|^2 + lambda_i |U_i|_F^2) / 2``.
    events : dict of ndarray
        The events log, one row per contact (empty without ``log``): ``time`` (E,),
        ``kind`` (E,) (codes into :data:`KINDS`), ``balls`` (E, 2) (-1 for a wall or
        obstacle), ``wall_axis`` (E,) (-1 if none), ``wall_upper`` (E,), ``obstacle`` (E,)
        (-1 if none), ``nu`` (E, n) (from the first ball to the other body), ``positions``
        (E, 2, n), and per slot the states before and after: ``pre_spin``, ``post_spin``
        (E, 2, n(n-1)/2) (the compact entries ``U_ij``, ``i < j``), ``pre_velocity``,
        ``post_velocity`` (E, 2, n). A one-ball contact's second slot is NaN.
    """

    summary: dict[str, Any]
    energy: dict[str, np.ndarray]
    events: dict[str, np.ndarray] = field(repr=False)


def simulate(
    scene: Scene | str | dict,
    events: int | None = None,
    time: float | None = None,
    *,
    log: bool = True,
) -> SimulationResult:
    """Run a scene with the event-driven simulator of ``noslip simulate``.

    Balls fly freely between events; at each ball-ball, ball-wall or ball-obstacle contact
    the pair's state jumps by the no-slip map (the generated f64 kernels). The run is
    deterministic: the same scene gives the same events, bit for bit.

    Parameters
    ----------
    scene : Scene, str or dict
        A :class:`Scene`, TOML text, or a dict with the TOML file's structure.
    events : int, optional
        Stop after this many contacts (at least 1).
    time : float, optional
        Stop at this simulated time (positive, finite). With neither, the scene's
        ``[simulation]`` values, else 100000 contacts.
    log : bool
        Keep every contact in :attr:`SimulationResult.events` (about 0.5 kB per contact
        while it runs).

    Raises
    ------
    InputError
        A bad scene (the message names the place) or limit.
    """
    if isinstance(scene, str):
        scene = Scene(scene)
    elif isinstance(scene, dict):
        scene = Scene.from_dict(scene)
    elif not isinstance(scene, Scene):
        raise InputError(f"scene: expected a Scene, TOML text or a dict, got {type(scene).__name__}")
    out = _native.simulate(scene, events, time, log)
    summary = json.loads(out["summary"])
    energy = dict(out["energy"])
    energy["energy"] = summary["energy_start"] * (1.0 + energy["drift"])
    return SimulationResult(summary=summary, energy=energy, events=dict(out["events"]))
