#pragma once
// The elastic model the constrained stepper integrates (paper 001 §3, §5): nodal forces and a
// PSD stiffness for the backward-Euler matrix A = M + h^2 K, and each element's energy U_e with
// its gradient, from which the energy-limiting constraints C_e = 1 - U_e/U_max are built.
#include <Eigen/Core>
#include <Eigen/Sparse>
#include <memory>
#include <string>

#include "sinew/element/discretization.hpp"

namespace sinew {

// Which gradient of U_e serves as the constraint Jacobian (paper 001 §4.2, §6.2).
enum class JacobianKind {
  Exact,   // the true gradient of U_e(x), including the change of the element rotation
  Warped,  // the warped elastic force R K (R^T x - X) with the rotation held fixed
};
JacobianKind parse_jacobian_kind(const std::string& text);  // "exact" | "warped"
const char* to_string(JacobianKind kind);

class ElementEnergyModel {
 public:
  virtual ~ElementEnergyModel() = default;
  virtual std::string name() const = 0;
  virtual const Discretization& discretization() const = 0;

  // U_e(x) (paper 001 Eq. 13) and dU_e/dx over the element's nodes (3 * nodes, node-major).
  virtual double element_energy(Eigen::Index e, const Eigen::VectorXd& x) const = 0;
  virtual Eigen::VectorXd element_energy_gradient(Eigen::Index e, const Eigen::VectorXd& x,
                                                  JacobianKind kind) const = 0;
  virtual bool supports(JacobianKind kind) const = 0;
  // A PSD approximation of d2U_e/dx2 (3 * nodes square): the curvature of the energy
  // constraints that the SQP iteration adds to its quadratic model (paper 001 §5).
  virtual Eigen::MatrixXd element_energy_hessian(Eigen::Index e, const Eigen::VectorXd& x) const = 0;

  // Internal elastic forces -dE/dx and a PSD approximation of d2E/dx2 (3V x 3V).
  virtual Eigen::VectorXd forces(const Eigen::VectorXd& x) const = 0;
  virtual Eigen::SparseMatrix<double> stiffness(const Eigen::VectorXd& x) const = 0;
  // Both at once; a model may share work between them (the corotational element rotations).
  virtual void forces_and_stiffness(const Eigen::VectorXd& x, Eigen::VectorXd& f, Eigen::SparseMatrix<double>& K) const {
    f = forces(x);
    K = stiffness(x);
  }
};

}  // namespace sinew
