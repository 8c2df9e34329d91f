#!/usr/bin/env python3
"""Checks tools/make-big-mesh.py's --split K on a closed tetrahedron (run by
CTest as make_big_mesh_split; exit 77, a skip, without numpy):

- K² triangles per source triangle, every vertex used;
- closed and consistently wound: every directed edge once, its reverse once
  (shared edges share their points), Euler characteristic 2;
- the same solid: the signed volume of the source, no zero-area triangle;
- the PLY written and read back gives the same counts.
"""
import importlib.util
import io
import os
import sys
import tempfile

try:
    import numpy as np
except ImportError:
    sys.exit(77)

HERE = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location("make_big_mesh", os.path.join(HERE, "make-big-mesh.py"))
mbm = importlib.util.module_from_spec(spec)
spec.loader.exec_module(mbm)

FACE = np.dtype([("n", "u1"), ("i", "<i4", (3,))])


def signed_volume(positions, triangles):
    v = positions[triangles].astype(np.float64)
    return np.einsum("ij,ij->i", v[:, 0], np.cross(v[:, 1], v[:, 2])).sum() / 6


def check(k, positions, triangles):
    vertex_count, triangle_count, write_positions, write_faces = mbm.split_mesh_writer(positions, triangles, k)
    out = io.BytesIO()
    write_positions(out)
    p = np.frombuffer(out.getvalue(), "<f4").reshape(-1, 3)
    out = io.BytesIO()
    write_faces(out)
    records = np.frombuffer(out.getvalue(), FACE)
    t = records["i"].astype(np.int64)
    assert np.all(records["n"] == 3)
    assert len(p) == vertex_count and len(t) == triangle_count == len(triangles) * k * k, (k, len(p), len(t))
    assert len(np.unique(t)) == vertex_count, "unused or missing vertices"
    directed = np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]])
    forward = set((directed[:, 0] * vertex_count + directed[:, 1]).tolist())
    backward = set((directed[:, 1] * vertex_count + directed[:, 0]).tolist())
    assert len(forward) == len(directed), "a directed edge twice: winding flipped or a duplicate"
    assert forward == backward, "an open edge: shared edges do not share their points"
    assert vertex_count - len(directed) // 2 + triangle_count == 2, "not a sphere's Euler characteristic"
    assert abs(signed_volume(p, t) - signed_volume(positions, triangles)) < 1e-5
    e1, e2 = p[t[:, 1]] - p[t[:, 0]], p[t[:, 2]] - p[t[:, 0]]
    assert np.linalg.norm(np.cross(e1, e2), axis=1).min() > 0, "a zero-area triangle"


def main():
    positions = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float32)
    triangles = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], dtype=np.int64)
    for k in (2, 3, 5, 11):
        check(k, positions, triangles)
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "tetra-split3.ply")
        vertex_count, triangle_count = mbm.write_split_ply(path, positions, triangles, 3)
        p, t = mbm.read_binary_ply(path)
        assert (len(p), len(t)) == (vertex_count, triangle_count) == (20, 36)
    print("make-big-mesh --split: ok")


if __name__ == "__main__":
    main()
