#!/usr/bin/env python3
"""Writes Cook's membrane as a legacy VTK hexahedral mesh (docs/verification.md).

The tapered panel with corners (0,0), (48,44), (48,60), (0,44) (mm), one layer of thickness 1 in
z, N x N trilinear hexahedra mapped from the unit square as in the reference computation
(x = 48 u; y between the lower edge 44/48 x and the upper edge 44 + 16/48 x at fraction v).
Vertex (i, j, k) is number k (N+1)^2 + j (N+1) + i, the numbering of
tests/verification_benchmarks_support.hpp (cook_membrane_mesh), which a test compares with the
checked-in files.

    python3 examples/verification/make_cook_membrane_mesh.py N [out.vtk]
"""
import sys


def cook_membrane_vtk(n_cells: int) -> str:
    n = n_cells + 1
    points = []
    for k in range(2):
        for j in range(n):
            for i in range(n):
                x = 48.0 * i / n_cells
                t = j / n_cells
                y = (1.0 - t) * (44.0 / 48.0) * x + t * (44.0 + (16.0 / 48.0) * x)
                points.append(f"{x:.17g} {y:.17g} {k}")

    def vid(i, j, k):
        return k * n * n + j * n + i

    cells = []
    for j in range(n_cells):
        for i in range(n_cells):
            ids = [vid(i, j, 0), vid(i + 1, j, 0), vid(i + 1, j + 1, 0), vid(i, j + 1, 0),
                   vid(i, j, 1), vid(i + 1, j, 1), vid(i + 1, j + 1, 1), vid(i, j + 1, 1)]
            cells.append("8 " + " ".join(map(str, ids)))
    lines = ["# vtk DataFile Version 3.0",
             f"Cook's membrane, {n_cells} x {n_cells} x 1 hexahedra (examples/verification/make_cook_membrane_mesh.py)",
             "ASCII", "DATASET UNSTRUCTURED_GRID", f"POINTS {len(points)} double", *points,
             f"CELLS {len(cells)} {9 * len(cells)}", *cells,
             f"CELL_TYPES {len(cells)}", *(["12"] * len(cells))]
    return "\n".join(lines) + "\n"


def main() -> int:
    if len(sys.argv) not in (2, 3) or not sys.argv[1].isdigit() or int(sys.argv[1]) < 1:
        print(__doc__, file=sys.stderr)
        return 2
    n_cells = int(sys.argv[1])
    out = sys.argv[2] if len(sys.argv) == 3 else f"cook_membrane_N{n_cells}.vtk"
    with open(out, "w", encoding="ascii") as f:
        f.write(cook_membrane_vtk(n_cells))
    return 0


if __name__ == "__main__":
    sys.exit(main())
