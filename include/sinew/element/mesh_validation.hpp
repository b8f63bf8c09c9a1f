#pragma once
// A mesh fit for simulation: valid topology (VolumeMesh::validate) and every element positively
// oriented and non-degenerate at every quadrature point.
#include <string>

#include "sinew/mesh/volume_mesh.hpp"

namespace sinew {

// Throws a sinew::Error naming `source` and the first bad element (out-of-range or repeated
// nodes, non-finite coordinates, or a rest Jacobian that is not positive at a quadrature point).
void validate_mesh(const VolumeMesh& mesh, const std::string& source);

}  // namespace sinew
