"""Type stubs of the native module (the Rust crate in python/src)."""

from fractions import Fraction
from os import PathLike
from typing import Any

import numpy as np
import numpy.typing as npt

DIMS: list[int]
__version__: str

class InputError(ValueError):
    """Bad input: the message names the field (``bodies[1].gamma2: ...``)."""

def collide_case(case: str, exact: bool) -> str: ...

_BodyArrays = tuple[
    npt.NDArray[Any], npt.NDArray[Any], npt.NDArray[Any], npt.NDArray[Any], npt.NDArray[Any]
]
_BatchOut = tuple[npt.NDArray[Any], npt.NDArray[Any], npt.NDArray[Any], npt.NDArray[Any]]

def collide_batch_f64(
    normal: npt.NDArray[Any],
    body1: _BodyArrays,
    body2: _BodyArrays,
    validate: bool,
    parallel: bool,
    out: _BatchOut | None = None,
) -> _BatchOut: ...
def collide_batch_f32(
    normal: npt.NDArray[Any],
    body1: _BodyArrays,
    body2: _BodyArrays,
    validate: bool,
    parallel: bool,
    out: _BatchOut | None = None,
) -> _BatchOut: ...
def collide_batch_law_f64(
    normal: npt.NDArray[Any],
    body1: _BodyArrays,
    body2: _BodyArrays,
    kind: str,
    law: list[npt.NDArray[Any]],
    validate: bool,
    parallel: bool,
    out: _BatchOut | None = None,
) -> _BatchOut: ...
def collide_batch_law_f32(
    normal: npt.NDArray[Any],
    body1: _BodyArrays,
    body2: _BodyArrays,
    kind: str,
    law: list[npt.NDArray[Any]],
    validate: bool,
    parallel: bool,
    out: _BatchOut | None = None,
) -> _BatchOut: ...
def reference_seconds(
    normal: npt.NDArray[np.float64],
    body1: _BodyArrays,
    body2: _BodyArrays,
    repeats: int,
    parallel: bool = True,
) -> dict[str, list[float]]: ...
def isa() -> str: ...
def batch_params_f64(
    dim: int,
    body: int,
    mass: npt.NDArray[np.float64] | None,
    radius: npt.NDArray[np.float64],
    lambda_: npt.NDArray[np.float64] | None,
    distribution: str | None,
) -> tuple[npt.NDArray[np.float64] | None, npt.NDArray[np.float64] | None]: ...
def batch_params_f32(
    dim: int,
    body: int,
    mass: npt.NDArray[np.float32] | None,
    radius: npt.NDArray[np.float32],
    lambda_: npt.NDArray[np.float32] | None,
    distribution: str | None,
) -> tuple[npt.NDArray[np.float32] | None, npt.NDArray[np.float32] | None]: ...
def lyapunov(
    scene: Scene,
    events: int,
    k: int | None,
    method: str,
    seed: int,
    blocks: int,
    every: int | None,
    contact: str | None,
) -> dict[str, Any]: ...
def orbits(
    scene: Scene,
    period: int,
    starts: list[list[str]],
    grid: int | None,
    contact: str | None,
    max_contacts: int | None = None,
) -> str: ...

class Scene:
    """A validated scene (the TOML format of ``noslip simulate``); pickles as its text."""

    def __init__(self, text: str, origin: str = "<string>") -> None: ...
    @staticmethod
    def from_file(path: str | PathLike[str]) -> Scene: ...
    @staticmethod
    def from_dict(scene: dict[str, Any], origin: str = "<dict>") -> Scene: ...
    @property
    def toml(self) -> str: ...
    @property
    def origin(self) -> str: ...
    @property
    def dim(self) -> int: ...
    @property
    def description(self) -> str: ...
    @property
    def balls(self) -> int: ...
    @property
    def ball_laws(self) -> dict[tuple[str, str], str | dict[str, Fraction]]: ...
    def __eq__(self, other: object) -> bool: ...
    def __hash__(self) -> int: ...

def simulate(
    scene: Scene,
    events: int | None,
    time: float | None,
    log: bool,
    boundary_map: bool,
    max_memory: int | None,
    html: bool = ...,
    observables: float | None = ...,
    pair_correlation: float | None = ...,
    pair_bins: int | None = ...,
    self_diffusion: float | None = ...,
    self_diffusion_from: float = ...,
    conserve_energy: bool = ...,
) -> dict[str, Any]: ...
def verify(dims: list[int], points: int) -> str: ...
def report(dims: list[int], samples: int, seed: int) -> str: ...
