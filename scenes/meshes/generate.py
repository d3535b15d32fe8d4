#!/usr/bin/env python3
"""Regenerates the mesh assets of the bundled scenes, and the two procedural textures.

    python3 scenes/meshes/generate.py

Writes (paths relative to the repository root):

    scenes/meshes/torus.ply   binary little-endian PLY, 4608 triangles, per-vertex normals
    scenes/meshes/blob.ply    ASCII PLY, a lumpy "bunny-like" blob, 5120 triangles, normals
    scenes/meshes/crate.obj   Wavefront OBJ cube with per-face texture coordinates (vt) and normals
    textures/checker.png      512x512 checkerboard, 8x8 squares
    textures/uvgrid.png       512x256 coloured grid with an orientation mark

Everything is y-up, in units of about one. Only the Python standard library is used, and the
output is deterministic (same bytes on every run).
"""

import math
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
TEXTURES = os.path.join(ROOT, "textures")


# ---------------------------------------------------------------------------------------------
# small vector helpers


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def normalize(a):
    n = math.sqrt(dot(a, a))
    return (a[0] / n, a[1] / n, a[2] / n) if n > 0 else (0.0, 1.0, 0.0)


def vertex_normals(positions, faces):
    """Area-weighted average of the face normals around each vertex."""
    acc = [(0.0, 0.0, 0.0)] * len(positions)
    for a, b, c in faces:
        n = cross(sub(positions[b], positions[a]), sub(positions[c], positions[a]))
        for i in (a, b, c):
            acc[i] = add(acc[i], n)
    return [normalize(n) for n in acc]


# ---------------------------------------------------------------------------------------------
# PLY / OBJ writers


def write_ply_binary(path, positions, normals, faces):
    header = (
        "ply\n"
        "format binary_little_endian 1.0\n"
        "comment torus, y-up\n"
        f"element vertex {len(positions)}\n"
        "property float x\nproperty float y\nproperty float z\n"
        "property float nx\nproperty float ny\nproperty float nz\n"
        f"element face {len(faces)}\n"
        "property list uchar int vertex_indices\n"
        "end_header\n"
    )
    with open(path, "wb") as f:
        f.write(header.encode("ascii"))
        for p, n in zip(positions, normals):
            f.write(struct.pack("<6f", *p, *n))
        for face in faces:
            f.write(struct.pack("<B3i", 3, *face))


def write_ply_ascii(path, positions, normals, faces, comment):
    with open(path, "w", newline="\n") as f:
        f.write("ply\nformat ascii 1.0\n")
        f.write(f"comment {comment}\n")
        f.write(f"element vertex {len(positions)}\n")
        f.write("property float x\nproperty float y\nproperty float z\n")
        f.write("property float nx\nproperty float ny\nproperty float nz\n")
        f.write(f"element face {len(faces)}\n")
        f.write("property list uchar int vertex_indices\n")
        f.write("end_header\n")
        for p, n in zip(positions, normals):
            f.write("%.5f %.5f %.5f %.4f %.4f %.4f\n" % (*p, *n))
        for a, b, c in faces:
            f.write(f"3 {a} {b} {c}\n")


# ---------------------------------------------------------------------------------------------
# meshes


def torus(major=0.7, minor=0.28, nu=72, nv=32):
    """A torus around the y axis, centred at the origin."""
    positions, normals, faces = [], [], []
    for i in range(nu):
        phi = 2 * math.pi * i / nu
        cp, sp = math.cos(phi), math.sin(phi)
        for j in range(nv):
            theta = 2 * math.pi * j / nv
            ct, st = math.cos(theta), math.sin(theta)
            positions.append(((major + minor * ct) * cp, minor * st, (major + minor * ct) * sp))
            normals.append((ct * cp, st, ct * sp))
    for i in range(nu):
        for j in range(nv):
            a = i * nv + j
            b = ((i + 1) % nu) * nv + j
            c = ((i + 1) % nu) * nv + (j + 1) % nv
            d = i * nv + (j + 1) % nv
            faces.append((a, d, c))
            faces.append((a, c, b))
    return positions, normals, faces


