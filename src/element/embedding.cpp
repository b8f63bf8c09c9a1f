#include "sinew/element/embedding.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "sinew/core/error.hpp"
#include "sinew/element/element_rule.hpp"

namespace sinew {
namespace {

constexpr int kHexCorner[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                  {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};

struct Local {
  Eigen::VectorXd weights;
  double outside = std::numeric_limits<double>::infinity();  // 0 inside the element
};

// Barycentric coordinates of p in tetrahedron X (4 x 3).
Local tet_local(const Eigen::Matrix<double, 4, 3>& X, const Eigen::Vector3d& p) {
  Eigen::Matrix3d D;
  for (int i = 0; i < 3; ++i) D.col(i) = (X.row(i + 1) - X.row(0)).transpose();
  const Eigen::Vector3d l = D.partialPivLu().solve(p - X.row(0).transpose());
  Local out;
  out.weights.resize(4);
  out.weights << 1.0 - l.sum(), l(0), l(1), l(2);
  out.outside = std::max(0.0, -out.weights.minCoeff());
  return out;
}

// Inverts the trilinear map of hexahedron X (8 x 3) by Newton's method from the centre; the
// map is affine on lattice cells, where one step is exact.
Local hex_local(const Eigen::Matrix<double, 8, 3>& X, const Eigen::Vector3d& p) {
  Eigen::Vector3d xi = Eigen::Vector3d::Zero();
  for (int it = 0; it < 20; ++it) {
    Eigen::Matrix<double, 8, 3> dN;
    for (int a = 0; a < 8; ++a) {
      const double sx = kHexCorner[a][0], sy = kHexCorner[a][1], sz = kHexCorner[a][2];
      dN(a, 0) = 0.125 * sx * (1 + sy * xi.y()) * (1 + sz * xi.z());
      dN(a, 1) = 0.125 * sy * (1 + sx * xi.x()) * (1 + sz * xi.z());
      dN(a, 2) = 0.125 * sz * (1 + sx * xi.x()) * (1 + sy * xi.y());
    }
    const Eigen::Vector3d r = X.transpose() * hex_shape_functions(xi) - p;
    const Eigen::Matrix3d J = X.transpose() * dN;
    const Eigen::Vector3d step = J.partialPivLu().solve(r);
    if (!step.allFinite()) break;
    xi -= step;
    if (step.norm() < 1e-14 * (1.0 + xi.norm())) break;
  }
  Local out;
  out.weights = hex_shape_functions(xi);
  out.outside = std::max(0.0, xi.cwiseAbs().maxCoeff() - 1.0);
  return out;
}

Local local_coordinates(const VolumeMesh& mesh, Eigen::Index e, const Eigen::Vector3d& p) {
  if (mesh.kind == ElementKind::Tet4) {
    Eigen::Matrix<double, 4, 3> X;
    for (int a = 0; a < 4; ++a) X.row(a) = mesh.vertices.row(mesh.elements(e, a));
    return tet_local(X, p);
  }
  Eigen::Matrix<double, 8, 3> X;
  for (int a = 0; a < 8; ++a) X.row(a) = mesh.vertices.row(mesh.elements(e, a));
  return hex_local(X, p);
}

// Elements by the cells of a uniform grid their bounding boxes overlap.
class ElementGrid {
 public:
  explicit ElementGrid(const VolumeMesh& mesh) {
    boxes_.resize(static_cast<size_t>(mesh.num_elements()));
    double mean_size = 0.0;
    for (Eigen::Index e = 0; e < mesh.num_elements(); ++e) {
      for (int a = 0; a < mesh.elements.cols(); ++a) boxes_[e].extend(Eigen::Vector3d(mesh.vertices.row(mesh.elements(e, a))));
      bounds_.extend(boxes_[e]);
      mean_size += boxes_[e].sizes().maxCoeff();
    }
    mean_size /= static_cast<double>(mesh.num_elements());
    // About one element per grid cell, at most 64 cells along the longest side (262,144 lists).
    h_ = std::max(mean_size, bounds_.sizes().maxCoeff() / 64.0);
    dims_ = ((bounds_.sizes() / h_).array().floor().cast<int>() + 1).matrix();
    cells_.resize(static_cast<size_t>(dims_.prod()));
    for (Eigen::Index e = 0; e < mesh.num_elements(); ++e) {
      const Eigen::Vector3i lo = cell(boxes_[e].min()), hi = cell(boxes_[e].max());
      for (int k = lo.z(); k <= hi.z(); ++k)
        for (int j = lo.y(); j <= hi.y(); ++j)
          for (int i = lo.x(); i <= hi.x(); ++i) cells_[index(i, j, k)].push_back(static_cast<int>(e));
    }
  }
  const std::vector<int>& candidates(const Eigen::Vector3d& p) const {
    static const std::vector<int> none;
    if (!bounds_.contains(p)) return none;
    const Eigen::Vector3i c = cell(p);
    return cells_[index(c.x(), c.y(), c.z())];
  }

 private:
  Eigen::Vector3i cell(const Eigen::Vector3d& p) const {
    return ((p - bounds_.min()) / h_).array().floor().cast<int>().max(0).min(dims_.array() - 1).matrix();
  }
  size_t index(int i, int j, int k) const { return (static_cast<size_t>(k) * dims_.y() + j) * dims_.x() + i; }

  std::vector<Eigen::AlignedBox3d> boxes_;
  Eigen::AlignedBox3d bounds_;
  double h_ = 1.0;
  Eigen::Vector3i dims_;
  std::vector<std::vector<int>> cells_;
};

}  // namespace

Eigen::MatrixX3d Embedding::positions(const Eigen::VectorXd& x) const {
  Eigen::MatrixX3d out = Eigen::MatrixX3d::Zero(num_points(), 3);
  for (Eigen::Index p = 0; p < num_points(); ++p)
    for (Eigen::Index a = 0; a < nodes.cols(); ++a) out.row(p) += weights(p, a) * x.segment<3>(3 * nodes(p, a)).transpose();
  return out;
}

Embedding embed_points(const VolumeMesh& mesh, const Eigen::MatrixX3d& points) {
  if (mesh.num_elements() == 0) throw Error("cannot embed points in a mesh without elements", "embedding");
  const int n = nodes_per_element(mesh.kind);
  const ElementGrid grid(mesh);
  Embedding out;
  out.nodes.resize(points.rows(), n);
  out.weights.resize(points.rows(), n);
  out.element.resize(static_cast<size_t>(points.rows()));
  for (Eigen::Index p = 0; p < points.rows(); ++p) {
    const Eigen::Vector3d x = points.row(p);
    if (!x.allFinite()) throw Error(fmt::format("point {} has a non-finite coordinate", p), "embedding");
    Local best;
    Eigen::Index best_e = -1;
    auto consider = [&](Eigen::Index e) {
      Local l = local_coordinates(mesh, e, x);
      if (l.outside < best.outside) best = std::move(l), best_e = e;
    };
    for (int e : grid.candidates(x)) {
      consider(e);
      if (best.outside == 0.0) break;
    }
    // Outside every candidate (a point beyond the mesh): the nearest element of all.
    if (best.outside > 1e-9)
      for (Eigen::Index e = 0; e < mesh.num_elements(); ++e) consider(e);
    out.element[static_cast<size_t>(p)] = static_cast<int>(best_e);
    out.weights.row(p) = best.weights.transpose();
    out.nodes.row(p) = mesh.elements.row(best_e);
    out.max_outside = std::max(out.max_outside, best.outside);
  }
  return out;
}

}  // namespace sinew
