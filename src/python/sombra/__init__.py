"""sombra: a ray tracer that is right to the last pixel, from Python (spec §19).

    import sombra
    scene = sombra.load("scenes/cornell-box-path.json")
    image = sombra.render(scene, spp=64)       # numpy float32 (height, width, 3), linear RGB
    sombra.write_image("out.png", image)

The keyword options are the command line's (``sombra render --help``), with
``-`` written ``_``: the same names, the same checks, the same numbers (a
render equals ``sombra render ... -o x.pfm`` float for float). A wrong input
raises :class:`Error` with the command line's one-line message (without its
``sombra: error:`` prefix); an argument of the wrong type raises TypeError.
"""

from __future__ import annotations

import json
import math
import os
import warnings
from typing import Any, Mapping, Optional, Sequence, Union

import numpy as np

from . import _sombra
from ._options import _EXPLAIN_OPTIONS, _RENDER_OPTIONS, _SCENE_OPTIONS, PathLike, Progress, _options, _path
from ._progress import Bar as _Bar
from ._scene import Scene

__all__ = ["Error", "Scene", "load", "render", "denoise", "explain", "explain_svg", "write_image", "read_image",
           "to_png"]

__version__: str = _sombra.__version__

#: A wrong input (scene, option value, array): a ValueError whose text is the
#: command line's one line, "WHERE: WHAT" (WHERE a file:line:col, a JSON path
#: or an option).
Error = _sombra.Error


def load(path: PathLike, **overrides: Any) -> Scene:
    """Reads a scene file (.json) or a model for a quick look (.obj, .ply,
    .gltf, .glb; spec §7).

    overrides: width, height, spp, seed, integrator ("direct" or "path"),
    max_depth, texture_filter ("bilinear" or "mipmap"): they replace the
    scene's "render" values, checked as the command line checks them.
    The reader's warnings are issued as RuntimeWarning.
    Raises Error for a file that is missing or wrong. A scene file's scene
    can be edited afterwards (see Scene); a model's quick look cannot.
    """
    file = _path(path, "load")
    options = _options("load", overrides, _SCENE_OPTIONS)
    if os.path.splitext(file)[1].lower() == ".json" and not os.path.isdir(file):
        return Scene._read(_sombra.read_scene_text(file), file, options)
    return Scene._wrap(_sombra.load(file, options))


def _scene_impl(scene: Any, function: str) -> Any:
    if not isinstance(scene, Scene):
        raise TypeError(f"{function}(): expected a sombra.Scene, not {type(scene).__name__}")
    return scene._assembled()


def render(scene: Scene, *, aov: Union[Sequence[str], str, None] = None, progress: Progress = None,
           **options: Any) -> Union[np.ndarray, dict]:
    """Renders the scene; returns the image as a float32 numpy array of
    shape (height, width, 3), linear RGB, top row first: the values
    ``sombra render SCENE -o x.pfm`` writes, float for float.

    options (the command line's, spec §1, §10, §18; None = as the scene says):
      width, height, spp, seed   image size, samples per pixel, random seed
      threads                    worker threads; 0 = all hardware threads
      integrator                 "direct" or "path"
      max_depth                  most scattering events on a path (path), 0 to 1024
      light_tree                 "auto", "on" or "off"
      texture_filter             "bilinear" or "mipmap"
      accel                      "bvh", "brute", or "embree" where built
      time                       seconds: render sample passes until the next would
                                 end past the budget (counted from this call)
      noise_threshold, min_spp   adaptive sampling
      crop                       (x0, y0, x1, y1): only those pixels, as in the whole image
      denoise                    True: the image denoised once the last pass is done
                                 (spec §25; at least 2 spp), as ``sombra render --denoise``
    aov: any of "albedo", "normal", "depth", "position", "spp", "variance",
      "noisy", "denoise": then the result is a dict of arrays, "color" the
      image, "albedo"/"normal"/"position" (height, width, 3), "depth"/"spp"
      (height, width), "variance" (height, width, 3): the estimated variance
      of each pixel's mean, per channel; "noisy" (with denoise=True only) the
      image before denoising; "denoise" adds every layer the denoiser reads,
      each under its own key: "variance", "denoise.A" and "denoise.B" (the
      means of each pixel's even- and odd-indexed samples), "denoise.albedoA",
      "denoise.albedoB", "denoise.normalA", "denoise.normalB" (height, width,
      3) and "denoise.depthA", "denoise.depthB" (height, width), what
      :func:`denoise` takes.
    progress: True for a text bar (on stderr, redrawn in place; in Jupyter
      one text output that updates), or a callable receiving
      (samples done, samples in all) about every 50 ms.

    The GIL is released while rendering; Ctrl-C raises KeyboardInterrupt
    within a second.
    """
    impl = _scene_impl(scene, "render")
    checked = _options("render", options, _RENDER_OPTIONS)
    if aov is not None:
        names = [aov] if isinstance(aov, str) else aov
        if not isinstance(names, (list, tuple)) or not all(isinstance(n, str) for n in names):
            raise TypeError("render(): aov must be a list of str (albedo, normal, depth, position, spp, variance, "
                            "noisy, denoise)")
        if names:
            checked["aov"] = list(names)
    bar = None
    if progress is True:
        bar = progress = _Bar.for_here()
    elif progress is False:
        progress = None
    elif progress is not None and not callable(progress):
        raise TypeError("render(): progress must be True, False, None or a callable(done, total)")
    try:
        out = _sombra.render(impl, checked, progress)
    finally:
        if bar is not None:
            bar.close()
    for text in out["warnings"]:
        warnings.warn(f"sombra: {text}", RuntimeWarning, stacklevel=2)
    if aov is None or not names:
        return out["color"]
    return {key: value for key, value in out.items() if isinstance(value, np.ndarray)}


