#pragma once
// Mass matrices from a uniform density: consistent (integrated N_a N_b with the element's own
// quadrature, exact for tets, 2x2x2 Gauss for hexes) and lumped (row sums of the consistent one).
#include <Eigen/Sparse>

#include "sinew/element/discretization.hpp"

namespace sinew {

// Per-vertex lumped masses (one entry per vertex).
Eigen::VectorXd lumped_mass(const Discretization& disc, double density);

// Consistent mass over DOFs (3V x 3V, the scalar matrix times I_3 per vertex pair).
Eigen::SparseMatrix<double> consistent_mass(const Discretization& disc, double density);

}  // namespace sinew
