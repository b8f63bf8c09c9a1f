#include "sinew/solver/chebyshev_smoother.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>

#include "sinew/core/error.hpp"

namespace sinew {

void ChebyshevSmoother::apply_inverse_diagonal(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  z.resize(r.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, inverse_.size(), 2048), [&](const auto& range) {
    for (size_t b = range.begin(); b != range.end(); ++b) {
      const Eigen::Index i = 3 * static_cast<Eigen::Index>(b);
      z.segment<3>(i).noalias() = inverse_[b] * r.segment<3>(i);
    }
  });
}

void ChebyshevSmoother::setup(const LinearOperator& A, std::span<const char> free, const ChebyshevSettings& settings) {
  if (A.rows() % 3 != 0) throw Error("expects 3 DOFs per vertex", "Chebyshev smoother");
  if (static_cast<Eigen::Index>(free.size()) != A.rows()) throw Error("the free-DOF mask does not match", "Chebyshev smoother");
  A_ = &A;
  settings_ = settings;
  const Eigen::Index n = A.rows();
  inverse_.resize(static_cast<size_t>(n / 3));
  tbb::parallel_for(Eigen::Index{0}, n / 3, [&](Eigen::Index b) {
    const Mat3 D = A.diagonal_block(b);
    Mat3 inv = Mat3::Zero();
    Eigen::LLT<Mat3> llt(D);
    if (llt.info() == Eigen::Success) {
      inv = llt.solve(Mat3::Identity());
    } else {
      for (int i = 0; i < 3; ++i) inv(i, i) = D(i, i) > 0.0 ? 1.0 / D(i, i) : 1.0;
    }
    inverse_[static_cast<size_t>(b)] = inv;
  });

  // Lanczos through preconditioned CG: its coefficients give the tridiagonal matrix whose
  // largest eigenvalue approaches lambda_max(D^-1 A) from below.
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n), r(n), z(n), p(n), Ap(n);
  for (Eigen::Index i = 0; i < n; ++i)  // a fixed, rough start vector over the free DOFs
    r[i] = free[static_cast<size_t>(i)] ? 1.0 + 0.5 * std::sin(1.7 * static_cast<double>(i) + 0.3) : 0.0;
  apply_inverse_diagonal(r, z);
  p = z;
  double rz = r.dot(z);
  std::vector<double> alpha, beta;
  for (int k = 0; k < settings.lanczos_steps && rz > 0.0; ++k) {
    A.apply(p, Ap);
    const double pAp = p.dot(Ap);
    if (!(pAp > 0.0)) break;
    const double a = rz / pAp;
    r.noalias() -= a * Ap;
    apply_inverse_diagonal(r, z);
    const double rz_next = r.dot(z);
    alpha.push_back(a);
    beta.push_back(rz_next / rz);
    if (!(rz_next > 1e-30 * rz)) break;
    p = z + beta.back() * p;
    rz = rz_next;
  }
  const int m = static_cast<int>(alpha.size());
  if (m == 0) {
    lambda_max_ = 1.0;
    return;
  }
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(m, m);
  for (int j = 0; j < m; ++j) {
    T(j, j) = 1.0 / alpha[static_cast<size_t>(j)] + (j > 0 ? beta[static_cast<size_t>(j) - 1] / alpha[static_cast<size_t>(j) - 1] : 0.0);
    if (j + 1 < m) T(j, j + 1) = T(j + 1, j) = std::sqrt(beta[static_cast<size_t>(j)]) / alpha[static_cast<size_t>(j)];
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(T, Eigen::EigenvaluesOnly);
  lambda_max_ = settings.safety * eig.eigenvalues().maxCoeff();
  if (!(lambda_max_ > 0.0) || !std::isfinite(lambda_max_)) lambda_max_ = 1.0;
}

void ChebyshevSmoother::smooth(const Eigen::VectorXd& b, Eigen::VectorXd& x, bool zero_start) const {
  // Chebyshev iteration on [lower, upper] (Saad, Iterative Methods, Alg. 12.1, preconditioned).
  const double upper = lambda_max_, lower = settings_.lower * lambda_max_;
  const double theta = 0.5 * (upper + lower), delta = 0.5 * (upper - lower);
  const double sigma = theta / delta;
  double rho = 1.0 / sigma;
  if (zero_start) {
    x.setZero(b.size());
    r_ = b;
  } else {
    A_->apply(x, Ad_);
    r_ = b - Ad_;
  }
  apply_inverse_diagonal(r_, z_);
  d_ = z_ / theta;
  for (int k = 0; k < settings_.degree; ++k) {
    x += d_;
    if (k + 1 == settings_.degree) break;
    A_->apply(d_, Ad_);
    r_ -= Ad_;
    apply_inverse_diagonal(r_, z_);
    const double rho_next = 1.0 / (2.0 * sigma - rho);
    d_ = (rho_next * rho) * d_ + (2.0 * rho_next / delta) * z_;
    rho = rho_next;
  }
}

}  // namespace sinew
