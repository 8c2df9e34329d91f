"""What the Python tests share: the module (or a clean skip when it was not
built), the built `sombra` executable they compare against, and a PFM reader."""

import os
import pathlib
import subprocess

import numpy as np
import pytest

REPO = pathlib.Path(__file__).resolve().parents[3]
SOMBRA_EXE = os.environ.get("SOMBRA_EXE", str(REPO / "build" / "release" / "src" / "app" / "sombra"))


def import_sombra():
    """The package, or a skip saying why (run with PYTHONPATH=build/release/python)."""
    return pytest.importorskip(
        "sombra", reason="the module is not importable: build with SOMBRA_BUILD_PYTHON=ON (pybind11-dev, "
        "python3-numpy) and run with PYTHONPATH=build/release/python /usr/bin/python3")


def run_cli(*args):
    """The command line, run for real: (exit status, stdout, stderr)."""
    if not os.path.exists(SOMBRA_EXE):
        pytest.skip(f"the sombra executable is not at {SOMBRA_EXE} (set SOMBRA_EXE)")
    p = subprocess.run([SOMBRA_EXE, *map(str, args)], cwd=REPO, capture_output=True, text=True, timeout=60)
    return p.returncode, p.stdout, p.stderr


def read_pfm(path):
    """A colour PFM as float32 (height, width, 3), top row first."""
    with open(path, "rb") as f:
        assert f.readline().strip() == b"PF"
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        dtype = "<f4" if scale < 0 else ">f4"
        data = np.frombuffer(f.read(), dtype=dtype).astype(np.float32)
    assert data.size == width * height * 3
    return data.reshape(height, width, 3)[::-1]  # PFM rows run bottom to top


@pytest.fixture(autouse=True)
def _in_repo(monkeypatch):
    monkeypatch.chdir(REPO)  # scenes/… paths as the command line is given them
