#pragma once
// Chebyshev polynomial smoothing over 3x3 block-Jacobi, the multigrid smoother: a fixed-degree
// polynomial in D^-1 A that damps the eigenvalues of D^-1 A in [lower * lambda_max, lambda_max]
// (the error components the coarse levels do not remove). Unlike damped Jacobi or Gauss-Seidel
// it needs no relaxation weight tuned to the Poisson ratio, and it is symmetric, so a V-cycle
// with it as pre- and post-smoother is a symmetric preconditioner for CG. lambda_max is
// estimated with a few Lanczos steps (preconditioned CG on a fixed start vector, so runs are
// deterministic) and enlarged by a safety factor.
#include <span>
#include <vector>

#include "sinew/core/types.hpp"
#include "sinew/linalg/linear_operator.hpp"

namespace sinew {

struct ChebyshevSettings {
  int degree = 2;             // operator applications per smoothing (pre or post)
  double lower = 0.1;         // damped interval starts at lower * lambda_max
  double safety = 1.1;        // lambda_max estimate times this
  int lanczos_steps = 10;     // CG steps for the estimate
};

class ChebyshevSmoother {
 public:
  // Builds D^-1 from A's diagonal blocks (a block that is not positive definite falls back to
  // its diagonal, as block_jacobi does) and estimates lambda_max(D^-1 A) over the free DOFs.
  void setup(const LinearOperator& A, std::span<const char> free, const ChebyshevSettings& settings);
  // Smooths A x = b starting from x (from zero when `zero_start`).
  void smooth(const Eigen::VectorXd& b, Eigen::VectorXd& x, bool zero_start) const;
  double lambda_max() const { return lambda_max_; }

 private:
  void apply_inverse_diagonal(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;

  const LinearOperator* A_ = nullptr;
  ChebyshevSettings settings_;
  std::vector<Mat3, Eigen::aligned_allocator<Mat3>> inverse_;
  double lambda_max_ = 1.0;
  mutable Eigen::VectorXd r_, d_, z_, Ad_;
};

}  // namespace sinew
