#pragma once
// A form that is a sum of element energies, E(x) = sum_e U_e(x_e), with the per-element
// interface that energy-limiting constraints, a matrix-free operator and a GPU backend use:
// element values, gradients, (PSD) Hessians and element-local Hessian-vector products.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "sinew/element/discretization.hpp"
#include "sinew/forms/form.hpp"

namespace sinew {

// Which gradient of U_e is asked for (paper 001 §4.2, §6.2).
enum class JacobianKind {
  Exact,   // the true gradient of U_e(x) (for a corotational element: including the change of the rotation)
  Warped,  // the warped elastic force R K (R^T x - X) with the rotation held fixed (corotational only)
};
JacobianKind parse_jacobian_kind(const std::string& text);  // "exact" | "warped"
const char* to_string(JacobianKind kind);

class ElementForm : public Form {
 public:
  virtual const Discretization& discretization() const = 0;

  // U_e(x).
  virtual double element_value(Eigen::Index e, const Eigen::VectorXd& x) const = 0;
  // Every element's U_e(x) (energies resized to the element count), in parallel; a form may
  // share work between the elements or with later per-element calls at the same x.
  virtual void element_values(const Eigen::VectorXd& x, std::vector<double>& energies) const;
  // dU_e/dx over the element's nodes (3 * nodes entries, node-major).
  virtual Eigen::VectorXd element_gradient(Eigen::Index e, const Eigen::VectorXd& x,
                                           JacobianKind kind = JacobianKind::Exact) const = 0;
  virtual bool supports(JacobianKind kind) const { return kind == JacobianKind::Exact; }
  // The element's block of the form's Hessian (3 * nodes square, PSD as add_hessian assembles it).
  virtual Eigen::MatrixXd element_hessian(Eigen::Index e, const Eigen::VectorXd& x) const = 0;
  // The same matrix written into He, whose storage loops over many elements reuse. The default
  // copies element_hessian(); a form that can fill He without a temporary overrides it.
  virtual void element_hessian_into(Eigen::Index e, const Eigen::VectorXd& x, Eigen::MatrixXd& He) const {
    He = element_hessian(e, x);
  }
  // y = H_e dx_e for the element's nodal increment dx_e (3 * nodes): what a matrix-free operator
  // applies. The default forms H_e; a form may do it without.
  virtual Eigen::VectorXd element_hessian_product(Eigen::Index e, const Eigen::VectorXd& x,
                                                  const Eigen::VectorXd& dx_e) const {
    return element_hessian(e, x) * dx_e;
  }

  // The elements are the Hessian's couplings.
  void couplings(std::vector<std::vector<int>>& cliques) const override;
};

}  // namespace sinew
