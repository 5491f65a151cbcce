"""Scenes and the event-driven simulator: :func:`simulate`."""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

from noslip import _native
from noslip._args import SceneLike, as_scene

__all__ = ["SimulationResult", "simulate", "KINDS", "MAX_MEMORY"]

#: The default cap, in bytes, on the records :func:`simulate` keeps (1 GiB).
MAX_MEMORY = 1 << 30

#: The contact kinds of :attr:`SimulationResult.events` ``["kind"]``, by code.
KINDS = ("ball-ball", "ball-wall", "ball-obstacle", "ball-boundary")


@dataclass(frozen=True)
class SimulationResult:
    """A run of a scene.

    Attributes
    ----------
    summary : dict
        The simulator's summary (as ``noslip simulate`` writes ``summary.json``): ``events``,
        ``ball_ball``, ``ball_wall``, ``ball_obstacle``, ``time``, ``seconds``,
        ``energy_start`` ``E_0``, ``energy_end``, ``energy_drift`` ``|E - E_0| / E_0``,
        ``momentum_drift``, ``angular_momentum_drift``, ``stopped``, ``kicks`` and
        ``energy_injected`` (a scene's ``[thermostat]``: its kicks and the energy they added,
        ``docs/granular.md``), ...
    energy : dict of ndarray
        Samples over the run (up to 2000, at least ``balls / 8`` contacts apart, so that a
        large gas's samples stay a small part of its run): ``events`` (contacts done), ``drift``
        ``(E - E_0) / E_0`` and ``energy`` ``E = E_0 (1 + drift)``, with
        ``E = sum_i m_i (|u_i|^2 + lambda_i |U_i|_F^2) / 2``.
    events : dict of ndarray
        The events log, one row per contact (empty without ``log``): ``time`` (E,),
        ``kind`` (E,) (codes into :data:`KINDS`), ``balls`` (E, 2) (-1 for a wall,
        obstacle or boundary), ``wall_axis`` (E,) (-1 if none), ``wall_upper`` (E,),
        ``obstacle`` (E,) (-1 if none), ``boundary`` (E,) (the table's boundary, -1 if none), ``nu`` (E, n) (from the first ball to the other body), ``positions``
        (E, 2, n), and per slot the states before and after: ``pre_spin``, ``post_spin``
        (E, 2, n(n-1)/2) (the compact entries ``U_ij``, ``i < j``), ``pre_velocity``,
        ``post_velocity`` (E, 2, n). A one-ball contact's second slot is NaN. A scene with
        a ``[thermostat]`` adds its kicks (K of them, in time order; the log's kick lines):
        ``kick`` (K,) (the kick's number, from 1), ``kick_time`` (K,),
        ``kick_velocities`` (K, N_b, n) (every ball's velocity after the kick, in ball
        order; spins are not kicked) and ``kick_energy_injected`` (K,), so that the start,
        the contacts' ``post_velocity`` and the kicks replay every velocity (K = 0 without a
        thermostat; ``3 (8 n N_b + 24)`` bytes a kick count against ``max_memory``, asked
        after every contact and every kick).
    boundary_map : dict of ndarray
        The boundary map, one row per contact of a ball with an immovable body (box wall,
        obstacle, table boundary), under the columns of ``noslip simulate --boundary-map``'s
        CSV (the same numbers, bit for bit; ``docs/tables.md``): ``event`` (1-based),
        ``time``, ``ball``, ``kind`` (``"box-wall"``, ``"obstacle"``, ``"boundary"``),
        ``id``, the contact point ``q0`` .. ``q{n-1}``, ``coordinate`` (2D: arc length along
        a flat boundary, the angle about a circle's centre; nD: the distance from a wall's
        point, the angle from ``e_0`` on a sphere), ``incidence`` and ``reflection`` (2D the
        signed angles from the normal, ``atan2(u . t, -u . nu)`` and
        ``atan2(u' . t, u' . nu)``; nD their sizes), ``normal_velocity`` ``u . nu``,
        ``tangential_velocity`` and ``_post`` (2D ``u . t``, ``t = (nu_1, -nu_0)``; nD
        ``|u - (u . nu) nu|``), ``spin`` and ``spin_post`` (2D ``c`` of ``U = c J``; nD
        the norm of the entries ``U_ij``, ``i < j``), ``scaled_spin`` and ``_post``
        ``sqrt(2 lambda)`` times the spin. Empty without ``boundary_map``.
    html : str or None
        The animation page (``html=True``), else None.
    observables : dict of ndarray
        The granular-gas observables (``observables=DT``), one row at the start and at the
        first contact at or after each multiple of ``DT``, the state just after it, under
        the columns of ``noslip simulate --observables``'s CSV (the same numbers, bit for
        bit; ``docs/granular.md``), units in the scene's mass ``M``, length ``L`` and time
        ``T``: ``time`` [T], ``contacts`` (int64), ``T_tr`` and ``T_rot`` (temperatures per
        degree of freedom, [M L^2 T^-2]; ``T_tr`` without the centre of mass's motion),
        ``energy``, ``collision_frequency`` [1/T] (ball-ball contacts per ball and unit time
        since the previous row, NaN in the first), ``lost_ball_ball``, ``lost_ball_wall``,
        ``lost_ball_obstacle``, ``lost_ball_boundary`` (energy lost so far at each kind of
        contact), ``injected`` (energy injected so far by a thermostat's kicks, 0 without
        one), ``pressure`` [M L^(2-n) T^-2] (kinetic plus the collisional virial since
        the previous row; a periodic box without obstacles only, else NaN), ``a2`` (the
        velocity cumulant, 0 for a Maxwellian), ``msd`` and ``msd_cm`` [L^2] (the mean
        square displacement since the start, unwrapped across periodic faces, and the same
        about the centre of mass; exact under a thermostat too, whose kicks end the
        flights) and, in a mixture, ``T_tr_s`` and
        ``T_rot_s`` for each species index ``s``, then ``msd_cm_s`` for each, then
        ``lost_ball_ball_A-B`` [M L^2 T^-2] for each unordered pair of species ``A-B`` (the
        energy lost so far at that pair's ball-ball contacts; they add up to
        ``lost_ball_ball`` to rounding) and ``contacts_A-B`` (int64, its contacts so far), ``A``
        and ``B`` the species' names (``species<i>`` for all unless every name is letters,
        digits and ``_`` and no two are equal), pairs in the order ``(0, 0), (0, 1), ...,
        (1, 1), ...``. Empty without ``observables``.
    pair_correlation : dict of ndarray
        ``g(r)`` averaged over the observables' rows (``pair_correlation=R_MAX``), as
        ``noslip simulate --pair-correlation`` writes ``pair-correlation.csv``: ``r`` [L]
        (the bins' centres) and ``g``. Empty without ``pair_correlation``.
    self_diffusion : dict
        The self-diffusion coefficient from the mean square displacement about the centre of
        mass in blocks of time (``self_diffusion=BLOCK``), as ``noslip simulate
        --self-diffusion`` writes ``self-diffusion.csv``: per block ``start`` and ``end`` [T]
        and ``D`` [L^2/T] (the slope of the block's msd over its last four fifths over ``2 n``),
        and the estimate ``mean`` [L^2/T] with its ``standard_error`` over the blocks
        (floats; NaN with fewer than two blocks). Empty without ``self_diffusion``.
    """

    summary: dict[str, Any]
    energy: dict[str, npt.NDArray[Any]]
    events: dict[str, npt.NDArray[Any]] = field(repr=False)
    boundary_map: dict[str, npt.NDArray[Any]] = field(repr=False, default_factory=dict)
    html: str | None = field(repr=False, default=None)
    observables: dict[str, npt.NDArray[Any]] = field(repr=False, default_factory=dict)
    pair_correlation: dict[str, npt.NDArray[Any]] = field(repr=False, default_factory=dict)
    self_diffusion: dict[str, Any] = field(repr=False, default_factory=dict)

    def __repr__(self) -> str:
        s = self.summary
        shown = ", ".join(
            f"{k}={s[k]!r}"
            for k in ("dim", "balls", "events", "time", "energy_drift", "stopped")
            if k in s
        )
        rows = len(next(iter(self.events.values()), ()))
        bmap = len(next(iter(self.boundary_map.values()), ()))
        samples = len(self.observables.get("time", ()))
        return (
            f"SimulationResult({shown}, energy samples={len(self.energy.get('drift', ()))}, "
            f"events log rows={rows}, boundary map rows={bmap}, observables rows={samples})"
        )


