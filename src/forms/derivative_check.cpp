#include "sinew/forms/derivative_check.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <random>

#include "sinew/core/finite_difference.hpp"

namespace sinew {

namespace {

BlockHessian empty_hessian(const Form& form, Eigen::Index dofs) {
  const Eigen::Index vertices = dofs / 3;
  std::vector<std::vector<int>> cliques;
  for (int v = 0; v < vertices; ++v) cliques.push_back({v});
  form.couplings(cliques);
  return BlockHessian(vertices, cliques);
}

Eigen::VectorXd gradient_of(const Form& form, const Eigen::VectorXd& y) {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(y.size());
  form.add_gradient(y, g);
  return g;
}

double ratio(double difference, double a, double b, double floor) {
  const double scale = std::max({a, b, floor});
  return scale > 0.0 ? difference / scale : 0.0;
}

}  // namespace

double point_extent(const Eigen::VectorXd& x) {
  if (x.size() < 6 || x.size() % 3 != 0) return 1.0;
  const auto points = x.reshaped(3, x.size() / 3);
  const double extent = (points.rowwise().maxCoeff() - points.rowwise().minCoeff()).maxCoeff();
  return extent > 0.0 && std::isfinite(extent) ? extent : 1.0;
}

FormDifferences form_differences(const Form& form, const Eigen::VectorXd& x, const FormCheckOptions& options) {
  const Eigen::Index n = x.size();
  FormDifferences d;
  d.step = options.step > 0.0 ? options.step : options.relative_step * point_extent(x);
  d.coordinate = n <= options.max_coordinate_dofs;
  if (d.coordinate) {
    d.directions = Eigen::MatrixXd::Identity(n, n);
  } else {
    std::mt19937 rng(options.seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    d.directions.resize(n, options.random_directions);
    for (Eigen::Index k = 0; k < d.directions.cols(); ++k) {
      for (Eigen::Index i = 0; i < n; ++i) d.directions(i, k) = normal(rng);
      d.directions.col(k).normalize();
    }
  }
  const Eigen::Index k = d.directions.cols();
  BlockHessian H = empty_hessian(form, n);
  form.add_exact_hessian(x, H);
  d.gradient = d.directions.transpose() * gradient_of(form, x);
  d.hessian = H.matrix() * d.directions;
  d.gradient_fd.resize(k);
  d.hessian_fd.resize(n, k);
  auto value = [&](const Eigen::VectorXd& y) { return form.value(y); };
  auto gradient = [&](const Eigen::VectorXd& y) { return gradient_of(form, y); };
  for (Eigen::Index j = 0; j < k; ++j) {
    const Eigen::VectorXd dj = d.directions.col(j);
    if (options.richardson) {
      d.gradient_fd(j) = richardson_difference(value, x, dj, d.step);
      d.hessian_fd.col(j) = richardson_difference(gradient, x, dj, d.step);
    } else {
      d.gradient_fd(j) = central_difference(value, x, dj, d.step);
      d.hessian_fd.col(j) = central_difference(gradient, x, dj, d.step);
    }
  }
  return d;
}

bool FormCheck::passed() const {
  const bool finite = std::isfinite(gradient_error) && std::isfinite(hessian_error) && std::isfinite(asymmetry);
  return finite && gradient_error <= tolerance && hessian_error <= tolerance && asymmetry <= tolerance &&
         (!projected || min_eigenvalue >= -tolerance);
}

FormCheck check_form(const Form& form, const Eigen::VectorXd& x, const FormCheckOptions& options) {
  FormCheck c;
  c.form = form.name();
  c.dofs = x.size();
  c.tolerance = options.tolerance;
  const FormDifferences d = form_differences(form, x, options);
  c.directions = static_cast<int>(d.directions.cols());
  c.coordinate = d.coordinate;
  c.step = d.step;

  const double g_floor = d.step * std::max(d.hessian.norm(), d.hessian_fd.norm());
  c.gradient_error = ratio((d.gradient - d.gradient_fd).norm(), d.gradient.norm(), d.gradient_fd.norm(), g_floor);
  const double h_floor = 1e-3 * gradient_of(form, x).norm() / point_extent(x);
  c.hessian_error = ratio((d.hessian - d.hessian_fd).norm(), d.hessian.norm(), d.hessian_fd.norm(), h_floor);

  BlockHessian used = empty_hessian(form, x.size());
  form.add_hessian(x, used);
  const Eigen::SparseMatrix<double>& A = used.matrix();
  const double norm = A.norm();
  const Eigen::SparseMatrix<double> At = A.transpose();
  c.asymmetry = norm > 0.0 ? (A - At).norm() / norm : 0.0;
  c.projected = form.projects_hessian();
  if (c.projected) {
    const double exact_norm = d.coordinate ? d.hessian.norm() : 0.0;
    if (d.coordinate) {
      c.projection_gap = exact_norm > 0.0 ? (Eigen::MatrixXd(A) - d.hessian).norm() / exact_norm : 0.0;
    } else {
      const Eigen::MatrixXd AD = A * d.directions;
      c.projection_gap = d.hessian.norm() > 0.0 ? (AD - d.hessian).norm() / d.hessian.norm() : 0.0;
    }
    if (norm == 0.0) {
      c.min_eigenvalue = 0.0;
      c.dense_eigenvalue = true;
    } else if (x.size() <= options.max_dense_dofs) {
      const Eigen::MatrixXd dense = 0.5 * (Eigen::MatrixXd(A) + Eigen::MatrixXd(At));
      c.min_eigenvalue = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(dense, Eigen::EigenvaluesOnly).eigenvalues().minCoeff() / norm;
      c.dense_eigenvalue = true;
    } else {
      const Eigen::MatrixXd AD = A * d.directions;
      c.min_eigenvalue = (d.directions.transpose() * AD).diagonal().minCoeff() / norm;
    }
  }
  return c;
}

}  // namespace sinew
