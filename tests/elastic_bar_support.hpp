#pragma once
// A bar of cells(0) x cells(1) x cells(2) unit cells (hexahedra, or each split into six
// tetrahedra), linear co-rotational (E = 1000) at rest with Poisson ratio nu, the vertices up to
// `pinned_height` pinned: the Hessian the preconditioner tests solve with.
#include <Eigen/Core>
#include <cmath>
#include <memory>
#include <vector>

#include "sinew/assembly/problem.hpp"
#include "sinew/element/discretization.hpp"
#include "sinew/forms/elastic_form.hpp"
#include "sinew/material/families/corotational.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/solver/solver_context.hpp"

namespace sinew::test {

struct ElasticBar {
  std::shared_ptr<Discretization> disc;
  std::unique_ptr<Problem> problem;
  Eigen::VectorXd x;
  std::vector<char> fixed;

  ElasticBar(const Eigen::Vector3i& cells, double nu, bool tets, double pinned_height) {
    VolumeMesh mesh = box_lattice(Eigen::Vector3d::Zero(), cells.cast<double>(), cells);
    if (tets) mesh = tetrahedralize_hexes(mesh);
    disc = std::make_shared<Discretization>(std::move(mesh));
    problem = std::make_unique<Problem>(disc->mesh().num_vertices());
    const double E = 1e3, lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
    problem->add_form(std::make_shared<ElasticForm>(disc, std::make_shared<LinearCorotational>(lambda, mu)));
    problem->set_discretization(disc);
    x = disc->mesh().rest_positions();
    fixed.assign(static_cast<size_t>(x.size()), 0);
    for (Eigen::Index v = 0; v < disc->mesh().num_vertices(); ++v)
      if (disc->mesh().vertices(v, 2) <= pinned_height)
        for (int i = 0; i < 3; ++i) fixed[static_cast<size_t>(3 * v + i)] = 1;
    problem->set_fixed(fixed);
  }
  // Fixes one more DOF.
  void fix(Eigen::Index dof) {
    fixed[static_cast<size_t>(dof)] = 1;
    problem->set_fixed(fixed);
  }
  SolverContext context() const { return {disc, problem->fixed()}; }
  // A smooth right-hand side, zero at the fixed DOFs.
  Eigen::VectorXd rhs() const {
    Eigen::VectorXd b(x.size());
    for (Eigen::Index i = 0; i < b.size(); ++i) b(i) = fixed[static_cast<size_t>(i)] ? 0.0 : std::cos(0.37 * static_cast<double>(i));
    return b;
  }
};

}  // namespace sinew::test
