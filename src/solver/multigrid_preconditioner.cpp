#include "sinew/solver/multigrid_preconditioner.hpp"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>

#include "sinew/core/error.hpp"
#include "sinew/linalg/single_precision_block_rows.hpp"
#include "sinew/linalg/symmetric_product.hpp"
#include "sinew/solver/serial_openmp.hpp"

namespace sinew {
namespace {

// The fine matrix with its values in single precision (when its pattern is not made of 3x3
// blocks, else SinglePrecisionBlockRows), for the smoother and the V-cycle's residual only (CG's own products stay in double). A product streams 8 bytes per nonzero
// instead of 12, and the V-cycle is only a preconditioner: a fixed linear operator either way.
class SinglePrecisionOperator final : public LinearOperator {
 public:
  void set(const Eigen::SparseMatrix<double>& A, const LinearOperator& original) {
    A_ = &A;
    original_ = &original;
    values_.resize(static_cast<size_t>(A.nonZeros()));
    const double* v = A.valuePtr();
    tbb::parallel_for(tbb::blocked_range<size_t>(0, values_.size(), 1 << 16), [&](const auto& r) {
      for (size_t k = r.begin(); k != r.end(); ++k) values_[k] = static_cast<float>(v[k]);
    });
  }
  Eigen::Index rows() const override { return A_->rows(); }
  void apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const override {
    symmetric_product(*A_, values_.data(), x, y);
  }
  Mat3 diagonal_block(Eigen::Index v) const override { return original_->diagonal_block(v); }

