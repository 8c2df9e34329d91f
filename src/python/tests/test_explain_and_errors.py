"""sombra.explain against `sombra explain --json`, and how every mistake is reported."""

import json
import pathlib

import numpy as np
import pytest

from conftest import REPO, import_sombra, run_cli

sombra = import_sombra()


@pytest.mark.parametrize("scene_file", ["scenes/cornell-box.json", "scenes/cornell-box-path.json"])
def test_explain_is_the_command_lines_json(scene_file):
    status, out, err = run_cli("explain", scene_file, 20, 17, "--sample", 1, "--spp", 4, "--width", 48,
                               "--height", 36, "--json")
    assert status == 0, err
    story = sombra.explain(sombra.load(scene_file), 20, 17, sample=1, spp=4, width=48, height=36)
    assert story == json.loads(out)
    assert story["pixel"] == [20, 17] and story["sample"] == 1


def test_a_missing_file_is_the_command_lines_one_line():
    status, _, err = run_cli("render", "scenes/no-such.json", "-o", "/tmp/never.png", "-q")
    assert status == 1
    with pytest.raises(sombra.Error) as caught:
        sombra.load("scenes/no-such.json")
    assert "sombra: error: " + str(caught.value) == err.strip()
    assert isinstance(caught.value, ValueError)


def test_bad_option_values_are_errors_naming_the_option():
    scene = sombra.load("scenes/cornell-box.json")
    with pytest.raises(sombra.Error, match="^--spp: spp must be between 1 and 65536$"):
        sombra.render(scene, spp=0)
    with pytest.raises(sombra.Error, match="--integrator"):
        sombra.render(scene, integrator="pth")
    with pytest.raises(sombra.Error, match="unknown AOV 'colour'"):
        sombra.render(scene, aov=["colour"])
    with pytest.raises(sombra.Error, match="--time"):
        sombra.render(scene, time=float("nan"))
    with pytest.raises(sombra.Error, match=r"pixel \(48, 0\): outside the 48x36 image"):
        sombra.explain(scene, 48, 0, width=48, height=36)
    # The same words as the command line's, from the library's own checks.
    with pytest.raises(sombra.Error, match="^--threads: must be between 0 and 4096, not 5000$"):
        sombra.render(scene, threads=5000)
    with pytest.raises(sombra.Error, match="^--max-depth: must be between 0 and 1024, not -1$"):
        sombra.render(scene, max_depth=-1)
    with pytest.raises(sombra.Error, match="^--seed: must be a non-negative integer, not -1$"):
        sombra.render(scene, seed=-1)
    with pytest.raises(sombra.Error, match="^--seed: must be below 2\\^64"):
        sombra.render(scene, seed=2**64)
    with pytest.raises(sombra.Error, match="^--width: out of range: 1000000000000000000000$"):
        sombra.render(scene, width=10**21)
    with pytest.raises(sombra.Error, match=r"^pixel \(1099511627776, 0\): outside the 48x36 image$"):
        sombra.explain(scene, 2**40, 0, width=48, height=36)
    for option, value, keyword in (("--threads", 5000, "threads"), ("--integrator", "pth", "integrator"),
                                   ("--min-spp", 0, "min_spp"), ("--time", 0.0, "time")):
        status, _, err = run_cli("render", "scenes/cornell-box.json", option, value, "-o", "/tmp/never.png", "-q")
        assert status == 2
        with pytest.raises(sombra.Error) as caught:
            sombra.render(scene, **{keyword: value})
        assert "command line: " + str(caught.value) + " (see" in err


def test_a_bad_dict_names_its_json_path():
    d = {"camera": {"origin": [0, 0, 1], "look_at": [0, 0, 0], "fov": 40},
         "materials": {"m": {"type": "diffuse", "kd": [0.5, 0.5]}},
         "objects": [{"file": "models/cornell-box.obj"}]}
    with pytest.raises(sombra.Error, match="/materials/m/kd"):
        sombra.Scene.from_dict(d, base_dir="scenes")


