"""sombra.Scene: a scene read from a file or a dict, or built from code
(private to the package; use sombra.Scene)."""

from __future__ import annotations

import json
import operator
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

    A scene read from a scene file or a dict is edited with the same calls
    (camera, render_settings, lights, add_light, add_material, set_transform,
    add_mesh, background, environment), as Mitsuba's ``load_dict`` and
    ``traverse`` users expect; the next render assembles it again from the
    mesh files it read the first time (kept in memory: no file is read
    twice). A model's quick look (``load("bunny.ply")``) cannot be edited:
    give ``Scene.from_dict({"objects": [{"file": "bunny.ply"}], ...})``.
    """

    def __init__(self) -> None:
        self._impl = None  # the assembled scene, made again after each change
        # The scene file's JSON as a dict: what every setter edits.
        self._doc: Optional[dict] = {"render": {}, "materials": {}, "lights": [], "objects": [], "media": {}}
        self._meshes: list = []  # _sombra.Mesh, copies of the arrays add_mesh was given
        self._name = "<scene>"  # how messages name it; its folder anchors relative paths
        self._overrides: dict = {}  # load()'s width=, spp=, ... (checked)
        self._cache = None  # the mesh files a scene read from a file or a dict has read

    @property
    def _from_code_only(self) -> bool:
        return self._name == "<scene>"

    @classmethod
    def _wrap(cls, impl: Any) -> "Scene":
        """A model's quick look: read-only."""
        scene = cls.__new__(cls)
        scene._impl = impl
        scene._doc = None
        scene._meshes = []
        scene._name = impl.source
        scene._overrides = {}
        scene._cache = None
        _warn(impl)
        return scene

    @classmethod
    def _read(cls, text: str, name: str, overrides: dict) -> "Scene":
        """A scene file's text (or a dict's JSON), read with a mesh cache and kept editable."""
        scene = cls.__new__(cls)
        scene._meshes = []
        scene._name = name
        scene._overrides = overrides
        scene._cache = _sombra.MeshCache()
        scene._impl = _sombra.load_text(text, name, overrides, [], scene._cache)
        try:
            doc = json.loads(text)
        except ValueError:  # JSON the reader takes and Python's does not: rendered, not edited
            doc = None
        scene._doc = doc if isinstance(doc, dict) else None
        _warn(scene._impl)
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
        return cls._read(text, name, _options("from_dict", overrides, _SCENE_OPTIONS))

    def _from_code(self, what: str) -> None:
        """Raises for a scene that cannot be edited: a model's quick look."""
        if self._doc is None:
            raise TypeError(f"Scene.{what}: {self._name} is a model's quick look, which cannot be edited; read "
                            f"it in a scene instead: Scene.from_dict({{\"objects\": [{{\"file\": ...}}], ...}})")

    def _check(self, kind: str, text: str, pointer: str) -> Any:
        """The reader's own check of one section, naming the scene as its
        messages do, relative paths taken from the scene's folder."""
        folder = "." if self._from_code_only else os.path.dirname(self._name) or "."
        return _sombra.check_part(kind, text, pointer, self._name, folder)

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
        self._check(part, json.dumps(plain), "/" + part)
        return plain

    def _assembled(self) -> Any:
        if self._impl is None:
            self._impl = _sombra.load_text(json.dumps(self._doc), self._name, self._overrides, self._meshes,
                                           self._cache)
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
        materials = {**self._doc.get("materials", {}), name: _plain(material)}
        self._check("materials", json.dumps(materials), "/materials")
        self._doc["materials"] = materials
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
        media = {**self._doc.get("media", {}), name: _plain(medium)}
        self._check("media", json.dumps(media), "/media")
        self._doc["media"] = media
        self._changed()

    def add_light(self, light: Mapping[str, Any]) -> None:
        """Adds a light, a dict as in a scene file's "lights" (point, spot,
        directional, quad)."""
        self._from_code("add_light")
        if not isinstance(light, Mapping):
            raise TypeError(f"add_light: light must be a dict, not {type(light).__name__}")
        self.lights = self._doc.get("lights", []) + [_plain(light)]

    @property
    def lights(self) -> list:
        """The scene file's "lights" (point, spot, directional, quad), a
        list of dicts (a copy). Set it to a new list to change, remove or
        add lights; each is checked as in a scene file."""
        self._from_code("lights")
        return json.loads(json.dumps(self._doc.get("lights", [])))

    @lights.setter
    def lights(self, lights: Sequence[Mapping[str, Any]]) -> None:
        self._from_code("lights")
        if not isinstance(lights, (list, tuple)) or not all(isinstance(x, Mapping) for x in lights):
            raise TypeError("Scene.lights: expected a list of dicts")
        plain = _plain(list(lights))
        self._check("lights", json.dumps(plain), "/lights")
        self._doc["lights"] = plain
        self._changed()

    @property
    def materials(self) -> dict:
        """The scene file's "materials" by name (a copy); add_material adds
        or replaces one. A mesh file's own materials (MTL, glTF) are not here."""
        self._from_code("materials")
        return json.loads(json.dumps(self._doc.get("materials", {})))

    @property
    def objects(self) -> list:
        """The scene's objects as a scene file's "objects" holds them (a
        copy): {"file": ...} for a mesh file, {"mesh": i} for one added with
        add_mesh, with "material", "transform", "instances" where given.
        set_transform changes an object's placement."""
        self._from_code("objects")
        return json.loads(json.dumps(self._doc.get("objects", [])))

    def set_transform(self, index: int, transform: Optional[Sequence[Mapping[str, Any]]]) -> None:
        """Places object ``index`` (as ``objects`` lists them) by
        ``transform``, a scene file's transform list (``[{"rotate": {"axis":
        [0, 1, 0], "degrees": 30}}, {"translate": [1, 0, 0]}]``), or None for
        none. The mesh is not read again."""
        self._from_code("set_transform")
        objects = self._doc.get("objects", [])
        index = operator.index(index)
        if not 0 <= index < len(objects):
            raise IndexError(f"Scene.set_transform: no object {index} (the scene has {len(objects)})")
        obj = dict(objects[index])
        if transform is None:
            obj.pop("transform", None)
        else:
            if not isinstance(transform, (list, tuple)):
                raise TypeError(f"set_transform: transform must be a list of steps, not {type(transform).__name__}")
            obj["transform"] = _plain(transform)
            self._check("transform", json.dumps(obj["transform"]), f"/objects/{index}/transform")
        self._doc["objects"] = objects[:index] + [obj] + objects[index + 1:]
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
        i = len(self._doc.get("objects", []))
        obj: dict = {"mesh": len(self._meshes)}
        if material is not None:
            if not isinstance(material, str):
                raise TypeError(f"add_mesh: material must be str, not {type(material).__name__}")
            if material not in self._doc.get("materials", {}) and material != "interface":
                raise Error(f"{self._name}: /objects/{i}/material: unknown material '{material}'")
            obj["material"] = material
        for key, name in (("interior", interior), ("exterior", exterior)):
            if name is None:
                continue
            if not isinstance(name, str):
                raise TypeError(f"add_mesh: {key} must be str, not {type(name).__name__}")
            if name not in self._doc.get("media", {}):
                raise Error(f"{self._name}: /objects/{i}/{key}: no medium '{name}' in /media")
            obj[key] = name
        if exterior is not None and interior is None:
            raise Error(f"{self._name}: /objects/{i}/exterior: 'exterior' needs 'interior' (the medium the object bounds)")
        if transform is not None:
            if not isinstance(transform, (list, tuple)):
                raise TypeError(f"add_mesh: transform must be a list of steps, not {type(transform).__name__}")
            obj["transform"] = _plain(transform)
            self._check("transform", json.dumps(obj["transform"]), f"/objects/{i}/transform")
        if instances is not None:
            if not isinstance(instances, (list, tuple)) or not instances:
                raise TypeError("add_mesh: instances must be a non-empty list of transform lists")
            obj["instances"] = _plain(instances)
            for k, steps in enumerate(obj["instances"]):
                self._check("transform", json.dumps(steps), f"/objects/{i}/instances/{k}")
        mesh = _sombra.make_mesh(positions, indices, normals, uvs, f"{self._name}: mesh {obj['mesh']}")
        self._meshes.append(mesh)
        self._doc["objects"] = self._doc.get("objects", []) + [obj]
        self._changed()

    @property
    def camera(self) -> Optional[dict]:
        """The camera, a dict as in a scene file's "camera" (spec §3, §17):
        the look-at form (origin, look_at, up, fov) or the basis form
        (origin, left, up, forward), with aperture_radius and
        focus_distance when it has a lens. A scene read from a file or a
        dict, or a quick look, gives the camera it renders from (a quick
        look's is the framing it chose, spec §7, or the glTF file's camera,
        whose orthographic kind, spec §24, shows as "orthographic": {"ymag":
        half-height} in place of "fov"); a scene from code's is None until
        set. Setting it (perspective, as in scene files) moves the camera of
        any scene but a quick look."""
        if not self._from_code_only:
            return self._assembled().camera
        camera = self._doc.get("camera")
        return None if camera is None else json.loads(json.dumps(camera))

    @camera.setter
    def camera(self, camera: Mapping[str, Any]) -> None:
        self._doc["camera"] = self._checked("camera", "camera", camera)
        self._changed()

    @property
    def background(self) -> Optional[list]:
        """The background colour [r, g, b]; None = black. A scene has a
        background or an environment, not both (spec §10): set the other to
        None first."""
        self._from_code("background")
        background = self._doc.get("background")
        return None if background is None else list(background)

    @background.setter
    def background(self, rgb: Optional[Sequence[float]]) -> None:
        self._from_code("background")
        if rgb is None:
            self._doc.pop("background", None)
        else:
            self._only_one("background", "environment", self._doc.get("environment"))
            self._doc["background"] = self._checked("background", "background", rgb, mapping=False)
        self._changed()

    @property
    def environment(self) -> Optional[dict]:
        """The environment map, a dict as in a scene file's "environment":
        ``{"file": "sky.exr", "scale": 1, "rotate_y": 0}``, the file
        relative to the working directory for a scene from code, to the
        scene's folder for one read from a file (spec §10). It replaces the
        background, lights the scene under ``integrator="path"`` and is
        read when set. None = none."""
        self._from_code("environment")
        environment = self._doc.get("environment")
        return None if environment is None else dict(environment)

    @environment.setter
    def environment(self, environment: Optional[Mapping[str, Any]]) -> None:
        self._from_code("environment")
        if environment is None:
            self._doc.pop("environment", None)
        else:
            if not isinstance(environment, Mapping):
                raise TypeError(f"Scene.environment: expected a dict, not {type(environment).__name__}")
            self._only_one("environment", "background", self._doc.get("background"))
            self._doc["environment"] = self._checked("environment", "environment", environment)
        self._changed()

    def _only_one(self, key: str, other: str, other_value: Any) -> None:
        if other_value is not None:
            raise Error(f"{self._name}: /{key}: give either 'background' or 'environment', not both (the map "
                        f"replaces the background); set Scene.{other} to None first")

    @property
    def render_settings(self) -> dict:
        """The settings a render starts from: width, height, spp, seed,
        integrator, max_depth, texture_filter. Setting them, as a dict like
        a scene file's "render", replaces the scene's (the keys it gives
        replace the defaults; for a scene read with ``load(..., width=...)``
        those overrides go too)."""
        if self._from_code_only:
            return self._check("render", json.dumps(self._doc.get("render", {})), "/render")
        return self._assembled().render_settings

    @render_settings.setter
    def render_settings(self, settings: Mapping[str, Any]) -> None:
        self._doc["render"] = self._checked("render_settings", "render", settings)
        self._overrides = {}
        self._changed()

    @property
    def triangle_count(self) -> int:
        """Triangles in the scene, every object's together."""
        if self._from_code_only:
            return sum(m.triangle_count for m in self._meshes)
        return self._assembled().triangle_count

    @property
    def instanced_triangle_count(self) -> int:
        """Triangles drawn: an instanced mesh counts once per instance
        (``triangle_count`` counts it once)."""
        if self._from_code_only:
            return sum(self._meshes[o["mesh"]].triangle_count * len(o.get("instances", [None]))
                       for o in self._doc.get("objects", []))
        return self._assembled().instanced_triangle_count

    @property
    def source(self) -> str:
        """The file the scene came from (``<dict>`` for a dict, ``<scene>``
        for one from code), as messages name it."""
        return "<scene>" if self._from_code_only else self._name

    def __repr__(self) -> str:
        s = self.render_settings
        return (f"<sombra.Scene {self.source!r}: {self.triangle_count} triangles, "
                f"{s['width']}x{s['height']}, {s['spp']} spp, {s['integrator']}>")
