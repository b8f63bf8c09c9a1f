#!/usr/bin/env python3
"""Quarter of a thick-walled cylinder as a Gmsh 2.2 mesh with physical groups.

    python3 make_thick_cylinder_mesh.py NR out.msh

Annulus A = 1 <= R <= B = 2, angle 0..90 degrees, NR radial x 2 NR circumferential hexahedra,
one layer of thickness (B - A) / NR in z. Physical groups (docs/verification.md, section 4):
surfaces "inner" (R = A), "outer" (R = B), "symmetry_y" (the face on y = 0),
"symmetry_x" (the face on x = 0), "bottom" (z = 0), "top" (z = thickness); volume "wall".
"""
import math
import os
import sys

A, B = 1.0, 2.0


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    nr = int(sys.argv[1])
    if nr < 1:
        sys.exit("NR must be >= 1")
    nt = 2 * nr
    h = (B - A) / nr
    n = nr + 1

    def vid(i, j, k):  # 1-based Gmsh node id
        return 1 + k * n * (nt + 1) + j * n + i

    nodes = []
    for k in range(2):
        for j in range(nt + 1):
            t = 0.5 * math.pi * j / nt
            for i in range(n):
                r = A + (B - A) * i / nr
                x, y = r * math.cos(t), r * math.sin(t)
                if j == nt:
                    x = 0.0  # exactly on the symmetry plane x = 0
                nodes.append((vid(i, j, k), x, y, k * h))

    groups = {"inner": (2, 1), "outer": (2, 2), "symmetry_y": (2, 3), "symmetry_x": (2, 4),
              "bottom": (2, 5), "top": (2, 6), "wall": (3, 7)}
    elements = []  # (type, tag, nodes)
    # Boundary quads carry the groups; Sinew finds the boundary faces from the hexahedra.
    for j in range(nt):
        for k in range(1):
            elements.append((3, 1, [vid(0, j, 0), vid(0, j, 1), vid(0, j + 1, 1), vid(0, j + 1, 0)]))
            elements.append((3, 2, [vid(nr, j, 0), vid(nr, j + 1, 0), vid(nr, j + 1, 1), vid(nr, j, 1)]))
    for i in range(nr):
        elements.append((3, 3, [vid(i, 0, 0), vid(i + 1, 0, 0), vid(i + 1, 0, 1), vid(i, 0, 1)]))
        elements.append((3, 4, [vid(i, nt, 0), vid(i, nt, 1), vid(i + 1, nt, 1), vid(i + 1, nt, 0)]))
    for j in range(nt):
        for i in range(nr):
            elements.append((3, 5, [vid(i, j, 0), vid(i, j + 1, 0), vid(i + 1, j + 1, 0), vid(i + 1, j, 0)]))
            elements.append((3, 6, [vid(i, j, 1), vid(i + 1, j, 1), vid(i + 1, j + 1, 1), vid(i, j + 1, 1)]))
    for j in range(nt):
        for i in range(nr):
            elements.append((5, 7, [vid(i, j, 0), vid(i + 1, j, 0), vid(i + 1, j + 1, 0), vid(i, j + 1, 0),
                                    vid(i, j, 1), vid(i + 1, j, 1), vid(i + 1, j + 1, 1), vid(i, j + 1, 1)]))

    lines = ["$MeshFormat", "2.2 0 8", "$EndMeshFormat", "$PhysicalNames", str(len(groups))]
    lines += [f'{dim} {tag} "{name}"' for name, (dim, tag) in groups.items()]
    lines += ["$EndPhysicalNames", "$Nodes", str(len(nodes))]
    lines += [f"{i} {x:.17g} {y:.17g} {z:.17g}" for i, x, y, z in nodes]
    lines += ["$EndNodes", "$Elements", str(len(elements))]
    lines += [f"{e + 1} {t} 2 {tag} {tag} " + " ".join(map(str, vs)) for e, (t, tag, vs) in enumerate(elements)]
    lines += ["$EndElements"]
    tmp = sys.argv[2] + ".tmp"
    with open(tmp, "w") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(tmp, sys.argv[2])


if __name__ == "__main__":
    main()
