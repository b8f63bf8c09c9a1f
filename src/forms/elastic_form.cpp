#include "sinew/forms/elastic_form.hpp"

#include <atomic>
#include <limits>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "sinew/core/error.hpp"

namespace sinew {

ElasticForm::ElasticForm(std::shared_ptr<const Discretization> disc,
                         std::shared_ptr<const Material> material, Projection projection)
    : disc_(std::move(disc)), material_(std::move(material)), projection_(projection) {}

double ElasticForm::value(const Eigen::VectorXd& x) const {
  const Discretization& d = *disc_;
  // Deterministic reduction: the same x gives bit-identical energies, which the line search needs.
  return tbb::parallel_deterministic_reduce(
      tbb::blocked_range<Eigen::Index>(0, d.num_elements(), 256), 0.0,
      [&](const tbb::blocked_range<Eigen::Index>& r, double acc) {
        for (Eigen::Index e = r.begin(); e != r.end(); ++e) {
          const Eigen::Matrix3Xd xe = d.element_positions(e, x);
          for (int q = 0; q < d.quadrature_points(); ++q) {
            const Mat3 F = xe * d.gradients(e, q);
            acc += material_->in_domain(F) ? d.weight(e, q) * material_->psi(F)
                                           : std::numeric_limits<double>::infinity();
          }
        }
        return acc;
      },
      std::plus<double>());
}

void ElasticForm::add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const {
  const Discretization& d = *disc_;
  const auto& elements = d.mesh().elements;
  for (const auto& group : d.color_groups()) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, group.size(), 64), [&](const auto& r) {
      for (size_t idx = r.begin(); idx != r.end(); ++idx) {
        const Eigen::Index e = group[idx];
        const Eigen::Matrix3Xd xe = d.element_positions(e, x);
        Eigen::Matrix3Xd ge = Eigen::Matrix3Xd::Zero(3, d.nodes());
        for (int q = 0; q < d.quadrature_points(); ++q) {
          const Eigen::MatrixX3d& D = d.gradients(e, q);
          ge += d.weight(e, q) * material_->pk1(xe * D) * D.transpose();
        }
        for (int a = 0; a < d.nodes(); ++a) g.segment<3>(3 * elements(e, a)) += ge.col(a);
      }
    });
  }
}

void ElasticForm::add_hessian(const Eigen::VectorXd& x, BlockHessian& H) const {
  const Discretization& d = *disc_;
  const auto& elements = d.mesh().elements;
  const int n = d.nodes();
  for (const auto& group : d.color_groups()) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, group.size(), 32), [&](const auto& r) {
      Eigen::MatrixXd K(3 * n, 3 * n);
      for (size_t idx = r.begin(); idx != r.end(); ++idx) {
        const Eigen::Index e = group[idx];
        const Eigen::Matrix3Xd xe = d.element_positions(e, x);
        K.setZero();
        for (int q = 0; q < d.quadrature_points(); ++q) {
          const Eigen::MatrixX3d& D = d.gradients(e, q);
          add_element_hessian(D, material_->projected_hessian(xe * D, projection_), d.weight(e, q), K);
        }
        for (int b = 0; b < n; ++b)
          for (int a = 0; a < n; ++a) {
            const int va = elements(e, a), vb = elements(e, b);
            H.add_block_at_slot(vb, H.slot(va, vb), K.block<3, 3>(3 * a, 3 * b));
          }
      }
    });
  }
}

double ElasticForm::element_value(Eigen::Index e, const Eigen::VectorXd& x) const {
  const Discretization& d = *disc_;
  const Eigen::Matrix3Xd xe = d.element_positions(e, x);
  double U = 0.0;
  for (int q = 0; q < d.quadrature_points(); ++q) U += d.weight(e, q) * material_->psi(xe * d.gradients(e, q));
  return U;
}

Eigen::VectorXd ElasticForm::element_gradient(Eigen::Index e, const Eigen::VectorXd& x, JacobianKind kind) const {
  if (kind != JacobianKind::Exact)
    throw Error("a hyperelastic material has no warped-force Jacobian; use \"exact\"", "jacobian");
  const Discretization& d = *disc_;
  const Eigen::Matrix3Xd xe = d.element_positions(e, x);
  Eigen::Matrix3Xd ge = Eigen::Matrix3Xd::Zero(3, d.nodes());
  for (int q = 0; q < d.quadrature_points(); ++q) {
    const Eigen::MatrixX3d& D = d.gradients(e, q);
    ge += d.weight(e, q) * material_->pk1(xe * D) * D.transpose();
  }
  return ge.reshaped();
}

Eigen::MatrixXd ElasticForm::element_hessian(Eigen::Index e, const Eigen::VectorXd& x) const {
  const Discretization& d = *disc_;
  const Eigen::Matrix3Xd xe = d.element_positions(e, x);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(3 * d.nodes(), 3 * d.nodes());
  for (int q = 0; q < d.quadrature_points(); ++q) {
    const Eigen::MatrixX3d& D = d.gradients(e, q);
    add_element_hessian(D, material_->projected_hessian(xe * D, projection_), d.weight(e, q), K);
  }
  return K;
}

bool ElasticForm::is_valid(const Eigen::VectorXd& x) const {
  if (material_->domain() == Domain::All) return x.allFinite();
  const Discretization& d = *disc_;
  std::atomic<bool> ok{true};
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, d.num_elements(), 256), [&](const auto& r) {
    for (Eigen::Index e = r.begin(); e != r.end() && ok.load(std::memory_order_relaxed); ++e) {
      const Eigen::Matrix3Xd xe = d.element_positions(e, x);
      for (int q = 0; q < d.quadrature_points(); ++q)
        if (!material_->in_domain(xe * d.gradients(e, q))) ok = false;
    }
  });
  return ok;
}

ElasticForm::ElementFields ElasticForm::element_fields(const Eigen::VectorXd& x) const {
  const Discretization& d = *disc_;
  ElementFields f;
  const Eigen::Index m = d.num_elements();
  f.energy.resize(m);
  f.J.resize(m);
  f.energy_density.resize(m);
  f.stress_norm.resize(m);
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, m, 256), [&](const auto& r) {
    for (Eigen::Index e = r.begin(); e != r.end(); ++e) {
      const Eigen::Matrix3Xd xe = d.element_positions(e, x);
      double energy = 0.0, J = 0.0, stress = 0.0, volume = 0.0;
      for (int q = 0; q < d.quadrature_points(); ++q) {
        const Mat3 F = xe * d.gradients(e, q);
        const double w = d.weight(e, q);
        const bool defined = material_->in_domain(F);
        energy += defined ? w * material_->psi(F) : std::numeric_limits<double>::infinity();
        stress += defined ? w * material_->pk1(F).norm() : std::numeric_limits<double>::infinity();
        J += w * F.determinant();
        volume += w;
      }
      f.energy(e) = energy;
      f.J(e) = J / volume;
      f.energy_density(e) = energy / volume;
      f.stress_norm(e) = stress / volume;
    }
  });
  return f;
}

}  // namespace sinew
