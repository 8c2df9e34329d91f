"""The render releases the GIL: other Python threads run meanwhile, two
renders run at once and give what one alone gives."""

import threading
import time

from conftest import import_sombra

sombra = import_sombra()

SMALL = dict(width=64, height=48)


def test_another_python_thread_runs_while_a_render_runs():
    scene = sombra.load("scenes/cornell-box-path.json")
    ticks = []
    stop = threading.Event()

    def count():
        while not stop.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.005)

    counter = threading.Thread(target=count)
    counter.start()
    try:
        start = time.monotonic()
        sombra.render(scene, spp=256, threads=1, **SMALL)
        end = time.monotonic()
    finally:
        stop.set()
        counter.join()
    assert end - start > 0.1, "the render was too short to tell"
    during = [t for t in ticks if start < t < end]
    # Held GIL: no tick at all during the render; released: one every ~5 ms.
    assert len(during) >= (end - start) / 0.05


def test_two_threads_render_two_scenes_and_the_same_scene_at_once():
    a = sombra.load("scenes/cornell-box-path.json")
    b = sombra.load("scenes/cornell-box.json")
    alone = [sombra.render(s, spp=8, **SMALL).tobytes() for s in (a, b, a)]
    results = [None] * 3

    def run(i, s):
        results[i] = sombra.render(s, spp=8, **SMALL).tobytes()

    threads = [threading.Thread(target=run, args=(i, s)) for i, s in enumerate((a, b, a))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert results == alone


def test_a_nul_in_a_path_is_refused():
    import pytest
    with pytest.raises(sombra.Error, match="NUL"):
        sombra.load("scenes/cornell-box.json\0.obj")
