// Preconditioned conjugate gradients over a LinearOperator, with Jacobi or 3x3 block-Jacobi
// preconditioning. Written on the operator (not on Eigen::ConjugateGradient, which needs the
// assembled matrix and multiplies with it on one core) so that the product runs in parallel
// through SparseOperator::apply and a matrix-free operator can use the same solver.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <vector>

#include "sinew/core/error.hpp"
#include "sinew/core/types.hpp"
#include "sinew/solver/linear_solver.hpp"

namespace sinew {
namespace {

// Inverse 3x3 diagonal vertex blocks (block-Jacobi) or inverse diagonal entries (Jacobi). A
// block that is not positive definite falls back to its diagonal, a non-positive diagonal entry
// to 1, so the preconditioner always exists and stays symmetric positive definite.
class Preconditioning {
 public:
  Preconditioning(const LinearOperator& op, Preconditioner kind) {
    const Eigen::Index blocks = op.rows() / 3;
    inverse_.resize(blocks);
    tbb::parallel_for(Eigen::Index{0}, blocks, [&](Eigen::Index b) {
      const Mat3 D = op.diagonal_block(b);
      Mat3 inv = Mat3::Zero();
      Eigen::LLT<Mat3> llt;
      if (kind == Preconditioner::BlockJacobi3) llt.compute(D);
      if (kind == Preconditioner::BlockJacobi3 && llt.info() == Eigen::Success) {
        inv = llt.solve(Mat3::Identity());
      } else {
        for (int i = 0; i < 3; ++i) inv(i, i) = D(i, i) > 0.0 ? 1.0 / D(i, i) : 1.0;
      }
      inverse_[b] = inv;
    });
  }

  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
    z.resize(r.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, inverse_.size(), 1024), [&](const auto& range) {
      for (size_t b = range.begin(); b != range.end(); ++b)
        z.segment<3>(3 * static_cast<Eigen::Index>(b)) = inverse_[b] * r.segment<3>(3 * static_cast<Eigen::Index>(b));
    });
  }

 private:
  std::vector<Mat3> inverse_;
};

class PcgSolver final : public LinearSolver {
 public:
  PcgSolver(Preconditioner kind, int max_iterations) : kind_(kind), max_iterations_(max_iterations) {}
  std::string name() const override {
    return kind_ == Preconditioner::Jacobi ? "pcg-jacobi" : "pcg-block-jacobi";
  }

  // Standard PCG from x = 0 (Newton directions are solved afresh); stops when
  // ||b - A x|| <= tolerance ||b||, as Eigen's CG does.
  LinearSolveReport solve(const LinearOperator& op, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                          double tolerance) override {
    if (op.rows() % 3 != 0) throw Error("PCG expects 3 DOFs per vertex", "solver.linear");
    const Eigen::Index n = op.rows();
    x.setZero(n);
    const double b_norm = b.norm();
    if (b_norm == 0.0) return {0, 0.0, true};
    const Preconditioning M(op, kind_);
    Eigen::VectorXd r = b, z(n), p(n), Ap(n);
    M.apply(r, z);
    p = z;
    double rz = r.dot(z);
    const double threshold = tolerance * b_norm;
    double r_norm = b_norm;
    int k = 0;
    while (k < max_iterations_ && r_norm > threshold) {
      op.apply(p, Ap);
      const double pAp = p.dot(Ap);
      // The projected Hessian is positive semi-definite; a direction of zero or negative
      // curvature (round-off on a singular system) ends the solve with the iterate so far.
      if (!(pAp > 0.0)) break;
      const double alpha = rz / pAp;
      x.noalias() += alpha * p;
      r.noalias() -= alpha * Ap;
      r_norm = r.norm();
      ++k;
      if (r_norm <= threshold) break;
      M.apply(r, z);
      const double rz_next = r.dot(z);
      p = z + (rz_next / rz) * p;
      rz = rz_next;
    }
    return {k, r_norm / b_norm, r_norm <= threshold};
  }

 private:
  Preconditioner kind_;
  int max_iterations_;
};

}  // namespace

std::unique_ptr<LinearSolver> make_cholmod_solver();

std::unique_ptr<LinearSolver> make_linear_solver(const LinearSolverSettings& s) {
  if (s.kind == "cholmod") return make_cholmod_solver();
  if (s.kind == "pcg") return std::make_unique<PcgSolver>(s.preconditioner, s.max_iterations);
  throw Error("unknown linear solver '" + s.kind + "' (expected cholmod or pcg)", "solver.linear");
}

}  // namespace sinew
