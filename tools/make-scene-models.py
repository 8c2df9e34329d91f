#!/usr/bin/env python3
"""Writes the meshes under scenes/models/ that sombra's own scenes use.

Run from the repository root: python3 tools/make-scene-models.py
The output is deterministic; the files are committed, so this only needs
running again after a change here.

- cornell-box.obj/.mtl: the Cornell box from the measurements published by
  the Cornell Program of Computer Graphics ("Cornell Box Data"), in
  millimetres, x to the left, y up, the open side towards -z. The light
  quad is lowered 0.5 mm below the ceiling so the two are not coplanar.
  Reflectances are the usual RGB approximations of the measured spectra.
- cornell-box-empty.obj: the same box without its light quad, for path-traced
  scenes that put a one-sided quad light (spec §10) in its place: the MTL
  light emits from both sides (spec §9), and its upper side, 0.5 mm under
  the ceiling, would light a sliver of ceiling so brightly that every path
  reaching it becomes a firefly.
- sphere.obj: a unit UV sphere (64 x 32) with exact vertex normals.
- cube.obj: a unit cube centred at the origin, flat faces.
- grid-box.obj: the cube [-1, 1]^3, the bounds of an OpenVDB grid made in
  that box (../shared/models/vdb/cloud.vdb): an object's transform places
  the grid and its boundary alike (spec §26), so the boundary must enclose
  the grid in the same coordinates.
"""
import math
import os

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes", "models")

# (name, material, quads); each quad's corners as published, in mm.
CORNELL = [
    ("floor", "white", [[(552.8, 0, 0), (0, 0, 0), (0, 0, 559.2), (549.6, 0, 559.2)]]),
    ("light", "light", [[(343.0, 548.3, 227.0), (343.0, 548.3, 332.0), (213.0, 548.3, 332.0), (213.0, 548.3, 227.0)]]),
    ("ceiling", "white", [[(556.0, 548.8, 0), (556.0, 548.8, 559.2), (0, 548.8, 559.2), (0, 548.8, 0)]]),
    ("back_wall", "white", [[(549.6, 0, 559.2), (0, 0, 559.2), (0, 548.8, 559.2), (556.0, 548.8, 559.2)]]),
    ("right_wall", "green", [[(0, 0, 559.2), (0, 0, 0), (0, 548.8, 0), (0, 548.8, 559.2)]]),
    ("left_wall", "red", [[(552.8, 0, 0), (549.6, 0, 559.2), (556.0, 548.8, 559.2), (556.0, 548.8, 0)]]),
    ("short_block", "white", [
        [(130.0, 165.0, 65.0), (82.0, 165.0, 225.0), (240.0, 165.0, 272.0), (290.0, 165.0, 114.0)],
        [(290.0, 0, 114.0), (290.0, 165.0, 114.0), (240.0, 165.0, 272.0), (240.0, 0, 272.0)],
        [(130.0, 0, 65.0), (130.0, 165.0, 65.0), (290.0, 165.0, 114.0), (290.0, 0, 114.0)],
        [(82.0, 0, 225.0), (82.0, 165.0, 225.0), (130.0, 165.0, 65.0), (130.0, 0, 65.0)],
        [(240.0, 0, 272.0), (240.0, 165.0, 272.0), (82.0, 165.0, 225.0), (82.0, 0, 225.0)],
    ]),
    ("tall_block", "white", [
        [(423.0, 330.0, 247.0), (265.0, 330.0, 296.0), (314.0, 330.0, 456.0), (472.0, 330.0, 406.0)],
        [(423.0, 0, 247.0), (423.0, 330.0, 247.0), (472.0, 330.0, 406.0), (472.0, 0, 406.0)],
        [(472.0, 0, 406.0), (472.0, 330.0, 406.0), (314.0, 330.0, 456.0), (314.0, 0, 456.0)],
        [(314.0, 0, 456.0), (314.0, 330.0, 456.0), (265.0, 330.0, 296.0), (265.0, 0, 296.0)],
        [(265.0, 0, 296.0), (265.0, 330.0, 296.0), (423.0, 330.0, 247.0), (423.0, 0, 247.0)],
    ]),
]

