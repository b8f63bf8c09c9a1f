#include "sinew/forms/hyperelastic_energy_model.hpp"

#include "sinew/core/error.hpp"

namespace sinew {

HyperelasticEnergyModel::HyperelasticEnergyModel(std::shared_ptr<const Discretization> disc,
                                                 std::shared_ptr<const Material> material)
    : form_(std::move(disc), std::move(material), Projection::Clamp) {
  form_.couplings(cliques_);
}

double HyperelasticEnergyModel::element_energy(Eigen::Index e, const Eigen::VectorXd& x) const {
  const Discretization& d = form_.discretization();
  const Eigen::Matrix3Xd xe = d.element_positions(e, x);
  double U = 0.0;
  for (int q = 0; q < d.quadrature_points(); ++q) U += d.weight(e, q) * form_.material().psi(xe * d.gradients(e, q));
  return U;
}

Eigen::VectorXd HyperelasticEnergyModel::element_energy_gradient(Eigen::Index e, const Eigen::VectorXd& x,
                                                                 JacobianKind kind) const {
  if (kind != JacobianKind::Exact)
    throw Error("a hyperelastic material has no warped-force Jacobian; use \"exact\"", "jacobian");
  const Discretization& d = form_.discretization();
  const Eigen::Matrix3Xd xe = d.element_positions(e, x);
  Eigen::Matrix3Xd ge = Eigen::Matrix3Xd::Zero(3, d.nodes());
  for (int q = 0; q < d.quadrature_points(); ++q) {
    const Eigen::MatrixX3d& D = d.gradients(e, q);
    ge += d.weight(e, q) * form_.material().pk1(xe * D) * D.transpose();
  }
  return ge.reshaped();
}

Eigen::MatrixXd HyperelasticEnergyModel::element_energy_hessian(Eigen::Index e, const Eigen::VectorXd& x) const {
  const Discretization& d = form_.discretization();
  const Eigen::Matrix3Xd xe = d.element_positions(e, x);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(3 * d.nodes(), 3 * d.nodes());
  for (int q = 0; q < d.quadrature_points(); ++q) {
    const Eigen::MatrixX3d& D = d.gradients(e, q);
    add_element_hessian(D, form_.material().projected_hessian(xe * D, Projection::Clamp), d.weight(e, q), K);
  }
  return K;
}

Eigen::VectorXd HyperelasticEnergyModel::forces(const Eigen::VectorXd& x) const {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
  form_.add_gradient(x, g);
  return -g;
}

Eigen::SparseMatrix<double> HyperelasticEnergyModel::stiffness(const Eigen::VectorXd& x) const {
  BlockHessian H(form_.discretization().mesh().num_vertices(), cliques_);
  form_.add_hessian(x, H);
  return H.matrix();
}

}  // namespace sinew
