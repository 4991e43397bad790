#!/usr/bin/env python3
"""The IBSM golden pairs (tests/ibsm/README.md): small models whose mmetric figures are recorded.

Deterministic: run from this folder, `python3 make_pairs.py`, to write the files committed beside it.
  sphere-a.ply / sphere-b.ply          closed, vertex colours; B moved along the normals, recoloured
  cap-a.ply / cap-b.ply                open hemisphere, vertex colours; B coarser, colours shifted
  torus-a.obj / torus-b.obj            textured, UVs from exactly 0 to 1 (seams duplicated); B's texture
                                       quantised and blurred (torus-a.png, torus-b.png)
  globe-a.obj / globe-b.obj            textured sphere, poles and seam duplicated; B a coarser sphere with
                                       the same texture (globe.png)
"""
import numpy as np
from PIL import Image, ImageFilter


def icosphere(subdivisions):
    t = (1 + 5 ** 0.5) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
         (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
         (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11),
         (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    vertices = [np.array(p, float) / np.linalg.norm(p) for p in v]
    for _ in range(subdivisions):
        middle = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in middle:
                p = vertices[a] + vertices[b]
                vertices.append(p / np.linalg.norm(p))
                middle[key] = len(vertices) - 1
            return middle[key]

        f = [tri for a, b, c in f for tri in
             ((a, mid(a, b), mid(c, a)), (b, mid(b, c), mid(a, b)), (c, mid(c, a), mid(b, c)),
              (mid(a, b), mid(b, c), mid(c, a)))]
    return np.array(vertices), np.array(f)


def write_ply(path, positions, faces, colours):
    with open(path, "w") as out:
        out.write("ply\nformat ascii 1.0\n")
        out.write(f"element vertex {len(positions)}\nproperty float x\nproperty float y\nproperty float z\n")
        out.write("property uchar red\nproperty uchar green\nproperty uchar blue\n")
        out.write(f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n")
        for p, c in zip(positions, colours):
            out.write(f"{p[0]:.6f} {p[1]:.6f} {p[2]:.6f} {c[0]} {c[1]} {c[2]}\n")
        for t in faces:
            out.write(f"3 {t[0]} {t[1]} {t[2]}\n")


def write_obj(path, positions, uvs, faces, texture):
    name = path[:-4]
    with open(name + ".mtl", "w") as out:
        out.write(f"newmtl surface\nKa 1 1 1\nKd 1 1 1\nKs 0 0 0\nmap_Kd {texture}\n")
    with open(path, "w") as out:
        out.write(f"mtllib {name}.mtl\nusemtl surface\n")
        for p in positions:
            out.write(f"v {p[0]:.6f} {p[1]:.6f} {p[2]:.6f}\n")
        for uv in uvs:
            out.write(f"vt {uv[0]:.6f} {uv[1]:.6f}\n")
        for t in faces:
            out.write("f " + " ".join(f"{i + 1}/{i + 1}" for i in t) + "\n")


def field(p):  # a smooth colour field over the unit sphere, code values
    return np.clip(np.round(128 + 110 * np.stack([p[:, 0], np.sin(3 * p[:, 1]), p[:, 2] * p[:, 0]], 1)), 0, 255)


def grid(n_u, n_v, place):  # a (n_u + 1) x (n_v + 1) vertex grid, seams duplicated, u and v from 0 to 1
    u, v = np.meshgrid(np.linspace(0, 1, n_u + 1), np.linspace(0, 1, n_v + 1), indexing="ij")
    uv = np.stack([u.ravel(), v.ravel()], 1)
    faces = []
    for i in range(n_u):
        for j in range(n_v):
            a, b, c, d = i * (n_v + 1) + j, (i + 1) * (n_v + 1) + j, (i + 1) * (n_v + 1) + j + 1, i * (n_v + 1) + j + 1
            faces += [(a, b, c), (a, c, d)]
    return place(uv[:, 0], uv[:, 1]), uv, np.array(faces)


def torus(u, v, big=1.0, small=0.35):
    a, b = 2 * np.pi * u, 2 * np.pi * v
    return np.stack([(big + small * np.cos(b)) * np.cos(a), small * np.sin(b), -(big + small * np.cos(b)) * np.sin(a)], 1)


def globe(u, v):
    # The seam 0.3 rad off the x-y plane: on that plane it would lie on the sample row through the
    # centre of mmetric's views along y, where mmetric's tie between the two sides goes to whichever
    # triangle it draws first (docs/colour.md).
    a, b = 2 * np.pi * u + 0.3, np.pi * (v - 0.5)
    return np.stack([np.cos(b) * np.cos(a), np.sin(b), -np.cos(b) * np.sin(a)], 1)


def texture(size):
    y, x = np.mgrid[0:size, 0:size] / size
    rgb = np.stack([128 + 120 * np.sin(9 * x + 2 * y), 128 + 120 * np.cos(7 * y), 255 * ((x * 8).astype(int) % 2)], 2)
    return Image.fromarray(np.clip(np.round(rgb), 0, 255).astype(np.uint8))


def main():
    positions, faces = icosphere(4)
    write_ply("sphere-a.ply", positions, faces, field(positions).astype(int))
    moved = positions * (1 + 0.01 * np.sin(5 * positions[:, :1]))[:, :1]
    colours_b = field(positions)
    colours_b[:, 0] = np.clip(colours_b[:, 0] + 7, 0, 255)
    colours_b[:, 1] = np.round(colours_b[:, 1] * 0.9)
    write_ply("sphere-b.ply", moved, faces, colours_b.astype(int))

    for name, level in (("cap-a.ply", 4), ("cap-b.ply", 3)):
        positions, faces = icosphere(level)
        keep = np.all(positions[faces][:, :, 1] >= -1e-9, axis=1)  # y >= 0: open at the equator
        used = np.unique(faces[keep])
        index = -np.ones(len(positions), int)
        index[used] = np.arange(len(used))
        colours = field(positions[used])
        if name == "cap-b.ply":
            colours[:, 2] = np.clip(colours[:, 2] - 12, 0, 255)
        write_ply(name, positions[used], index[faces[keep]], colours.astype(int))

    image = texture(256)
    image.save("torus-a.png")
    degraded = Image.fromarray((np.asarray(image) // 16 * 16 + 8).astype(np.uint8)).filter(ImageFilter.BoxBlur(1))
    degraded.save("torus-b.png")
    positions, uvs, faces = grid(48, 24, torus)
    write_obj("torus-a.obj", positions, uvs, faces, "torus-a.png")
    write_obj("torus-b.obj", positions, uvs, faces, "torus-b.png")

    texture(128).transpose(Image.FLIP_LEFT_RIGHT).save("globe.png")
    for name, (n_u, n_v) in (("globe-a.obj", (64, 32)), ("globe-b.obj", (24, 12))):
        positions, uvs, faces = grid(n_u, n_v, globe)
        write_obj(name, positions, uvs, faces, "globe.png")


if __name__ == "__main__":
    main()
