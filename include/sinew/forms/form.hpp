#pragma once
// A term of the total energy (PolyFEM's "forms"): elastic, corotational, gravity and loads,
// inertia, damping, penalty and self-contact, bone springs. Each exposes value, gradient and a
// PSD Hessian; Newton and the integrators know only the sum (assembly/problem.hpp). Forms that are
// sums over elements also expose the per-element interface (element_form.hpp).
#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

#include "sinew/linalg/block_hessian.hpp"
#include "sinew/linalg/element_matrices.hpp"

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
  // True where add_hessian projects to PSD; add_exact_hessian then gives the true d2E/dx2 (the
  // derivative checker, forms/derivative_check.hpp, checks that one against differences of the
  // gradient, and the projected one for symmetry and definiteness).
  virtual bool projects_hessian() const { return false; }
  virtual void add_exact_hessian(const Eigen::VectorXd& x, BlockHessian& H) const { add_hessian(x, H); }

  // Matrix-free Newton systems (Problem::set_matrix_free): a form that supports it keeps its
  // Hessian as element matrices (prepare_hessian_product at each linearisation point, projected
  // unless `exact`) and applies it, instead of adding it to the assembled matrix.
  virtual bool supports_hessian_product() const { return false; }
  virtual void prepare_hessian_product(const Eigen::VectorXd& /*x*/, bool /*exact*/) {}
  // y += H p, and diagonal[v] += the 3x3 diagonal block of vertex v, for the prepared H.
  virtual void add_hessian_product(const Eigen::VectorXd& /*p*/, Eigen::VectorXd& /*y*/) const {}
  virtual void add_hessian_diagonal(std::vector<Mat3>& /*diagonal*/) const {}
  // The prepared Hessian as element matrices (global frame), for preconditioners that need more
  // than products (linalg/element_matrices.hpp): how many, and element e's vertices (returns
  // how many) and, unless K is null, its matrix.
  virtual Eigen::Index hessian_product_elements() const { return 0; }
  virtual int hessian_product_element(Eigen::Index /*e*/, int* /*vertices*/, ElementMatrix* /*K*/) const { return 0; }
  // Bytes the prepared Hessian keeps.
  virtual std::size_t hessian_product_bytes() const { return 0; }

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
  // Called after every accepted Newton step. A form may add terms here, never remove or refit
  // them (so the energy changes finitely often per solve), and returns true if it did.
  virtual bool add_at_iterate(const Eigen::VectorXd& /*x*/) { return false; }
  // Called at every linearisation point (Problem::hessian, once per Newton iterate, before the
  // Hessian is assembled). A form whose force has no potential (a follower pressure on an open
  // surface) restarts there the path along which its energy, minus the work of its force, is
  // integrated, so each line search from x sees the force's exact work; value(x) must not change.
  virtual void linearize_at(const Eigen::VectorXd& /*x*/) {}
  // True if the last refresh changed couplings(): the Hessian pattern is then rebuilt.
  virtual bool couplings_changed() const { return false; }
  // False for a form whose gradient and Hessian are deliberate approximations of its value's
  // derivatives (the corotational warped force), so a derivative check reports instead of fails.
  virtual bool exact_derivatives() const { return true; }
};

}  // namespace sinew
