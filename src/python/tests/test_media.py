"""A scene filled with a homogeneous medium (spec §26) from Python: the same
floats as the command line, and max_volume_depth as an option."""

import json

import pytest

from conftest import REPO, import_sombra, read_pfm, run_cli

sombra = import_sombra()


@pytest.fixture(scope="module")
def fog_file(tmp_path_factory):
    scene = json.loads((REPO / "scenes" / "cornell-box-path.json").read_text())
    scene["media"] = {"fog": {"type": "homogeneous", "sigma_a": [0.1, 0.2, 0.3], "sigma_s": [1, 1, 1], "g": 0.4}}
    scene["render"]["medium"] = "fog"
    for obj in scene["objects"]:
        obj["file"] = str(REPO / "scenes" / obj["file"])
    path = tmp_path_factory.mktemp("media") / "fog.json"
    path.write_text(json.dumps(scene))
    return path


def test_a_fog_render_is_the_command_lines(tmp_path, fog_file):
    out = tmp_path / "cli.pfm"
    status, _, err = run_cli("render", fog_file, "-o", out, "-q", "--width", 24, "--height", 20, "--spp", 2,
                             "--max-volume-depth", 3)
    assert status == 0, err
    image = sombra.render(sombra.load(fog_file), width=24, height=20, spp=2, max_volume_depth=3)
    assert image.tobytes() == read_pfm(out).tobytes()
    # The fog changes the image: without scattering in it (depth 0) light still dims.
    assert image.tobytes() != sombra.render(sombra.load(fog_file), width=24, height=20, spp=2,
                                            max_volume_depth=0).tobytes()


def test_max_volume_depth_is_an_option_checked_as_the_command_line_does(fog_file):
    assert sombra.load(fog_file, max_volume_depth=5).render_settings["max_volume_depth"] == 5
    assert sombra.load(fog_file).render_settings["max_volume_depth"] == 256
    with pytest.raises(sombra.Error, match="^--max-volume-depth: must be between 0 and 65536, not -1$"):
        sombra.render(sombra.load(fog_file), max_volume_depth=-1)
    with pytest.raises(TypeError, match="max_volume_depth must be int"):
        sombra.render(sombra.load(fog_file), max_volume_depth=2.5)


CUBE_POSITIONS = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0], [0, 0, 1], [1, 0, 1], [0, 1, 1], [1, 1, 1]]
CUBE_TRIANGLES = [[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4], [0, 4, 2], [2, 4, 6],
                  [1, 3, 5], [3, 7, 5], [2, 6, 3], [3, 6, 7]]


def smoke_box_scene():
    """A scene from code: a box of smoke (interface surfaces) over a lit floor."""
    import numpy as np
    s = sombra.Scene()
    s.add_medium("smoke", {"type": "homogeneous", "sigma_a": [0.3, 0.5, 0.8], "sigma_s": [2, 2, 2], "g": 0.3})
    s.add_material("floor", {"type": "diffuse", "kd": [0.6, 0.6, 0.6]})
    s.add_mesh(np.array(CUBE_POSITIONS, dtype=float), np.array(CUBE_TRIANGLES), material="interface",
               interior="smoke", transform=[{"translate": [-0.5, 0, -0.5]}])
    s.add_mesh(np.array([[-3, 0, -3], [3, 0, -3], [3, 0, 3], [-3, 0, 3]], dtype=float),
               np.array([[0, 2, 1], [0, 3, 2]]), material="floor")
    s.add_light({"type": "point", "position": [0.3, 3, 1], "intensity": [20, 20, 20]})
    s.camera = {"origin": [0, 1.2, 3.5], "look_at": [0, 0.5, 0], "fov": 40}
    s.render_settings = {"integrator": "path", "width": 24, "height": 20, "spp": 2}
    return s


def test_a_medium_inside_a_mesh_from_code_renders_as_the_scene_file_does(tmp_path):
    obj = tmp_path / "cube.obj"
    obj.write_text("".join(f"v {x} {y} {z}\n" for x, y, z in CUBE_POSITIONS) +
                   "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in CUBE_TRIANGLES))
    floor = tmp_path / "floor.obj"
    floor.write_text("v -3 0 -3\nv 3 0 -3\nv 3 0 3\nv -3 0 3\nf 1 3 2\nf 1 4 3\n")
    scene = {
        "render": {"integrator": "path", "width": 24, "height": 20, "spp": 2},
        "media": {"smoke": {"type": "homogeneous", "sigma_a": [0.3, 0.5, 0.8], "sigma_s": [2, 2, 2], "g": 0.3}},
        "materials": {"floor": {"type": "diffuse", "kd": [0.6, 0.6, 0.6]}},
        "lights": [{"type": "point", "position": [0.3, 3, 1], "intensity": [20, 20, 20]}],
        "camera": {"origin": [0, 1.2, 3.5], "look_at": [0, 0.5, 0], "fov": 40},
        "objects": [{"file": str(obj), "material": "interface", "interior": "smoke",
                     "transform": [{"translate": [-0.5, 0, -0.5]}]},
                    {"file": str(floor), "material": "floor"}],
    }
    path = tmp_path / "smoke.json"
    path.write_text(json.dumps(scene))
    out = tmp_path / "cli.pfm"
    status, _, err = run_cli("render", path, "-o", out, "-q")
    assert status == 0, err
    image = sombra.render(smoke_box_scene())
    assert image.tobytes() == read_pfm(out).tobytes()
    # The smoke is there: without it the floor under the box is lit otherwise.
    scene["objects"][0].pop("interior")
    path.write_text(json.dumps(scene))
    assert sombra.render(sombra.load(path)).tobytes() != image.tobytes()


def test_media_from_code_are_checked_when_given():
    import numpy as np
    s = sombra.Scene()
    with pytest.raises(sombra.Error, match=r"^<scene>: /media/milk/g: g must lie strictly between -1 and 1$"):
        s.add_medium("milk", {"type": "homogeneous", "g": 1})
    with pytest.raises(TypeError, match="add_medium: medium must be a dict"):
        s.add_medium("milk", [1, 2])
    with pytest.raises(sombra.Error, match=r"^<scene>: /objects/0/interior: no medium 'milk' in /media$"):
        s.add_mesh(np.array(CUBE_POSITIONS, dtype=float), np.array(CUBE_TRIANGLES), interior="milk")
    s.add_medium("milk", {"type": "homogeneous", "sigma_s": [5, 5, 5]})
    with pytest.raises(sombra.Error, match=r"^<scene>: /objects/0/exterior: 'exterior' needs 'interior'"):
        s.add_mesh(np.array(CUBE_POSITIONS, dtype=float), np.array(CUBE_TRIANGLES), exterior="milk")