def simulate(
    scene: SceneLike,
    events: int | None = None,
    time: float | None = None,
    *,
    log: bool = False,
    boundary_map: bool = False,
    max_memory: int = MAX_MEMORY,
    html: bool = False,
    observables: float | None = None,
    pair_correlation: float | None = None,
    pair_bins: int = 100,
    self_diffusion: float | None = None,
    self_diffusion_from: float = 0.0,
    conserve_energy: bool = False,
) -> SimulationResult:
    """Run a scene with the event-driven simulator of ``noslip simulate``.

    Balls fly freely between events; at each contact (ball-ball, ball-wall, ball-obstacle,
    ball-boundary of a table) the pair's state jumps by the contact map (the no-slip map of
    the generated f64 kernels, or a specular reflection where the scene makes a contact
    smooth). The run is
    deterministic: the same scene gives the same events, bit for bit.

    Parameters
    ----------
    scene : Scene, str, os.PathLike or dict
        A :class:`Scene`, TOML text, a file (``pathlib.Path``; text is always TOML, a file
        name as text gets a hint), or a dict with the TOML file's structure.
    events : int, optional
        Stop after this many contacts (at least 1).
    time : float, optional
        Stop at this simulated time (positive, finite and a normal float, at least
        ``2.2e-308``, as ``noslip simulate --time``). Each of ``events`` and ``time``
        overrides the scene's ``[simulation]`` key of that name only, as the CLI's flags do:
        the run stops at whichever limit comes first, so ``time=`` alone still stops at the
        scene's ``events`` if it has one (``summary["time"]`` shows where it stopped). With
        no limit from either, 100000 contacts.
    log : bool
        Keep every contact in :attr:`SimulationResult.events` (``3 (57 + 56 n + 32 s)``
        bytes a contact are counted against ``max_memory``, ``s = n(n-1)/2``: 603 in 2D,
        963 in 3D; the factor 3 is the arrays' growth by doubling).
    boundary_map : bool
        Keep the boundary map, :attr:`SimulationResult.boundary_map` (about 0.25 kB a
        contact in 2D, three times that counted against ``max_memory``).
    max_memory : int
        The cap, in bytes, on the records kept (``log``, ``boundary_map``); default
        :data:`MAX_MEMORY`, 1 GiB.
    html : bool
        Keep the run as the animation page of ``noslip simulate --html``,
        :attr:`SimulationResult.html`: one self-contained HTML document (under about 2 MB
        whatever the run; ``docs/animation.md``). In a notebook, show it with
        ``IPython.display.HTML`` in an ``<iframe srcdoc=...>``.
    observables : float, optional
        Sample the granular-gas observables every this much simulated time (positive and
        finite), as ``noslip simulate --observables``: :attr:`SimulationResult.observables`
        (648 bytes a row with one species; in a mixture 72 more a species and 48 more a pair
        of species; counted against ``max_memory``).
    pair_correlation : float, optional
        Also sample ``g(r)`` up to this distance at every row but the first (needs
        ``observables``; a box periodic on every axis, without obstacles or other
        boundaries, and at most half its shortest side), in ``pair_bins`` bins:
        :attr:`SimulationResult.pair_correlation` (``docs/granular.md``).
    pair_bins : int
        The bins of ``pair_correlation`` (default 100).
    self_diffusion : float, optional
        Also estimate the self-diffusion coefficient in blocks of this much
        simulated time (needs ``observables``; at least 4 of its intervals), each its own
        time origin: :attr:`SimulationResult.self_diffusion` (``docs/granular.md``).
    self_diffusion_from : float
        The start of the first block (default 0: the start's row).
    conserve_energy : bool
        Correct every no-slip contact onto the energy its balls had before it, as
        ``noslip simulate --conserve-energy`` (``docs/accuracy.md``, "An energy-conserving
        correction"): the energy then random-walks instead of drifting by the kernels'
        rounding bias. The contacts differ from the uncorrected run's by an ulp or two;
        rough and Walton contacts are left as their law gives them. Recorded as
        ``summary["conserve_energy"]``.

    Raises
    ------
    InputError
        A bad scene (the message names the place), limit or ``observables`` interval, or
        records beyond ``max_memory`` (naming ``events`` or ``time``).
    KeyboardInterrupt
        Ctrl-C (SIGINT) during the run: the loop looks at Python's signals every 1024
        contacts once 50 ms have passed, so it stops within about 0.1 s; the partial run is
        discarded.
    """
    out = _native.simulate(
        as_scene(scene),
        events,
        time,
        log,
        boundary_map,
        max_memory,
        html,
        observables,
        pair_correlation,
        pair_bins,
        self_diffusion,
        self_diffusion_from,
        conserve_energy,
    )
    summary = json.loads(out["summary"])
    energy = dict(out["energy"])
    energy["energy"] = summary["energy_start"] * (1.0 + energy["drift"])
    bmap = {k: np.asarray(v) for k, v in out["boundary_map"].items()}
    return SimulationResult(
        summary=summary,
        energy=energy,
        events=dict(out["events"]),
        boundary_map=bmap,
        html=out["html"],
        observables=dict(out["observables"]),
        pair_correlation=dict(out["pair_correlation"]),
        self_diffusion=dict(out["self_diffusion"]),
    )
