"""Scenes built from code: meshes from numpy arrays render as the same mesh
from an OBJ file, and every piece is checked when it is given."""

import json
import warnings

import numpy as np
import pytest

from conftest import REPO, import_sombra

sombra = import_sombra()

CHECKER = str(REPO / "scenes" / "textures" / "checker.png")
MATERIALS = {"floor": {"type": "diffuse", "kd": {"texture": CHECKER}},
             "gold": {"type": "phong", "kd": [0.5, 0.4, 0.1], "ks": [0.4, 0.4, 0.3], "shininess": 40}}
LIGHTS = [{"type": "point", "position": [0.5, 3, 2], "intensity": [12, 12, 12]},
          {"type": "quad", "corner": [-1, 2.5, -1], "edge1": [1, 0, 0], "edge2": [0, 0, 1], "radiance": [3, 3, 3]}]
CAMERA = {"origin": [0, 1.5, 4], "look_at": [0, 0.3, 0], "fov": 45}
RENDER = {"width": 40, "height": 30, "spp": 4, "integrator": "path", "max_depth": 3}
TRANSFORM = [{"rotate": {"axis": [0, 1, 0], "degrees": 30}}, {"translate": [0.2, 0.1, 0]}]


def wavy_grid(n=6):
    """A bumpy grid with normals and uvs, float32 values."""
    u, v = np.meshgrid(np.linspace(0, 1, n), np.linspace(0, 1, n))
    x, z = u * 2 - 1, v * 2 - 1
    y = 0.15 * np.sin(3 * x) * np.cos(2 * z)
    positions = np.stack([x, y, z], -1).reshape(-1, 3).astype(np.float32)
    normals = np.stack([-0.45 * np.cos(3 * x) * np.cos(2 * z), np.ones_like(x), 0.3 * np.sin(3 * x) * np.sin(2 * z)],
                       -1).reshape(-1, 3).astype(np.float32)
    uvs = np.stack([u, v], -1).reshape(-1, 2).astype(np.float32)
    q = np.arange(n * n).reshape(n, n)[:-1, :-1].ravel()
    indices = np.concatenate([np.stack([q, q + n, q + 1], -1), np.stack([q + 1, q + n, q + n + 1], -1)])
    return positions, indices, normals, uvs


def write_obj(path, positions, indices, normals, uvs):
    # %.9g writes each float32 so that it reads back as the same float32.
    with open(path, "w") as f:
        for p in positions:
            f.write("v %.9g %.9g %.9g\n" % tuple(p))
        for n in normals:
            f.write("vn %.9g %.9g %.9g\n" % tuple(n))
        for t in uvs:
            f.write("vt %.9g %.9g\n" % tuple(t))
        for a, b, c in indices + 1:
            f.write(f"f {a}/{a}/{a} {b}/{b}/{b} {c}/{c}/{c}\n")


def dressed_scene():
    """A code scene with the materials, lights, camera and settings, no meshes."""
    s = sombra.Scene()
    for name, m in MATERIALS.items():
        s.add_material(name, m)
    for light in LIGHTS:
        s.add_light(light)
    s.camera = CAMERA
    s.render_settings = RENDER
    return s


def code_scene(positions, indices, normals, uvs):
    s = dressed_scene()
    s.add_mesh(positions, indices, normals=normals, uvs=uvs, material="floor")
    s.add_mesh(positions * 0.3, indices, normals=normals, material="gold", transform=TRANSFORM)
    return s


def test_a_mesh_from_arrays_renders_as_the_same_mesh_from_an_obj_file(tmp_path):
    positions, indices, normals, uvs = wavy_grid()
    write_obj(tmp_path / "grid.obj", positions, indices, normals, uvs)
    write_obj(tmp_path / "small.obj", positions * 0.3, indices, normals, np.zeros((0, 2)))
    scene_file = {"render": RENDER, "camera": CAMERA, "materials": MATERIALS, "lights": LIGHTS,
                  "objects": [{"file": "grid.obj", "material": "floor"},
                              {"file": "small.obj", "material": "gold", "transform": TRANSFORM}]}
    (tmp_path / "scene.json").write_text(json.dumps(scene_file))
    from_file = sombra.render(sombra.load(tmp_path / "scene.json"))
    from_code = sombra.render(code_scene(positions, indices, normals, uvs))
    assert from_file.shape == (30, 40, 3) and from_file.std() > 0
    assert from_code.tobytes() == from_file.tobytes()
    # The arrays were copied: changing them afterwards changes nothing.
    s = code_scene(positions, indices, normals, uvs)
    positions[:] = 0
    assert sombra.render(s).tobytes() == from_file.tobytes()


