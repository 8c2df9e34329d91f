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
