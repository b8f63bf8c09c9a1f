#include "sinew/forms/inertia_form.hpp"

#include <fmt/format.h>

#include "sinew/core/error.hpp"
#include "sinew/element/mass.hpp"

namespace sinew {

MassMatrix::MassMatrix(const Discretization& disc, double density, MassKind kind)
    : kind_(kind), lumped_(lumped_mass(disc, density)) {
  if (kind == MassKind::Consistent) {
    // consistent_mass is the scalar matrix times I_3; keep one scalar entry per vertex pair.
    const Eigen::SparseMatrix<double> full = consistent_mass(disc, density);
    std::vector<Eigen::Triplet<double>> t;
    for (Eigen::Index c = 0; c < full.outerSize(); c += 3)
      for (Eigen::SparseMatrix<double>::InnerIterator it(full, c); it; ++it)
        if (it.row() % 3 == 0) t.emplace_back(it.row() / 3, c / 3, it.value());
    scalar_.resize(lumped_.size(), lumped_.size());
    scalar_.setFromTriplets(t.begin(), t.end());
    const auto& elements = disc.mesh().elements;
    for (Eigen::Index e = 0; e < elements.rows(); ++e) {
      std::vector<int> clique(elements.cols());
      for (Eigen::Index a = 0; a < elements.cols(); ++a) clique[a] = elements(e, a);
      elements_.push_back(std::move(clique));
    }
  }
}

void MassMatrix::couplings(std::vector<std::vector<int>>& cliques) const {
  cliques.insert(cliques.end(), elements_.begin(), elements_.end());
}

Eigen::VectorXd MassMatrix::apply(const Eigen::VectorXd& x) const {
  const auto X = x.reshaped(3, x.size() / 3);
  Eigen::MatrixXd Y(3, X.cols());
  if (kind_ == MassKind::Lumped) {
    Y = X * lumped_.asDiagonal();
  } else {
    Y = (scalar_ * X.transpose()).transpose();
  }
  return Y.reshaped();
}

void MassMatrix::add_to(BlockHessian& H, double scale) const {
  if (kind_ == MassKind::Lumped) {
    for (Eigen::Index v = 0; v < lumped_.size(); ++v)
      H.add_block(static_cast<int>(v), static_cast<int>(v), scale * lumped_(v) * Mat3::Identity());
    return;
  }
  for (Eigen::Index c = 0; c < scalar_.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(scalar_, c); it; ++it)
      H.add_block(static_cast<int>(it.row()), static_cast<int>(c), scale * it.value() * Mat3::Identity());
}

InertiaForm::InertiaForm(std::shared_ptr<const MassMatrix> mass, double time_step)
    : mass_(std::move(mass)), h_(time_step), x_pred_(Eigen::VectorXd::Zero(3 * mass_->lumped().size())) {
  if (!(time_step > 0.0) || !std::isfinite(time_step))
    throw Error(fmt::format("must be a positive finite number, got {}", time_step), "time_step");
}

void InertiaForm::set_prediction(const Eigen::VectorXd& x_n, const Eigen::VectorXd& v_n) { x_pred_ = x_n + h_ * v_n; }

double InertiaForm::value(const Eigen::VectorXd& x) const {
  const Eigen::VectorXd d = x - x_pred_;
  return 0.5 / (h_ * h_) * d.dot(mass_->apply(d));
}

void InertiaForm::add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const {
  g += mass_->apply(x - x_pred_) / (h_ * h_);
}

void InertiaForm::add_hessian(const Eigen::VectorXd&, BlockHessian& H) const { mass_->add_to(H, 1.0 / (h_ * h_)); }

DampingForm::DampingForm(std::shared_ptr<const MassMatrix> mass, std::shared_ptr<const Form> elastic,
                         Eigen::Index num_vertices, double alpha, double beta, double time_step)
    : mass_(std::move(mass)), elastic_(std::move(elastic)), alpha_(alpha), beta_(beta), h_(time_step),
      x_n_(Eigen::VectorXd::Zero(3 * num_vertices)) {
  if (!(alpha >= 0.0) || !(beta >= 0.0) || !std::isfinite(alpha) || !std::isfinite(beta))
    throw Error("Rayleigh coefficients must be finite and >= 0", "rayleigh");
  if (beta_ > 0.0) {
    std::vector<std::vector<int>> cliques;
    elastic_->couplings(cliques);
    stiffness_ = std::make_unique<BlockHessian>(num_vertices, cliques);
  }
}

void DampingForm::couplings(std::vector<std::vector<int>>& cliques) const {
  mass_->couplings(cliques);
  if (stiffness_) elastic_->couplings(cliques);
}

void DampingForm::begin_step(const Eigen::VectorXd& x_n) {
  x_n_ = x_n;
  if (stiffness_) {
    stiffness_->set_zero();
    elastic_->add_hessian(x_n, *stiffness_);
  }
}

Eigen::VectorXd DampingForm::apply_D(const Eigen::VectorXd& y) const {
  Eigen::VectorXd out = alpha_ * mass_->apply(y);
  if (stiffness_) out += beta_ * (stiffness_->matrix() * y);
  return out;
}

double DampingForm::value(const Eigen::VectorXd& x) const {
  const Eigen::VectorXd d = x - x_n_;
  return 0.5 / h_ * d.dot(apply_D(d));
}

void DampingForm::add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const { g += apply_D(x - x_n_) / h_; }

void DampingForm::add_hessian(const Eigen::VectorXd&, BlockHessian& H) const {
  if (alpha_ > 0.0) mass_->add_to(H, alpha_ / h_);
  if (!stiffness_) return;
  // K is made of full 3x3 vertex blocks, so the three columns of vertex b walk the same rows.
  const Eigen::SparseMatrix<double>& K = stiffness_->matrix();
  using It = Eigen::SparseMatrix<double>::InnerIterator;
  for (Eigen::Index b = 0; b < K.outerSize() / 3; ++b) {
    It c0(K, 3 * b), c1(K, 3 * b + 1), c2(K, 3 * b + 2);
    while (c0) {
      const int a = static_cast<int>(c0.row() / 3);
      Mat3 block;
      for (int i = 0; i < 3; ++i, ++c0, ++c1, ++c2) {
        block(i, 0) = c0.value();
        block(i, 1) = c1.value();
        block(i, 2) = c2.value();
      }
      H.add_block(a, static_cast<int>(b), beta_ / h_ * block);
    }
  }
}

}  // namespace sinew
