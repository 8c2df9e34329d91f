"""progress=True: the text bar (private to the package).

In a terminal the bar is one line on stderr, redrawn in place with a
carriage return and ended with a newline. In Jupyter (an IPython kernel) it
is one text output that each redraw replaces (IPython's display with a
display_id, then update_display): a notebook shows a single line that
updates, and a saved or nbconvert-executed notebook keeps the last state,
never a line per update. Either way the bar is redrawn only when its whole
percentage changes: at most 101 draws a render.
"""

from __future__ import annotations

import sys
from typing import Callable, Optional, TextIO

_WIDTH = 30


def bar_text(done: int, total: int) -> str:
    """The bar for `done` of `total` samples, e.g. "sombra: [###.....]  10%"."""
    percent = _percent(done, total)
    filled = percent * _WIDTH // 100
    return f"sombra: [{'#' * filled}{'.' * (_WIDTH - filled)}] {percent:3d}%"


def _percent(done: int, total: int) -> int:
    return min(100, done * 100 // total) if total > 0 else 100


def notebook_display() -> Optional[Callable[[str], None]]:
    """A function that shows a text and then replaces it in place, when this
    runs in a Jupyter kernel; None elsewhere (a terminal, plain IPython)."""
    ipython = sys.modules.get("IPython")
    if ipython is None or "ipykernel" not in sys.modules:
        return None
    shell = ipython.get_ipython()
    if shell is None or not hasattr(shell, "kernel"):
        return None
    from IPython.display import display  # pylint: disable=import-outside-toplevel

    handle = None

    def show(text: str) -> None:
        nonlocal handle
        data = {"text/plain": text}
        if handle is None:
            handle = display(data, raw=True, display_id=True)
        else:
            handle.update(data, raw=True)

    return show


class Bar:
    """The callable given to the render as progress(done, total)."""

    def __init__(self, stream: Optional[TextIO] = None, show: Optional[Callable[[str], None]] = None) -> None:
        self.shown = -1
        self.stream = stream
        self.show = show

    @classmethod
    def for_here(cls) -> "Bar":
        """A bar for where this Python runs: Jupyter's output, else stderr."""
        return cls(show=notebook_display())

    def __call__(self, done: int, total: int) -> None:
        percent = _percent(done, total)
        if percent == self.shown:
            return
        self.shown = percent
        if self.show is not None:
            self.show(bar_text(done, total))
            return
        stream = self.stream if self.stream is not None else sys.stderr
        stream.write("\r" + bar_text(done, total))
        stream.flush()

    def close(self) -> None:
        """Ends the terminal's line (a notebook's output stays as it is)."""
        if self.shown >= 0 and self.show is None:
            stream = self.stream if self.stream is not None else sys.stderr
            stream.write("\n")
            stream.flush()
