// Preconditioned conjugate gradients (Eigen) with Jacobi or 3x3 block-Jacobi preconditioning.
#include <Eigen/IterativeLinearSolvers>
#include <vector>

#include "sinew/core/error.hpp"
#include "sinew/core/types.hpp"
#include "sinew/solver/linear_solver.hpp"

namespace sinew {
namespace {

// Inverts the 3x3 diagonal vertex blocks; a block that is not invertible falls back to
// its diagonal (or identity) so the preconditioner always exists.
class BlockJacobi3 {
 public:
  using StorageIndex = int;
  enum { ColsAtCompileTime = Eigen::Dynamic, MaxColsAtCompileTime = Eigen::Dynamic };

  BlockJacobi3() = default;
  template <class MatType>
  explicit BlockJacobi3(const MatType& A) { compute(A); }

  Eigen::Index rows() const { return 3 * static_cast<Eigen::Index>(inverse_.size()); }
  Eigen::Index cols() const { return rows(); }

  template <class MatType>
  BlockJacobi3& analyzePattern(const MatType&) { return *this; }
  template <class MatType>
  BlockJacobi3& factorize(const MatType& A) { return compute(A); }
  template <class MatType>
  BlockJacobi3& compute(const MatType& A) {
    const Eigen::Index blocks = A.rows() / 3;
    inverse_.assign(blocks, Mat3::Zero());
    std::vector<Mat3> diag(blocks, Mat3::Zero());
    for (Eigen::Index c = 0; c < A.outerSize(); ++c)
      for (typename MatType::InnerIterator it(A, c); it; ++it)
        if (it.row() / 3 == it.col() / 3) diag[it.col() / 3](it.row() % 3, it.col() % 3) = it.value();
    for (Eigen::Index b = 0; b < blocks; ++b) {
      Eigen::LLT<Mat3> llt(diag[b]);
      if (llt.info() == Eigen::Success) {
        inverse_[b] = llt.solve(Mat3::Identity());
      } else {
        for (int i = 0; i < 3; ++i) inverse_[b](i, i) = diag[b](i, i) > 0 ? 1.0 / diag[b](i, i) : 1.0;
      }
    }
    return *this;
  }

  template <typename Rhs, typename Dest>
  void _solve_impl(const Rhs& b, Dest& x) const {
    for (size_t k = 0; k < inverse_.size(); ++k) x.template segment<3>(3 * k) = inverse_[k] * b.template segment<3>(3 * k);
  }
  template <typename Rhs>
  inline const Eigen::Solve<BlockJacobi3, Rhs> solve(const Eigen::MatrixBase<Rhs>& b) const {
    return Eigen::Solve<BlockJacobi3, Rhs>(*this, b.derived());
  }
  Eigen::ComputationInfo info() { return Eigen::Success; }

 private:
  std::vector<Mat3> inverse_;
};

template <class Precond>
class PcgSolver final : public LinearSolver {
 public:
  PcgSolver(std::string name, int max_iterations) : name_(std::move(name)) { cg_.setMaxIterations(max_iterations); }
  std::string name() const override { return name_; }
  LinearSolveReport solve(const LinearOperator& op, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                          double tolerance) override {
    // Eigen's CG runs on the assembled matrix; a matrix-free operator needs a CG over
    // LinearOperator::apply, which arrives with the matrix-free backend.
    if (!op.matrix()) throw Error("this PCG needs an assembled matrix", "solver.linear");
    const Eigen::SparseMatrix<double>& A = *op.matrix();
    cg_.setTolerance(tolerance);
    cg_.compute(A);
    x = cg_.solve(b);  // zero initial guess: Newton directions are solved afresh
    return {static_cast<int>(cg_.iterations()), cg_.error(), cg_.info() == Eigen::Success};
  }

 private:
  std::string name_;
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper, Precond> cg_;
};

}  // namespace

std::unique_ptr<LinearSolver> make_cholmod_solver();

std::unique_ptr<LinearSolver> make_linear_solver(const LinearSolverSettings& s) {
  if (s.kind == "cholmod") return make_cholmod_solver();
  if (s.kind == "pcg") {
    if (s.preconditioner == Preconditioner::Jacobi)
      return std::make_unique<PcgSolver<Eigen::DiagonalPreconditioner<double>>>("pcg-jacobi", s.max_iterations);
    return std::make_unique<PcgSolver<BlockJacobi3>>("pcg-block-jacobi", s.max_iterations);
  }
  throw Error("unknown linear solver '" + s.kind + "' (expected cholmod or pcg)", "solver.linear");
}

}  // namespace sinew
