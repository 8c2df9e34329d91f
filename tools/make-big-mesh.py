#!/usr/bin/env python3
"""Writes the large meshes for the cost-growth benchmark (tools/bench.sh).

    python3 tools/make-big-mesh.py [--levels 2] [--source ../shared/models/dragon.ply] [--out build/bench-meshes]
    python3 tools/make-big-mesh.py --split 11      # one mesh: every triangle cut into 11² = 121

Each level is a midpoint subdivision of the one before: every triangle is
cut into four at its edge midpoints (shared edges share their midpoint, so
the mesh stays connected). The full Stanford dragon (871,414 triangles)
gives 3.49 M triangles at level 1 and 13.9 M at level 2. The surface is not
smoothed (no Loop weights): the shape and the image stay the dragon's, only
the triangle count grows, which is what the benchmark varies.

--split K instead cuts every triangle of the source once into K² (each edge
into K equal parts, the points of a shared edge shared by both triangles,
so the mesh stays connected), named <source stem>-split<K>.ply: K = 11 on
the dragon gives 105,441,094 triangles and 52.7 M vertices (2.0 GB), the
benchmark's "about 100 M". It is written in slices of faces, so that the
script needs about 1.5 GB of memory, not the whole mesh's index arrays.

Output: binary little-endian PLY (float x, y, z; uchar-counted int index
lists). About 265 MB at level 2: it goes under build/, never into the
repository. Needs numpy (Debian python3-numpy).
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


def split_layout(k):
    """The K² sub-triangles of one triangle (a, b, c) on its grid of points
    p(i, j) = a + i/K (b − a) + j/K (c − a), i + j ≤ K, numbered row by row.
    Returns (ij, triangles): ij the (i, j) of each grid point, triangles the
    K² sub-triangles as grid-point numbers, wound like (a, b, c)."""
    ij = np.array([(i, j) for j in range(k + 1) for i in range(k + 1 - j)], dtype=np.int64)
    number = {(int(i), int(j)): n for n, (i, j) in enumerate(ij)}
    triangles = []
    for j in range(k):
        for i in range(k - j):
            triangles.append((number[i, j], number[i + 1, j], number[i, j + 1]))  # pointing up
            if i + j <= k - 2:
                triangles.append((number[i + 1, j], number[i + 1, j + 1], number[i, j + 1]))  # pointing down
    assert len(triangles) == k * k
    return ij, np.array(triangles, dtype=np.int64)


def split_mesh_writer(positions, triangles, k):
    """Cuts every triangle into K² (see split_layout). Vertices are numbered
    the source's first, then K − 1 points per distinct edge (from its lower
    to its higher vertex number), then (K − 1)(K − 2)/2 inside each triangle.
    Returns (vertex_count, triangle_count, write_positions(f),
    write_faces(f)): the two writers emit the PLY body in slices."""
    n, m = len(positions), len(triangles)
    a, b, c = triangles[:, 0], triangles[:, 1], triangles[:, 2]
    ends = np.concatenate([np.stack([a, b], 1), np.stack([b, c], 1), np.stack([c, a], 1)])
    lo, hi = ends.min(axis=1), ends.max(axis=1)
    keys, edge_of = np.unique(lo * n + hi, return_inverse=True)
    edge_of = edge_of.reshape(3, m).T  # per triangle: edges ab, bc, ca
    forward = (ends[:, 0] < ends[:, 1]).reshape(3, m).T  # the edge runs lo → hi in the triangle's order
    edge_count = len(keys)
    ij, local = split_layout(k)
    i, j = ij[:, 0], ij[:, 1]
    inside = (i > 0) & (j > 0) & (i + j < k)
    inside_count = int(inside.sum())
    edge_base, inside_base = n, n + edge_count * (k - 1)
    vertex_count = inside_base + m * inside_count
    # Grid point p → which corner, edge or inside point it is: the edge's
    # step t counted from the triangle's own first corner of that edge.
    corner = np.full(len(ij), -1)
    corner[(i == 0) & (j == 0)], corner[(i == k) & (j == 0)], corner[(i == 0) & (j == k)] = 0, 1, 2
    on_edge = np.full(len(ij), -1)
    step = np.zeros(len(ij), dtype=np.int64)
    ab_points, bc_points, ca_points = (j == 0) & (i > 0) & (i < k), (i + j == k) & (i > 0) & (j > 0), (i == 0) & (j > 0) & (j < k)
    on_edge[ab_points], step[ab_points] = 0, i[ab_points]
    on_edge[bc_points], step[bc_points] = 1, j[bc_points]
    on_edge[ca_points], step[ca_points] = 2, k - j[ca_points]
    inside_number = np.cumsum(inside) - 1

    def write_positions(f):
        f.write(positions.astype("<f4").tobytes())
        t = np.arange(1, k, dtype=np.float64) / k
        for start in range(0, edge_count, 1 << 18):
            e = keys[start:start + (1 << 18)]
            p_lo, p_hi = positions[e // n].astype(np.float64), positions[e % n].astype(np.float64)
            points = p_lo[:, None, :] + t[None, :, None] * (p_hi - p_lo)[:, None, :]
            f.write(points.astype("<f4").tobytes())
        wa, wb, wc = ((k - i - j) / k)[inside], (i / k)[inside], (j / k)[inside]
        for start in range(0, m, 1 << 16):
            tri = triangles[start:start + (1 << 16)]
            pa, pb, pc = (positions[tri[:, q]].astype(np.float64) for q in range(3))
            points = (wa[None, :, None] * pa[:, None, :] + wb[None, :, None] * pb[:, None, :] +
                      wc[None, :, None] * pc[:, None, :])
            f.write(points.astype("<f4").tobytes())

    face_type = np.dtype([("n", "u1"), ("i", "<i4", (3,))])

    def write_faces(f):
        for start in range(0, m, 1 << 15):
            stop = min(m, start + (1 << 15))
            tri, edges, fwd = triangles[start:stop], edge_of[start:stop], forward[start:stop]
            number = np.empty((stop - start, len(ij)), dtype=np.int64)
            for p in np.flatnonzero(corner >= 0):
                number[:, p] = tri[:, corner[p]]
            for p in np.flatnonzero(on_edge >= 0):
                e, s = on_edge[p], step[p]
                along = np.where(fwd[:, e], s, k - s)  # steps from the edge's lower vertex
                number[:, p] = edge_base + edges[:, e] * (k - 1) + along - 1
            for p in np.flatnonzero(inside):
                number[:, p] = inside_base + np.arange(start, stop) * inside_count + inside_number[p]
            records = np.empty((stop - start) * len(local), dtype=face_type)
            records["n"] = 3
            records["i"] = number[:, local].reshape(-1, 3)
            f.write(records.tobytes())

    return vertex_count, m * k * k, write_positions, write_faces


def write_ply(path, comment, vertex_count, face_count, write_body):
    """Writes a binary little-endian PLY of float x y z vertices and
    uchar-counted int index lists: the header, then write_body(file), into a
    temporary file renamed over `path` at the end (never half a file)."""
    header = (
        "ply\nformat binary_little_endian 1.0\n"
        f"comment {comment} by sombra tools/make-big-mesh.py\n"
        f"element vertex {vertex_count}\nproperty float x\nproperty float y\nproperty float z\n"
        f"element face {face_count}\nproperty list uchar int vertex_indices\nend_header\n")
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        f.write(header.encode("ascii"))
        write_body(f)
    os.replace(tmp, path)


def write_split_ply(path, positions, triangles, k):
    vertex_count, triangle_count, write_positions, write_faces = split_mesh_writer(positions, triangles, k)
    if vertex_count >= 2**31:
        sys.exit(f"{path}: {vertex_count:,} vertices do not fit PLY's int indices")

    def write_body(f):
        write_positions(f)
        write_faces(f)

    write_ply(path, f"every triangle cut into {k}x{k}", vertex_count, triangle_count, write_body)
    return vertex_count, triangle_count


def write_binary_ply(path, positions, triangles):
    face_type = np.dtype([("n", "u1"), ("i", "<i4", (3,))])
    records = np.empty(len(triangles), dtype=face_type)
    records["n"] = 3
    records["i"] = triangles

    def write_body(f):
        f.write(positions.astype("<f4").tobytes())
        f.write(records.tobytes())

    write_ply(path, "midpoint subdivision", len(positions), len(triangles), write_body)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--source", default=os.path.join(ROOT, "..", "shared", "models", "dragon.ply"))
    parser.add_argument("--out", default=os.path.join(ROOT, "build", "bench-meshes"))
    parser.add_argument("--levels", type=int, default=2, choices=range(1, 4))
    parser.add_argument("--split", type=int, metavar="K", help="instead: cut every triangle into K² (2 ≤ K ≤ 16)")
    args = parser.parse_args()
    if args.split is not None and not 2 <= args.split <= 16:
        sys.exit("--split K takes 2 ≤ K ≤ 16")

    os.makedirs(args.out, exist_ok=True)
    stem = os.path.splitext(os.path.basename(args.source))[0]
    positions, triangles = read_binary_ply(args.source)
    if args.split is not None:
        path = os.path.join(args.out, f"{stem}-split{args.split}.ply")
        vertex_count, triangle_count = write_split_ply(path, positions, triangles, args.split)
        print(f"{path}: {triangle_count:,} triangles, {vertex_count:,} vertices")
        return
    for level in range(1, args.levels + 1):
        positions, triangles = subdivide(positions, triangles)
        path = os.path.join(args.out, f"{stem}-sub{level}.ply")
        write_binary_ply(path, positions, triangles)
        print(f"{path}: {len(triangles):,} triangles, {len(positions):,} vertices")


if __name__ == "__main__":
    main()