def denoise(layers: Mapping[str, np.ndarray], *, threads: Optional[int] = None) -> np.ndarray:
    """Denoises the layers ``render(scene, aov=["denoise"], ...)`` returns
    (spec §25): a float32 array (height, width, 3), equal float for float to
    ``render(scene, denoise=True, ...)`` with the same options. Keys beside
    the denoiser's are ignored.

    threads: worker threads, 0 (or None) = all; the result is the same for any.
    Raises Error naming the layer for one missing, of the wrong shape, or
    holding a NaN (or a negative colour); TypeError for a value that is not a
    numpy array of a float dtype. The GIL is released while denoising;
    Ctrl-C raises KeyboardInterrupt within a second.
    """
    if not isinstance(layers, Mapping):
        raise TypeError(f"denoise(): expected the dict render(..., aov=[\"denoise\"]) returns, "
                        f"not {type(layers).__name__}")
    checked = _options("denoise", {"threads": threads}, {"threads": _RENDER_OPTIONS["threads"]})
    given = {key: value for key, value in layers.items() if isinstance(key, str)}
    return _sombra.denoise(given, checked)


def explain(scene: Scene, x: int, y: int, sample: int = 0, **options: Any) -> dict:
    """The story of pixel (x, y) (column, row) for its sample ``sample``
    (spec §14): the object ``sombra explain SCENE X Y --json`` prints, with
    "pixel", "sample", "value" (equal, to the last bit, to what the render
    computes for that sample), "camera_ray", "hit", "lights" and "vertices".

    options: width, height, spp, seed, threads, integrator, max_depth,
    light_tree, texture_filter, accel, frame, as for :func:`render`, and
    denoise: True adds "denoise" (spec §25), as ``sombra explain --denoise``
    does: the pixel of ``render(scene, denoise=True, ...)`` with the same
    options, its raw value, and every weight the denoiser gave a pixel's
    half-buffer colour to make it. It renders the whole image first.
    """
    impl = _scene_impl(scene, "explain")
    for name, value in (("x", x), ("y", y), ("sample", sample)):
        if isinstance(value, bool) or not isinstance(value, int):
            raise TypeError(f"explain(): {name} must be int, not {type(value).__name__}")
    return json.loads(_sombra.explain(impl, x, y, sample, _options("explain", options, _EXPLAIN_OPTIONS))[0])


def explain_svg(scene: Scene, x: int, y: int, sample: int = 0, *, exposure: float = 0, tonemap: str = "none",
                **options: Any) -> str:
    """The picture of pixel (x, y)'s story as SVG text, what ``sombra explain
    SCENE X Y --svg FILE`` writes: the path drawn in the scene from the side
    and from the camera, over a quick render of the image (``picture_spp``
    samples; with denoise=True the render that was denoised), shown with
    ``exposure`` and ``tonemap`` as write_image shows images. Options as
    for :func:`explain`."""
    impl = _scene_impl(scene, "explain_svg")
    for name, value in (("x", x), ("y", y), ("sample", sample)):
        if isinstance(value, bool) or not isinstance(value, int):
            raise TypeError(f"explain_svg(): {name} must be int, not {type(value).__name__}")
    if isinstance(exposure, bool) or not isinstance(exposure, (int, float)) or not math.isfinite(exposure):
        raise TypeError(f"explain_svg(): exposure must be a finite number, not {exposure!r}")
    return _sombra.explain(impl, x, y, sample, _options("explain_svg", options, _EXPLAIN_OPTIONS),
                           (float(exposure), _tonemap(tonemap, "explain_svg")))[1]


def write_image(path: PathLike, array: np.ndarray, exposure: float = 0, tonemap: str = "none") -> None:
    """Writes a (height, width, 3) float image, linear RGB, as the path's
    extension says: .png or .jpg (8-bit sRGB of radiance × 2^exposure, then
    ``tonemap``: "none" clamps, "pbr-neutral" is Khronos' PBR Neutral), .pfm
    or .exr (linear floats; a tone mapper is an Error there). The file is
    written whole or not at all. Raises Error for a wrong shape, a NaN, or a
    file that cannot be written.
    """
    if isinstance(exposure, bool) or not isinstance(exposure, (int, float)):
        raise TypeError(f"write_image(): exposure must be a number, not {type(exposure).__name__}")
    if not math.isfinite(exposure):
        raise Error(f"exposure: must be a finite number, not {exposure}")
    _sombra.write_image(_path(path, "write_image"), array, float(exposure), _tonemap(tonemap, "write_image"))


def _tonemap(name: str, caller: str) -> str:
    if not isinstance(name, str):
        raise TypeError(f"{caller}(): tonemap must be a str, not {type(name).__name__}")
    return name


def read_image(path: PathLike) -> np.ndarray:
    """An image file as a float32 array (height, width, 3) of linear RGB, top
    row first: .pfm and .exr as stored (what write_image wrote, float for
    float), .hdr, and PNG, JPEG, TGA, BMP decoded from sRGB (a grey image
    fills the three channels, alpha is dropped). Raises Error for a missing,
    unreadable or damaged file."""
    return _sombra.read_image(_path(path, "read_image"))


def to_png(array: np.ndarray, exposure: float = 0, tonemap: str = "none") -> bytes:
    """The PNG file write_image would write, as bytes (for notebooks:
    ``IPython.display.Image(sombra.to_png(img))``)."""
    if isinstance(exposure, bool) or not isinstance(exposure, (int, float)):
        raise TypeError(f"to_png(): exposure must be a number, not {type(exposure).__name__}")
    if not math.isfinite(exposure):
        raise Error(f"exposure: must be a finite number, not {exposure}")
    return _sombra.to_png(array, float(exposure), _tonemap(tonemap, "to_png"))