CORNELL_MTL = """# Cornell box materials: RGB approximations of the measured reflectances.
newmtl white
Kd 0.725 0.71 0.68
Ks 0 0 0

newmtl red
Kd 0.63 0.065 0.05
Ks 0 0 0

newmtl green
Kd 0.14 0.45 0.091
Ks 0 0 0

newmtl light
Kd 0.78 0.78 0.78
Ks 0 0 0
Ke 17 12 4
"""


def fmt(x):
    return ("%.6f" % x).rstrip("0").rstrip(".") if x != int(x) else str(int(x))


def write_cornell(file_name="cornell-box.obj", with_light=True):
    lines = ["# Cornell box, published measurements (mm)%s. Made by tools/make-scene-models.py."
             % ("" if with_light else ", without the light quad"),
             "mtllib cornell-box.mtl"]
    n = 0
    for name, material, quads in CORNELL:
        if name == "light" and not with_light:
            continue
        lines += ["o " + name, "usemtl " + material]
        for quad in quads:
            for v in quad:
                lines.append("v " + " ".join(fmt(c) for c in v))
            lines.append("f %d %d %d %d" % (n + 1, n + 2, n + 3, n + 4))
            n += 4
    with open(os.path.join(OUT, file_name), "w") as f:
        f.write("\n".join(lines) + "\n")
    with open(os.path.join(OUT, "cornell-box.mtl"), "w") as f:
        f.write(CORNELL_MTL)


def write_sphere(rings=32, segments=64):
    lines = ["# Unit UV sphere, %d x %d, exact normals. Made by tools/make-scene-models.py." % (segments, rings)]
    verts = [(0.0, 1.0, 0.0)]
    for r in range(1, rings):
        theta = math.pi * r / rings
        for s in range(segments):
            phi = 2 * math.pi * s / segments
            verts.append((math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi)))
    verts.append((0.0, -1.0, 0.0))
    for v in verts:
        lines.append("v %.6f %.6f %.6f" % v)
    for v in verts:
        lines.append("vn %.6f %.6f %.6f" % v)

    def ring(r, s):  # 1-based index of vertex s on ring r (1 .. rings-1)
        return 2 + (r - 1) * segments + (s % segments)

    last = len(verts)
    for s in range(segments):
        a, b = ring(1, s), ring(1, s + 1)
        lines.append("f %d//%d %d//%d %d//%d" % (1, 1, a, a, b, b))
    for r in range(1, rings - 1):
        for s in range(segments):
            a, b, c, d = ring(r, s), ring(r + 1, s), ring(r + 1, s + 1), ring(r, s + 1)
            lines.append("f %d//%d %d//%d %d//%d %d//%d" % (a, a, b, b, c, c, d, d))
    for s in range(segments):
        a, b = ring(rings - 1, s), ring(rings - 1, s + 1)
        lines.append("f %d//%d %d//%d %d//%d" % (a, a, last, last, b, b))
    with open(os.path.join(OUT, "sphere.obj"), "w") as f:
        f.write("\n".join(lines) + "\n")


def write_cube(name="cube.obj", half=0.5, title="Unit cube centred at the origin"):
    lines = ["# %s, flat faces. Made by tools/make-scene-models.py." % title]
    for x in (-half, half):
        for y in (-half, half):
            for z in (-half, half):
                lines.append("v %g %g %g" % (x, y, z))
    # Vertex k has bits (x, y, z) = (k>>2, k>>1, k) & 1; faces wound outwards.
    faces = [(1, 2, 4, 3), (5, 7, 8, 6), (1, 5, 6, 2), (3, 4, 8, 7), (1, 3, 7, 5), (2, 6, 8, 4)]
    for f in faces:
        lines.append("f %d %d %d %d" % f)
    with open(os.path.join(OUT, name), "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    write_cornell()
    write_cornell("cornell-box-empty.obj", with_light=False)
    write_sphere()
    write_cube()
    write_cube("grid-box.obj", 1.0, "The cube [-1, 1]^3 around an OpenVDB grid")
