#pragma once
// Jacobi ("jacobi": inverse diagonal entries) and 3x3 block-Jacobi ("block_jacobi": inverse
// vertex blocks, the default). Both need only LinearOperator::diagonal_block, so they work with
// matrix-free operators. A block that is not positive definite falls back to its diagonal, a
// non-positive diagonal entry to 1, so the preconditioner always exists and stays SPD.
#include <vector>

#include "sinew/core/types.hpp"
#include "sinew/solver/preconditioner.hpp"

namespace sinew {

class DiagonalPreconditioner final : public Preconditioner {
 public:
  enum class Blocks { Scalar, Vertex3 };
  explicit DiagonalPreconditioner(Blocks blocks) : blocks_(blocks) {}
  std::string name() const override { return blocks_ == Blocks::Scalar ? "jacobi" : "block_jacobi"; }
  void setup(const LinearOperator& A, const SolverContext& context) override;
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) override;

 private:
  Blocks blocks_;
  std::vector<Mat3> inverse_;  // per vertex (diagonal for Jacobi)
};

}  // namespace sinew
