#!/usr/bin/env python3
"""Writes the mesh pairs mmetric's `compare --mode pcc` is tested on (tests/mpeg_test.cpp): meshes
as a mesh codec (V-DMC) outputs them, decimated and quantised. Made from roving-datasets' models
(build/datasets, `bash scripts/build.sh` makes them); rerun from the repository root:
    /usr/bin/python3 tests/data/mpeg/make_meshes.py build/datasets

- fandisk10: A is the Fandisk decimated to 3,236 triangles, quantised to 10 bits, vertex colours
  from the position; B the 646-triangle decimation on the same grid, its colours with noise.
- rocker8: A is the Rocker Arm decimated to 1,004 triangles, quantised to 8 bits; B the same mesh
  requantised to a step of 4 (degenerate triangles included); no colour.
- fandisk10_points_b.ply: B's vertices alone, a point cloud (mmetric passes clouds through).
"""
import os
import struct
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
rng = np.random.Generator(np.random.PCG64(47))


def read_ply(path):
    """Vertices and triangles of roving-datasets' binary PLYs (float x y z, uchar/int lists)."""
    with open(path, "rb") as f:
        header = []
        while not header or header[-1] != "end_header":
            header.append(f.readline().decode().strip())
        data = f.read()
    counts = {line.split()[1]: int(line.split()[2]) for line in header if line.startswith("element")}
    props = [line.split() for line in header if line.startswith("property") and "list" not in line]
    fmt = {"float": "f4", "double": "f8", "uchar": "u1", "int": "i4", "uint": "u4"}
    vertex = np.frombuffer(data, dtype=[(p[2], "<" + fmt[p[1]]) for p in props], count=counts["vertex"])
    offset = vertex.nbytes
    faces = np.frombuffer(data, dtype=[("n", "u1"), ("i", "<i4", 3)], count=counts["face"], offset=offset)
    return np.stack([vertex["x"], vertex["y"], vertex["z"]], axis=1).astype(np.float64), faces["i"].astype(np.int64)


def write_ply(name, vertices, faces=None, colours=None):
    header = ["ply", "format binary_little_endian 1.0", f"element vertex {len(vertices)}",
              "property float x", "property float y", "property float z"]
    fields = [("x", "<f4"), ("y", "<f4"), ("z", "<f4")]
    if colours is not None:
        header += ["property uchar red", "property uchar green", "property uchar blue"]
        fields += [("red", "u1"), ("green", "u1"), ("blue", "u1")]
    if faces is not None:
        header += [f"element face {len(faces)}", "property list uchar int vertex_indices"]
    header.append("end_header")
    rows = np.zeros(len(vertices), dtype=fields)
    rows["x"], rows["y"], rows["z"] = vertices.T
    if colours is not None:
        rows["red"], rows["green"], rows["blue"] = colours.T
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(("\n".join(header) + "\n").encode())
        f.write(rows.tobytes())
        if faces is not None:
            for t in faces:
                f.write(struct.pack("<Biii", 3, *t))


def colours_of(v):
    return np.clip(np.round(127.5 + 127.5 * np.sin(v / 60 + np.array([0.0, 2.0, 4.0]))), 0, 255).astype(np.uint8)


datasets = sys.argv[1]
va, fa = read_ply(os.path.join(datasets, "fandisk-3236.ply"))
vb, fb = read_ply(os.path.join(datasets, "fandisk-646.ply"))
low, scale = va.min(0), 1023 / (va.max(0) - va.min(0)).max()
qa, qb = np.round((va - low) * scale), np.round((vb - low) * scale)
write_ply("fandisk10_a.ply", qa, fa, colours_of(qa))
noisy = np.clip(colours_of(qb).astype(int) + rng.integers(-8, 9, size=qb.shape), 0, 255).astype(np.uint8)
write_ply("fandisk10_b.ply", qb, fb, noisy)
write_ply("fandisk10_points_b.ply", qb, None, noisy)

v, f = read_ply(os.path.join(datasets, "rocker-arm-1004.ply"))
q = np.round((v - v.min(0)) * 255 / (v.max(0) - v.min(0)).max())
write_ply("rocker8_a.ply", q, f)
write_ply("rocker8_b.ply", np.round(q / 4) * 4, f)
