#include "sinew/element/nodal_fields.hpp"

#include <cmath>
#include <fmt/format.h>

#include "sinew/core/error.hpp"

namespace sinew {

Eigen::VectorXd nodal_average(const Discretization& disc, const Eigen::VectorXd& per_element) {
  const VolumeMesh& mesh = disc.mesh();
  if (per_element.size() != mesh.num_elements())
    throw Error(fmt::format("{} element values for {} elements", per_element.size(), mesh.num_elements()), "nodal_average");
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(mesh.num_vertices()), weight = Eigen::VectorXd::Zero(mesh.num_vertices());
  for (Eigen::Index e = 0; e < mesh.num_elements(); ++e) {
    if (!std::isfinite(per_element(e))) continue;
    const double w = disc.rest_volume(e);
    for (Eigen::Index a = 0; a < mesh.elements.cols(); ++a) {
      sum(mesh.elements(e, a)) += w * per_element(e);
      weight(mesh.elements(e, a)) += w;
    }
  }
  for (Eigen::Index v = 0; v < sum.size(); ++v) sum(v) = weight(v) > 0.0 ? sum(v) / weight(v) : 0.0;  // 0: in no element or only non-finite ones
  return sum;
}

Eigen::VectorXd interpolate_at_points(const Embedding& embedding, const Eigen::VectorXd& nodal) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(embedding.num_points());
  for (Eigen::Index p = 0; p < embedding.num_points(); ++p)
    for (Eigen::Index a = 0; a < embedding.nodes.cols(); ++a) {
      const int n = embedding.nodes(p, a);
      if (n < 0 || n >= nodal.size()) throw Error(fmt::format("point {} uses node {} of {}", p, n, nodal.size()), "interpolate_at_points");
      out(p) += embedding.weights(p, a) * nodal(n);
    }
  return out;
}

}  // namespace sinew
