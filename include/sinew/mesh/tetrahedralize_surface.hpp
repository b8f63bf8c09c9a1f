#pragma once
// Tetrahedral meshing of the solid a closed triangle surface bounds, through Gmsh's C++ API.
// The surface's triangles become the boundary of the tetrahedral mesh unchanged (so a render
// surface embedded in the result lies exactly on its boundary); `max_edge` bounds the edge
// length of the tetrahedra inside.
#include "sinew/mesh/triangle_surface.hpp"
#include "sinew/mesh/volume_mesh.hpp"

namespace sinew {

// Throws a sinew::Error when the surface is not closed or Gmsh cannot mesh it (for instance a
// self-intersecting surface); the result is validated (no inverted or degenerate tetrahedra).
VolumeMesh tetrahedralize_surface(const TriangleSurface& surface, double max_edge);

}  // namespace sinew
