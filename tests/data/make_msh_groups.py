#!/usr/bin/python3
"""Writes the Gmsh test meshes with physical groups (run from this folder), in the layouts Gmsh
itself writes (Mesh.MshFileVersion 2.2 and 4.1, ASCII):

groups_v22.msh  two hexahedra on [0,2]x[0,1]x[0,1], version 2.2 (physical tag = first element tag)
groups_v41.msh  the same box as twelve tetrahedra, version 4.1 ($Entities carry the physical tags)
../../examples/features/meshes/beam_groups.msh  a 1 x 0.2 x 0.2 beam of 5 x 1 x 1 hexahedra split
                into tetrahedra, version 4.1, with groups "beam" (volume), "wall" (x = 0), "tip" (x = 1)

Groups (dimension, tag, name): (3, 1, "solid") both elements; (2, 1, "bottom") the faces at z = 0
(the tag repeats the volume's); (2, 2, "left") x = 0; (2, 3, "right") x = 2; (2, 7, unnamed) the top
of the second hexahedron; (2, 9, "unused") a name without elements. The face at y = 0 is written
without a physical group. Node tags are 101..112 (not 1-based), so the reader must map them.
"""

# Vertex k at x = k % 3, y = (k // 3) % 2, z = k // 6; tags 101 + k.
NODES = [(k % 3, (k // 3) % 2, k // 6) for k in range(12)]
TAG = [101 + k for k in range(12)]


def v(x, y, z):
    return x + 3 * y + 6 * z


HEXES = [[v(i, 0, 0), v(i + 1, 0, 0), v(i + 1, 1, 0), v(i, 1, 0),
          v(i, 0, 1), v(i + 1, 0, 1), v(i + 1, 1, 1), v(i, 1, 1)] for i in (0, 1)]
# Faces as quads (outward), by group.
FACES = {
    "bottom": [[v(i, 0, 0), v(i, 1, 0), v(i + 1, 1, 0), v(i + 1, 0, 0)] for i in (0, 1)],
    "left": [[v(0, 0, 0), v(0, 0, 1), v(0, 1, 1), v(0, 1, 0)]],
    "right": [[v(2, 0, 0), v(2, 1, 0), v(2, 1, 1), v(2, 0, 1)]],
    "top7": [[v(1, 0, 1), v(2, 0, 1), v(2, 1, 1), v(1, 1, 1)]],
    "front": [[v(i, 0, 0), v(i + 1, 0, 0), v(i + 1, 0, 1), v(i, 0, 1)] for i in (0, 1)],
}
SURFACE_TAG = {"bottom": 1, "left": 2, "right": 3, "top7": 7, "front": 0}
NAMES = [(3, 1, "solid"), (2, 1, "bottom"), (2, 2, "left"), (2, 3, "right"), (2, 9, "unused")]


def det(a, b, c, d):
    u = [b[i] - a[i] for i in range(3)]
    w = [c[i] - a[i] for i in range(3)]
    t = [d[i] - a[i] for i in range(3)]
    return (u[0] * (w[1] * t[2] - w[2] * t[1]) - u[1] * (w[0] * t[2] - w[2] * t[0])
            + u[2] * (w[0] * t[1] - w[1] * t[0]))


def tets(h):
    # Six tetrahedra around the diagonal 0-6, each made positive.
    out = []
    for a, b in ((1, 2), (2, 3), (3, 7), (7, 4), (4, 5), (5, 1)):
        t = [h[0], h[a], h[b], h[6]]
        if det(*[NODES[k] for k in t]) < 0:
            t[1], t[2] = t[2], t[1]
        out.append(t)
    return out


def triangles(q):
    return [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]


def names_section():
    lines = ["$PhysicalNames", str(len(NAMES))]
    lines += [f'{d} {t} "{n}"' for d, t, n in NAMES]
    return lines + ["$EndPhysicalNames"]


def write_v22(path):
    lines = ["$MeshFormat", "2.2 0 8", "$EndMeshFormat"] + names_section()
    lines += ["$Nodes", str(len(NODES))]
    lines += [f"{TAG[k]} {x} {y} {z}" for k, (x, y, z) in enumerate(NODES)]
    lines += ["$EndNodes"]
    elements = []
    for group, quads in FACES.items():
        for q in quads:  # type 3 quads; tags: physical, elementary
            elements.append(f"3 2 {SURFACE_TAG[group]} {10 + len(elements)} " + " ".join(str(TAG[k]) for k in q))
    for h in HEXES:
        elements.append("5 2 1 1 " + " ".join(str(TAG[k]) for k in h))
    lines += ["$Elements", str(len(elements))] + [f"{i + 1} {e}" for i, e in enumerate(elements)] + ["$EndElements"]
    open(path, "w").write("\n".join(lines) + "\n")


def write_v41(path):
    lines = ["$MeshFormat", "4.1 0 8", "$EndMeshFormat"] + names_section()
    # Entities: no points or curves, one surface entity per face group (entity tags 1..5), one volume.
    groups = list(FACES)
    lines += ["$Entities", f"0 0 {len(groups)} 1"]
    for e, group in enumerate(groups, start=1):
        phys = SURFACE_TAG[group]
        tags = f"1 {phys}" if phys else "0"
        lines.append(f"{e} 0 0 0 2 1 1 {tags} 0")
    lines.append("1 0 0 0 2 1 1 1 1 5 1 2 3 4 5")
    lines.append("$EndEntities")
    lines += ["$Nodes", f"1 {len(NODES)} {TAG[0]} {TAG[-1]}", f"3 1 0 {len(NODES)}"]
    lines += [str(t) for t in TAG] + [f"{x} {y} {z}" for (x, y, z) in NODES] + ["$EndNodes"]
    blocks, count = [], 0
    for e, group in enumerate(groups, start=1):
        tris = [t for q in FACES[group] for t in triangles(q)]
        blocks.append(f"2 {e} 2 {len(tris)}")
        for t in tris:
            count += 1
            blocks.append(f"{count} " + " ".join(str(TAG[k]) for k in t))
    volume = [t for h in HEXES for t in tets(h)]
    blocks.append(f"3 1 4 {len(volume)}")
    for t in volume:
        count += 1
        blocks.append(f"{count} " + " ".join(str(TAG[k]) for k in t))
    lines += ["$Elements", f"{len(groups) + 1} {count} 1 {count}"] + blocks + ["$EndElements"]
    open(path, "w").write("\n".join(lines) + "\n")


def write_beam(path):
    # Same layouts on a 6 x 2 x 2 grid of nodes, spacing 0.2.
    def b(i, j, k):
        return i + 6 * j + 12 * k
    nodes = [(round(0.2 * (n % 6), 10), round(0.2 * ((n // 6) % 2), 10), round(0.2 * (n // 12), 10)) for n in range(24)]
    hexes = [[b(i, 0, 0), b(i + 1, 0, 0), b(i + 1, 1, 0), b(i, 1, 0), b(i, 0, 1), b(i + 1, 0, 1), b(i + 1, 1, 1), b(i, 1, 1)]
             for i in range(5)]
    faces = {"wall": [b(0, 0, 0), b(0, 0, 1), b(0, 1, 1), b(0, 1, 0)], "tip": [b(5, 0, 0), b(5, 1, 0), b(5, 1, 1), b(5, 0, 1)]}
    global NODES
    saved, NODES = NODES, nodes
    volume = [t for h in hexes for t in tets(h)]
    NODES = saved
    lines = ["$MeshFormat", "4.1 0 8", "$EndMeshFormat", "$PhysicalNames", "3",
             '3 1 "beam"', '2 2 "wall"', '2 3 "tip"', "$EndPhysicalNames",
             "$Entities", "0 0 2 1", "1 0 0 0 0 0.2 0.2 1 2 0", "2 1 0 0 1 0.2 0.2 1 3 0",
             "1 0 0 0 1 0.2 0.2 1 1 2 1 2", "$EndEntities",
             "$Nodes", f"1 {len(nodes)} 1 {len(nodes)}", f"3 1 0 {len(nodes)}"]
    lines += [str(n + 1) for n in range(len(nodes))] + [f"{x:g} {y:g} {z:g}" for (x, y, z) in nodes] + ["$EndNodes"]
    blocks, count = [], 0
    for e, name in enumerate(("wall", "tip"), start=1):
        tris = triangles(faces[name])
        blocks.append(f"2 {e} 2 {len(tris)}")
        for t in tris:
            count += 1
            blocks.append(f"{count} " + " ".join(str(k + 1) for k in t))
    blocks.append(f"3 1 4 {len(volume)}")
    for t in volume:
        count += 1
        blocks.append(f"{count} " + " ".join(str(k + 1) for k in t))
    lines += ["$Elements", f"3 {count} 1 {count}"] + blocks + ["$EndElements"]
    open(path, "w").write("\n".join(lines) + "\n")


write_v22("groups_v22.msh")
write_v41("groups_v41.msh")
write_beam("../../examples/features/meshes/beam_groups.msh")
