#pragma once
// Backward Euler (paper 001 §5 writes its linearised velocity update, Eq. 19) posed as the
// minimisation of the incremental potential:
//   E_inertia(x) = 1/(2 h^2) (x - x_pred)^T M (x - x_pred),  x_pred = x_n + h v_n,
// added to the elastic and external potentials, so that grad = 0 is
//   M (x - x_n - h v_n) / h^2 = f(x), i.e. M (v_{n+1} - v_n) / h = f(x_{n+1}).
// Gravity stays a separate linear form (ExternalForceForm).
#include <Eigen/Sparse>
#include <memory>

#include "sinew/element/discretization.hpp"
#include "sinew/forms/form.hpp"

namespace sinew {

enum class MassKind { Lumped, Consistent };

// The mass matrix as a vertex-scalar matrix (the DOF matrix is it times I_3 per vertex pair).
class MassMatrix {
 public:
  MassMatrix(const Discretization& disc, double density, MassKind kind);
  MassKind kind() const { return kind_; }
  // y = M x over DOFs.
  Eigen::VectorXd apply(const Eigen::VectorXd& x) const;
  double kinetic_energy(const Eigen::VectorXd& v) const { return 0.5 * v.dot(apply(v)); }
  // H += scale * M.
  void add_to(BlockHessian& H, double scale) const;
  const Eigen::VectorXd& lumped() const { return lumped_; }  // per-vertex masses (row sums)
  // The vertex groups the matrix couples (the elements, for a consistent mass).
  void couplings(std::vector<std::vector<int>>& cliques) const;

 private:
  MassKind kind_;
  std::vector<std::vector<int>> elements_;  // consistent only
  Eigen::VectorXd lumped_;
  Eigen::SparseMatrix<double> scalar_;  // consistent only: V x V
};

class InertiaForm final : public Form {
 public:
  InertiaForm(std::shared_ptr<const MassMatrix> mass, double time_step);

  std::string name() const override { return "inertia"; }
  // Starts a step from positions x_n with velocities v_n (the prediction x_n + h v_n).
  void set_prediction(const Eigen::VectorXd& x_n, const Eigen::VectorXd& v_n);
  double time_step() const { return h_; }

  double value(const Eigen::VectorXd& x) const override;
  void add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void add_hessian(const Eigen::VectorXd& x, BlockHessian& H) const override;
  void couplings(std::vector<std::vector<int>>& cliques) const override { mass_->couplings(cliques); }

 private:
  std::shared_ptr<const MassMatrix> mass_;
  double h_;
  Eigen::VectorXd x_pred_;
};

// Rayleigh damping D = alpha M + beta K(x_n), K the (projected) elastic Hessian at the step's
// start, as the dissipation potential of the step:
//   E_damping(x) = 1/(2 h) (x - x_n)^T D (x - x_n),  grad = D v_{n+1}.
class DampingForm final : public Form {
 public:
  DampingForm(std::shared_ptr<const MassMatrix> mass, std::shared_ptr<const Form> elastic, Eigen::Index num_vertices,
              double alpha, double beta, double time_step);

  std::string name() const override { return "damping"; }
  // Freezes D at the step's start x_n.
  void begin_step(const Eigen::VectorXd& x_n);

  double value(const Eigen::VectorXd& x) const override;
  void add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void add_hessian(const Eigen::VectorXd& x, BlockHessian& H) const override;
  void couplings(std::vector<std::vector<int>>& cliques) const override;

 private:
  Eigen::VectorXd apply_D(const Eigen::VectorXd& y) const;
  std::shared_ptr<const MassMatrix> mass_;
  std::shared_ptr<const Form> elastic_;
  double alpha_, beta_, h_;
  Eigen::VectorXd x_n_;
  std::unique_ptr<BlockHessian> stiffness_;  // beta > 0 only: K(x_n)
};

}  // namespace sinew
