"""progress=True: one line on stderr redrawn with carriage returns in a
terminal, one display updated in place in Jupyter; never a line per update."""

import io

from conftest import import_sombra

sombra = import_sombra()
from sombra import _progress  # noqa: E402  (after the skip above)


def test_the_terminal_bar_redraws_one_line_at_most_101_times():
    stream = io.StringIO()
    bar = _progress.Bar(stream=stream)
    for done in range(0, 100_001, 7):  # 14 286 calls
        bar(done, 100_000)
    bar(100_000, 100_000)
    text = stream.getvalue()
    assert "\n" not in text
    assert 2 <= text.count("\r") <= 101
    assert text.endswith("] 100%")
    bar.close()
    assert stream.getvalue().endswith("100%\n") and stream.getvalue().count("\n") == 1


def test_the_notebook_bar_updates_one_display_and_writes_no_stream():
    shown, stream = [], io.StringIO()
    bar = _progress.Bar(stream=stream, show=shown.append)
    for done in range(0, 1001):
        bar(done, 1000)
    bar.close()
    assert stream.getvalue() == ""
    assert len(shown) == 101 and shown[0].endswith("  0%") and shown[-1].endswith("100%")
    assert all("\r" not in text and "\n" not in text for text in shown)


def test_outside_a_kernel_the_bar_goes_to_stderr():
    assert _progress.notebook_display() is None  # pytest is no Jupyter kernel
    assert _progress.Bar.for_here().show is None


def test_a_render_with_progress_true_draws_one_line_on_stderr(capsys):
    scene = sombra.load("scenes/cornell-box-path.json")
    sombra.render(scene, width=32, height=32, spp=4, progress=True)
    err = capsys.readouterr().err
    assert err.startswith("\rsombra: [") and err.endswith("] 100%\n") and err.count("\n") == 1


def test_bar_text_at_the_ends_and_for_an_empty_render():
    assert _progress.bar_text(0, 10) == "sombra: [" + "." * 30 + "]   0%"
    assert _progress.bar_text(10, 10) == "sombra: [" + "#" * 30 + "] 100%"
    assert _progress.bar_text(0, 0).endswith("100%")
