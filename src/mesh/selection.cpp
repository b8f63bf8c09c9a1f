#include "sinew/mesh/selection.hpp"

#include <algorithm>
#include <fmt/format.h>

#include "sinew/core/error.hpp"

namespace sinew {

std::vector<int> select_vertices(const Eigen::MatrixX3d& rest, const VertexSelector& selector,
                                 const std::string& context) {
  std::vector<int> out;
  // Tolerance relative to the model size, so selections on exact lattice planes are stable.
  const double scale = rest.rows() ? (rest.colwise().maxCoeff() - rest.colwise().minCoeff()).norm() : 1.0;
  const double tol = 1e-9 * std::max(scale, 1e-300);
  if (const auto* box = std::get_if<BoxSelector>(&selector)) {
    for (Eigen::Index v = 0; v < rest.rows(); ++v) {
      const Eigen::Vector3d p = rest.row(v).transpose();
      if (((p - box->lo).array() >= -tol).all() && ((box->hi - p).array() >= -tol).all()) out.push_back(static_cast<int>(v));
    }
  } else if (const auto* plane = std::get_if<PlaneSelector>(&selector)) {
    const double len = plane->normal.norm();
    if (!(len > 0.0)) throw Error("plane normal must be non-zero", context);
    const Eigen::Vector3d n = plane->normal / len;
    for (Eigen::Index v = 0; v < rest.rows(); ++v)
      if ((rest.row(v).transpose() - plane->point).dot(n) >= -tol) out.push_back(static_cast<int>(v));
  } else {
    for (int v : std::get<IndexSelector>(selector).indices) {
      if (v < 0 || v >= rest.rows())
        throw Error(fmt::format("vertex index {} out of range (mesh has {} vertices)", v, rest.rows()), context);
      out.push_back(v);
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  if (out.empty()) throw Error("selection contains no vertex", context);
  return out;
}

}  // namespace sinew
