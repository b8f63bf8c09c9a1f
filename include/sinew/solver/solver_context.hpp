#pragma once
// What a linear solver or preconditioner may know about the system besides its matrix: the
// discretisation it comes from, the lattice grid when the mesh is a lattice (geometric
// multigrid coarsens on it), and which DOFs are fixed (their rows and columns are the identity).
// Every part is optional: a solve on a bare matrix gets an empty context.
#include <Eigen/Core>
#include <memory>
#include <span>

#include "sinew/element/discretization.hpp"
#include "sinew/mesh/lattice_structure.hpp"

namespace sinew {

struct SolverContext {
  std::shared_ptr<const Discretization> discretization;  // null when unknown
  std::span<const char> fixed;  // one flag per DOF (empty: none known); valid during the solve

  // The mesh's lattice grid, or nullptr (no discretisation, or not a lattice).
  const LatticeStructure* lattice() const {
    return discretization && discretization->mesh().lattice ? &*discretization->mesh().lattice : nullptr;
  }
  bool is_fixed(Eigen::Index dof) const {
    return !fixed.empty() && fixed[static_cast<size_t>(dof)] != 0;
  }
};

}  // namespace sinew
