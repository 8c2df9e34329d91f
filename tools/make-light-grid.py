#!/usr/bin/env python3
"""Writes scenes/models/light-grid.obj/.mtl: a 32 x 32 grid of small emissive
quads (2048 triangles) hung 0.6 to 2.6 above the ground, tilted at random,
in three MTL materials (warm, cool and dim white Ke, two decades apart), for
scenes/many-lights-path.json, the light tree's test scene.

Run from the repository root: python3 tools/make-light-grid.py
Deterministic (fixed seed); the files are committed.
"""
import math
import os
import random

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes", "models")

MTL = """newmtl warm
Kd 0 0 0
Ke 12 7 3
newmtl cool
Ke 1.5 2.5 4
Kd 0 0 0
newmtl dim
Kd 0 0 0
Ke 0.15 0.15 0.15
"""


def main():
    rng = random.Random(20180801)
    lines = ["# light-grid.obj: written by tools/make-light-grid.py", "mtllib light-grid.mtl"]
    faces = {"warm": [], "cool": [], "dim": []}
    v = 0
    for i in range(32):
        for j in range(32):
            c = (-8 + 0.5 * i + rng.uniform(-0.1, 0.1), rng.uniform(0.6, 2.6), -8 + 0.5 * j + rng.uniform(-0.1, 0.1))
            # Normal mostly down, tilted up to ~60 degrees.
            theta, phi = rng.uniform(0, math.radians(60)), rng.uniform(0, 2 * math.pi)
            n = (math.sin(theta) * math.cos(phi), -math.cos(theta), math.sin(theta) * math.sin(phi))
            t = (0.0, n[2], -n[1])  # n x (1, 0, 0)
            tl = math.sqrt(t[1] ** 2 + t[2] ** 2)
            t = (0.0, t[1] / tl, t[2] / tl)
            b = (n[1] * t[2] - n[2] * t[1], n[2] * t[0] - n[0] * t[2], n[0] * t[1] - n[1] * t[0])
            h = rng.uniform(0.04, 0.09)
            for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                p = [c[k] + h * (su * t[k] + sv * b[k]) for k in range(3)]
                lines.append("v %.5f %.5f %.5f" % tuple(p))
            faces[rng.choice(["warm", "cool", "cool", "dim"])].append((v + 1, v + 2, v + 3, v + 4))
            v += 4
    for name, quads in faces.items():
        lines.append("usemtl " + name)
        lines += ["f %d %d %d %d" % q for q in quads]
    with open(os.path.join(OUT, "light-grid.obj"), "w") as f:
        f.write("\n".join(lines) + "\n")
    with open(os.path.join(OUT, "light-grid.mtl"), "w") as f:
        f.write(MTL)


if __name__ == "__main__":
    main()
