"""sombra.render against `sombra render`: the same floats, the AOVs, the time budget."""

import json
import time

import numpy as np
import pytest

from conftest import import_sombra, read_pfm, run_cli

sombra = import_sombra()

SMALL = dict(width=48, height=36)


@pytest.mark.parametrize("scene_file,spp", [("scenes/cornell-box.json", 4), ("scenes/cornell-box-path.json", 8)])
def test_render_equals_the_command_lines_pfm_float_for_float(tmp_path, scene_file, spp):
    out = tmp_path / "cli.pfm"
    status, _, err = run_cli("render", scene_file, "-o", out, "-q", "--width", 48, "--height", 36, "--spp", spp)
    assert status == 0, err
    image = sombra.render(sombra.load(scene_file), spp=spp, **SMALL)
    assert image.dtype == np.float32 and image.shape == (36, 48, 3)
    assert image.any()
    assert image.tobytes() == read_pfm(out).tobytes()


def test_overrides_given_to_load_equal_those_given_to_render():
    a = sombra.render(sombra.load("scenes/cornell-box.json", spp=2, seed=3, **SMALL))
    b = sombra.render(sombra.load("scenes/cornell-box.json"), spp=2, seed=3, **SMALL)
    c = sombra.render(sombra.load("scenes/cornell-box.json"), spp=2, seed=4, **SMALL)
    assert a.tobytes() == b.tobytes()
    assert a.tobytes() != c.tobytes()  # the seed reached the render


def test_from_dict_renders_as_the_file_does():
    import json
    with open("scenes/cornell-box.json") as f:
        d = json.load(f)
    a = sombra.render(sombra.Scene.from_dict(d, base_dir="scenes"), **SMALL)
    b = sombra.render(sombra.load("scenes/cornell-box.json"), **SMALL)
    assert a.tobytes() == b.tobytes()


def test_aovs_come_back_as_a_dict_of_arrays():
    scene = sombra.load("scenes/cornell-box.json")
    out = sombra.render(scene, spp=4, aov=["albedo", "normal", "position", "depth", "spp"], **SMALL)
    assert set(out) == {"color", "albedo", "normal", "position", "depth", "spp"}
    for name in ("color", "albedo", "normal", "position"):
        assert out[name].shape == (36, 48, 3) and out[name].dtype == np.float32
    for name in ("depth", "spp"):
        assert out[name].shape == (36, 48)
    assert (out["spp"] == 4).all()  # every pixel took the 4 samples asked for
    assert out["color"].tobytes() == sombra.render(scene, spp=4, **SMALL).tobytes()  # the AOVs change nothing
    # A pixel where every sample hits: the mean of unit normals is at most 1 long, and not 0.
    centre = np.linalg.norm(out["normal"][18, 24])
    assert 0.5 < centre <= 1.0 + 1e-5
    assert np.isfinite(out["depth"][18, 24]) and out["depth"][18, 24] > 0


def test_the_variance_aov_comes_back_per_channel():
    scene = sombra.load("scenes/cornell-box-path.json")
    out = sombra.render(scene, spp=4, aov=["variance"], **SMALL)
    assert set(out) == {"color", "variance"}
    assert out["variance"].shape == (36, 48, 3) and out["variance"].dtype == np.float32
    assert (out["variance"] >= 0).all() and out["variance"].max() > 0
    again = sombra.render(scene, spp=4, aov=["variance"], threads=1, **SMALL)
    assert again["variance"].tobytes() == out["variance"].tobytes()
    assert out["color"].tobytes() == sombra.render(scene, spp=4, **SMALL).tobytes()  # the AOV changes nothing


def test_a_time_budget_returns_and_equals_the_spp_it_reached():
    scene = sombra.load("scenes/cornell-box-path.json")
    start = time.monotonic()
    out = sombra.render(scene, time=0.3, aov=["spp"], **SMALL)
    assert time.monotonic() - start < 3.0
    reached = int(out["spp"][0, 0])
    assert reached >= 2 and (out["spp"] == reached).all()
    again = sombra.render(scene, spp=reached, **SMALL)
    assert out["color"].tobytes() == again.tobytes()


def test_a_progress_callable_is_called_and_its_exception_stops_the_render():
    calls = []

    def progress(done, total):
        calls.append((done, total))
        raise RuntimeError("stop here")

    scene = sombra.load("scenes/cornell-box-path.json")
    start = time.monotonic()
    with pytest.raises(RuntimeError, match="stop here"):
        sombra.render(scene, width=256, height=256, spp=4096, threads=1, progress=progress)
    assert time.monotonic() - start < 2.0
    assert len(calls) == 1 and calls[0][1] == 256 * 256 * 4096 and 0 <= calls[0][0] <= calls[0][1]
    # The scene is still usable, and a render that ends reports its end.
    calls.clear()
    sombra.render(scene, spp=2, width=8, height=8, progress=lambda done, total: calls.append((done, total)))
    assert calls[-1] == (8 * 8 * 2, 8 * 8 * 2)


