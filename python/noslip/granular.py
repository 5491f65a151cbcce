"""Granular gases for sweeps: a freely cooling rough gas (:func:`cooling_gas`), its
homogeneous cooling state's ``T_rot / T_tr`` measured by the simulator
(:func:`cooling_ratio`) and the two-temperature kinetic theory's value
(:func:`two_temperature_ratio`); ``docs/granular.md``.

The rough law ``{e, beta}``: at a contact the normal part of the contact point's relative
velocity is multiplied by ``-e`` and the tangential part by ``-beta``; temperatures are per
degree of freedom, ``T_tr`` without the centre of mass's motion (``noslip simulate
--observables``).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from noslip._args import is_integer, is_real
from noslip._native import InputError, Scene
from noslip.simulate import simulate

__all__ = [
    "cooling_gas",
    "cooling_ratio",
    "driven_gas",
    "driven_ratio",
    "two_temperature_ratio",
]

def _uniform_gamma2(dim: int) -> float:
    """``gamma^2 = 2 lambda / R^2 = I / (m R^2)`` of a uniform ball in R^n: ``2 / (n + 2)``."""
    return 2.0 / (dim + 2.0)


def _ball_volume(dim: int) -> float:
    """The volume of a ball of radius 1/2 in R^n: ``pi^(n/2) / (2^n Gamma(n/2 + 1))``."""
    return float(math.pi ** (dim / 2) * 0.5**dim / math.gamma(dim / 2 + 1))


def two_temperature_ratio(dim: int, e: float, beta: float, gamma2: float | None = None) -> float:
    """The homogeneous cooling state's ``T_rot / T_tr`` of the two-temperature theory.

    A dilute gas of equal rough balls in R^n with Maxwellian velocities at ``T_tr`` and
    ``T_rot`` (Huthmann & Zippelius 1997; Luding, Huthmann, McNamara & Zippelius 1998;
    derived for any ``n`` in ``docs/granular.md``): with ``k = gamma^2``,
    ``eta = k (1 + beta) / (2 (1 + k))`` and ``tau`` the contacts per ball,

    ``n dT_tr/dtau = -a T_tr + b T_rot``, ``a = 1 - e^2 + 2 (n-1) eta (1 - eta)``,
    ``b = 2 (n-1) eta^2 / k``; ``n dT_rot/dtau = c T_tr - d T_rot``, ``c = 4 eta^2 / k``,
    ``d = 4 (eta / k) (1 - eta / k)``;

    the ratio is the positive root of ``b r^2 + (d - a) r - c = 0``.

    Parameters
    ----------
    dim : int
        The dimension ``n >= 2``.
    e, beta : float
        Normal (``0 <= e <= 1``) and tangential (``-1 < beta <= 1``) restitution.
    gamma2 : float, optional
        ``2 lambda / R^2`` of the balls (``0 < gamma2 <= 2 / n``); default a uniform ball's,
        ``2 / (n + 2)``.

    Returns
    -------
    float
        ``T_rot / T_tr``; NaN at ``beta = -1`` (rotation is decoupled: the ratio keeps its
        start).

    Examples
    --------
    >>> round(two_temperature_ratio(3, 1.0, 1.0), 12)
    1.0
    >>> round(two_temperature_ratio(3, 0.9, 0.5), 4)
    0.8671
    """
    if dim < 2:
        raise ValueError(f"dim: must be at least 2, got {dim}")
    if not 0.0 <= e <= 1.0:
        raise ValueError(f"e: must be in [0, 1], got {e}")
    if not -1.0 <= beta <= 1.0:
        raise ValueError(f"beta: must be in [-1, 1], got {beta}")
    k = _uniform_gamma2(dim) if gamma2 is None else float(gamma2)
    if not 0.0 < k <= 2.0 / dim:
        raise ValueError(f"gamma2: must be in (0, 2/n], got {gamma2}")
    eta = k * (1.0 + beta) / (2.0 * (1.0 + k))
    a = 1.0 - e * e + 2.0 * (dim - 1) * eta * (1.0 - eta)
    b = 2.0 * (dim - 1) * eta * eta / k
    c = 4.0 * eta * eta / k
    d = 4.0 * eta / k * (1.0 - eta / k)
    if b == 0.0:
        return math.nan
    return ((a - d) + math.sqrt((a - d) ** 2 + 4.0 * b * c)) / (2.0 * b)


def _check_gas(balls: Any, phi: Any) -> None:
    """``balls`` a positive integer and ``phi`` in ``(0, 1)``, naming the argument (they
    size the box: 0 divided by zero and a negative count made a complex side)."""
    if not is_integer(balls) or balls < 1:
        raise InputError(f"balls: must be a positive integer, got {balls!r}")
    if not (is_real(phi) and 0 < float(phi) < 1):
        raise InputError(f"phi: must be a packing fraction in (0, 1), got {phi!r}")


def cooling_gas(
    e: float,
    beta: float,
    *,
    dim: int = 3,
    balls: int = 500,
    phi: float = 0.02,
    seed: int = 1,
) -> Scene:
    """A freely cooling gas of rough balls: ``balls`` uniform balls of radius 1/2 and mass 1
    in a periodic cube at packing fraction ``phi``, the rough law ``{e, beta}`` at every
    contact, a Maxwellian start at temperature 1 (every degree of freedom), placed at random
    with ``seed``.

    Raises
    ------
    InputError
        ``balls`` not a positive integer or ``phi`` not in ``(0, 1)``, naming it (and the
        scene's own checks, naming the field).
    """
    _check_gas(balls, phi)
    side = (int(balls) * _ball_volume(dim) / float(phi)) ** (1.0 / dim)
    return Scene.from_dict(
        {
            "description": f"cooling rough gas, e = {e}, beta = {beta}",
            "dim": dim,
            "box": {"size": [side] * dim, "boundary": ["periodic"] * dim},
            "contact": {"balls": {"e": e, "beta": beta}},
            "species": [{"mass": 1, "radius": "1/2", "count": int(balls)}],
            "random": {"seed": seed, "velocities": "maxwellian"},
        },
        origin=f"cooling_gas(e={e}, beta={beta}, dim={dim}, balls={balls}, phi={phi})",
    )


def driven_gas(
    e: float,
    beta: float,
    *,
    strength: float,
    interval: float,
    dim: int = 3,
    balls: int = 500,
    phi: float = 0.02,
    seed: int = 1,
) -> Scene:
    """:func:`cooling_gas` driven to a steady state by the white-noise thermostat.

    Every ``interval`` of time each ball's velocity gets a normal increment of variance
    ``strength**2 * interval`` per component, less the increments' mean (the momentum is
    kept); spins are not kicked (``[thermostat]``, ``docs/granular.md``, "A driven steady
    state"). The kicks heat ``T_tr`` at ``dT/dt = m strength**2``; their random stream is
    seeded with ``seed``.

    Raises
    ------
    ValueError
        ``strength`` or ``interval`` not positive and finite, naming it.
    """
    for name, value in (("strength", strength), ("interval", interval)):
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"{name}: must be positive and finite, got {value}")
    base = cooling_gas(e, beta, dim=dim, balls=balls, phi=phi, seed=seed)
    thermostat = (
        f'\n[thermostat]\nkind = "white-noise"\nstrength = "{float(strength)!r}"\n'
        f'interval = "{float(interval)!r}"\nseed = {seed}\n'
    )
    return Scene(
        base.toml.replace("cooling rough gas", "driven rough gas") + thermostat,
        origin=f"driven_gas(e={e}, beta={beta}, strength={strength}, interval={interval})",
    )


def driven_ratio(dim: int, e: float, beta: float, gamma2: float | None = None) -> float:
    """``T_rot / T_tr`` of a gas driven in translation only, in the two-temperature theory.

    The kicks do not reach the spins, so the rotational temperature's equation of
    :func:`two_temperature_ratio`, ``n dT_rot/dtau = c T_tr - d T_rot``, has no other source:
    its stationarity gives ``c / d = eta / (1 - eta / k)`` whatever the forcing and ``e``
    (``e`` is checked, though unused). Accurate near perfect roughness (``beta`` about 0.9,
    ``docs/granular.md``).
    """
    two_temperature_ratio(dim, e, beta, gamma2)  # the same checks, naming the field
    if beta == -1.0:
        return math.nan  # smooth balls: the spins are decoupled, no steady ratio
    k = _uniform_gamma2(dim) if gamma2 is None else gamma2
    eta = k * (1.0 + beta) / (2.0 * (1.0 + k))
    return eta / (1.0 - eta / k)


def cooling_ratio(
    e: float,
    beta: float,
    *,
    dim: int = 3,
    balls: int = 500,
    phi: float = 0.02,
    seed: int = 1,
    collisions: float = 60.0,
) -> dict[str, Any]:
    """``T_rot / T_tr`` of :func:`cooling_gas`, measured, beside the theory's value.

    The gas is run for ``collisions`` contacts per ball from equal temperatures, sampled
    about 20 times per initial collision time; the ratio is averaged over the rows of the
    second half (by contacts per ball), where at moderate and large roughness it has
    relaxed to its plateau (``docs/granular.md`` gives the relaxation rate; at small
    roughness, ``beta <= 0``, it relaxes slowly: use more collisions).

    Returns
    -------
    dict
        ``ratio`` (the mean over the window), ``ratio_spread`` (the standard deviation of
        the window's rows, not an error bar: rows are correlated), ``theory``
        (:func:`two_temperature_ratio`), ``t_tr_drop`` (``T_tr`` at the end over at the
        start), ``rows`` (rows averaged).

    Raises
    ------
    InputError
        ``collisions`` not positive and finite, or :func:`cooling_gas`'s arguments, naming
        them.
    """
    if not (is_real(collisions) and 0 < float(collisions) < math.inf):
        raise InputError(f"collisions: must be positive and finite, got {collisions!r}")
    scene = cooling_gas(e, beta, dim=dim, balls=balls, phi=phi, seed=seed)
    # The dilute collision frequency at temperature 1 (docs/granular.md, Haff's law:
    # 2 pi^((n-1)/2) / Gamma(n/2) rho sigma^(n-1) sqrt(T/m), sigma = 1) sets the sampling.
    rho = phi / _ball_volume(dim)
    omega = 2 * math.pi ** ((dim - 1) / 2) / math.gamma(dim / 2) * rho
    run = simulate(scene, events=max(1, int(collisions * balls / 2)), observables=0.05 / omega)
    obs = run.observables
    per_ball = 2.0 * obs["contacts"] / balls
    window = per_ball >= collisions / 2
    ratio = obs["T_rot"][window] / obs["T_tr"][window]
    return {
        "ratio": float(np.mean(ratio)),
        "ratio_spread": float(np.std(ratio)),
        "theory": two_temperature_ratio(dim, e, beta),
        "t_tr_drop": float(obs["T_tr"][-1] / obs["T_tr"][0]),
        "rows": int(np.count_nonzero(window)),
    }
