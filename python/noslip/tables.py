"""Billiard tables as scenes, and observables of them for sweeps.

The Sinai table: one rough disk (radius ``1/20``, mass 1) in the periodic unit square with a
fixed disk obstacle of radius ``radius`` at the centre; the disk's inertia is
``gamma2 = 2 lambda / R^2`` in ``[0, 1]`` (0: a point mass, the classical Sinai billiard;
``1/2`` uniform; 1 a ring).
"""

from __future__ import annotations

from typing import Any

from noslip._native import Scene
from noslip.dynamics import lyapunov
from noslip.simulate import simulate

__all__ = ["sinai", "sinai_collision_rate", "sinai_lyapunov"]


def sinai(gamma2: float, radius: float, *, disk_radius: str = "1/20") -> Scene:
    """The no-slip Sinai table with obstacle radius ``radius`` and the disk's ``gamma2``
    (the disk starts at ``(1/10, 1/10)`` with velocity ``(0.6, 0.8)`` and no spin)."""
    return Scene.from_dict(
        {
            "description": f"no-slip Sinai table, gamma2 = {gamma2}, obstacle radius {radius}",
            "dim": 2,
            "box": {"size": [1, 1], "boundary": ["periodic", "periodic"]},
            "species": [
                {"name": "disk", "mass": 1, "radius": disk_radius, "gamma2": gamma2}
            ],
            "ball": [
                {
                    "species": 0,
                    "position": ["1/10", "1/10"],
                    "velocity": ["0.6", "0.8"],
                    "angular_velocity": 0,
                }
            ],
            "obstacle": [{"position": ["1/2", "1/2"], "radius": radius}],
        },
        origin=f"sinai(gamma2={gamma2}, radius={radius})",
    )


def sinai_collision_rate(gamma2: float, radius: float, events: int = 2000) -> dict[str, Any]:
    """Collisions per unit time of the disk with the obstacle over ``events`` contacts, and
    the run's relative energy drift (a check: the map conserves energy)."""
    run = simulate(sinai(gamma2, radius), events=events, log=False)
    s = run.summary
    return {"collision_rate": s["events"] / s["time"], "energy_drift": s["energy_drift"]}


def sinai_lyapunov(gamma2: float, radius: float, events: int = 20_000) -> dict[str, Any]:
    """The largest Lyapunov exponent of the no-slip Sinai table, per unit time, with its
    standard error (``noslip.lyapunov`` by tangent maps and QR, the largest only, over
    ``events`` contacts in 10 measured blocks after a warm-up block), and per contact."""
    run = lyapunov(sinai(gamma2, radius), events, k=1)
    return {
        "lyapunov": float(run.per_time[0]),
        "lyapunov_error": float(run.per_time_error[0]),
        "lyapunov_per_contact": float(run.per_contact[0]),
    }
