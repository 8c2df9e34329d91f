"""Ctrl-C during a render: KeyboardInterrupt within a second, in a real process."""

import os
import signal
import subprocess
import sys
import textwrap
import threading
import time

from conftest import REPO, import_sombra

import_sombra()

SCRIPT = textwrap.dedent("""
    import sys, time, sombra
    scene = sombra.load("scenes/cornell-box-path.json")
    print("rendering", flush=True)
    try:
        sombra.render(scene, width=512, height=512, spp=65536)
    except KeyboardInterrupt:
        print("interrupted", time.monotonic(), flush=True)
        sys.exit(3)
    print("finished", flush=True)
""")


def test_sigint_raises_keyboard_interrupt_within_a_second():
    p = subprocess.Popen([sys.executable, "-c", SCRIPT], cwd=REPO, env=os.environ.copy(), stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    # A render that ignores the signal would run for hours: the readline below would block, so kill it.
    watchdog = threading.Timer(20.0, p.kill)
    watchdog.start()
    try:
        assert p.stdout.readline().strip() == "rendering"
        time.sleep(0.3)  # well inside the render
        sent = time.monotonic()
        p.send_signal(signal.SIGINT)
        line = p.stdout.readline().split()
        assert line[:1] == ["interrupted"], p.stderr.read()
        assert float(line[1]) - sent < 1.0
        assert p.wait(timeout=5) == 3
    finally:
        watchdog.cancel()
        p.kill()
        p.wait()


def test_an_interrupt_from_another_thread_stops_the_render_and_the_scene_stays_usable():
    import _thread

    import pytest
    sombra = import_sombra()
    scene = sombra.load("scenes/cornell-box-path.json")
    timer = threading.Timer(0.2, _thread.interrupt_main)
    start = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            sombra.render(scene, width=512, height=512, spp=65536)
    finally:
        timer.cancel()
    assert time.monotonic() - start < 1.2  # 0.2 s until the interrupt, then within a second
    assert sombra.render(scene, width=8, height=8, spp=1).shape == (8, 8, 3)
