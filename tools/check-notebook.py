#!/usr/bin/env python3
"""Executes examples/tour.ipynb with Debian's jupyter-nbconvert (so the
notebook can never rot) and checks what it drew: no cell failed, the
matplotlib figures came out as images, and progress=True drew one text
output that ended at 100 % (updated in place: no stream of bars).

usage: check-notebook.py NOTEBOOK    (CTest runs it as python_notebook, with
PYTHONPATH naming the built package). Exit status 77 (CTest: skipped) when
jupyter-nbconvert is not installed, unless SOMBRA_REQUIRE_JUPYTER is set
(CI: .ci/run), which makes that a failure.
"""

from __future__ import annotations

import json
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile

SKIP = 77


def fail(what: str) -> int:
    print(f"sombra: error: {NOTEBOOK}: {what}", file=sys.stderr)
    return 1


def texts(output: dict) -> list[str]:
    """An output's text: a stream's, or a display's text/plain."""
    if output.get("output_type") == "stream":
        return ["".join(output.get("text", ""))]
    data = output.get("data", {})
    return ["".join(data["text/plain"])] if "text/plain" in data else []


def check(executed: dict) -> str | None:
    outputs = [o for cell in executed["cells"] if cell["cell_type"] == "code" for o in cell.get("outputs", [])]
    errors = [o for o in outputs if o.get("output_type") == "error"]
    if errors:
        return f"a cell raised {errors[0].get('ename')}: {errors[0].get('evalue')}"
    images = [o for o in outputs if "image/png" in o.get("data", {})]
    if len(images) < 3:
        return f"expected at least 3 figures (image/png outputs), found {len(images)}"
    bars = [(o, t) for o in outputs for t in texts(o) if "sombra: [" in t]
    if len(bars) != 1:
        return f"progress=True: expected one bar output updated in place, found {len(bars)}"
    output, text = bars[0]
    if output.get("output_type") == "stream" or "\n" in text.strip() or not text.strip().endswith("100%"):
        return f"progress=True: the bar is not one display that ends at 100%: {text!r}"
    return None


def main() -> int:
    nbconvert = shutil.which("jupyter-nbconvert")
    if nbconvert is None:
        if os.environ.get("SOMBRA_REQUIRE_JUPYTER"):
            return fail("jupyter-nbconvert is not installed and SOMBRA_REQUIRE_JUPYTER is set "
                        "(tools/install-deps.sh --test installs it)")
        print(f"skipped: jupyter-nbconvert is not installed (Debian's jupyter-nbconvert); {NOTEBOOK} not run")
        return SKIP
    with tempfile.TemporaryDirectory() as tmp:
        # Kernel, IPython and matplotlib state in the temporary folder: nothing written to $HOME.
        env = dict(os.environ, JUPYTER_RUNTIME_DIR=tmp, IPYTHONDIR=tmp, MPLCONFIGDIR=tmp,
                   PYDEVD_DISABLE_FILE_VALIDATION="1")
        # The kernel runs in the notebook's folder: a relative PYTHONPATH would point elsewhere there.
        paths = [p for p in env.get("PYTHONPATH", "").split(os.pathsep) if p]
        env["PYTHONPATH"] = os.pathsep.join(os.path.abspath(p) for p in paths)
        result = subprocess.run([nbconvert, "--execute", "--to", "notebook", "--output-dir", tmp,
                                 "--ExecutePreprocessor.timeout=120", NOTEBOOK],
                                env=env, capture_output=True, text=True, check=False)
        out = pathlib.Path(tmp) / pathlib.Path(NOTEBOOK).name
        if result.returncode != 0 or not out.is_file():
            sys.stderr.write(result.stderr[-4000:])
            return fail(f"jupyter-nbconvert --execute failed (exit status {result.returncode})")
        problem = check(json.loads(out.read_text()))
    if problem:
        return fail(problem)
    print(f"{NOTEBOOK}: executed, every cell ran, figures and progress bar as expected")
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        print("usage: check-notebook.py NOTEBOOK", file=sys.stderr)
        sys.exit(2)
    NOTEBOOK = sys.argv[1]
    sys.exit(main())
