#!/usr/bin/python3
"""Writes examples/meshes/arm.obj: the elbow-flexion arm of paper 000 Fig. 2/10 (upper arm with a
biceps bulge, elbow, forearm with a flexor bulge) as a closed, manifold triangle surface.

The shape is the signed distance arm_sdf() of experiments/elbow_experiment.cpp (same parts and
numbers, keep both in step), extracted with marching cubes (python3-skimage). Units: metres; the
arm lies along +x (shoulder at x = 0, elbow at x = 0.30, wrist at x = 0.56), biceps side +z.

    /usr/bin/python3 scripts/make_arm_mesh.py   (Debian python3-numpy, python3-skimage) [--spacing 0.004] [--out examples/meshes/arm.obj]
"""
import argparse
import os
import sys

import numpy as np
from skimage import measure

ELBOW_X, WRIST_X = 0.30, 0.56


def smooth_min(a, b, k):
    h = np.clip(0.5 + 0.5 * (b - a) / k, 0.0, 1.0)
    return b + (a - b) * h - k * h * (1.0 - h)


def tapered_capsule(p, a, b, ra, rb):
    a, b = np.asarray(a, float), np.asarray(b, float)
    ab = b - a
    t = np.clip(((p - a) @ ab) / (ab @ ab), 0.0, 1.0)
    closest = a + t[..., None] * ab
    return np.linalg.norm(p - closest, axis=-1) - (ra + t * (rb - ra))


def ellipsoid(p, c, r):
    q = p - np.asarray(c, float)
    r = np.asarray(r, float)
    k0 = np.linalg.norm(q / r, axis=-1)
    k1 = np.linalg.norm(q / (r * r), axis=-1)
    with np.errstate(divide="ignore", invalid="ignore"):
        d = np.where(k1 > 0.0, k0 * (k0 - 1.0) / np.where(k1 > 0.0, k1, 1.0), -r.min())
    return d


def arm_sdf(p):
    upper = tapered_capsule(p, (0, 0, 0), (ELBOW_X, 0, 0), 0.044, 0.040)
    biceps = ellipsoid(p, (0.15, 0.0, 0.024), (0.10, 0.034, 0.036))
    fore = tapered_capsule(p, (ELBOW_X, 0, 0), (WRIST_X, 0, 0), 0.040, 0.026)
    flexors = ellipsoid(p, (0.37, 0.0, 0.012), (0.08, 0.036, 0.030))
    d = smooth_min(upper, biceps, 0.012)
    d = smooth_min(d, fore, 0.012)
    return smooth_min(d, flexors, 0.012)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--spacing", type=float, default=0.004, help="marching-cubes grid spacing in metres")
    ap.add_argument("--out", default=os.path.join(os.path.dirname(__file__), "..", "examples", "meshes", "arm.obj"))
    args = ap.parse_args()
    h = args.spacing
    # Padded bounds of arm_bounds() so the surface is closed inside the grid.
    lo, hi = np.array([-0.06, -0.07, -0.07]), np.array([0.60, 0.07, 0.08])
    axes = [np.arange(lo[i], hi[i] + 0.5 * h, h) for i in range(3)]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1)
    field = arm_sdf(grid)
    verts, faces, _, _ = measure.marching_cubes(field, level=0.0, spacing=(h, h, h))
    verts += lo
    # Marching cubes puts a vertex on every crossed grid edge, so where the field is zero at a
    # grid node several vertices coincide (after the 5-decimal rounding of the file, too) and
    # the triangles between them have zero area. Weld vertices equal at the written precision
    # and drop the triangles that collapse (an edge collapse: the surface stays closed).
    verts, inverse = np.unique(np.round(verts, 5), axis=0, return_inverse=True)
    faces = inverse.reshape(-1)[faces]
    faces = faces[(faces[:, 0] != faces[:, 1]) & (faces[:, 1] != faces[:, 2]) & (faces[:, 2] != faces[:, 0])]
    # skimage orients triangles for increasing values outward-negative; make normals point out
    # (from negative inside to positive outside) by checking the signed volume.
    v0, v1, v2 = verts[faces[:, 0]], verts[faces[:, 1]], verts[faces[:, 2]]
    volume = np.einsum("ij,ij->i", v0, np.cross(v1, v2)).sum() / 6.0
    if volume < 0:
        faces = faces[:, ::-1]
        volume = -volume
    # Closed and manifold: every edge in exactly two triangles, once in each direction.
    edges = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    directed = {tuple(e) for e in edges.tolist()}
    if len(directed) != len(edges) or any((b, a) not in directed for a, b in directed):
        sys.exit("make_arm_mesh: surface is not closed and manifold")
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    tmp = args.out + ".tmp"
    with open(tmp, "w") as f:
        f.write("# Sinew elbow-flexion arm (scripts/make_arm_mesh.py), metres, +x shoulder to wrist, +z biceps side\n")
        f.write(f"# {len(verts)} vertices, {len(faces)} triangles, enclosed volume {volume:.6e} m^3\n")
        for v in verts:
            f.write(f"v {v[0]:.5f} {v[1]:.5f} {v[2]:.5f}\n")
        for t in faces + 1:
            f.write(f"f {t[0]} {t[1]} {t[2]}\n")
    os.replace(tmp, args.out)
    print(f"wrote {args.out}: {len(verts)} vertices, {len(faces)} triangles, volume {volume:.4e} m^3")


if __name__ == "__main__":
    main()
