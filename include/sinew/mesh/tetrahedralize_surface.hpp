#pragma once
// Tetrahedral meshing of the solid a closed triangle surface bounds, through Gmsh's C++ API.
// The surface's triangles become the boundary of the tetrahedral mesh (so a render surface
// embedded in the result lies exactly on its boundary); triangles with an edge longer than
// `max_edge` are first split in their own plane (the shape does not change), because Gmsh
// keeps the boundary it is given and grows the inside from it: without the split a unit cube
// of 12 triangles became 6 tetrahedra whatever max_edge was. `max_edge` then bounds the edge
// length of the tetrahedra inside.
#include "sinew/mesh/triangle_surface.hpp"
#include "sinew/mesh/volume_mesh.hpp"

namespace sinew {

// Throws a sinew::Error when the surface is not closed or Gmsh cannot mesh it (for instance a
// self-intersecting surface); the result is validated (no inverted or degenerate tetrahedra).
VolumeMesh tetrahedralize_surface(const TriangleSurface& surface, double max_edge);

// Splits the surface's edges longer than max_edge at their midpoints, longest first (longest-
// edge bisection: each split halves the edge in both faces that share it, so the surface stays
// closed, keeps its orientation and its shape, and triangles do not degenerate). Existing
// vertices keep their indices. Throws a sinew::Error when the result would need more than
// `max_faces` triangles (a max_edge far too small for the surface).
TriangleSurface bisect_long_edges(const TriangleSurface& surface, double max_edge, Eigen::Index max_faces = 2'000'000);

}  // namespace sinew
