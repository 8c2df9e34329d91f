"""sombra.Scene: a scene read from a file or a dict, or built from code
(private to the package; use sombra.Scene)."""

from __future__ import annotations

import json
import os
from typing import Any, Mapping, Optional, Sequence

import numpy as np

from . import _sombra
from ._options import _SCENE_OPTIONS, PathLike, _options, _path, _plain, _warn

Error = _sombra.Error


class Scene:
    """A scene to render: geometry, materials, lights, camera and render
    settings (the scene file's "render" section with any overrides).

    Made by :func:`load` (a scene file or a model), :meth:`Scene.from_dict`
    (the scene-file schema as a dict), or from code::

        s = sombra.Scene()
        s.add_material("clay", {"type": "diffuse", "kd": [0.7, 0.6, 0.5]})
        s.add_mesh(positions, indices, material="clay")   # numpy (N, 3) floats, (M, 3) ints
        s.add_light({"type": "point", "position": [0, 3, 2], "intensity": [20, 20, 20]})
        s.camera = {"origin": [0, 1, 4], "look_at": [0, 0.5, 0], "fov": 40}
        s.render_settings = {"width": 320, "height": 240, "spp": 16}

    Each piece has the meaning and the checks of the scene-file key of the
    same name (spec §2–§17) and is checked when it is given: a bad value
    raises Error there (naming it as in a file, "<scene>: /materials/clay/kd: ..."),
    not at render time.
    """

    def __init__(self) -> None:
        self._impl = None  # the assembled scene, made again after each change
        self._camera = None
        self._materials: dict = {}
        self._lights: list = []
        self._render: dict = {}
        self._background = None
        self._environment = None
        self._meshes: list = []  # _sombra.Mesh, copies of the arrays given
        self._objects: list = []  # {"mesh": i, "material": …, "transform": …}
        self._media: dict = {}

    @classmethod
    def _wrap(cls, impl: Any) -> "Scene":
        scene = cls.__new__(cls)
        scene._impl = impl
        scene._meshes = None  # read from a file or a dict: not built from code
        _warn(impl)
        return scene

    @classmethod
    def from_dict(cls, d: Mapping[str, Any], base_dir: PathLike = ".", **overrides: Any) -> "Scene":
        """The scene a scene file holding ``d`` would be (spec §2): the same
        keys, the same checks, errors naming the JSON path
        (``<dict>: /materials/white/kd: ...``). Relative paths in it (mesh
        files, textures) are relative to ``base_dir``. ``overrides`` as for
        :func:`load`."""
        if not isinstance(d, Mapping):
            raise TypeError(f"Scene.from_dict: expected a dict, not {type(d).__name__}")
        text = json.dumps(_plain(d))
        name = os.path.join(_path(base_dir, "Scene.from_dict: base_dir"), "<dict>")
        return cls._wrap(_sombra.load_text(text, name, _options("from_dict", overrides, _SCENE_OPTIONS)))

    def _from_code(self, what: str) -> None:
        if self._meshes is None:
            raise TypeError(f"Scene.{what}: this scene was read from a file or a dict; build one from code "
                            "with sombra.Scene()")

    def _changed(self) -> None:
        self._impl = None

    def _checked(self, name: str, part: str, value: Any, mapping: bool = True) -> Any:
        """``value`` (a scene from code's piece ``name``, the scene file's
        section ``part``) as plain JSON data, after the reader's own check of
        that section: what every setter stores."""
        self._from_code(name)
        if mapping and not isinstance(value, Mapping):
            raise TypeError(f"Scene.{name}: expected a dict, not {type(value).__name__}")
        plain = _plain(value)
        _sombra.check_part(part, json.dumps(plain), "/" + part)
        return plain

    def _assembled(self) -> Any:
        if self._impl is None:
            d: dict = {"render": self._render, "materials": self._materials, "lights": self._lights,
                       "objects": self._objects, "media": self._media}
            if self._camera is not None:
                d["camera"] = self._camera
            if self._background is not None:
                d["background"] = self._background
            if self._environment is not None:
                d["environment"] = self._environment
            self._impl = _sombra.load_text(json.dumps(d), "<scene>", {}, self._meshes)
            _warn(self._impl)
        return self._impl

    def add_material(self, name: str, material: Mapping[str, Any]) -> None:
        """Adds (or replaces) the material ``name``, a dict as in a scene
        file's "materials" (type, kd, ks, ...; textures relative to the
        working directory)."""
        self._from_code("add_material")
        if not isinstance(name, str):
            raise TypeError(f"add_material: name must be str, not {type(name).__name__}")
        if not isinstance(material, Mapping):
            raise TypeError(f"add_material: material must be a dict, not {type(material).__name__}")
        materials = {**self._materials, name: _plain(material)}
        _sombra.check_part("materials", json.dumps(materials), "/materials")
        self._materials = materials
        self._changed()

    def add_medium(self, name: str, medium: Mapping[str, Any]) -> None:
        """Adds (or replaces) the participating medium ``name``, a dict as in
        a scene file's "media" (spec §26): ``{"type": "homogeneous",
        "sigma_a": [...], "sigma_s": [...], "g": 0, "emission": [...],
        "scale": 1}``. A mesh bounds it with ``add_mesh(..., interior=name)``;
        ``render_settings = {"medium": name}`` fills the space outside every
        object with it; a camera dict's "medium" starts the camera in it."""
        self._from_code("add_medium")
        if not isinstance(name, str):
            raise TypeError(f"add_medium: name must be str, not {type(name).__name__}")
        if not isinstance(medium, Mapping):
            raise TypeError(f"add_medium: medium must be a dict, not {type(medium).__name__}")
        media = {**self._media, name: _plain(medium)}
        _sombra.check_part("media", json.dumps(media), "/media")
        self._media = media
        self._changed()

    def add_light(self, light: Mapping[str, Any]) -> None:
        """Adds a light, a dict as in a scene file's "lights" (point, spot,
        directional, quad)."""
        self._from_code("add_light")
        if not isinstance(light, Mapping):
            raise TypeError(f"add_light: light must be a dict, not {type(light).__name__}")
        lights = self._lights + [_plain(light)]
        _sombra.check_part("lights", json.dumps(lights), "/lights")
        self._lights = lights
        self._changed()

    def add_mesh(self, positions: np.ndarray, indices: np.ndarray, normals: Optional[np.ndarray] = None,
                 uvs: Optional[np.ndarray] = None, material: Optional[str] = None,
                 transform: Optional[Sequence[Mapping[str, Any]]] = None,
                 instances: Optional[Sequence[Sequence[Mapping[str, Any]]]] = None,
                 interior: Optional[str] = None, exterior: Optional[str] = None) -> None:
        """Adds a triangle mesh from numpy arrays (copied): positions float
        (N, 3), indices integer (M, 3) into positions, optional per-vertex
        normals float (N, 3) and uvs float (N, 2). ``material`` names one
        added with add_material, or is "interface" (a boundary rays cross
        unchanged, spec §26), else the default diffuse grey. ``interior``
        and ``exterior`` name media added with add_medium: the mesh bounds
        ``interior`` on the side its winding normals point away from
        (``exterior``, default the render's medium, on the other);
        ``transform`` is a scene file's transform list
        (``[{"scale": 2}, {"translate": [0, 1, 0]}]``). It renders exactly
        as the same mesh read from an OBJ file. ``instances``, a list of
        transform lists, draws the mesh once per entry (each applied after
        ``transform``) and stores it once (spec §23)."""
        self._from_code("add_mesh")
        i = len(self._objects)
        obj: dict = {"mesh": len(self._meshes)}
        if material is not None:
            if not isinstance(material, str):
                raise TypeError(f"add_mesh: material must be str, not {type(material).__name__}")
            if material not in self._materials and material != "interface":
                raise Error(f"<scene>: /objects/{i}/material: unknown material '{material}'")
            obj["material"] = material
        for key, name in (("interior", interior), ("exterior", exterior)):
            if name is None:
                continue
            if not isinstance(name, str):
                raise TypeError(f"add_mesh: {key} must be str, not {type(name).__name__}")
            if name not in self._media:
                raise Error(f"<scene>: /objects/{i}/{key}: no medium '{name}' in /media")
            obj[key] = name
        if exterior is not None and interior is None:
            raise Error(f"<scene>: /objects/{i}/exterior: 'exterior' needs 'interior' (the medium the object bounds)")
        if transform is not None:
            if not isinstance(transform, (list, tuple)):
                raise TypeError(f"add_mesh: transform must be a list of steps, not {type(transform).__name__}")
            obj["transform"] = _plain(transform)
            _sombra.check_part("transform", json.dumps(obj["transform"]), f"/objects/{i}/transform")
        if instances is not None:
            if not isinstance(instances, (list, tuple)) or not instances:
                raise TypeError("add_mesh: instances must be a non-empty list of transform lists")
            obj["instances"] = _plain(instances)
            for k, steps in enumerate(obj["instances"]):
                _sombra.check_part("transform", json.dumps(steps), f"/objects/{i}/instances/{k}")
        mesh = _sombra.make_mesh(positions, indices, normals, uvs, f"<scene>: mesh {obj['mesh']}")
        self._meshes.append(mesh)
        self._objects.append(obj)
        self._changed()

    @property
    def camera(self) -> Optional[dict]:
        """The camera, a dict as in a scene file's "camera" (spec §3, §17):
        the look-at form (origin, look_at, up, fov) or the basis form
        (origin, left, up, forward), with aperture_radius and
        focus_distance when it has a lens. A quick look's is the framing it
        chose (spec §7), or the glTF file's camera, whose orthographic kind
        (spec §24) shows as "orthographic": {"ymag": half-height} in place
        of "fov"; a scene from code's is None until set (perspective only,
        as in scene files). Read-only
        for a scene read from a file or a dict: render it from elsewhere
        with ``Scene.from_dict`` and another "camera"."""
        if self._meshes is None:
            return self._impl.camera
        return None if self._camera is None else json.loads(json.dumps(self._camera))

    @camera.setter
    def camera(self, camera: Mapping[str, Any]) -> None:
        self._camera = self._checked("camera", "camera", camera)
        self._changed()

    @property
    def background(self) -> Optional[list]:
        """The background colour [r, g, b] (a scene from code); None = black.
        A scene has a background or an environment, not both (spec §10):
        set the other to None first."""
        self._from_code("background")
        return self._background

    @background.setter
    def background(self, rgb: Optional[Sequence[float]]) -> None:
        self._from_code("background")
        if rgb is not None:
            self._only_one("background", "environment", self._environment)
        self._background = None if rgb is None else self._checked("background", "background", rgb, mapping=False)
        self._changed()

    @property
    def environment(self) -> Optional[dict]:
        """The environment map (a scene from code), a dict as in a scene
        file's "environment": ``{"file": "sky.exr", "scale": 1, "rotate_y":
        0}``, the file relative to the working directory (spec §10). It
        replaces the background, lights the scene under ``integrator="path"``
        and is read when set. None = none."""
        self._from_code("environment")
        return None if self._environment is None else dict(self._environment)

    @environment.setter
    def environment(self, environment: Optional[Mapping[str, Any]]) -> None:
        self._from_code("environment")
        if environment is not None:
            if not isinstance(environment, Mapping):
                raise TypeError(f"Scene.environment: expected a dict, not {type(environment).__name__}")
            self._only_one("environment", "background", self._background)
        self._environment = None if environment is None else self._checked("environment", "environment", environment)
        self._changed()

    @staticmethod
    def _only_one(key: str, other: str, other_value: Any) -> None:
        if other_value is not None:
            raise Error(f"<scene>: /{key}: give either 'background' or 'environment', not both (the map replaces "
                        f"the background); set Scene.{other} to None first")

    @property
    def render_settings(self) -> dict:
        """The settings a render starts from: width, height, spp, seed,
        integrator, max_depth, texture_filter. A scene from code may set
        them, as a dict like a scene file's "render" (the keys it gives
        replace the defaults)."""
        if self._meshes is not None:
            return _sombra.check_part("render", json.dumps(self._render), "/render")
        return self._impl.render_settings

    @render_settings.setter
    def render_settings(self, settings: Mapping[str, Any]) -> None:
        self._render = self._checked("render_settings", "render", settings)
        self._changed()

    @property
    def triangle_count(self) -> int:
        """Triangles in the scene, every object's together."""
        if self._meshes is not None:
            return sum(m.triangle_count for m in self._meshes)
        return self._impl.triangle_count

    @property
    def instanced_triangle_count(self) -> int:
        """Triangles drawn: an instanced mesh counts once per instance
        (``triangle_count`` counts it once)."""
        if self._meshes is not None:
            return sum(m.triangle_count * len(o.get("instances", [None]))
                       for m, o in zip(self._meshes, self._objects))
        return self._impl.instanced_triangle_count

    @property
    def source(self) -> str:
        """The file the scene came from (``<dict>`` for a dict, ``<scene>``
        for one from code), as messages name it."""
        return "<scene>" if self._meshes is not None else self._impl.source

    def __repr__(self) -> str:
        s = self.render_settings
        return (f"<sombra.Scene {self.source!r}: {self.triangle_count} triangles, "
                f"{s['width']}x{s['height']}, {s['spp']} spp, {s['integrator']}>")
