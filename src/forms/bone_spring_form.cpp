#include "sinew/forms/bone_spring_form.hpp"

#include <cmath>

#include "sinew/core/error.hpp"

namespace sinew {

BoneSpringForm::BoneSpringForm(std::shared_ptr<const Rig> rig, RigBinding binding, Eigen::MatrixX3d rest,
                               double stiffness)
    : rig_(std::move(rig)), binding_(std::move(binding)), rest_(std::move(rest)), k_(stiffness) {
  if (!(std::isfinite(k_) && k_ > 0.0)) throw Error("bone spring stiffness must be positive", "bone_springs");
  set_frame(0.0);
}

void BoneSpringForm::set_frame(double frame) { targets_ = rig_targets(*rig_, binding_, rest_, frame); }

double BoneSpringForm::value(const Eigen::VectorXd& x) const {
  double e = 0.0;
  for (int v : binding_.bound_vertices) e += 0.5 * k_ * (x.segment<3>(3 * v) - targets_.segment<3>(3 * v)).squaredNorm();
  return e;
}

void BoneSpringForm::add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const {
  for (int v : binding_.bound_vertices) g.segment<3>(3 * v) += k_ * (x.segment<3>(3 * v) - targets_.segment<3>(3 * v));
}

void BoneSpringForm::add_hessian(const Eigen::VectorXd& /*x*/, BlockHessian& H) const {
  const Mat3 K = k_ * Mat3::Identity();
  for (int v : binding_.bound_vertices) H.add_block(v, v, K);
}

void BoneSpringForm::couplings(std::vector<std::vector<int>>& cliques) const {
  for (int v : binding_.bound_vertices) cliques.push_back({v});
}

}  // namespace sinew
