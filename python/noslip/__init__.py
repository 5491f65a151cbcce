"""noslip: no-slip collisions of rigid balls in R^n, from Python.

At contact, two balls' angular velocities ``U_i`` (skew ``n x n`` matrices) and centre
velocities ``u_i`` jump by the reflection, in the kinetic-energy metric, across the velocities
with no slip at the contact point (the model: ``docs/derivation.md``). The kernels are the
generated, exactly verified Rust kernels of the ``noslip`` workspace.

- :func:`collide`: one collision, floats or exact ``Fraction``\\ s (the JSON case format of
  ``noslip collide``).
- :func:`collide_batch`: a batch on NumPy arrays (float64 or float32), GIL released, threads.
- :class:`Scene`, :func:`simulate`: scenes (TOML) and the event-driven simulator.
- :func:`lyapunov`: Lyapunov exponents of a scene (tangent maps with QR, or two trajectories);
  :func:`orbits`: periodic orbits of a one-ball table, with their stability.
- :func:`verify`, :func:`report`: the exact verification and the accuracy report.
- :func:`sweep`: a function over a parameter grid as Dask tasks, streamed to a store.
- :mod:`noslip.tables` (billiard tables) and :mod:`noslip.granular` (a cooling rough gas, its
  ``T_rot / T_tr`` measured and from kinetic theory): functions for sweeps.
- :func:`read_log`, :func:`read_boundary_map`, :func:`read_observables`: ``noslip
  simulate``'s Parquet outputs as pandas DataFrames, units in ``attrs`` (pyarrow, the
  ``sweep`` extra).
- :class:`InputError`: bad input (a ``ValueError`` naming the field).

``noslip.__version__`` is the package's version. Long native calls (:func:`simulate`,
:func:`lyapunov`, :func:`orbits`, :func:`verify`, :func:`report`, :func:`collide_batch`)
stop on Ctrl-C with ``KeyboardInterrupt``, discarding their partial results.

See ``docs/python.md``.
"""

from noslip._native import DIMS, InputError, Scene, __version__
from noslip.batch import collide_batch, isa
from noslip.case import collide
from noslip.checks import report, verify
from noslip.columnar import read_boundary_map, read_log, read_observables
from noslip.dynamics import LyapunovResult, OrbitsResult, lyapunov, orbits
from noslip.simulate import SimulationResult, simulate
from noslip.sweep import sweep
from noslip import granular, tables

__all__ = [
    "__version__",
    "DIMS",
    "InputError",
    "LyapunovResult",
    "OrbitsResult",
    "Scene",
    "SimulationResult",
    "collide",
    "collide_batch",
    "granular",
    "isa",
    "lyapunov",
    "orbits",
    "read_boundary_map",
    "read_log",
    "read_observables",
    "report",
    "simulate",
    "sweep",
    "tables",
    "verify",
]
