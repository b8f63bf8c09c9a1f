#pragma once
// Mirror-numbered elements (a file written with the opposite handedness) made positive.
#include "sinew/mesh/volume_mesh.hpp"

namespace sinew {

// Renumbers every element whose rest volume is negative: a tetrahedron swaps nodes 1 and 2,
// a hexahedron swaps its bottom and top faces. Returns how many were flipped. Degenerate
// elements and hexahedra with Jacobians of both signs are left for VolumeMesh::validate.
Eigen::Index reorient_inverted_elements(VolumeMesh& mesh);

}  // namespace sinew