def icosphere(subdivisions):
    t = (1 + math.sqrt(5)) / 2
    verts = [
        (-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0),
        (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
        (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1),
    ]
    verts = [normalize(v) for v in verts]
    faces = [
        (0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11),
        (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6), (7, 1, 8),
        (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9),
        (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1),
    ]
    for _ in range(subdivisions):
        cache = {}

        def midpoint(a, b):
            key = (min(a, b), max(a, b))
            if key not in cache:
                m = normalize(add(verts[a], verts[b]))
                cache[key] = len(verts)
                verts.append(m)
            return cache[key]

        new_faces = []
        for a, b, c in faces:
            ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
            new_faces += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = new_faces
    return verts, faces


def blob():
    """A lumpy creature: a squashed body with a head bump in front and two long ears.

    The unit sphere is pushed out along a sum of smooth bumps; the result sits on y = 0 and
    faces +z, about 1.2 units long.
    """
    dirs, faces = icosphere(4)
    bumps = [
        # (direction, height, sharpness)
        (normalize((0.0, 0.55, 0.85)), 0.45, 6.0),   # head, up and forward
        (normalize((-0.25, 1.0, 0.15)), 0.75, 40.0),  # left ear
        (normalize((0.25, 1.0, 0.15)), 0.75, 40.0),   # right ear
        (normalize((0.0, 0.1, -1.0)), 0.15, 12.0),   # tail
        (normalize((0.0, -1.0, 0.0)), -0.25, 3.0),   # flat-ish underside
    ]
    positions = []
    for d in dirs:
        r = 1.0
        for b, h, k in bumps:
            r += h * math.exp(k * (dot(d, b) - 1.0))
        # a gentle ripple so the surface is not perfectly smooth
        r += 0.02 * math.sin(9 * d[0]) * math.sin(7 * d[1]) * math.sin(8 * d[2])
        positions.append((0.5 * r * d[0] * 1.1, 0.5 * r * d[1] * 0.85, 0.5 * r * d[2] * 1.25))
    lowest = min(p[1] for p in positions)
    positions = [(x, y - lowest, z) for x, y, z in positions]
    return positions, vertex_normals(positions, faces), faces


def write_crate_obj(path):
    """A unit cube centred at the origin; each face maps the whole texture, upright."""
    # (normal, right, up) for each face, seen from outside.
    sides = [
        ((0, 0, 1), (1, 0, 0), (0, 1, 0)),
        ((0, 0, -1), (-1, 0, 0), (0, 1, 0)),
        ((1, 0, 0), (0, 0, -1), (0, 1, 0)),
        ((-1, 0, 0), (0, 0, 1), (0, 1, 0)),
        ((0, 1, 0), (1, 0, 0), (0, 0, -1)),
        ((0, -1, 0), (1, 0, 0), (0, 0, 1)),
    ]
    lines = ["# textured cube, y-up, side 1, centred at the origin", "o crate"]
    vs, vts, vns, fs = [], [], [], []
    for n, r, u in sides:
        base = len(vs)
        for s, t in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            vs.append(tuple(0.5 * (n[k] + s * r[k] + t * u[k]) for k in range(3)))
        vns.append(n)
        vi = [base + 1, base + 2, base + 3, base + 4]
        ni = len(vns)
        # texture coordinates in the usual OBJ convention: v = 0 at the bottom of the image
        ti = [1, 2, 3, 4]
        fs.append(" ".join(f"{vi[k]}/{ti[k]}/{ni}" for k in range(4)))
    vts = [(0, 0), (1, 0), (1, 1), (0, 1)]
    lines += ["v %g %g %g" % v for v in vs]
    lines += ["vt %g %g" % t for t in vts]
    lines += ["vn %g %g %g" % n for n in vns]
    lines += ["f " + f for f in fs]
    with open(path, "w", newline="\n") as f:
        f.write("\n".join(lines) + "\n")


# ---------------------------------------------------------------------------------------------
# PNG textures


def write_png(path, width, height, pixel):
    rows = bytearray()
    for y in range(height):
        rows.append(0)
        for x in range(width):
            rows.extend(pixel(x, y))

    def chunk(kind, data):
        c = struct.pack(">I", len(data)) + kind + data
        return c + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    png = b"\x89PNG\r\n\x1a\n"
    png += chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(bytes(rows), 9))
    png += chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


def checker(x, y):
    light = ((x // 64) + (y // 64)) % 2 == 0
    return (235, 225, 205) if light else (60, 70, 95)


def hsv(h, s, v):
    i = int(h * 6) % 6
    f = h * 6 - int(h * 6)
    p, q, t = v * (1 - s), v * (1 - s * f), v * (1 - s * (1 - f))
    r, g, b = [(v, t, p), (q, v, p), (p, v, t), (p, q, v), (t, p, v), (v, p, q)][i]
    return (int(r * 255), int(g * 255), int(b * 255))


# A 5x7 letter "F": asymmetric both ways, so a flipped or mirrored mapping shows at once.
GLYPH_F = ["#####", "#....", "#....", "####.", "#....", "#....", "#...."]


def uvgrid(x, y):
    w, h = 512, 256
    # the "F" in the top-left cell, 4 px per glyph pixel
    gx, gy = (x - 12) // 4, (y - 4) // 4
    if 0 <= gx < 5 and 0 <= gy < 7 and GLYPH_F[gy][gx] == "#":
        return (255, 255, 255)
    if x % 32 in (0, 31) or y % 32 in (0, 31):
        return (20, 20, 20)
    cx, cy = x // 32, y // 32
    return hsv(cx / 16, 0.55 + 0.05 * (cy % 2), 0.95 - 0.5 * cy / 8)


# ---------------------------------------------------------------------------------------------


def main():
    os.makedirs(TEXTURES, exist_ok=True)
    p, n, f = torus()
    write_ply_binary(os.path.join(HERE, "torus.ply"), p, n, f)
    p, n, f = blob()
    write_ply_ascii(os.path.join(HERE, "blob.ply"), p, n, f, "lumpy blob, y-up, sits on y = 0")
    write_crate_obj(os.path.join(HERE, "crate.obj"))
    write_png(os.path.join(TEXTURES, "checker.png"), 512, 512, checker)
    write_png(os.path.join(TEXTURES, "uvgrid.png"), 512, 256, uvgrid)


if __name__ == "__main__":
    main()
