"""Arguments shared by the entry points: a scene given as a :class:`Scene`, TOML text, a
dict or a path; integers and real numbers as Python or NumPy scalars."""

from __future__ import annotations

import os
from typing import Any, Mapping, Union

import numpy as np

from noslip._native import InputError, Scene

#: What the entry points take as a scene.
SceneLike = Union[Scene, str, "os.PathLike[str]", Mapping[str, Any]]


def as_scene(scene: SceneLike) -> Scene:
    """``scene`` as a :class:`Scene`: a Scene as it is, ``str`` as TOML text, an
    ``os.PathLike`` (``pathlib.Path``) as a file (:meth:`Scene.from_file`), a mapping as
    :meth:`Scene.from_dict`.

    Raises
    ------
    InputError
        Anything else, naming ``scene``; a bad scene, naming the place.
    """
    if isinstance(scene, Scene):
        return scene
    if isinstance(scene, str):
        try:
            scene.encode("utf-8")
        except UnicodeEncodeError as e:
            raise InputError(
                f"scene: TOML text that is not valid Unicode (a lone surrogate at character "
                f"{e.start})"
            ) from None
        return Scene(scene)
    if isinstance(scene, os.PathLike):
        return Scene.from_file(scene)
    if isinstance(scene, Mapping):
        return Scene.from_dict(dict(scene))
    raise InputError(
        "scene: expected a Scene, TOML text, a path (os.PathLike) or a dict, got "
        f"{type(scene).__name__}"
    )


def is_integer(x: Any) -> bool:
    """Whether ``x`` is an integer, Python's or NumPy's (a bool is not)."""
    return isinstance(x, (int, np.integer)) and not isinstance(x, (bool, np.bool_))


def is_real(x: Any) -> bool:
    """Whether ``x`` is a real number, an integer or a float, Python's or NumPy's (a bool is
    not)."""
    return is_integer(x) or isinstance(x, (float, np.floating))
