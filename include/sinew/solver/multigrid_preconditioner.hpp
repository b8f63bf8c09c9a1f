#pragma once
// Geometric multigrid for hexahedral lattices ("multigrid"): one V-cycle per application, on
// the hierarchy of coarsened lattices (solver/lattice_hierarchy.hpp) with Galerkin coarse
// operators P^T A P (trilinear P, 3x3 blocks, linalg/galerkin_product.hpp), Chebyshev over
// block-Jacobi smoothing before and after each coarse correction
// (solver/chebyshev_smoother.hpp) and a CHOLMOD factorisation on the coarsest level. The
// V-cycle is symmetric and positive definite, so it serves as CG's preconditioner.
//
// The hierarchy is built once per discretisation, the symbolic Galerkin products once per
// sparsity pattern; each setup (each Newton matrix) recomputes the coarse operators, the
// smoothers' eigenvalue estimates and the coarse factorisation. It needs the mesh's lattice grid
// (SolverContext::lattice(); without one it is block-Jacobi) and either the assembled matrix or,
// for a matrix-free operator, its element matrices: then the finest level smooths with the
// operator's own products and the first coarse level is P^T A P summed over the elements
// (linalg/element_galerkin.hpp), so the fine matrix is never formed.
#include <Eigen/CholmodSupport>
#include <memory>
#include <vector>

#include "sinew/linalg/block_sparse_matrix.hpp"
#include "sinew/linalg/element_galerkin.hpp"
#include "sinew/linalg/galerkin_product.hpp"
#include "sinew/linalg/pattern_memo.hpp"
#include "sinew/solver/chebyshev_smoother.hpp"
#include "sinew/solver/diagonal_preconditioners.hpp"
#include "sinew/solver/lattice_hierarchy.hpp"
#include "sinew/solver/preconditioner.hpp"

namespace sinew {

struct MultigridSettings {
  ChebyshevSettings smoother;
  Eigen::Index coarsest_dofs = 3000;  // coarsen until a level has at most this many DOFs
  int max_levels = 12;
};

class MultigridPreconditioner final : public Preconditioner {
 public:
  explicit MultigridPreconditioner(MultigridSettings settings = {});
  ~MultigridPreconditioner() override;
  std::string name() const override { return "multigrid"; }
  void setup(const LinearOperator& A, const SolverContext& context) override;
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) override;

  // Levels in use after setup (1 without a lattice), and DOFs per level.
  int levels() const { return lattice_ ? static_cast<int>(levels_.size()) : 1; }
  std::vector<Eigen::Index> level_dofs() const;

 private:
  struct Level;
  void build_hierarchy(const VolumeMesh& mesh);
  void cycle(size_t l, const Eigen::VectorXd& b, Eigen::VectorXd& x);

  MultigridSettings settings_;
  const void* lattice_ = nullptr;  // the discretisation the hierarchy was built for
  std::shared_ptr<const void> keep_;  // keeps that discretisation alive
  std::vector<std::unique_ptr<Level>> levels_;
  // The assembled fine pattern the Galerkin products are for: its id where the operator has one,
  // else a copy.
  PatternMemo fine_pattern_;
  ElementGalerkin element_galerkin_;          // level 1 from a matrix-free operator's elements
  bool from_elements_ = false;                // the symbolic products are for element matrices
  bool fallback_only_ = false;                // element matrices on a single level: block-Jacobi
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> coarse_llt_;
  bool coarse_analysed_ = false;
  bool coarse_indefinite_ = false;  // the true Hessian's coarsest level is not positive definite
  DiagonalPreconditioner fallback_{DiagonalPreconditioner::Blocks::Vertex3};
};

}  // namespace sinew
