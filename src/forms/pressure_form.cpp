#include "sinew/forms/pressure_form.hpp"

#include <fmt/format.h>
#include <map>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

// A quadrature point on the reference face: weight, shape functions and their derivatives in
// the face coordinates (u, w).
struct FacePoint {
  double weight;
  std::array<double, 4> N, Nu, Nw;
};

// Triangle (0,0), (1,0), (0,1): the centroid rule is exact (n da is constant, N linear).
// Bilinear quad on [0,1]^2, nodes (0,0), (1,0), (1,1), (0,1): 2x2 Gauss, exact for the force,
// the stiffness and the enclosed volume (polynomials of degree <= 2 in u and in w).
const std::vector<FacePoint>& face_rule(std::size_t nodes) {
  static const std::vector<FacePoint> triangle{{0.5, {1 / 3.0, 1 / 3.0, 1 / 3.0, 0}, {-1, 1, 0, 0}, {-1, 0, 1, 0}}};
  static const std::vector<FacePoint> quad = [] {
    std::vector<FacePoint> q;
    const double g = 0.5 / std::sqrt(3.0);
    for (double u : {0.5 - g, 0.5 + g})
      for (double w : {0.5 - g, 0.5 + g})
        q.push_back({0.25,
                     {(1 - u) * (1 - w), u * (1 - w), u * w, (1 - u) * w},
                     {-(1 - w), 1 - w, w, -w},
                     {-(1 - u), -u, u, 1 - u}});
    return q;
  }();
  return nodes == 3 ? triangle : quad;
}

Mat3 cross_matrix(const Vec3& a) {
  Mat3 A;
  A << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return A;
}

}  // namespace

PressureForm::PressureForm(std::vector<std::vector<int>> faces, const Eigen::VectorXd& rest, double pressure)
    : faces_(std::move(faces)), pressure_(pressure), path_start_(rest) {
  if (faces_.empty()) throw Error("a pressure load needs at least one face", "pressure");
  if (!std::isfinite(pressure_)) throw Error("the pressure must be finite", "pressure");
  // Net directed use of each edge: interior edges of a consistently oriented surface cancel;
  // what is left is the surface's rim, in its faces' orientation.
  std::map<std::pair<int, int>, int> net;
  Vec3 sum = Vec3::Zero();
  int corners = 0;
  for (const auto& f : faces_) {
    if (f.size() != 3 && f.size() != 4) throw Error(fmt::format("a face has {} nodes (3 or 4)", f.size()), "pressure");
    for (std::size_t k = 0; k < f.size(); ++k) {
      const int a = f[k], b = f[(k + 1) % f.size()];
      if (a < 0 || b < 0 || 3 * std::max(a, b) + 2 >= rest.size())
        throw Error(fmt::format("face vertex out of range ({} vertices)", rest.size() / 3), "pressure");
      a < b ? ++net[{a, b}] : --net[{b, a}];
      sum += rest.segment<3>(3 * a);
      ++corners;
    }
  }
  for (const auto& [edge, count] : net)
    for (int k = 0; k < std::abs(count); ++k)
      boundary_edges_.push_back(count > 0 ? std::array<int, 2>{edge.first, edge.second}
                                          : std::array<int, 2>{edge.second, edge.first});
  origin_ = sum / corners;
  rest_volume_ = enclosed_volume(rest);
}

double PressureForm::enclosed_volume(const Eigen::VectorXd& x) const {
  double V = 0.0;
  for (const auto& f : faces_)
    for (const FacePoint& q : face_rule(f.size())) {
      Vec3 p = Vec3::Zero(), xu = Vec3::Zero(), xw = Vec3::Zero();
      for (std::size_t k = 0; k < f.size(); ++k) {
        const Vec3 xk = x.segment<3>(3 * f[k]);
        p += q.N[k] * xk;
        xu += q.Nu[k] * xk;
        xw += q.Nw[k] * xk;
      }
      V += q.weight * (p - origin_).dot(xu.cross(xw)) / 3.0;
    }
  return V;
}

double PressureForm::value(const Eigen::VectorXd& x) const {
  if (closed()) return scale_ * pressure_ * (enclosed_volume(x) - rest_volume_);
  // Energy at the path's start plus the gradient's integral along the segment to x, which is
  // quadratic in the segment's parameter: 2-point Gauss is exact.
  const Eigen::VectorXd step = x - path_start_;
  const double g = 0.5 / std::sqrt(3.0);
  double E = path_energy_;
  for (double t : {0.5 - g, 0.5 + g}) {
    Eigen::VectorXd grad = Eigen::VectorXd::Zero(x.size());
    add_gradient(path_start_ + t * step, grad);
    E += 0.5 * grad.dot(step);
  }
  return E;
}

void PressureForm::linearize_at(const Eigen::VectorXd& x) {
  if (closed() || x.size() != path_start_.size()) return;
  path_energy_ = value(x);
  path_start_ = x;
}

bool PressureForm::begin_solve(const Eigen::VectorXd& x) {
  linearize_at(x);
  return false;  // the energy at x is unchanged
}

void PressureForm::add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const {
  const double p = scale_ * pressure_;
  for (const auto& f : faces_)
    for (const FacePoint& q : face_rule(f.size())) {
      Vec3 xu = Vec3::Zero(), xw = Vec3::Zero();
      for (std::size_t k = 0; k < f.size(); ++k) {
        xu += q.Nu[k] * x.segment<3>(3 * f[k]);
        xw += q.Nw[k] * x.segment<3>(3 * f[k]);
      }
      const Vec3 n_da = q.weight * xu.cross(xw);  // the area-weighted outward normal
      for (std::size_t k = 0; k < f.size(); ++k) g.segment<3>(3 * f[k]) += p * q.N[k] * n_da;
    }
}

Eigen::VectorXd PressureForm::forces(const Eigen::VectorXd& x) const {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
  add_gradient(x, g);
  return -g;
}

void PressureForm::add_hessian(const Eigen::VectorXd& x, BlockHessian& H) const {
  const double p = scale_ * pressure_;
  for (const auto& f : faces_) {
    const std::size_t n = f.size();
    // K(a, b) = d g_a / d x_b = p sum_q w N_a (N_b,w [x_u]x - N_b,u [x_w]x).
    std::array<std::array<Mat3, 4>, 4> K;
    for (auto& row : K) row.fill(Mat3::Zero());
    for (const FacePoint& q : face_rule(n)) {
      Vec3 xu = Vec3::Zero(), xw = Vec3::Zero();
      for (std::size_t k = 0; k < n; ++k) {
        xu += q.Nu[k] * x.segment<3>(3 * f[k]);
        xw += q.Nw[k] * x.segment<3>(3 * f[k]);
      }
      const Mat3 Xu = cross_matrix(xu), Xw = cross_matrix(xw);
      for (std::size_t a = 0; a < n; ++a)
        for (std::size_t b = 0; b < n; ++b) K[a][b] += p * q.weight * q.N[a] * (q.Nw[b] * Xu - q.Nu[b] * Xw);
    }
    for (std::size_t a = 0; a < n; ++a)
      for (std::size_t b = 0; b < n; ++b) H.add_block(f[a], f[b], Mat3(0.5 * (K[a][b] + K[b][a].transpose())));
  }
}

void PressureForm::couplings(std::vector<std::vector<int>>& cliques) const {
  for (const auto& f : faces_) cliques.push_back(f);
}

}  // namespace sinew
