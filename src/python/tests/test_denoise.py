"""sombra.render(denoise=True), the "noisy" and "denoise" AOVs and sombra.denoise
against `sombra render --denoise` (spec §25)."""

import json
import threading
import time

import numpy as np
import pytest

from conftest import REPO, import_sombra, read_pfm, run_cli

sombra = import_sombra()

SCENE = "scenes/cornell-box-path.json"
SMALL = dict(width=48, height=40, spp=4)
LAYERS = {"variance": 3, "denoise.A": 3, "denoise.B": 3, "denoise.albedoA": 3, "denoise.albedoB": 3,
          "denoise.normalA": 3, "denoise.normalB": 3, "denoise.depthA": 1, "denoise.depthB": 1}


@pytest.fixture(scope="module")
def scene():
    return sombra.load(SCENE)


@pytest.fixture(scope="module")
def denoised(scene):
    return sombra.render(scene, denoise=True, **SMALL)


@pytest.fixture(scope="module")
def layers(scene):
    return sombra.render(scene, aov=["denoise"], **SMALL)


def test_render_denoise_equals_the_command_lines_float_for_float(tmp_path, denoised):
    out = tmp_path / "cli.pfm"
    status, _, err = run_cli("render", SCENE, "-o", out, "-q", "--width", 48, "--height", 40, "--spp", 4, "--denoise")
    assert status == 0, err
    assert denoised.dtype == np.float32 and denoised.shape == (40, 48, 3)
    assert denoised.tobytes() == read_pfm(out).tobytes()
    assert np.isfinite(denoised).all() and (denoised >= 0).all()


def test_the_denoised_image_is_the_same_on_any_thread_count(scene, denoised):
    assert sombra.render(scene, denoise=True, threads=1, **SMALL).tobytes() == denoised.tobytes()


def test_the_denoise_aov_holds_every_layer_the_denoiser_reads(scene, layers):
    assert set(layers) == {"color"} | set(LAYERS)
    for name, channels in LAYERS.items():
        assert layers[name].dtype == np.float32, name
        assert layers[name].shape == ((40, 48, 3) if channels == 3 else (40, 48)), name
    # The halves are each pixel's even and odd samples: their mean is the image.
    halves = 0.5 * (layers["denoise.A"].astype(np.float64) + layers["denoise.B"])
    assert np.allclose(halves, layers["color"], rtol=1e-5, atol=1e-6)
    assert layers["color"].tobytes() == sombra.render(scene, **SMALL).tobytes()  # gathering changes no pixel


def test_denoise_of_the_layers_equals_render_denoise(layers, denoised):
    assert sombra.denoise(layers).tobytes() == denoised.tobytes()
    assert sombra.denoise(layers, threads=1).tobytes() == denoised.tobytes()
    # Other keys are ignored; float64 arrays are read as the float32 values they hold.
    wider = {name: value.astype(np.float64) for name, value in layers.items()}
    wider["albedo"] = "not a layer the denoiser reads"
    assert sombra.denoise(wider).tobytes() == denoised.tobytes()


def test_noisy_is_the_image_before_denoising(scene, denoised):
    out = sombra.render(scene, denoise=True, aov=["noisy", "variance"], **SMALL)
    assert set(out) == {"color", "noisy", "variance"}
    assert out["color"].tobytes() == denoised.tobytes()
    assert out["noisy"].tobytes() == sombra.render(scene, **SMALL).tobytes()


def test_noisy_without_denoise_is_an_error_naming_the_option(scene):
    with pytest.raises(sombra.Error, match="^--aov: noisy is the image before denoising: it needs --denoise$"):
        sombra.render(scene, aov=["noisy"], **SMALL)


def test_denoise_below_two_samples_is_the_command_lines_error(tmp_path, scene):
    with pytest.raises(sombra.Error, match="^--denoise: needs at least 2 samples per pixel"):
        sombra.render(scene, denoise=True, width=48, height=40, spp=1)
    # A scene whose own spp is 1: the command line's line (a command-line
    # error there, exit status 2, as the other option errors are).
    with open(SCENE) as f:
        d = json.load(f)
    d["render"].update(spp=1, width=48, height=40)
    for o in d["objects"]:
        o["file"] = str((REPO / "scenes" / o["file"]).resolve())
    one = tmp_path / "one.json"
    one.write_text(json.dumps(d))
    with pytest.raises(sombra.Error) as caught:
        sombra.render(sombra.load(one), denoise=True)
    status, _, err = run_cli("render", one, "--denoise", "-o", tmp_path / "never.png", "-q")
    assert status == 2
    assert err.strip() == "sombra: error: command line: " + str(caught.value)
    assert str(caught.value).startswith("--denoise: needs at least 2 samples per pixel")
    assert not (tmp_path / "never.png").exists()


