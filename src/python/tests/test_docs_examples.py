"""Issue 39: docs/python.md's examples run as written. Every ```python
block, in order, in one namespace, in a folder where scenes/ is the
repository's; the arrays the text leaves to the reader (positions,
indices, normals, uvs) are a small grid."""
import os
import re

import numpy as np
import pytest

from conftest import REPO, import_sombra

sombra = import_sombra()


def python_blocks(markdown):
    return re.findall(r"^```python\n(.*?)^```", markdown, flags=re.S | re.M)


def test_every_python_block_of_the_guide_runs(tmp_path, monkeypatch):
    blocks = python_blocks((REPO / "docs" / "python.md").read_text())
    assert len(blocks) >= 8, "the guide's python blocks were not found"
    (tmp_path / "scenes").symlink_to(REPO / "scenes")
    monkeypatch.chdir(tmp_path)
    n = 5
    u, v = np.meshgrid(np.linspace(0, 1, n), np.linspace(0, 1, n))
    quads = [(j * n + i, j * n + i + 1, (j + 1) * n + i + 1, (j + 1) * n + i) for j in range(n - 1) for i in range(n - 1)]
    namespace = {
        "positions": np.stack([u.ravel() - 0.5, np.zeros(n * n), v.ravel() - 0.5], axis=1),
        "indices": np.array([t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))]),
        "normals": np.tile([0.0, 1.0, 0.0], (n * n, 1)),
        "uvs": np.stack([u.ravel(), v.ravel()], axis=1),
        "__name__": "docs_example",
    }
    for k, block in enumerate(blocks):
        try:
            exec(compile(block, f"docs/python.md block {k}", "exec"), namespace)
        except Exception as e:  # noqa: BLE001 - which block failed, and why
            pytest.fail(f"docs/python.md python block {k} fails: {type(e).__name__}: {e}\n{block}")
    assert os.path.exists("out.png")
