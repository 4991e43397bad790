#!/usr/bin/env python3
"""Writes the point-cloud pairs the MPEG figures are tested on (tests/mpeg_test.cpp), deterministically
(NumPy's PCG64, seeded). Rerun: python3 tests/data/mpeg/make_clouds.py (from the repository root).

- sphere10: A is 8,000 points on a sphere of radius 40 voxelised at 10 bits (integer coordinates,
  so some fall on one voxel: duplicates), with unit normals and colours; B is A coded as a
  geometry codec would, every coordinate requantised to a step of 2 (many duplicates), the colours
  with noise; B has no normals (pc_error takes D2's normals from A alone).
- torus11: 11-bit voxels of a torus, A with normals, B moved by rounded Gaussian noise; no colour.
- bunny_float: a float-coordinate cloud (not voxelised) with normals and colour, B jittered.
- sphere10's A once more, without normals (sphere10_a_bare), and its normals in a file of their own
  (sphere10_a_normals, pc_error's --inputNorm): A's points shuffled, with other normals (A's
  tilted at random), so that which normal a merged point keeps is the file's own.
- sphere10_a_nan_normals: sphere10's A with 60 of its normals NaN.
"""
import os
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
rng = np.random.Generator(np.random.PCG64(20261126))


def write_ply(name, points, normals=None, colours=None):
    fields = [("x", "<f4"), ("y", "<f4"), ("z", "<f4")]
    header = ["ply", "format binary_little_endian 1.0", f"element vertex {len(points)}",
              "property float x", "property float y", "property float z"]
    if normals is not None:
        fields += [("nx", "<f4"), ("ny", "<f4"), ("nz", "<f4")]
        header += ["property float nx", "property float ny", "property float nz"]
    if colours is not None:
        fields += [("red", "u1"), ("green", "u1"), ("blue", "u1")]
        header += ["property uchar red", "property uchar green", "property uchar blue"]
    header.append("end_header")
    rows = np.zeros(len(points), dtype=fields)
    rows["x"], rows["y"], rows["z"] = points.T
    if normals is not None:
        rows["nx"], rows["ny"], rows["nz"] = normals.T
    if colours is not None:
        rows["red"], rows["green"], rows["blue"] = colours.T
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(("\n".join(header) + "\n").encode())
        f.write(rows.tobytes())


def colours_of(points, scale):
    c = 127.5 + 127.5 * np.sin(points / scale + np.array([0.0, 2.0, 4.0]))
    return np.clip(np.round(c), 0, 255).astype(np.uint8)


def unit(v):
    return v / np.linalg.norm(v, axis=1, keepdims=True)


# sphere10
directions = unit(rng.normal(size=(8000, 3)))
a = np.round(512 + 40 * directions)
normals = unit(a - 512).astype(np.float32)
colours = colours_of(a, 9.0)
write_ply("sphere10_a.ply", a, normals, colours)
sphere = a, normals, colours
b = np.round(a / 2) * 2
noisy = np.clip(colours.astype(int) + rng.integers(-12, 13, size=colours.shape), 0, 255).astype(np.uint8)
write_ply("sphere10_b.ply", b, None, noisy)

# torus11
u, v = rng.uniform(0, 2 * np.pi, size=(2, 8000))
R, r = 600.0, 200.0
centre = np.array([1024.0, 1024.0, 1024.0])
surface = np.stack([(R + r * np.cos(v)) * np.cos(u), (R + r * np.cos(v)) * np.sin(u), r * np.sin(v)], axis=1)
ring = np.stack([R * np.cos(u), R * np.sin(u), np.zeros_like(u)], axis=1)
a = np.round(centre + surface)
write_ply("torus11_a.ply", a, unit(surface - ring).astype(np.float32))
b = np.clip(np.round(a + rng.normal(scale=1.5, size=a.shape)), 0, 2047)
write_ply("torus11_b.ply", b)

# bunny_float: an ellipsoid with bumps, in float coordinates
directions = unit(rng.normal(size=(6000, 3)))
radius = 1 + 0.1 * np.sin(5 * directions[:, 0]) * np.cos(3 * directions[:, 1])
a = (directions * radius[:, None] * np.array([0.08, 0.06, 0.05])).astype(np.float32)
# normals of the ellipsoid without the bumps: close, not exact, as estimated normals are
normals = unit(directions / np.array([0.08, 0.06, 0.05]) ** 2).astype(np.float32)
write_ply("blob_float_a.ply", a, normals, colours_of(a, 0.01))
b = (a + rng.normal(scale=0.0008, size=a.shape)).astype(np.float32)
write_ply("blob_float_b.ply", b, None, colours_of(b, 0.0105))

# sphere10's normals in a file of their own (drawn last: the files above stay as they were)
a, normals, colours = sphere
write_ply("sphere10_a_bare.ply", a, None, colours)
order = rng.permutation(len(a))
tilted = unit(normals + 0.3 * rng.normal(size=normals.shape)).astype(np.float32)
write_ply("sphere10_a_normals.ply", a[order], tilted[order])

# sphere10's A with normals as some tools write them: not unit (lengths 0.25 to 3) and a few of
# length 0. pc_error uses them as they are (D2 scales by the squared length); drawn last.
a, normals, colours = sphere
lengths = rng.uniform(0.25, 3.0, size=(len(a), 1))
lengths[rng.choice(len(a), size=40, replace=False)] = 0
write_ply("sphere10_a_scaled_normals.ply", a, (normals * lengths).astype(np.float32), colours)

# sphere10's A with 60 normals NaN, as a failed normal estimation writes them: pc_error computes on
# (D2 adds the coordinates' differences, unsquared, for a nearest point with a NaN normal); drawn last.
a, normals, colours = sphere
broken = normals.copy()
broken[rng.choice(len(a), size=60, replace=False)] = np.nan
write_ply("sphere10_a_nan_normals.ply", a, broken, colours)
