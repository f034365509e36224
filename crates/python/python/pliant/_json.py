"""Scene dicts to JSON text for ``Scene.from_dict``: numpy arrays and numpy numbers are
written as lists and numbers; NaN and infinity are refused (the scene format rejects
them everywhere)."""

import json
from typing import Any


def _plain(value: Any) -> Any:
    tolist = getattr(value, "tolist", None)
    if callable(tolist):  # numpy arrays and numpy scalars
        return tolist()
    raise TypeError(f"{type(value).__name__} is not a scene value (numbers, strings, lists, dicts)")


def dumps(scene: Any) -> str:
    """The scene dict as JSON text."""
    return json.dumps(scene, allow_nan=False, default=_plain)
