"""tools/make-man.py: the man page from the CLI's own help (CLI11's layout
read into sections, roff escaped), and the page made from the built binary
names every subcommand and option and reads without groff warnings."""

import gzip
import importlib.util
import os
import re
import shutil
import subprocess
import sys

import pytest
from conftest import REPO, SOMBRA_EXE

spec = importlib.util.spec_from_file_location("make_man", REPO / "tools" / "make-man.py")
make_man = importlib.util.module_from_spec(spec)
sys.modules["make_man"] = make_man  # dataclasses look their module up there
spec.loader.exec_module(make_man)

HELP = """Render a scene
Usage: sombra render [OPTIONS] input

Positionals:
  input TEXT REQUIRED         Scene file (.json)

Options:
  -h,--help                   Print this help message and exit
  input TEXT REQUIRED         Scene file (.json)
  --integrator TEXT:{direct,path}
                              Integrator: direct light only, or
                              a path tracer
"""


def test_the_help_is_read_into_sections():
    h = make_man.parse_help(HELP)
    assert h.description == "Render a scene"
    assert h.usage == "sombra render [OPTIONS] input"
    assert h.sections["Positionals"] == [("input TEXT REQUIRED", "Scene file (.json)")]
    assert h.sections["Options"][-1] == ("--integrator TEXT:{direct,path}",
                                         "Integrator: direct light only, or a path tracer")


def test_roff_escapes_hyphens_backslashes_and_control_characters():
    assert make_man.roff("--spp") == "\\-\\-spp"
    assert make_man.roff("a\\b") == "a\\eb"
    assert make_man.roff(".pfm or 'x'") == "\\&.pfm or 'x'"


def test_the_page_from_the_built_binary(tmp_path):
    if not os.path.exists(SOMBRA_EXE):
        pytest.skip(f"the sombra executable is not at {SOMBRA_EXE} (set SOMBRA_EXE)")
    page = tmp_path / "sombra.1.gz"
    subprocess.run(["/usr/bin/python3", str(REPO / "tools" / "make-man.py"), SOMBRA_EXE, str(page)], check=True)
    raw = page.read_bytes()
    assert raw[4:8] == b"\0\0\0\0"  # gzip without a time stamp (reproducible)
    text = gzip.decompress(raw).decode()
    for needed in ('.SH "SOMBRA RENDER"', '.SH "SOMBRA EXPLAIN"', "\\-\\-output", "\\-\\-noise\\-threshold",
                   "\\-\\-svg", "\\-\\-version", ".SH EXIT STATUS"):
        assert needed in text, needed
    if shutil.which("man") is None:
        return
    env = {k: v for k, v in os.environ.items() if k != "LD_PRELOAD"}  # man is no sanitized program
    shown = subprocess.run(["man", "--warnings", "-l", str(page)], capture_output=True, text=True,
                           env=dict(env, MANWIDTH="80", MANPAGER="cat"), check=True)
    assert shown.stderr == ""
    plain = re.sub(".\b", "", shown.stdout)  # without the overstrike that makes bold
    assert "sombra render [OPTIONS] input" in plain and "--max-depth INT" in plain