def test_denoise_takes_a_bool(scene):
    for value in (1, "yes", 1.0):
        with pytest.raises(TypeError, match="denoise must be bool"):
            sombra.render(scene, denoise=value, **SMALL)
    assert sombra.render(scene, denoise=False, **SMALL).tobytes() == sombra.render(scene, **SMALL).tobytes()


def test_a_missing_layer_is_an_error_naming_it(layers):
    partial = {name: value for name, value in layers.items() if name != "denoise.albedoB"}
    with pytest.raises(sombra.Error, match="^layers: no layer 'denoise.albedoB'"):
        sombra.denoise(partial)


def test_a_layer_of_the_wrong_shape_is_an_error_naming_it(layers):
    wrong = dict(layers, **{"denoise.depthA": layers["denoise.normalA"]})
    with pytest.raises(sombra.Error, match=r"^layers\['denoise.depthA'\]: shape \(40, 48, 3\) is not \(40, 48\)$"):
        sombra.denoise(wrong)
    smaller = dict(layers, **{"denoise.B": layers["denoise.B"][:20]})
    with pytest.raises(sombra.Error, match=r"^layers\['denoise.B'\]: shape \(20, 48, 3\) is not \(40, 48, 3\)$"):
        sombra.denoise(smaller)
    with pytest.raises(sombra.Error, match=r"^layers\['variance'\]: shape \(40, 48, 0\) is not"):
        sombra.denoise(dict(layers, variance=np.zeros((40, 48, 0), np.float32)))


def test_a_nan_is_an_error_naming_its_layer_and_pixel(layers):
    broken = {name: value.copy() for name, value in layers.items()}
    broken["denoise.normalA"][2, 3, 1] = np.nan
    with pytest.raises(sombra.Error, match=r"^layers: denoise.normalA.Y: nan at pixel \(3, 2\)"):
        sombra.denoise(broken)
    negative = dict(layers, **{"denoise.A": -layers["denoise.A"] - 1})
    with pytest.raises(sombra.Error, match=r"^layers: denoise.A.R: .* is not a colour from 0 to 1e12$"):
        sombra.denoise(negative)


def test_wrong_types_are_type_errors(layers):
    with pytest.raises(TypeError, match="expected the dict"):
        sombra.denoise([layers["variance"]])
    with pytest.raises(TypeError, match=r"layers\['denoise.A'\]: expected a numpy array, not list"):
        sombra.denoise(dict(layers, **{"denoise.A": layers["denoise.A"].tolist()}))
    with pytest.raises(TypeError, match="expected a float dtype"):
        sombra.denoise(dict(layers, **{"denoise.A": layers["denoise.A"].astype(np.int32)}))
    with pytest.raises(TypeError, match="threads must be int"):
        sombra.denoise(layers, threads="2")


def test_an_interrupt_stops_a_long_denoise_within_a_second():
    import _thread
    rng = np.random.default_rng(3)
    h, w = 480, 640  # many seconds of denoising on a few threads
    big = {name: rng.random((h, w, 3) if channels == 3 else (h, w), dtype=np.float32)
           for name, channels in LAYERS.items()}
    timer = threading.Timer(0.2, _thread.interrupt_main)
    start = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            sombra.denoise(big, threads=2)
    finally:
        timer.cancel()
    assert time.monotonic() - start < 1.2


def test_explain_denoise_is_the_command_lines_json_and_the_rendered_pixel(scene, denoised):
    status, out, err = run_cli("explain", SCENE, 30, 22, "--width", 48, "--height", 40, "--spp", 4, "--denoise",
                               "--json")
    assert status == 0, err
    story = sombra.explain(scene, 30, 22, denoise=True, **SMALL)
    assert story == json.loads(out)
    terms = story["denoise"]["weights"]
    assert terms, "the denoised pixel has its weights"
    for c in range(3):
        assert sum(t["w"][c] for t in terms) == pytest.approx(1.0, abs=1e-4)
    assert story["denoise"]["value"] == pytest.approx(denoised[22, 30].tolist(), rel=1e-5, abs=1e-6)


def test_explain_without_denoise_has_no_denoise_story(scene):
    assert "denoise" not in sombra.explain(scene, 30, 22, **SMALL)
    with pytest.raises(TypeError, match="denoise must be bool"):
        sombra.explain(scene, 30, 22, denoise=1, **SMALL)