def test_wrong_types_raise_type_error():
    scene = sombra.load("scenes/cornell-box.json")
    with pytest.raises(TypeError):
        sombra.render(scene, spp="4")
    with pytest.raises(TypeError):
        sombra.render(scene, spp=True)
    with pytest.raises(TypeError):
        sombra.render(scene, sppp=4)
    with pytest.raises(TypeError):
        sombra.render("scenes/cornell-box.json")
    with pytest.raises(TypeError):
        sombra.load(42)
    with pytest.raises(TypeError):
        sombra.explain(scene, 1.5, 2)
    with pytest.raises(TypeError):
        sombra.Scene.from_dict([1, 2])
    with pytest.raises(TypeError):
        sombra.write_image("/tmp/x.pfm", [[[0.0, 0.0, 0.0]]])
    with pytest.raises(TypeError):
        sombra.to_png(np.zeros((2, 2, 3), dtype=np.int32))


@pytest.mark.parametrize("array,message", [
    (np.zeros((4, 4), dtype=np.float32), r"shape \(4, 4\) is not \(height, width, 3\)"),
    (np.zeros((4, 4, 4), dtype=np.float32), r"shape \(4, 4, 4\)"),
    (np.zeros((0, 4, 3), dtype=np.float32), r"shape \(0, 4, 3\)"),
    (np.full((2, 3, 3), np.nan, dtype=np.float32), r"NaN at pixel \(0, 0\)"),
])
def test_hostile_images_are_refused(tmp_path, array, message):
    with pytest.raises(sombra.Error, match=message):
        sombra.write_image(tmp_path / "x.pfm", array)
    with pytest.raises(sombra.Error, match=message):
        sombra.to_png(array)
    assert not (tmp_path / "x.pfm").exists()


def test_a_non_finite_exposure_is_refused(tmp_path):
    image = np.ones((2, 2, 3), dtype=np.float32)
    with pytest.raises(sombra.Error, match="exposure"):
        sombra.write_image(tmp_path / "x.png", image, exposure=float("inf"))
    with pytest.raises(sombra.Error, match="exposure"):
        sombra.to_png(image, exposure=float("nan"))
    assert not (tmp_path / "x.png").exists()


def test_write_image_round_trips_through_pfm_and_png(tmp_path):
    from conftest import read_pfm
    rng = np.random.default_rng(1)
    image = rng.random((5, 7, 3), dtype=np.float32) * 4
    sombra.write_image(tmp_path / "x.pfm", image)
    assert read_pfm(tmp_path / "x.pfm").tobytes() == image.tobytes()
    # A non-contiguous float64 view is taken as the float32 values it rounds to.
    sombra.write_image(str(tmp_path / "y.pfm"), image.astype(np.float64)[:, ::-1][:, ::-1])
    assert read_pfm(tmp_path / "y.pfm").tobytes() == image.tobytes()
    sombra.write_image(tmp_path / "z.pfm", image.astype(">f4"))  # big-endian float32 is float32
    assert read_pfm(tmp_path / "z.pfm").tobytes() == image.tobytes()
    sombra.write_image(tmp_path / "x.png", image, exposure=-1)
    png = pathlib.Path(tmp_path / "x.png").read_bytes()
    assert png.startswith(b"\x89PNG") and png == sombra.to_png(image, exposure=-1)
    assert png != sombra.to_png(image)


def test_write_image_takes_a_tone_mapper_and_jpeg(tmp_path, tmp_path_factory):
    # Spec §27: the command line's --tonemap, the same bytes as its PNG.
    rng = np.random.default_rng(2)
    image = rng.random((6, 8, 3), dtype=np.float32) * 3
    mapped = sombra.to_png(image, exposure=0.5, tonemap="pbr-neutral")
    assert mapped != sombra.to_png(image, exposure=0.5)
    sombra.write_image(tmp_path / "t.png", image, exposure=0.5, tonemap="pbr-neutral")
    assert (tmp_path / "t.png").read_bytes() == mapped
    sombra.write_image(tmp_path / "t.jpg", image, tonemap="pbr-neutral")
    assert (tmp_path / "t.jpg").read_bytes()[:3] == b"\xff\xd8\xff"
    with pytest.raises(sombra.Error, match="tonemap applies to 8-bit outputs"):
        sombra.write_image(tmp_path / "t.exr", image, tonemap="pbr-neutral")
    assert not (tmp_path / "t.exr").exists()
    with pytest.raises(sombra.Error, match="^--tonemap: expected none or pbr-neutral, not 'aces'$"):
        sombra.to_png(image, tonemap="aces")
    with pytest.raises(TypeError, match="tonemap must be a str"):
        sombra.to_png(image, tonemap=1)


