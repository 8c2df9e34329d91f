#!/usr/bin/env python3
"""Writes the large meshes for the cost-growth benchmark (tools/bench.sh).

    python3 tools/make-big-mesh.py [--levels 2] [--source ../shared/models/dragon.ply] [--out build/bench-meshes]

Each level is a midpoint subdivision of the one before: every triangle is
cut into four at its edge midpoints (shared edges share their midpoint, so
the mesh stays connected). The full Stanford dragon (871,414 triangles)
gives 3.49 M triangles at level 1 and 13.9 M at level 2. The surface is not
smoothed (no Loop weights): the shape and the image stay the dragon's, only
the triangle count grows, which is what the benchmark varies.

Output: binary little-endian PLY (float x, y, z; uchar-counted int index
lists), named <source stem>-sub<level>.ply. About 265 MB at level 2: it goes
under build/, never into the repository. Needs numpy (Debian python3-numpy).
"""
import argparse
import os
import sys

import numpy as np

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))


def read_binary_ply(path):
    """Positions (n×3 float32) and triangles (m×3 int64) of a binary little-endian
    PLY with 'element vertex' float x y z and 'element face' 'list uchar int'."""
    with open(path, "rb") as f:
        header = []
        while True:
            line = f.readline()
            if not line:
                sys.exit(f"{path}: no end_header")
            line = line.decode("ascii").strip()
            header.append(line)
            if line == "end_header":
                break
        if "format binary_little_endian 1.0" not in header:
            sys.exit(f"{path}: only binary little-endian PLY is supported")
        vertices = faces = None
        vertex_props = []
        for line in header:
            words = line.split()
            if words[:2] == ["element", "vertex"]:
                vertices = int(words[2])
            elif words[:2] == ["element", "face"]:
                faces = int(words[2])
            elif words[:1] == ["property"] and faces is None:
                vertex_props.append(words[1:])
        if vertex_props != [["float", "x"], ["float", "y"], ["float", "z"]]:
            sys.exit(f"{path}: expected vertex properties 'float x, y, z', got {vertex_props}")
        positions = np.frombuffer(f.read(12 * vertices), dtype="<f4").reshape(vertices, 3)
        face_type = np.dtype([("n", "u1"), ("i", "<i4", (3,))])
        records = np.frombuffer(f.read(face_type.itemsize * faces), dtype=face_type)
        if not np.all(records["n"] == 3):
            sys.exit(f"{path}: only triangle faces are supported")
        return positions, records["i"].astype(np.int64)


def subdivide(positions, triangles):
    """One midpoint subdivision: (a, b, c) → (a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)."""
    n = len(positions)
    a, b, c = triangles[:, 0], triangles[:, 1], triangles[:, 2]
    edges = np.concatenate([np.stack([a, b], 1), np.stack([b, c], 1), np.stack([c, a], 1)])
    lo, hi = edges.min(axis=1), edges.max(axis=1)
    keys, edge_of = np.unique(lo * n + hi, return_inverse=True)
    ends_lo, ends_hi = keys // n, keys % n
    mid = (0.5 * (positions[ends_lo].astype(np.float64) + positions[ends_hi])).astype(np.float32)
    m = len(triangles)
    ab, bc, ca = (n + edge_of[:m], n + edge_of[m:2 * m], n + edge_of[2 * m:])
    new_triangles = np.concatenate([
        np.stack([a, ab, ca], 1), np.stack([ab, b, bc], 1), np.stack([ca, bc, c], 1), np.stack([ab, bc, ca], 1)])
    return np.concatenate([positions, mid]), new_triangles


def write_binary_ply(path, positions, triangles):
    face_type = np.dtype([("n", "u1"), ("i", "<i4", (3,))])
    records = np.empty(len(triangles), dtype=face_type)
    records["n"] = 3
    records["i"] = triangles
    header = (
        "ply\nformat binary_little_endian 1.0\n"
        f"comment midpoint subdivision by sombra tools/make-big-mesh.py\n"
        f"element vertex {len(positions)}\nproperty float x\nproperty float y\nproperty float z\n"
        f"element face {len(triangles)}\nproperty list uchar int vertex_indices\nend_header\n")
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        f.write(header.encode("ascii"))
        f.write(positions.astype("<f4").tobytes())
        f.write(records.tobytes())
    os.replace(tmp, path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--source", default=os.path.join(ROOT, "..", "shared", "models", "dragon.ply"))
    parser.add_argument("--out", default=os.path.join(ROOT, "build", "bench-meshes"))
    parser.add_argument("--levels", type=int, default=2, choices=range(1, 4))
    args = parser.parse_args()

    os.makedirs(args.out, exist_ok=True)
    stem = os.path.splitext(os.path.basename(args.source))[0]
    positions, triangles = read_binary_ply(args.source)
    for level in range(1, args.levels + 1):
        positions, triangles = subdivide(positions, triangles)
        path = os.path.join(args.out, f"{stem}-sub{level}.ply")
        write_binary_ply(path, positions, triangles)
        print(f"{path}: {len(triangles):,} triangles, {len(positions):,} vertices")


if __name__ == "__main__":
    main()