@pytest.mark.parametrize("scene_file", ["scenes/cornell-box.json", "scenes/spot-sun-dof.json"])
def test_a_loaded_scenes_camera_reads_back_as_the_file_gives_it(scene_file):
    import json
    with open(scene_file) as f:
        d = json.load(f)
    camera = sombra.load(scene_file).camera
    assert set(camera) == set(d["camera"]) | ({"up", "fov"} if "look_at" in d["camera"] else set())
    for key, value in d["camera"].items():
        assert camera[key] == pytest.approx(value), key
    # Given back to from_dict it renders the same image.
    d["camera"] = camera
    a = sombra.render(sombra.Scene.from_dict(d, base_dir="scenes"), spp=2, **SMALL)
    b = sombra.render(sombra.load(scene_file), spp=2, **SMALL)
    assert a.tobytes() == b.tobytes()


def test_a_quick_looks_camera_is_the_framing_it_chose():
    camera = sombra.load("scenes/models/cube.obj").camera
    assert set(camera) == {"origin", "look_at", "up", "fov"}
    assert camera["fov"] == pytest.approx(40)
    assert camera["origin"][2] > camera["look_at"][2]  # in front of the model (+z)


def test_a_frame_of_an_animated_scene_is_the_command_lines(tmp_path):
    (tmp_path / "square.obj").write_text("v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n")
    keyed = {"keys": [{"time": 0, "transform": [{"scale": 0.5}]},
                      {"time": 1, "transform": [{"rotate": {"axis": [0, 1, 0], "degrees": 60}}, {"translate": [0.5, 0, 0]}]}]}
    scene = {"render": {"width": 24, "height": 16, "spp": 2}, "animation": {"fps": 4, "frames": [0, 4]},
             "camera": {"origin": [0, 0, 4], "look_at": [0, 0, 0], "fov": 50},
             "lights": [{"type": "point", "position": [0, 1, 3], "intensity": [8, 8, 8]}],
             "objects": [{"file": "square.obj", "transform": keyed}]}
    (tmp_path / "a.json").write_text(json.dumps(scene))
    s = sombra.load(tmp_path / "a.json")
    frames = {f: sombra.render(s, frame=f) for f in (0, 3)}
    assert frames[0].tobytes() != frames[3].tobytes()
    assert sombra.render(s).tobytes() == frames[0].tobytes()  # the first frame without one
    status, _, err = run_cli("render", tmp_path / "a.json", "-q", "--frame", 3, "-o", tmp_path / "f3.pfm")
    assert status == 0, err
    assert frames[3].tobytes() == read_pfm(tmp_path / "f3.pfm").tobytes()


def write_orthographic_gltf(path):
    """A unit square at z = 0 seen by an orthographic camera at z = 2 whose
    view is 2 high (ymag 1, spec §24), with a point light beside it."""
    import base64
    import struct
    positions = [(-0.5, -0.5, 0), (0.5, -0.5, 0), (0.5, 0.5, 0), (-0.5, 0.5, 0)]
    data = b"".join(struct.pack("<3f", *p) for p in positions) + struct.pack("<6I", 0, 1, 2, 0, 2, 3)
    doc = {
        "asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 2000}]}},
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 48, "byteLength": 24}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                       "min": [-0.5, -0.5, 0], "max": [0.5, 0.5, 0]},
                      {"bufferView": 1, "componentType": 5125, "count": 6, "type": "SCALAR"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "cameras": [{"type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 10}}],
        "nodes": [{"mesh": 0}, {"camera": 0, "translation": [0, 0, 2]},
                  {"translation": [0, 0, 3], "extensions": {"KHR_lights_punctual": {"light": 0}}}],
        "scenes": [{"nodes": [0, 1, 2]}],
        "scene": 0,
    }
    path.write_text(json.dumps(doc))


def test_an_orthographic_gltf_camera_renders_as_the_command_line_does(tmp_path):
    model = tmp_path / "ortho.gltf"
    write_orthographic_gltf(model)
    scene = sombra.load(model)
    assert scene.camera["orthographic"] == {"ymag": 1.0} and "fov" not in scene.camera
    out = tmp_path / "cli.pfm"
    status, _, err = run_cli("render", model, "-o", out, "-q", "--width", 32, "--height", 32, "--spp", 1)
    assert status == 0, err
    image = sombra.render(scene, width=32, height=32, spp=1, aov=["depth"])
    assert image["color"].tobytes() == read_pfm(out).tobytes()
    # The square is half the view's height and width: the middle 16 × 16
    # pixels, each 2 away along the parallel rays.
    hit = np.isfinite(image["depth"])
    assert hit[8:24, 8:24].all() and hit.sum() == 16 * 16
    assert np.allclose(image["depth"][hit], 2.0)
