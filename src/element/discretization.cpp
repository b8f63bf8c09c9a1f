#include "sinew/element/discretization.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "sinew/element/element_rule.hpp"
#include "sinew/element/mesh_validation.hpp"

namespace sinew {
namespace {

// Greedy colouring of elements by shared vertices, in element order.
std::vector<std::vector<Eigen::Index>> color_elements(const VolumeMesh& mesh) {
  std::vector<std::vector<Eigen::Index>> vertex_elements(mesh.num_vertices());
  for (Eigen::Index e = 0; e < mesh.num_elements(); ++e)
    for (Eigen::Index a = 0; a < mesh.elements.cols(); ++a) vertex_elements[mesh.elements(e, a)].push_back(e);
  std::vector<int> color(mesh.num_elements(), -1);
  std::vector<std::vector<Eigen::Index>> groups;
  std::vector<char> used;
  for (Eigen::Index e = 0; e < mesh.num_elements(); ++e) {
    used.assign(groups.size() + 1, 0);
    for (Eigen::Index a = 0; a < mesh.elements.cols(); ++a)
      for (Eigen::Index other : vertex_elements[mesh.elements(e, a)])
        if (color[other] >= 0) used[color[other]] = 1;
    int c = 0;
    while (used[c]) ++c;
    color[e] = c;
    if (c == static_cast<int>(groups.size())) groups.emplace_back();
    groups[c].push_back(e);
  }
  return groups;
}

// Greedy colouring of runs of consecutive elements by shared vertices. Runs of up to 1,024
// elements, at least ~32 runs when the mesh allows, so that each colour has work for several
// threads.
std::vector<std::vector<Discretization::ElementRun>> color_runs(const VolumeMesh& mesh) {
  const Eigen::Index n = mesh.num_elements();
  const Eigen::Index length = std::clamp<Eigen::Index>((n + 31) / 32, 16, 1024);
  const Eigen::Index runs = (n + length - 1) / length;
  // Runs touching each vertex (in increasing order, without repeats).
  std::vector<std::vector<int>> vertex_runs(mesh.num_vertices());
  for (Eigen::Index e = 0; e < n; ++e) {
    const int r = static_cast<int>(e / length);
    for (Eigen::Index a = 0; a < mesh.elements.cols(); ++a) {
      auto& list = vertex_runs[mesh.elements(e, a)];
      if (list.empty() || list.back() != r) list.push_back(r);
    }
  }
  std::vector<std::vector<int>> neighbours(runs);
  for (const auto& list : vertex_runs)
    for (int r : list)
      for (int o : list)
        if (o != r) neighbours[r].push_back(o);
  std::vector<int> color(runs, -1);
  std::vector<std::vector<Discretization::ElementRun>> groups;
  std::vector<char> used;
  for (Eigen::Index r = 0; r < runs; ++r) {
    used.assign(groups.size() + 1, 0);
    for (int o : neighbours[r])
      if (color[o] >= 0) used[color[o]] = 1;
    int c = 0;
    while (used[c]) ++c;
    color[r] = c;
    if (c == static_cast<int>(groups.size())) groups.emplace_back();
    groups[c].push_back({r * length, std::min(n, (r + 1) * length)});
  }
  return groups;
}

// Hash of a key of rounded edge coordinates.
struct KeyHash {
  size_t operator()(const std::vector<long long>& key) const {
    size_t h = key.size();
    for (long long v : key) h ^= std::hash<long long>()(v) + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
    return h;
  }
};

// Edge vectors X_a - X_0 (a = 1..n-1) of element e, as rows.
Eigen::MatrixX3d edge_vectors(const VolumeMesh& mesh, Eigen::Index e) {
  const Eigen::Index n = mesh.elements.cols();
  Eigen::MatrixX3d E(n - 1, 3);
  for (Eigen::Index a = 1; a < n; ++a) E.row(a - 1) = mesh.vertices.row(mesh.elements(e, a)) - mesh.vertices.row(mesh.elements(e, 0));
  return E;
}

}  // namespace

Discretization::Discretization(VolumeMesh mesh, const std::string& source) : mesh_(std::move(mesh)) {
  validate_mesh(mesh_, source);
  const QuadratureRule& rule = quadrature_rule(mesh_.kind);
  nodes_ = nodes_per_element(mesh_.kind);
  qpoints_ = static_cast<int>(rule.weights.size());
  // Rest shapes are grouped by their edge vectors rounded to a grid of 1e-9 of the mesh's
  // extent, and an element joins a group only if its edges agree with the group's first
  // element to 1e-12 of its own size (rounding can split equal shapes, never merge unequal ones).
  const double extent = mesh_.num_vertices() > 0
                            ? (mesh_.vertices.colwise().maxCoeff() - mesh_.vertices.colwise().minCoeff()).norm()
                            : 1.0;
  const double grid = 1e-9 * (extent > 0.0 ? extent : 1.0);
  std::unordered_map<std::vector<long long>, std::vector<int>, KeyHash> groups;
  std::vector<Eigen::Index> representative;  // first element of each rest shape
  shape_.resize(static_cast<size_t>(mesh_.num_elements()));
  std::vector<long long> key(static_cast<size_t>(3 * (nodes_ - 1)));
  for (Eigen::Index e = 0; e < mesh_.num_elements(); ++e) {
    const Eigen::MatrixX3d E = edge_vectors(mesh_, e);
    for (Eigen::Index a = 0; a < E.rows(); ++a)
      for (int c = 0; c < 3; ++c) key[static_cast<size_t>(3 * a + c)] = std::llround(E(a, c) / grid);
    auto& candidates = groups[key];
    int found = -1;
    for (int s : candidates) {
      const Eigen::MatrixX3d R = edge_vectors(mesh_, representative[static_cast<size_t>(s)]);
      if ((R - E).cwiseAbs().maxCoeff() <= 1e-12 * E.cwiseAbs().maxCoeff()) {
        found = s;
        break;
      }
    }
    if (found < 0) {
      found = static_cast<int>(representative.size());
      representative.push_back(e);
      candidates.push_back(found);
    }
    shape_[static_cast<size_t>(e)] = found;
  }
  dN_dX_.reserve(representative.size() * static_cast<size_t>(qpoints_));
  weight_.reserve(representative.size() * static_cast<size_t>(qpoints_));
  for (const Eigen::Index e : representative) {
    Eigen::MatrixX3d X(nodes_, 3);
    for (int a = 0; a < nodes_; ++a) X.row(a) = mesh_.vertices.row(mesh_.elements(e, a));
    for (int q = 0; q < qpoints_; ++q) {
      const Mat3 J = X.transpose() * rule.dN_dxi[q];  // dX/dxi
      dN_dX_.push_back(rule.dN_dxi[q] * J.inverse());
      weight_.push_back(rule.weights[q] * J.determinant());
    }
  }
  colors_ = color_elements(mesh_);
  run_colors_ = color_runs(mesh_);
}

double Discretization::rest_volume(Eigen::Index e) const {
  double v = 0.0;
  for (int q = 0; q < qpoints_; ++q) v += weight(e, q);
  return v;
}

Eigen::Matrix3Xd Discretization::element_positions(Eigen::Index e, const Eigen::VectorXd& x) const {
  Eigen::Matrix3Xd xe(3, nodes_);
  for (int a = 0; a < nodes_; ++a) xe.col(a) = x.segment<3>(3 * mesh_.elements(e, a));
  return xe;
}

Mat3 Discretization::deformation_gradient(Eigen::Index e, int q, const Eigen::VectorXd& x) const {
  return element_positions(e, x) * gradients(e, q);
}

void add_element_hessian(const Eigen::MatrixX3d& D, const Mat9& H, double w, Eigen::MatrixXd& K) {
  const Eigen::Index n = D.rows();
  // T = H B with B(3k+i, 3b+i) = D(b,k): T(:, 3b+j) = sum_l H(:, 3l+j) D(b,l).
  Eigen::Matrix<double, 9, Eigen::Dynamic> T(9, 3 * n);
  for (Eigen::Index b = 0; b < n; ++b)
    for (int j = 0; j < 3; ++j)
      T.col(3 * b + j) = H.col(j) * D(b, 0) + H.col(3 + j) * D(b, 1) + H.col(6 + j) * D(b, 2);
  // K += w B^T T: row 3a+i of B^T T is sum_k D(a,k) T(3k+i, :).
  for (Eigen::Index a = 0; a < n; ++a)
    for (int i = 0; i < 3; ++i)
      K.row(3 * a + i) += w * (D(a, 0) * T.row(i) + D(a, 1) * T.row(3 + i) + D(a, 2) * T.row(6 + i));
}

}  // namespace sinew