def test_instances_render_as_the_same_instances_from_a_file_and_count_once(tmp_path):
    positions, indices, normals, uvs = wavy_grid()
    placed = [[{"translate": [-0.6, 0.2, 0]}], [{"scale": [-1, 1, 1]}, {"translate": [0.6, 0.2, 0]}]]
    write_obj(tmp_path / "grid.obj", positions, indices, normals, uvs)
    write_obj(tmp_path / "small.obj", positions * 0.3, indices, normals, np.zeros((0, 2)))
    scene_file = {"render": RENDER, "camera": CAMERA, "materials": MATERIALS, "lights": LIGHTS,
                  "objects": [{"file": "grid.obj", "material": "floor"},
                              {"file": "small.obj", "material": "gold", "transform": TRANSFORM,
                               "instances": placed}]}
    (tmp_path / "scene.json").write_text(json.dumps(scene_file))
    from_file = sombra.load(tmp_path / "scene.json")
    s = dressed_scene()
    s.add_mesh(positions, indices, normals=normals, uvs=uvs, material="floor")
    s.add_mesh(positions * 0.3, indices, normals=normals, material="gold", transform=TRANSFORM, instances=placed)
    one, quad = len(indices), 2
    assert (from_file.triangle_count, from_file.instanced_triangle_count) == (2 * one + quad, 3 * one + quad)
    assert (s.triangle_count, s.instanced_triangle_count) == (2 * one, 3 * one)  # the quad light joins when loaded
    assert sombra.render(s).tobytes() == sombra.render(from_file).tobytes()
    with pytest.raises(sombra.Error, match=r"/objects/2/instances/1/0/scale"):
        s.add_mesh(positions, indices, instances=[[], [{"scale": 0}]])
    with pytest.raises(TypeError, match="instances"):
        s.add_mesh(positions, indices, instances=[])


def test_pieces_are_checked_when_given():
    s = sombra.Scene()
    with pytest.raises(sombra.Error, match=r"^<scene>: /materials/x/kd: expected an array of 3 numbers$"):
        s.add_material("x", {"type": "diffuse", "kd": [1, 2]})
    with pytest.raises(sombra.Error, match=r"/lights/0/position: missing required key 'position'"):
        s.add_light({"type": "spot"})
    with pytest.raises(sombra.Error, match=r"^<scene>: /camera"):
        s.camera = {"origin": [0, 0, 0]}
    with pytest.raises(sombra.Error, match=r"/render/spp: must be between 1 and 65536"):
        s.render_settings = {"spp": 0}
    assert s.render_settings["spp"] == 1  # the refused value was not kept
    with pytest.raises(sombra.Error, match=r"/objects/0/transform/0/scale"):
        s.add_mesh(np.eye(3), np.array([[0, 1, 2]]), transform=[{"scale": 0}])
    with pytest.raises(sombra.Error, match=r"/objects/0/material: unknown material 'nope'"):
        s.add_mesh(np.eye(3), np.array([[0, 1, 2]]), material="nope")
    with pytest.raises(sombra.Error, match="/camera"):
        sombra.render(s)  # nothing was added, and a render needs a camera


