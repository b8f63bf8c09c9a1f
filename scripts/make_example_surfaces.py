#!/usr/bin/env python3
"""Writes the closed example surfaces in examples/meshes/ (standard library only, deterministic).

  torus.obj / torus.ply   a torus (R = 0.35, r = 0.15) around z, centred at (0.5, 0.5, 0.15)
  blob.off                a bumpy sphere: an icosphere (3 subdivisions) with a radial wave
  sphere.stl              an icosphere of radius 0.5 (2 subdivisions), ASCII STL
  two_cubes_edge.obj      unit cubes [0,1]^3 and [1,2]x[1,2]x[0,1] sharing one edge: closed,
                          not manifold along that edge (the non-manifold voxelisation case)
Run: python3 scripts/make_example_surfaces.py [OUTPUT_DIR]
"""
import math
import os
import sys


def torus(nu=32, nv=16, R=0.35, r=0.15, c=(0.5, 0.5, 0.15)):
    verts, faces = [], []
    for i in range(nu):
        u = 2 * math.pi * i / nu
        for j in range(nv):
            v = 2 * math.pi * j / nv
            verts.append((c[0] + (R + r * math.cos(v)) * math.cos(u), c[1] + (R + r * math.cos(v)) * math.sin(u),
                          c[2] + r * math.sin(v)))
    idx = lambda i, j: (i % nu) * nv + (j % nv)
    for i in range(nu):
        for j in range(nv):
            a, b, cc, d = idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)
            faces += [(a, b, cc), (a, cc, d)]  # outward: u then v is counter-clockwise from outside
    return verts, faces


def icosphere(levels, radius=1.0, center=(0.0, 0.0, 0.0), bump=None):
    t = (1 + math.sqrt(5)) / 2
    verts = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
             (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    verts = [tuple(x / math.sqrt(1 + t * t) for x in v) for v in verts]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
             (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11),
             (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(levels):
        cache, out = {}, []

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in cache:
                m = [(verts[a][k] + verts[b][k]) / 2 for k in range(3)]
                n = math.sqrt(sum(x * x for x in m))
                verts.append(tuple(x / n for x in m))
                cache[key] = len(verts) - 1
            return cache[key]

        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            out += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = out
    scaled = []
    for v in verts:
        s = radius * (bump(v) if bump else 1.0)
        scaled.append(tuple(center[k] + s * v[k] for k in range(3)))
    return scaled, faces


def two_cubes_edge():
    def cube(o):
        return [(o[0] + x, o[1] + y, o[2] + z) for z in (0, 1) for y in (0, 1) for x in (0, 1)]
    # Quads of a unit cube with corners numbered x + 2y + 4z, outward.
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    verts, faces = [], []
    for origin in ((0, 0, 0), (1, 1, 0)):
        ids = []
        for p in cube(origin):
            if p not in verts:
                verts.append(p)
            ids.append(verts.index(p))
        for a, b, c, d in quads:
            faces += [(ids[a], ids[b], ids[c]), (ids[a], ids[c], ids[d])]
    return verts, faces


def fmt(x):
    return repr(round(x, 12))


def write_obj(path, verts, faces):
    with open(path, "w") as f:
        f.write("# written by scripts/make_example_surfaces.py\n")
        for v in verts:
            f.write("v " + " ".join(fmt(x) for x in v) + "\n")
        for a, b, c in faces:
            f.write(f"f {a + 1} {b + 1} {c + 1}\n")


def write_off(path, verts, faces):
    with open(path, "w") as f:
        f.write(f"OFF\n# written by scripts/make_example_surfaces.py\n{len(verts)} {len(faces)} 0\n")
        for v in verts:
            f.write(" ".join(fmt(x) for x in v) + "\n")
        for a, b, c in faces:
            f.write(f"3 {a} {b} {c}\n")


def write_ply(path, verts, faces):
    with open(path, "w") as f:
        f.write(f"ply\nformat ascii 1.0\ncomment written by scripts/make_example_surfaces.py\n"
                f"element vertex {len(verts)}\nproperty double x\nproperty double y\nproperty double z\n"
                f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n")
        for v in verts:
            f.write(" ".join(fmt(x) for x in v) + "\n")
        for a, b, c in faces:
            f.write(f"3 {a} {b} {c}\n")


def write_stl(path, verts, faces):
    with open(path, "w") as f:
        f.write("solid sphere\n")
        for a, b, c in faces:
            p, q, r = verts[a], verts[b], verts[c]
            u = [q[k] - p[k] for k in range(3)]
            w = [r[k] - p[k] for k in range(3)]
            n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]
            ln = math.sqrt(sum(x * x for x in n))
            f.write("  facet normal " + " ".join(fmt(x / ln) for x in n) + "\n    outer loop\n")
            for v in (p, q, r):
                f.write("      vertex " + " ".join(fmt(x) for x in v) + "\n")
            f.write("    endloop\n  endfacet\n")
        f.write("endsolid sphere\n")


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "examples", "meshes")
    os.makedirs(out, exist_ok=True)
    t = torus()
    write_obj(os.path.join(out, "torus.obj"), *t)
    write_ply(os.path.join(out, "torus.ply"), *t)
    wave = lambda v: 1.0 + 0.12 * math.sin(3 * math.atan2(v[1], v[0])) * (1 - v[2] * v[2])
    write_off(os.path.join(out, "blob.off"), *icosphere(3, 0.4, (0.5, 0.5, 0.5), wave))
    write_stl(os.path.join(out, "sphere.stl"), *icosphere(2, 0.5, (0.0, 0.0, 0.0)))
    write_obj(os.path.join(out, "two_cubes_edge.obj"), *two_cubes_edge())


if __name__ == "__main__":
    main()
