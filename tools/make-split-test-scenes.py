#!/usr/bin/env python3
"""Writes the two synthetic scenes of the optimisation log's step P7, made
where spatial splits should matter, into a folder (default build/bench-split):

- slivers.obj + slivers.json: 20,000 long thin triangles (0.8 long, about
  0.004 wide) in random directions around random points of the unit cube,
  a "hairball"; seen from the front, one point light.
- cornell-rotated.json: the shared Cornell box turned 35 degrees about an
  oblique axis through its middle, so its walls are no longer axis-aligned,
  around the Stanford bunny (both from ../shared/models).

    tools/make-split-test-scenes.py [FOLDER]
"""
import json
import math
import os
import random
import sys


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    out = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build", "bench-split"))
    models = os.path.join(os.path.dirname(root), "shared", "models")
    os.makedirs(out, exist_ok=True)

    rng = random.Random(1)
    with open(os.path.join(out, "slivers.obj"), "w") as f:
        for i in range(20000):
            c = [rng.random() for _ in range(3)]
            d = [rng.gauss(0, 1) for _ in range(3)]
            norm = math.sqrt(sum(x * x for x in d))
            d = [x / norm * 0.4 for x in d]
            w = [rng.gauss(0, 1) * 0.004 for _ in range(3)]
            a = [c[k] - d[k] for k in range(3)]
            b = [c[k] + d[k] for k in range(3)]
            e = [c[k] + d[k] + w[k] for k in range(3)]
            for p in (a, b, e):
                f.write("v %f %f %f\n" % tuple(p))
            f.write("f %d %d %d\n" % (3 * i + 1, 3 * i + 2, 3 * i + 3))
    slivers = {
        "render": {"width": 640, "height": 640, "spp": 1, "seed": 0},
        "background": [0.2, 0.2, 0.2],
        "camera": {"origin": [0.5, 0.5, 3.0], "look_at": [0.5, 0.5, 0.5], "up": [0, 1, 0], "fov": 40},
        "lights": [{"type": "point", "position": [0.5, 2.5, 2.0], "intensity": [5, 5, 5]}],
        "objects": [{"file": "slivers.obj"}],
    }
    rotated = {
        "render": {"width": 1024, "height": 1024, "spp": 1, "seed": 0},
        "background": [0, 0, 0],
        "camera": {"origin": [0, 1, 3.7], "look_at": [0, 1, 0], "up": [0, 1, 0], "fov": 40},
        "lights": [{"type": "point", "position": [-0.005, 1.9, -0.03], "intensity": [5, 4.2, 3.2]}],
        "objects": [
            {"file": os.path.join(models, "CornellBox-Original.obj"),
             "transform": [{"translate": [0, -1, 0]}, {"rotate": {"axis": [1, 1, 0.3], "degrees": 35}},
                           {"translate": [0, 1, 0]}]},
            {"file": os.path.join(models, "stanford-bunny.obj"),
             "transform": [{"scale": 3}, {"translate": [0, 0.5, 0]}]},
        ],
    }
    for name, scene in (("slivers.json", slivers), ("cornell-rotated.json", rotated)):
        with open(os.path.join(out, name), "w") as f:
            json.dump(scene, f, indent=2)
            f.write("\n")
    print(out)


if __name__ == "__main__":
    main()
