#include "sinew/forms/penalty_contact_form.hpp"

#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

// IPC's friction mollifier f0 (Li et al. 2020, eq. 14) and f1 = f0', f1(s)/s and f1'(s), with
// threshold eps: C1 at s = eps, f0(s) = s beyond it.
double f0(double s, double eps) { return s >= eps ? s : -s * s * s / (3 * eps * eps) + s * s / eps + eps / 3; }
double f1_over_s(double s, double eps) { return s >= eps ? 1.0 / s : -s / (eps * eps) + 2.0 / eps; }
double f1_prime(double s, double eps) { return s >= eps ? 0.0 : -2.0 * s / (eps * eps) + 2.0 / eps; }

Mat3 project_psd(const Mat3& A) {
  Eigen::SelfAdjointEigenSolver<Mat3> es(A);
  const Eigen::Vector3d l = es.eigenvalues().cwiseMax(0.0);
  return es.eigenvectors() * l.asDiagonal() * es.eigenvectors().transpose();
}

}  // namespace

Eigen::VectorXd boundary_vertex_areas(const VolumeMesh& mesh, const BoundarySurface& surface) {
  Eigen::VectorXd a = Eigen::VectorXd::Zero(mesh.num_vertices());
  for (Eigen::Index t = 0; t < surface.triangles.rows(); ++t) {
    const Eigen::Vector3d p0 = mesh.vertices.row(surface.triangles(t, 0));
    const Eigen::Vector3d p1 = mesh.vertices.row(surface.triangles(t, 1));
    const Eigen::Vector3d p2 = mesh.vertices.row(surface.triangles(t, 2));
    const double area = 0.5 * (p1 - p0).cross(p2 - p0).norm();
    for (int k = 0; k < 3; ++k) a(surface.triangles(t, k)) += area / 3.0;
  }
  return a;
}

PenaltyContactForm::PenaltyContactForm(std::vector<std::shared_ptr<const Obstacle>> obstacles,
                                       std::vector<ContactParameters> parameters, std::vector<int> vertices,
                                       Eigen::VectorXd areas, bool project_hessian)
    : obstacles_(std::move(obstacles)), params_(std::move(parameters)), vertices_(std::move(vertices)),
      areas_(std::move(areas)), project_(project_hessian) {
  if (params_.size() != obstacles_.size()) throw Error("one set of contact parameters per obstacle", "contact");
  for (const auto& p : params_)
    if (!(p.stiffness > 0.0) || !(p.friction >= 0.0) || !std::isfinite(p.stiffness) || !std::isfinite(p.friction))
      throw Error("stiffness must be positive and friction >= 0, both finite", "contact");
}

void PenaltyContactForm::begin_step(const Eigen::VectorXd& x_n, double frame0, double frame1, double slip_epsilon) {
  frame_ = frame1;
  epsilon_ = slip_epsilon;
  friction_.clear();
  for (size_t o = 0; o < obstacles_.size(); ++o) {
    if (params_[o].friction <= 0.0) continue;
    for (int v : vertices_) {
      const Eigen::Vector3d p = x_n.segment<3>(3 * v);
      const SurfaceQuery q = obstacles_[o]->query(p, frame1);
      if (q.distance >= 0.0) continue;
      FrictionPair f;
      f.vertex = v;
      f.obstacle = static_cast<int>(o);
      f.normal_force = areas_(v) * params_[o].stiffness * -q.distance;
      f.tangent = Mat3::Identity() - q.normal * q.normal.transpose();
      // The obstacle point now at the contact was here at frame0: its motion over the step.
      f.origin = p - obstacles_[o]->displacement(q.closest, frame1, frame0);
      friction_.push_back(f);
    }
  }
}

double PenaltyContactForm::value(const Eigen::VectorXd& x) const {
  double e = stats(x).penalty_energy;
  for (const auto& f : friction_) {
    const Eigen::Vector3d u = f.tangent * (x.segment<3>(3 * f.vertex) - f.origin);
    e += params_[f.obstacle].friction * f.normal_force * f0(u.norm(), epsilon_);
  }
  return e;
}

ContactStats PenaltyContactForm::stats(const Eigen::VectorXd& x) const {
  ContactStats s;
  for (size_t o = 0; o < obstacles_.size(); ++o)
    for (int v : vertices_) {
      const double d = obstacles_[o]->query(x.segment<3>(3 * v), frame_).distance;
      if (d >= 0.0) continue;
      s.contacts += 1;
      s.max_penetration = std::max(s.max_penetration, -d);
      s.penalty_energy += 0.5 * areas_(v) * params_[o].stiffness * d * d;
    }
  return s;
}

void PenaltyContactForm::add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const {
  for (size_t o = 0; o < obstacles_.size(); ++o)
    for (int v : vertices_) {
      const SurfaceQuery q = obstacles_[o]->query(x.segment<3>(3 * v), frame_);
      if (q.distance < 0.0) g.segment<3>(3 * v) += areas_(v) * params_[o].stiffness * q.distance * q.normal;
    }
  for (const auto& f : friction_) {
    const Eigen::Vector3d u = f.tangent * (x.segment<3>(3 * f.vertex) - f.origin);
    // d f0(|u|)/dx = f1(s) T u / s, and T u = u.
    g.segment<3>(3 * f.vertex) += params_[f.obstacle].friction * f.normal_force * f1_over_s(u.norm(), epsilon_) * u;
  }
}

void PenaltyContactForm::add_hessian(const Eigen::VectorXd& x, BlockHessian& H) const {
  for (size_t o = 0; o < obstacles_.size(); ++o)
    for (int v : vertices_) {
      const SurfaceQuery q = obstacles_[o]->query(x.segment<3>(3 * v), frame_);
      if (q.distance >= 0.0) continue;
      // d/dx (a k d n) = a k (n n^T + d dn/dx); the curvature part is negative inside a convex
      // obstacle, hence the projection.
      Mat3 K = areas_(v) * params_[o].stiffness * (q.normal * q.normal.transpose() + q.distance * q.normal_derivative);
      H.add_block(v, v, project_ ? project_psd(K) : K);
    }
  for (const auto& f : friction_) {
    const Eigen::Vector3d u = f.tangent * (x.segment<3>(3 * f.vertex) - f.origin);
    const double s = u.norm();
    // Hessian of f0(|u|) in the tangent plane: f1' u^ u^T + (f1 / s)(T - u^ u^T); both terms are
    // PSD (f1' >= 0, f1 / s > 0), so no projection is needed.
    Mat3 Hu = f1_over_s(s, epsilon_) * f.tangent;
    if (s > 0.0) {
      const Eigen::Vector3d uh = u / s;
      Hu += (f1_prime(s, epsilon_) - f1_over_s(s, epsilon_)) * uh * uh.transpose();
    }
    H.add_block(f.vertex, f.vertex, params_[f.obstacle].friction * f.normal_force * f.tangent * Hu * f.tangent);
  }
}

}  // namespace sinew
