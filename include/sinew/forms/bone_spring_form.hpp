#pragma once
// Soft bone binding: E = sum over bound vertices k/2 |x_v - t_v(frame)|^2, with t_v the vertex's
// rest position carried by its bone's transform. Convex, Hessian k I on each bound vertex.
#include <memory>

#include "sinew/forms/form.hpp"
#include "sinew/motion/rig.hpp"

namespace sinew {

class BoneSpringForm final : public Form {
 public:
  BoneSpringForm(std::shared_ptr<const Rig> rig, RigBinding binding, Eigen::MatrixX3d rest, double stiffness);
  std::string name() const override { return "bone_springs"; }

  // Moves the targets to frame `frame`.
  void set_frame(double frame);
  const Eigen::VectorXd& targets() const { return targets_; }

  double value(const Eigen::VectorXd& x) const override;
  void add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void add_hessian(const Eigen::VectorXd& x, BlockHessian& H) const override;
  void couplings(std::vector<std::vector<int>>& cliques) const override;

 private:
  std::shared_ptr<const Rig> rig_;
  RigBinding binding_;
  Eigen::MatrixX3d rest_;
  double k_;
  Eigen::VectorXd targets_;
};

}  // namespace sinew
