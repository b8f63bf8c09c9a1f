#pragma once
// A term of the total energy (PolyFEM's "forms"): elastic, corotational, gravity and loads,
// inertia, damping, penalty and self-contact, bone springs. Each exposes value, gradient and a
// PSD Hessian; Newton and the integrators know only the sum (assembly/problem.hpp). Forms that are
// sums over elements also expose the per-element interface (element_form.hpp).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "sinew/linalg/block_hessian.hpp"

namespace sinew {

class Form {
 public:
  virtual ~Form() = default;
  virtual std::string name() const = 0;

  virtual double value(const Eigen::VectorXd& x) const = 0;
  // g += dE/dx
  virtual void add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const = 0;
  // H += d2E/dx2 (projected to PSD where the term is not convex)
  virtual void add_hessian(const Eigen::VectorXd& x, BlockHessian& H) const = 0;

  // Vertex groups the Hessian couples (for the sparsity pattern).
  virtual void couplings(std::vector<std::vector<int>>& /*cliques*/) const {}
  // False where the energy is undefined at x (e.g. an inverted element of a log-based
  // material): the line search treats such a step as infinitely costly.
  virtual bool is_valid(const Eigen::VectorXd& /*x*/) const { return true; }
  // Lagged state (e.g. self-contact targets), frozen while Newton iterates. begin_solve is
  // called at the start of each Newton solve (a quasistatic load step or a time step); refresh
  // whenever Newton has converged with the current state, and Newton goes on iterating if it
  // returns true (the energy changed). A form must change its energy only finitely often per
  // solve (e.g. only add terms in refresh), so the solve sees one energy between changes and
  // ends. Both return true if the energy changed.
  virtual bool begin_solve(const Eigen::VectorXd& /*x*/) { return false; }
  virtual bool refresh(const Eigen::VectorXd& /*x*/) { return false; }
  // True if the last refresh changed couplings(): the Hessian pattern is then rebuilt.
  virtual bool couplings_changed() const { return false; }
  // False for a form whose gradient and Hessian are deliberate approximations of its value's
  // derivatives (the corotational warped force), so a derivative check reports instead of fails.
  virtual bool exact_derivatives() const { return true; }
};

}  // namespace sinew
