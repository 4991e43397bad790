#!/usr/bin/env python3
"""Writes a small scene laid out as the DTU MVS evaluation data set is (tests/dtu_test.cpp checks
`roving measure --protocol dtu` on it against DTUeval-python's own figures). Rerun from the
repository root:  /usr/bin/python3 tests/data/dtu/make_dataset.py

Units are DTU's millimetres. No random numbers: every coordinate follows from a formula.
- Points/stl/stl001_total.ply: the "structured light" ground truth, a point cloud: a sphere of
  radius 10 (Fibonacci lattice, 20,000 points), the table it stands on (z = -11, below the
  ground plane, so the protocol drops it) and a small far cluster at x = 35 (beyond max_dist of
  everything reconstructed, so completeness drops it).
- ObsMask/ObsMask1_10.mat: BB [-40, 40]^3, Res 2, ObsMask (41^3) observed where x < 8, but for
  the block y > 6, z < -4 (so that its three axes differ).
- ObsMask/Plane1.mat: P = [0 0 1 10.5]', the ground plane z = -10.5 (points with P.[x 1] > 0 kept).
- scan1_mesh.ply: the reconstruction, a mesh: the sphere with a ripple of 0.15, missing its cap
  above z = 8, a stray square 3.5 mm off its side (observed, within max_dist), a stray square far
  away at (-30, -30) (observed, beyond max_dist), a zero-area triangle and two unreferenced vertices.
- scan1_points.ply: the same reconstruction as a point cloud (its vertices and face centres).
"""
import os
import struct

import numpy as np
import scipy.io

HERE = os.path.dirname(os.path.abspath(__file__))


def write_ply(path, vertices, faces=None):
    header = ["ply", "format binary_little_endian 1.0", f"element vertex {len(vertices)}",
              "property float x", "property float y", "property float z"]
    if faces is not None:
        header += [f"element face {len(faces)}", "property list uchar int vertex_indices"]
    header.append("end_header")
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(("\n".join(header) + "\n").encode())
        f.write(np.asarray(vertices, dtype="<f4").tobytes())
        for t in faces if faces is not None else []:
            f.write(struct.pack("<Biii", 3, *t))


def fibonacci_sphere(n, radius):
    i = np.arange(n) + 0.5
    z = 1 - 2 * i / n
    r = np.sqrt(1 - z * z)
    phi = np.pi * (3 - np.sqrt(5)) * i
    return radius * np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1)


def ground_truth():
    sphere = fibonacci_sphere(20000, 10.0)
    g = np.arange(-14, 14.01, 0.5)
    table = np.stack(np.meshgrid(g, g, [-11.0], indexing="ij"), axis=-1).reshape(-1, 3)
    c = np.arange(-1, 1.01, 0.5)
    far = np.stack(np.meshgrid(35 + c, c, c, indexing="ij"), axis=-1).reshape(-1, 3)
    return np.concatenate([sphere, table, far])


def square(centre, u, v, size, cells):
    """A square of `cells` x `cells` quads (two triangles each) in the plane of u and v."""
    s = np.linspace(-size / 2, size / 2, cells + 1)
    a, b = np.meshgrid(s, s, indexing="ij")
    vertices = centre + a.reshape(-1, 1) * u + b.reshape(-1, 1) * v
    faces = []
    for i in range(cells):
        for j in range(cells):
            p = i * (cells + 1) + j
            faces += [(p, p + cells + 1, p + 1), (p + 1, p + cells + 1, p + cells + 2)]
    return vertices, np.array(faces)


def reconstruction():
    rings, segments = 40, 80
    theta = np.linspace(0, np.pi, rings + 1)[1:-1]  # the poles apart
    phi = np.linspace(0, 2 * np.pi, segments, endpoint=False)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    r = 10 + 0.15 * np.sin(3 * t) * np.sin(2 * p)
    vertices = np.stack([r * np.sin(t) * np.cos(p), r * np.sin(t) * np.sin(p), r * np.cos(t)], axis=-1).reshape(-1, 3)
    faces = []
    for i in range(rings - 2):
        for j in range(segments):
            a, b = i * segments + j, i * segments + (j + 1) % segments
            c, d = a + segments, b + segments
            if vertices[a, 2] > 8 or vertices[c, 2] > 8:
                continue  # the missing cap
            faces += [(a, c, b), (b, c, d)]
    parts = [(vertices, np.array(faces))]
    parts.append(square(np.array([0.0, -13.5, 0.0]), np.array([1.0, 0, 0]), np.array([0, 0, 1.0]), 4, 4))
    parts.append(square(np.array([-30.0, -30.0, 0.0]), np.array([1.0, 0, 0]), np.array([0, 0, 1.0]), 2, 2))
    all_vertices, all_faces = [], []
    base = 0
    for v, f in parts:
        all_vertices.append(v)
        all_faces.append(f + base)
        base += len(v)
    extra = np.array([[1.0, 1.0, 12.0], [1.0, 1.0, 12.0], [2.0, 2.0, 12.0], [5.0, -12.0, 3.0], [-5.0, -12.0, 3.0]])
    all_vertices.append(extra)
    all_faces.append(np.array([[base, base + 1, base + 2]]))  # zero area; the last two unreferenced
    return np.concatenate(all_vertices), np.concatenate(all_faces)


def main():
    write_ply(os.path.join(HERE, "Points/stl/stl001_total.ply"), ground_truth())
    n = 41
    ix = np.arange(n)
    x, y, z = np.meshgrid(ix * 2.0 - 40, ix * 2.0 - 40, ix * 2.0 - 40, indexing="ij")
    observed = (x < 8) & ~((y > 6) & (z < -4))
    os.makedirs(os.path.join(HERE, "ObsMask"), exist_ok=True)
    scipy.io.savemat(os.path.join(HERE, "ObsMask/ObsMask1_10.mat"),
                     {"ObsMask": observed, "BB": np.array([[-40.0, -40, -40], [40, 40, 40]]), "Res": 2.0},
                     do_compression=True)
    scipy.io.savemat(os.path.join(HERE, "ObsMask/Plane1.mat"), {"P": np.array([[0.0], [0], [1], [10.5]])})
    vertices, faces = reconstruction()
    write_ply(os.path.join(HERE, "scan1_mesh.ply"), vertices, faces)
    centres = vertices[faces].mean(axis=1)
    write_ply(os.path.join(HERE, "scan1_points.ply"), np.concatenate([vertices, centres]))


if __name__ == "__main__":
    main()
