"""The keyword options of sombra's functions, type-checked for the compiled
module (which checks their values as the command line does), and the small
conversions every function shares (private to the package)."""

from __future__ import annotations

import json
import numbers
import operator
import os
import warnings
from typing import Any, Callable, Mapping, Union

import numpy as np

from . import _sombra

PathLike = Union[str, "os.PathLike[str]"]
Progress = Union[bool, Callable[[int, int], Any], None]

# keyword → (command-line option, the Python types it takes). bool is refused
# where a number is asked for, though Python counts it an int; numpy's
# integers and floats count as Python's (whatever operator.index or
# numbers.Real take). The option's name is what errors about its value say,
# as on the command line.
_INT = (int,)
_NUMBER = (int, float)
_STR = (str,)
_BOOL = (bool,)
_SCENE_OPTIONS = {
    "width": ("--width", _INT),
    "height": ("--height", _INT),
    "spp": ("--spp", _INT),
    "seed": ("--seed", _INT),
    "integrator": ("--integrator", _STR),
    "max_depth": ("--max-depth", _INT),
    "max_volume_depth": ("--max-volume-depth", _INT),
    "texture_filter": ("--texture-filter", _STR),
}
_RUN_OPTIONS = {
    **_SCENE_OPTIONS,
    "threads": ("--threads", _INT),
    "accel": ("--accel", _STR),
    "light_tree": ("--light-tree", _STR),
    "frame": ("--frame", _INT),
}
_EXPLAIN_OPTIONS = {
    **_RUN_OPTIONS,
    "denoise": ("--denoise", _BOOL),
}
_RENDER_OPTIONS = {
    **_RUN_OPTIONS,
    "time": ("--time", _NUMBER),
    "noise_threshold": ("--noise-threshold", _NUMBER),
    "min_spp": ("--min-spp", _INT),
    "crop": ("--crop", (tuple, list, np.ndarray)),
    "denoise": ("--denoise", _BOOL),
}


def _options(function: str, options: Mapping[str, Any], table: Mapping[str, tuple]) -> dict:
    """The keyword options given (not None), their types checked."""
    checked = {}
    for key, value in options.items():
        if key not in table:
            raise TypeError(f"{function}() got an unexpected keyword argument '{key}'")
        if value is None:
            continue  # None means "as the scene says", like leaving the option out
        _, types = table[key]
        plain = _plain_number(value, types)
        if plain is None:
            names = " or ".join(t.__name__ for t in types)
            raise TypeError(f"{function}(): {key} must be {names}, not {type(value).__name__}")
        checked[key] = plain
    return checked


def _plain_number(value: Any, types: tuple) -> Any:
    """`value` as the Python type `types` asks for (a numpy int as an int,
    a numpy float as a float, a numpy bool as a bool), or None."""
    is_bool = isinstance(value, (bool, np.bool_))
    if types is _BOOL:
        return bool(value) if is_bool else None
    if is_bool:
        return None
    if types is _INT or types is _NUMBER:
        try:
            return operator.index(value)
        except TypeError:
            pass
        if types is _NUMBER and isinstance(value, numbers.Real):
            return float(value)
        return None
    return value if isinstance(value, types) else None


def _warn(scene_impl: Any) -> None:
    for text in scene_impl.warnings:
        warnings.warn(f"sombra: {text}", RuntimeWarning, stacklevel=3)


def _plain(value: Any) -> Any:
    """A copy of a dict or list as plain JSON values (numpy numbers and
    arrays as Python ones), so later changes to the caller's value do not
    reach the scene."""
    def convert(v: Any) -> Any:
        if isinstance(v, np.ndarray):
            return v.tolist()
        if isinstance(v, np.generic):
            return v.item()
        raise TypeError(f"{type(v).__name__} is not a JSON value")
    return json.loads(json.dumps(value, default=convert))


def _path(path: PathLike, what: str) -> str:
    if not isinstance(path, (str, os.PathLike)):
        raise TypeError(f"{what}: expected a path (str or os.PathLike), not {type(path).__name__}")
    text = os.fspath(path)
    if not isinstance(text, str):
        raise TypeError(f"{what}: expected a str path, not {type(text).__name__}")
    if "\0" in text:
        # The system would read the path up to the NUL, and open another file.
        raise _sombra.Error(f"{text!r}: the path contains a NUL character")
    return text