@pytest.mark.parametrize("positions,indices,error,message", [
    (np.array([[np.nan, 0, 0], [1, 0, 0], [0, 1, 0]]), [[0, 1, 2]], sombra.Error, r"positions\[0\] is not finite"),
    (np.eye(3), [[0, 1, 3]], sombra.Error, r"indices\[0\] refers to vertex 3, past the 3 vertices"),
    (np.eye(3), [[0, -1, 2]], sombra.Error, r"indices\[0\] holds -1"),
    (np.eye(3), [[0, 1, 2**40]], sombra.Error, r"indices\[0\] holds 1099511627776"),
    (np.eye(3), np.array([[0, 1, 2**64 - 1]], dtype=np.uint64), sombra.Error, r"holds 18446744073709551615,"),
    (np.eye(3)[:, :2], [[0, 1, 2]], sombra.Error, r"positions: shape \(3, 2\) is not \(N, 3\)"),
    (np.eye(3), [0, 1, 2], sombra.Error, r"indices: shape \(3,\) is not \(N, 3\)"),
    (np.eye(3), np.zeros((0, 3), dtype=int), sombra.Error, "no triangles"),
    (np.eye(3).tolist(), [[0, 1, 2]], TypeError, "positions: expected a numpy array"),
    (np.eye(3).astype(np.int32), [[0, 1, 2]], TypeError, "positions: expected a float dtype"),
    (np.eye(3), np.array([[0.0, 1.0, 2.0]]), TypeError, "indices: expected an integer dtype"),
])
def test_hostile_arrays_are_refused(positions, indices, error, message):
    s = sombra.Scene()
    with pytest.raises(error, match=message):
        s.add_mesh(positions, np.asarray(indices) if isinstance(indices, list) else indices)
    assert s.triangle_count == 0


def test_normals_and_uvs_must_match_the_vertices():
    s = sombra.Scene()
    with pytest.raises(sombra.Error, match="2 normals for 3 vertices"):
        s.add_mesh(np.eye(3), np.array([[0, 1, 2]]), normals=np.eye(3)[:2])
    with pytest.raises(sombra.Error, match=r"uvs: shape \(3, 3\) is not \(N, 2\)"):
        s.add_mesh(np.eye(3), np.array([[0, 1, 2]]), uvs=np.eye(3))


def test_a_models_quick_look_cannot_be_edited():
    with pytest.raises(TypeError, match=r"quick look, which cannot be edited; read it in a scene instead"):
        sombra.load(REPO / "scenes" / "models" / "cube.obj").add_light({"position": [0, 1, 0], "intensity": [1, 1, 1]})


SKY = REPO.parent / "shared" / "envmaps" / "sunset.exr"


def test_an_environment_map_set_from_code_renders_as_in_a_scene_file(tmp_path):
    if not SKY.exists():
        pytest.skip(f"shared/ not found at {SKY}")
    positions, indices, normals, uvs = wavy_grid()
    sky = {"file": str(SKY), "scale": 0.5, "rotate_y": 30}
    write_obj(tmp_path / "grid.obj", positions, indices, normals, uvs)
    write_obj(tmp_path / "small.obj", positions * 0.3, indices, normals, np.zeros((0, 2)))
    scene_file = {"render": RENDER, "camera": CAMERA, "materials": MATERIALS, "lights": LIGHTS, "environment": sky,
                  "objects": [{"file": "grid.obj", "material": "floor"},
                              {"file": "small.obj", "material": "gold", "transform": TRANSFORM}]}
    (tmp_path / "scene.json").write_text(json.dumps(scene_file))
    from_file = sombra.render(sombra.load(tmp_path / "scene.json"))
    s = code_scene(positions, indices, normals, uvs)
    without = sombra.render(s)
    s.environment = sky
    assert s.environment == sky
    assert sombra.render(s).tobytes() == from_file.tobytes()
    assert from_file.tobytes() != without.tobytes()  # the map was seen and lit the scene
    s.environment = None
    assert sombra.render(s).tobytes() == without.tobytes()


def test_background_and_environment_exclude_each_other_and_bad_maps_are_refused():
    if not SKY.exists():
        pytest.skip(f"shared/ not found at {SKY}")
    s = sombra.Scene()
    s.background = [0.1, 0.2, 0.3]
    with pytest.raises(sombra.Error, match=r"^<scene>: /environment: give either 'background' or 'environment'"):
        s.environment = {"file": str(SKY)}
    s.background = None
    s.environment = {"file": str(SKY)}
    with pytest.raises(sombra.Error, match=r"^<scene>: /background: give either"):
        s.background = [0, 0, 0]
    with pytest.raises(sombra.Error, match=r"/environment"):
        s.environment = {"file": "no-such-sky.exr"}
    with pytest.raises(sombra.Error, match=r"/environment/scale"):
        s.environment = {"file": str(SKY), "scale": -1}
    with pytest.raises(TypeError):
        s.environment = "sky.exr"
    assert s.environment == {"file": str(SKY)}  # the refused values changed nothing


