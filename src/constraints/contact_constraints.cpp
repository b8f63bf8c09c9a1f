#include "sinew/constraints/contact_constraints.hpp"

#include "sinew/core/error.hpp"

namespace sinew {

ContactProvider ground_plane_contacts(const Eigen::Vector3d& normal, double offset, double friction,
                                      double margin) {
  if (!(normal.norm() > 0.0)) throw Error("ground normal must be non-zero", "ground");
  const Eigen::Vector3d n = normal.normalized();
  return [n, offset, friction, margin](const Eigen::VectorXd& x, double /*step_start*/, double /*step_end*/) {
    std::vector<ContactCandidate> out;
    for (Eigen::Index v = 0; v < x.size() / 3; ++v) {
      const double gap = n.dot(x.segment<3>(3 * v)) - offset;
      if (gap < margin) out.push_back({static_cast<int>(v), n, gap, friction, Eigen::Vector3d::Zero()});
    }
    return out;
  };
}

}  // namespace sinew
