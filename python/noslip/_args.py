"""Arguments shared by the entry points: a scene given as a :class:`Scene`, TOML text, a
dict or a path."""

from __future__ import annotations

import os
from typing import Any, Mapping, Union

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
        return Scene(scene)
    if isinstance(scene, os.PathLike):
        return Scene.from_file(scene)
    if isinstance(scene, Mapping):
        return Scene.from_dict(dict(scene))
    raise InputError(
        "scene: expected a Scene, TOML text, a path (os.PathLike) or a dict, got "
        f"{type(scene).__name__}"
    )
