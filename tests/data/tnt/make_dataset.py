#!/usr/bin/env python3
"""Writes a small scene laid out as a Tanks and Temples evaluation folder is (tests/tnt_test.cpp
checks `roving measure --protocol tanks-and-temples` on it against the toolbox's own figures).
Rerun from the repository root:  /usr/bin/python3 tests/data/tnt/make_dataset.py

Units are metres, as the benchmark's; tau 0.01 (Barn's and Meetingroom's), so tau / 2 = 0.005
thins both clouds. The only random numbers come from NumPy's PCG64 under a fixed seed.
- Bench.ply: the laser-scan ground truth, a point cloud: a sphere of radius 0.25 standing on the
  ground (a Fibonacci lattice of 25,000 points), the ground around it (a 1 cm grid over
  [-0.6, 0.6]^2, part of it outside the crop polygon) and a far cluster at x = 2 (outside it).
- Bench.json: the crop volume (Open3D's SelectionPolygonVolume): a non-convex hexagon across x and
  y, from z = -0.05 to z = 0.47 (the sphere's cap above is cropped away).
- Bench_trans.txt: the 4 x 4 alignment taking the reconstruction to the ground truth (a rotation
  of 0.3 rad, a scale of 1.1 and a shift), written as np.savetxt writes run.py's.
- Bench_mesh.ply: the reconstruction in its own frame, a mesh: the sphere on a latitude-longitude
  grid (140 x 220) with a ripple of 3 mm and noise of 2 mm, missing its cap above z = 0.45 (in the
  ground truth's frame), and a stray square (within the crop, off the surface).
- Bench_points.ply: the same reconstruction as a point cloud (the mesh's vertices).
For run.py's registration (RANSAC on the camera trajectories, then three rounds of ICP):
- Bench_COLMAP_SfM.log: the scene's reference trajectory, 60 cameras on a ring around the sphere,
  in the frame Bench_trans.txt takes to the ground truth (the reconstruction's above).
- Bench_moved_points.ply: the reconstruction in a frame of its own (turned 0.05 rad, scaled by
  0.97 and shifted a few cm from the one above), as another pipeline would have made it.
- Bench_moved.log: its camera trajectory, a video of 1,700 frames in that frame (more than 1,600:
  run.py then picks the reference's frames by the mapping file), each camera 2 mm off (normal
  noise), and three of the picked frames 0.4 m off (outliers RANSAC must leave out).
- Bench_mapping_reference.txt: which of the video's frames (1-based) each reference camera is.
"""
import json
import os
import struct

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))


def write_ply(path, vertices, faces=None):
    header = ["ply", "format binary_little_endian 1.0", f"element vertex {len(vertices)}",
              "property float x", "property float y", "property float z"]
    if faces is not None:
        header += [f"element face {len(faces)}", "property list uchar int vertex_indices"]
    header.append("end_header")
    with open(path, "wb") as f:
        f.write(("\n".join(header) + "\n").encode())
        f.write(np.asarray(vertices, dtype="<f4").tobytes())
        for t in faces if faces is not None else []:
            f.write(struct.pack("<Biii", 3, *t))


def ground_truth():
    n = 25000
    k = np.arange(n) + 0.5
    polar = np.arccos(1 - 2 * k / n)
    azimuth = np.pi * (1 + 5 ** 0.5) * k
    sphere = 0.25 * np.stack([np.sin(polar) * np.cos(azimuth), np.sin(polar) * np.sin(azimuth), np.cos(polar)], 1)
    sphere[:, 2] += 0.25
    g = np.arange(-0.6, 0.6 + 1e-9, 0.01)
    gx, gy = np.meshgrid(g, g, indexing="ij")
    ground = np.stack([gx.ravel(), gy.ravel(), np.zeros(gx.size)], 1)
    ground = ground[np.hypot(ground[:, 0], ground[:, 1]) > 0.05]  # under the sphere: unseen
    far = np.stack([2 + 0.01 * np.arange(500) % 0.2, 0.001 * np.arange(500), np.full(500, 0.1)], 1)
    return np.concatenate([sphere, ground, far])


def alignment():
    axis = np.array([1.0, 2.0, 3.0]) / np.sqrt(14.0)
    angle = 0.3
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    rotation = np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * k @ k
    t = np.eye(4)
    t[:3, :3] = 1.1 * rotation
    t[:3, 3] = [0.5, -0.2, 0.1]
    return t