def test_read_image_reads_back_what_write_image_wrote(tmp_path):
    rng = np.random.default_rng(3)
    image = rng.random((5, 7, 3), dtype=np.float32) * 3
    for name in ("a.pfm", "a.exr"):
        sombra.write_image(tmp_path / name, image)
        back = sombra.read_image(tmp_path / name)
        assert back.dtype == np.float32 and back.tobytes() == image.tobytes(), name
    # 8-bit files come back linear: each value within half a code of sRGB.
    sombra.write_image(tmp_path / "a.png", image)
    png = sombra.read_image(tmp_path / "a.png")
    assert png.shape == (5, 7, 3)
    clamped = np.minimum(image, 1)
    assert np.all(np.abs(png - clamped) <= 0.02 * np.maximum(clamped, 0.05))
    # A grey PFM fills three channels.
    (tmp_path / "g.pfm").write_bytes(b"Pf\n2 1\n-1.0\n" + np.array([0.25, 2.0], "<f4").tobytes())
    assert sombra.read_image(tmp_path / "g.pfm").tolist() == [[[0.25] * 3, [2.0] * 3]]
    (tmp_path / "short.pfm").write_bytes(b"PF\n100000 100000\n-1.0\n" + bytes(12))
    with pytest.raises(sombra.Error, match="out of range"):
        sombra.read_image(tmp_path / "short.pfm")
    (tmp_path / "cut.pfm").write_bytes(b"PF\n2 2\n-1.0\n" + bytes(12))
    with pytest.raises(sombra.Error, match="holds 24 bytes, not the 60 its header says"):
        sombra.read_image(tmp_path / "cut.pfm")
    with pytest.raises(sombra.Error, match="missing.png"):
        sombra.read_image(tmp_path / "missing.png")
    assert isinstance(sombra.__version__, str) and sombra.__version__.count(".") == 2


def test_explain_svg_is_the_command_lines_picture(tmp_path):
    scene_file = REPO / "scenes" / "cornell-box-path.json"
    s = sombra.load(scene_file, width=24, height=20, spp=4)
    for extra, options in (([], {}), (["--exposure", "1", "--tonemap", "pbr-neutral"],
                                      {"exposure": 1, "tonemap": "pbr-neutral"})):
        out = tmp_path / "cli.svg"
        status, _, err = run_cli("explain", scene_file, 12, 9, "--width", 24, "--height", 20, "--spp", 4, "--json",
                                 "--svg", out, *extra)
        assert status == 0, err
        svg = sombra.explain_svg(s, 12, 9, **options)
        assert svg.startswith("<svg") or svg.startswith("<?xml")
        assert svg == out.read_text()
    with pytest.raises(sombra.Error, match="--tonemap"):
        sombra.explain_svg(s, 1, 1, tonemap="filmic")


def test_the_package_ships_its_types():
    # PEP 561: py.typed, and a stub naming every function and class of _sombra.
    import ast
    import pathlib
    folder = pathlib.Path(sombra.__file__).parent
    assert (folder / "py.typed").exists()
    stub = ast.parse((folder / "_sombra.pyi").read_text())
    stubbed = {node.name for node in stub.body if isinstance(node, (ast.FunctionDef, ast.ClassDef))}
    compiled = {name for name in dir(sombra._sombra) if not name.startswith("__")}
    assert stubbed == compiled