 private:
  const Eigen::SparseMatrix<double>* A_ = nullptr;
  const LinearOperator* original_ = nullptr;
  std::vector<float> values_;
};

}  // namespace

// Level l: its operator (the Newton matrix on level 0, a Galerkin product below), free-DOF
// mask, smoother, and the interpolation from level l + 1 with its symbolic Galerkin product.
struct MultigridPreconditioner::Level {
  Eigen::Index dofs = 0;
  const LinearOperator* A = nullptr;
  const LinearOperator* smoothed = nullptr;  // what the smoother and the residual use
  SinglePrecisionBlockRows single_blocks;    // level 0: A in single precision, block rows
  SinglePrecisionOperator single;            // the same for a pattern that is not in 3x3 blocks
  BlockSparseMatrix coarse_matrix;  // levels >= 1: the operator
  std::vector<char> free;
  ChebyshevSmoother smoother;
  VertexInterpolation interpolation;  // from level l + 1 (not on the coarsest level)
  GalerkinProduct galerkin;           // A_{l+1} = P^T A_l P
  Eigen::VectorXd residual, coarse_b, coarse_x;
};

MultigridPreconditioner::MultigridPreconditioner(MultigridSettings settings) : settings_(settings) {
  // As in the direct solver: a failed attempt is reported through info(), never printed (CHOLMOD
  // writes its warnings to stdout, into a run's machine-readable output).
  coarse_llt_.cholmod().print = 0;
}
MultigridPreconditioner::~MultigridPreconditioner() = default;

std::vector<Eigen::Index> MultigridPreconditioner::level_dofs() const {
  std::vector<Eigen::Index> dofs;
  for (const auto& level : levels_) dofs.push_back(level->dofs);
  return dofs;
}

void MultigridPreconditioner::build_hierarchy(const VolumeMesh& mesh) {
  LatticeHierarchy h = lattice_hierarchy(mesh, std::max<Eigen::Index>(1, settings_.coarsest_dofs / 3), settings_.max_levels);
  levels_.clear();
  for (size_t l = 0; l < h.levels.size(); ++l) {
    auto level = std::make_unique<Level>();
    level->dofs = 3 * h.levels[l].vertices();
    if (l < h.interpolations.size()) level->interpolation = std::move(h.interpolations[l]);
    levels_.push_back(std::move(level));
  }
  fine_pattern_.forget();
  coarse_analysed_ = false;
}

void MultigridPreconditioner::setup(const LinearOperator& A, const SolverContext& context) {
  const LatticeStructure* lattice = context.lattice();
  if (!lattice) {  // no grid to coarsen: block-Jacobi
    lattice_ = nullptr;
    keep_.reset();
    levels_.clear();
    fallback_.setup(A, context);
    return;
  }
  // The fine operator: an assembled matrix, or (matrix-free Newton systems) element matrices from
  // which the first coarse level is formed directly (linalg/element_galerkin.hpp).
  const Eigen::SparseMatrix<double>* matrix = A.matrix();
  const ElementMatrices* elements = matrix ? nullptr : A.element_matrices();
  if (!matrix && !elements)
    throw Error("needs the assembled matrix or the operator's element matrices", "preconditioner multigrid");
  const VolumeMesh& mesh = context.discretization->mesh();
  if (A.rows() != 3 * mesh.num_vertices())
    throw Error(fmt::format("the matrix has {} rows, the lattice {} DOFs", A.rows(), 3 * mesh.num_vertices()),
                "preconditioner multigrid");
  if (lattice_ != context.discretization.get()) {
    build_hierarchy(mesh);
    lattice_ = context.discretization.get();
    keep_ = context.discretization;
  }
  fallback_only_ = levels_.size() == 1 && elements;
  if (fallback_only_) {  // nothing to coarsen to and no matrix to factorise: block-Jacobi
    fallback_.setup(A, context);
    return;
  }

  // Symbolic products again when the matrix's pattern (or the elements) changed (contacts come
  // and go).
  Eigen::SparseMatrix<double> compressed;
  const Eigen::SparseMatrix<double>* fine = matrix;
  if (matrix && !matrix->isCompressed()) {
    compressed = *matrix;
    compressed.makeCompressed();
    fine = &compressed;
  }
  // The operator's pattern id where it has one (a Newton Hessian: no copy of its pattern, ~4
  // bytes per nonzero, and no comparison per setup); else the pattern compared with a copy.
  const std::uint64_t pattern_id = fine == matrix ? A.pattern_id() : 0;
  const bool same_pattern = elements ? from_elements_ && element_galerkin_.structure_id() == elements->structure_id()
                                     : fine_pattern_.same_or_remember(*fine, pattern_id) && !from_elements_;
  if (!same_pattern) {
    std::vector<std::vector<int>> pattern;
    size_t first = 0;
    if (elements) {
      fine_pattern_.forget();
      element_galerkin_ = ElementGalerkin(*elements, levels_[0]->interpolation);
      levels_[1]->coarse_matrix = element_galerkin_.make_coarse();
      pattern = block_pattern(levels_[1]->coarse_matrix);
      first = 1;
    } else {
      pattern = block_pattern(*fine);
    }
    for (size_t l = first; l + 1 < levels_.size(); ++l) {
      Level& L = *levels_[l];
      L.galerkin = GalerkinProduct(pattern, L.interpolation);
      levels_[l + 1]->coarse_matrix = L.galerkin.make_coarse();
      pattern = block_pattern(levels_[l + 1]->coarse_matrix);
    }
    from_elements_ = elements != nullptr;
    coarse_analysed_ = false;
  }

  // Numeric: free masks, coarse operators, smoothers.
  Level& L0 = *levels_[0];
  L0.A = &A;
  L0.free.assign(static_cast<size_t>(A.rows()), 1);
  for (Eigen::Index i = 0; i < A.rows(); ++i)
    if (context.is_fixed(i)) L0.free[static_cast<size_t>(i)] = 0;
  for (size_t l = 0; l < levels_.size(); ++l) {
    Level& L = *levels_[l];
    if (l > 0) {
      Level& F = *levels_[l - 1];
      L.free = F.interpolation.coarse_free(F.free);
      if (l == 1 && elements)
        element_galerkin_.compute(*elements, F.free, L.free, L.coarse_matrix);
      else if (l == 1)
        F.galerkin.compute(*fine, F.free, L.free, L.coarse_matrix);
      else
        F.galerkin.compute(F.coarse_matrix, F.free, L.free, L.coarse_matrix);
      L.A = &L.coarse_matrix;
    }
    L.smoothed = L.A;
    if (l == 0 && matrix && levels_.size() > 1 && fine == matrix) {  // (a compressed copy would not outlive setup)
      if (L.single_blocks.set(*fine, A)) {
        L.smoothed = &L.single_blocks;
      } else {
        L.single.set(*fine, A);
        L.smoothed = &L.single;
      }
    }
    if (l + 1 < levels_.size()) L.smoother.setup(*L.smoothed, L.free, settings_.smoother);
  }

  // Coarsest level: CHOLMOD, shifted slightly if round-off left it singular.
  const Level& C = *levels_.back();
  const Eigen::SparseMatrix<double> lower =
      levels_.size() == 1 ? Eigen::SparseMatrix<double>(fine->triangularView<Eigen::Lower>()) : C.coarse_matrix.lower_triangle();
  const SerialOpenMpScope serial_cholmod;
  if (!coarse_analysed_) {
    coarse_llt_.analyzePattern(lower);
    coarse_analysed_ = true;
  }
  double shift = 0.0;
  coarse_indefinite_ = false;
  // A true (unprojected) Hessian may be indefinite: then its failure is the answer, as with the
  // direct solver. Every application returns NaN, PCG stops at once unconverged and Newton falls
  // back to the projected Hessian (a shifted factorisation would hide the indefiniteness).
  const int attempts = context.may_be_indefinite ? 1 : 6;
  for (int attempt = 0; attempt < attempts; ++attempt) {
    coarse_llt_.setShift(shift);
    coarse_llt_.factorize(lower);
    if (coarse_llt_.info() == Eigen::Success) return;
    const double diag = lower.diagonal().cwiseAbs().maxCoeff();
    shift = shift == 0.0 ? 1e-10 * diag : shift * 100.0;
  }
  if (context.may_be_indefinite) {
    coarse_indefinite_ = true;
    return;
  }
  throw Error("the coarsest level could not be factorised", "preconditioner multigrid");
}

void MultigridPreconditioner::cycle(size_t l, const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  Level& L = *levels_[l];
  if (l + 1 == levels_.size()) {
    if (coarse_indefinite_) {
      x.setConstant(b.size(), std::numeric_limits<double>::quiet_NaN());
      return;
    }
    const SerialOpenMpScope serial_cholmod;
    x = coarse_llt_.solve(b);
    return;
  }
  Level& next = *levels_[l + 1];
  L.smoother.smooth(b, x, /*zero_start=*/true);
  L.smoothed->apply(x, L.residual);
  L.residual = b - L.residual;
  L.interpolation.restrict_to(L.residual, L.free, L.coarse_b);
  cycle(l + 1, L.coarse_b, L.coarse_x);
  L.interpolation.prolong(L.coarse_x, L.free, x, /*add=*/true);
  L.smoother.smooth(b, x, /*zero_start=*/false);
  (void)next;
}

void MultigridPreconditioner::apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) {
  if (!lattice_ || fallback_only_) {
    fallback_.apply(r, z);
    return;
  }
  cycle(0, r, z);
}

}  // namespace sinew