def test_a_render_warns_as_the_command_line_does():
    # Spec §27: nothing emits light (one RuntimeWarning, a black image); a
    # noise threshold that cannot stop a pixel early.
    s = sombra.Scene()
    s.camera = {"origin": [0, 0, 3], "look_at": [0, 0, 0]}
    s.add_mesh(np.array([[-1, -1, 0], [1, -1, 0], [0, 1, 0]], np.float32), np.array([[0, 1, 2]], np.uint32))
    with pytest.warns(RuntimeWarning, match="nothing in the scene emits light") as caught:
        image = sombra.render(s, width=8, height=6, spp=1)
    assert len(caught) == 1
    assert not image.any()
    s.add_light({"type": "point", "position": [0, 0, 2], "intensity": [1, 1, 1]})
    with pytest.warns(RuntimeWarning, match="^sombra: --noise-threshold cannot stop any pixel early"):
        sombra.render(s, width=8, height=6, spp=4, noise_threshold=0.1)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        sombra.render(s, width=8, height=6, spp=32, noise_threshold=0.1, min_spp=4)


def test_a_crop_is_its_window_of_the_whole_render():
    # Spec §27: crop=(x0, y0, x1, y1), the command line's --crop.
    s = sombra.load(REPO / "scenes" / "cornell-box-path.json", width=40, height=30, spp=8)
    whole = sombra.render(s)
    crop = sombra.render(s, crop=(5, 4, 33, 21))
    assert crop.shape == (17, 28, 3)
    assert crop.tobytes() == np.ascontiguousarray(whole[4:21, 5:33]).tobytes()
    adaptive = sombra.render(s, crop=[5, 4, 33, 21], noise_threshold=0.1, min_spp=4)
    assert adaptive.tobytes() == np.ascontiguousarray(
        sombra.render(s, noise_threshold=0.1, min_spp=4)[4:21, 5:33]).tobytes()
    with pytest.raises(sombra.Error, match="^--crop: expected X0 Y0 X1 Y1 with 0 <= X0 < X1 <= 40"):
        sombra.render(s, crop=(0, 0, 41, 5))
    with pytest.raises(sombra.Error, match="--crop"):
        sombra.render(s, crop=(3, 3, 2, 5))
    with pytest.raises(sombra.Error, match="--crop"):
        sombra.render(s, crop=(0, 0, 4))


def test_a_denoised_crop_is_its_window_of_the_whole_denoised_render():
    # Spec §27: rendered grown by the denoiser's reach, then cut; wide enough
    # that the grown window is not the whole image.
    s = sombra.load(REPO / "scenes" / "cornell-box-path.json", width=200, height=120, spp=2)
    whole = sombra.render(s, denoise=True, aov=["noisy"])
    crop = sombra.render(s, denoise=True, aov=["noisy"], crop=(140, 80, 180, 110))
    assert crop["color"].shape == (30, 40, 3)
    for layer in ("color", "noisy"):
        assert crop[layer].tobytes() == np.ascontiguousarray(whole[layer][80:110, 140:180]).tobytes(), layer


def test_numpy_numbers_are_taken_as_python_numbers():
    # Issue 39: numpy users pass np.int64 and np.float32 where ints and floats are meant.
    s = sombra.load(REPO / "scenes" / "cornell-box-path.json", width=np.int64(12), height=np.int32(9))
    image = sombra.render(s, spp=np.uint8(4), seed=np.int64(3), noise_threshold=np.float32(0.5), min_spp=np.int16(2),
                          denoise=np.bool_(False))
    assert image.shape == (9, 12, 3)
    assert image.tobytes() == sombra.render(s, spp=4, seed=3, noise_threshold=float(np.float32(0.5)),
                                            min_spp=2).tobytes()
    with pytest.raises(TypeError, match="width must be int, not float"):
        sombra.render(s, width=12.0)
    with pytest.raises(TypeError, match="spp must be int, not bool"):
        sombra.render(s, spp=np.bool_(True))