def reconstruction():
    rng = np.random.default_rng(20261127)
    rows, columns = 140, 220
    polar = (np.arange(rows) + 0.5) / rows * np.pi
    azimuth = np.arange(columns) / columns * 2 * np.pi
    p, a = np.meshgrid(polar, azimuth, indexing="ij")
    radius = 0.25 + 0.003 * np.sin(7 * p) * np.cos(5 * a) + np.clip(rng.normal(0, 0.002, p.shape), -0.006, 0.006)
    points = np.stack([radius * np.sin(p) * np.cos(a), radius * np.sin(p) * np.sin(a), 0.25 + radius * np.cos(p)], 2)
    keep_rows = int(np.argmax(0.25 + 0.25 * np.cos(polar) <= 0.45))  # the first row below the cap
    points = points[keep_rows:].reshape(-1, 3)
    kept = rows - keep_rows
    faces = []
    for r in range(kept - 1):
        for c in range(columns):
            a0, a1 = r * columns + c, r * columns + (c + 1) % columns
            b0, b1 = a0 + columns, a1 + columns
            faces += [(a0, b0, a1), (a1, b0, b1)]
    # A stray square, 20 x 20 vertices, 6 cm beside the sphere: inside the crop, far from the truth.
    s = np.linspace(0, 0.08, 20)
    sx, sz = np.meshgrid(s, s, indexing="ij")
    square = np.stack([0.31 + 0 * sx.ravel(), -0.04 + sx.ravel(), 0.15 + sz.ravel()], 1)
    base = len(points)
    for i in range(19):
        for j in range(19):
            v = base + i * 20 + j
            faces += [(v, v + 20, v + 1), (v + 1, v + 20, v + 21)]
    points = np.concatenate([points, square])
    # Into the reconstruction's own frame: the alignment's inverse.
    t = np.linalg.inv(alignment())
    local = points @ t[:3, :3].T + t[:3, 3]
    return local, faces


def look_at(eye, target):
    """A camera-to-world pose looking from `eye` at `target`, z forward, y down (as COLMAP's)."""
    forward = (target - eye) / np.linalg.norm(target - eye)
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    down = np.cross(forward, right)
    pose = np.eye(4)
    pose[:3, :3] = np.stack([right, down, forward], 1)
    pose[:3, 3] = eye
    return pose


def moved():
    """The similarity from the reference trajectory's frame to the moved reconstruction's."""
    axis = np.array([-2.0, 1.0, 2.0]) / 3.0
    angle = 0.05
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    t = np.eye(4)
    t[:3, :3] = 0.97 * (np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * k @ k)
    t[:3, 3] = [0.03, -0.02, 0.01]
    return t


def write_log(path, poses):
    """A trajectory as the toolbox's write_trajectory writes it: per camera 'i i+1 count', then its 4 x 4."""
    with open(path, "w") as f:
        for i, pose in enumerate(poses):
            f.write(f"{i} {i + 1} {len(poses)}\n")
            f.write("\n".join(" ".join(f"{v:.12f}" for v in row) for row in pose) + "\n")


def trajectories():
    rng = np.random.default_rng(20261129)
    frames, picked = 1700, 60
    angles = np.arange(frames) / frames * 2 * np.pi
    centre = np.array([0.0, 0.0, 0.25])
    in_truth = [look_at(np.array([0.9 * np.cos(a), 0.9 * np.sin(a), 0.5 + 0.05 * np.sin(3 * a)]), centre)
                for a in angles]
    to_reference = np.linalg.inv(alignment())
    video = [moved() @ to_reference @ pose for pose in in_truth]
    for pose in video:
        pose[:3, 3] += rng.normal(0, 0.002, 3)
    frame_of = np.round(np.arange(picked) * frames / picked + 7).astype(int)  # 0-based
    for outlier in frame_of[[5, 23, 41]]:
        radial = video[outlier][:3, 3] - (moved() @ to_reference @ np.append(centre, 1))[:3]
        video[outlier][:3, 3] += 0.4 * radial / np.linalg.norm(radial)
    reference = [to_reference @ in_truth[f] for f in frame_of]
    return reference, video, frame_of


def main():
    write_ply(os.path.join(HERE, "Bench.ply"), ground_truth())
    np.savetxt(os.path.join(HERE, "Bench_trans.txt"), alignment())
    crop = {"class_name": "SelectionPolygonVolume", "version_major": 1, "version_minor": 0,
            "orthogonal_axis": "Z", "axis_min": -0.05, "axis_max": 0.47,
            "bounding_polygon": [[-0.5, -0.45, 0.0], [0.55, -0.5, 0.0], [0.5, 0.1, 0.0], [0.1, 0.15, 0.0],
                                 [0.45, 0.55, 0.0], [-0.45, 0.5, 0.0]]}
    with open(os.path.join(HERE, "Bench.json"), "w") as f:
        json.dump(crop, f, indent=1)
        f.write("\n")
    points, faces = reconstruction()
    write_ply(os.path.join(HERE, "Bench_mesh.ply"), points, faces)
    write_ply(os.path.join(HERE, "Bench_points.ply"), points)
    m = moved()
    write_ply(os.path.join(HERE, "Bench_moved_points.ply"), points @ m[:3, :3].T + m[:3, 3])
    reference, video, frame_of = trajectories()
    write_log(os.path.join(HERE, "Bench_COLMAP_SfM.log"), reference)
    write_log(os.path.join(HERE, "Bench_moved.log"), video)
    with open(os.path.join(HERE, "Bench_mapping_reference.txt"), "w") as f:
        f.write(f"{len(frame_of)}\n{len(video)}\n")
        f.write("".join(f"{i} {frame + 1}\n" for i, frame in enumerate(frame_of)))


if __name__ == "__main__":
    main()
